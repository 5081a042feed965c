#pragma once
// The physical groups a finished mesh of a drawing is written with: the tags a solver selects a
// boundary or a part by. Numbered from the drawing alone, never from what a domain keeps, so a
// group has the same id and name with any --domain, and ids are disjoint across dimensions (GetFEM
// merges the tags of 2.2 files across dimensions; Gmsh and meshio do not need it, nothing loses by it):
//
//   1 primary, 2 secondary, 3 boundary   lines, by what they lie on (io/high_order_mesh.hpp)
//   4 domain                             the triangles, when not tagged by region
//   5 border                             lines on the border of the meshed domain
//   6 + s                                lines on the curves of drawn element s (the soup's
//                                        sources, s = 0 .. S-1), named by its id, else TAG#INDEX
//   6 + S + k                            region k: 0 the background, then each (element, fill) the
//                                        drawing paints, in paint order, shown by the domain or not
//                                        (a stroke read as an area: its element, ".stroke")
//
// A line is in several groups at once: its kind's, "border" when on the border, and every drawn
// element it lies on. Where curves of several elements coincide (two shapes sharing a side), the
// line is in each element's group: that is how Gmsh's own overlapping physical groups behave, and a
// solver selecting one shape's outline gets all of it.
#include <string>
#include <vector>

#include "io/high_order_mesh.hpp"
#include "svg/feature_soup.hpp"

namespace curvemesh::regions {

// An element's name: its id, else TAG#INDEX (its position in the document).
std::string element_name(const svg::SourceElement& element);

// The physical line group of drawn element `source` (an index into FeatureSoup::sources).
int element_group(int source);

// The physical surface of region `key` (0 the background, then RegionKeys::names' order) of a
// drawing with `sources` drawn elements.
int region_group(int key, int sources);

// Every region a drawing can have, whatever part of it a mesh keeps: the background (key 0), then
// each (element, fill) pair of its fill layers, in paint order of their first layer, and each
// (element, stroke paint) pair of its strokes read as areas. Names are the element's
// (element_name), its stroke's that with ".stroke" after it, "background", and a second use of a
// name gets "@2", a third "@3" (an element painted in two colours through <use>, two elements with
// one id).
struct RegionKeys {
  std::vector<int> of_layer;       // per fill layer: its key
  std::vector<std::string> names;  // per key
  std::vector<int> source;         // per key: the element (-1 for the background)
  std::vector<svg::Paint> fill;    // per key (none for the background)
};
RegionKeys region_keys(const svg::FeatureSoup& soup);

// The lines on the border of the mesh: on an edge of exactly one triangle.
std::vector<char> border_lines(const io::HighOrderMesh& mesh);

// Puts each line of `mesh` in "border" when it is on the mesh's border, and in the group of each
// element of `elements[l]` (indices into soup.sources, any order), naming those groups. Names that
// would repeat within lines ("border", two elements with one id) get "@2", "@3", numbered over all
// of the drawing's elements, so a group's name does not depend on the domain either.
void add_line_groups(io::HighOrderMesh& mesh, const std::vector<std::vector<int>>& elements,
                     const svg::FeatureSoup& soup);

}  // namespace curvemesh::regions
