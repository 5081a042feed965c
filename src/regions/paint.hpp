#pragma once
// Which filled shape of the drawing each face of a finished mesh shows, decided as a browser
// paints: every filled element (fill not none) covers the points whose winding number with
// respect to its own outline is inside under its fill rule (nonzero or evenodd), after its
// transforms and <use>; the visible one is the topmost in paint order. Opacity, gradients and
// patterns do not change coverage; clip paths and masks are not applied.
//
// A face is bounded by feature lines on input curves, so each shape's winding number is the same
// all over it, except where the mesh follows an outline only within ε (secondary lines) or drops
// a piece of it (degenerate curves). There the face's samples disagree, and each of its triangles
// is decided on its own, at its sample point farthest from that outline. (Not at the first point
// more than ε from it: a secondary line may leave one curve for a neighbour's envelope, so a
// triangle can reach well into a thin shape drawn over it.) A face that lies entirely on an
// outline, as far as doubles can tell, is not guessed: classify throws Undecided.
#include <stdexcept>
#include <string>
#include <vector>

#include "io/high_order_mesh.hpp"
#include "regions/faces.hpp"
#include "svg/feature_soup.hpp"

namespace curvemesh::regions {

struct ClassifyOptions {
  // How far the mesh's feature lines may lie from the input curves (ε, absolute): the least
  // distance from an outline worth knowing for a sample point.
  double clearance = 0;
  // Below this distance (absolute) a point counts as lying on an outline.
  double resolution = 0;
  // A stroke narrower than this (absolute; FillLayer::width) paints no face: the mesh keeps the
  // two sides of the wider ones apart (μ is made small enough for them), not of these, and the
  // faces between them, where there are any, are slivers of whatever lies along the stroke.
  double min_stroke_width = 0;
};

// Whether layer `layer` of `fills` is one classify leaves out (a stroke below min_stroke_width).
bool too_narrow(const svg::FillLayer& layer, const ClassifyOptions& options);

// Thrown when a face's side of a shape's outline cannot be decided.
class Undecided : public std::runtime_error {
 public:
  Undecided(int layer, int face) : std::runtime_error("undecided face"), layer(layer), face(face) {}
  int layer, face;
};

// The faces of `mesh` (the whole box, linear or curved) and the visible fill layer of each. A
// layer covers a face inside its outline and inside each of its clip paths (`clips`, the soup's,
// which its FillLayer::clips index): inside one of a clip path's shapes.
Classification classify(const io::HighOrderMesh& mesh, const std::vector<svg::FillLayer>& fills,
                        const ClassifyOptions& options, const std::vector<svg::ClipPath>& clips = {});

// A part of the mesh's triangles tagged by what is painted on them.
struct Region {
  int physical = 0;    // its physical surface tag (regions/groups.hpp: region_group), the same in any domain
  std::string name;    // the element's id, else TAG#INDEX (document index), or "background"; "@2"... on a repeat
  svg::Paint fill;     // none for the background
  int source = -1;     // the soup's source element, -1 for the background
  int triangles = 0;
  double area = 0;     // of its (curved) triangles
};

struct Painted {
  io::HighOrderMesh mesh;           // the domain's triangles; physical tags by region when tagged
  std::vector<int> node_origin;     // per node of `mesh`: its node in the whole mesh
  std::vector<int> face;            // per triangle of `mesh`: its face in the whole mesh
  std::vector<int> layer;           // per triangle: its visible fill layer, -1 none (or not classified)
  std::vector<Region> regions;      // the regions the domain shows, by physical tag; empty unless tagged
  int region_of(int triangle) const;  // index into `regions` (tagged meshes only)
};

// The triangles of `whole` in `domain`, each tagged with the physical surface of its region when
// `tag_regions` (one per visible element and fill, and "background", numbered by the whole drawing:
// regions/groups.hpp): what `curvemesh mesh --regions --domain ...` writes. The classification must have its fills classified when
// tagging or for Domain::filled.
Painted paint(const io::HighOrderMesh& whole, const Classification& classification, const svg::FeatureSoup& soup,
              Domain domain, bool tag_regions);

}  // namespace curvemesh::regions
