#pragma once
// Which part of a meshed drawing a problem lives on, and cutting a mesh open along curves.
//
// The mesh of a drawing covers its whole box; the feature lines divide it into regions
// (triangles connected across edges that are no feature line). A region's depth is the number
// of feature lines crossed from the box's border: the regions touching the border have depth 0,
// a region next to one of depth k has at most k + 1. Odd depth is the drawing's "inside" under
// the even–odd rule (a square with a round hole: the ring has depth 1, the hole 2).
#include <array>
#include <vector>

#include "io/high_order_mesh.hpp"

namespace curvemesh::fem {

// For every triangle, the line on each of its edges (-1 for none): lines are matched to edges
// by their end nodes.
std::vector<std::array<int, 3>> edge_lines(const io::HighOrderMesh& mesh);

struct Regions {
  std::vector<int> of_triangle;  // region index per triangle
  std::vector<int> depth;        // per region
  int count() const { return static_cast<int>(depth.size()); }
};

// Regions separated by primary and secondary lines.
Regions find_regions(const io::HighOrderMesh& mesh);

// The triangles with keep[t] set, their nodes (renumbered, in order of first use) and the lines
// on their edges; line_origin (if given) gets the input line of each line kept, node_origin the
// input node of each node.
io::HighOrderMesh submesh(const io::HighOrderMesh& mesh, const std::vector<char>& keep,
                          std::vector<int>* line_origin = nullptr, std::vector<int>* node_origin = nullptr);

// The mesh cut open along the lines with cut[l] set: the triangles on the two sides of a cut
// line get separate copies of its nodes (corners and inner nodes), so that unknowns on the two
// sides are independent; a cut line's loose end (a curve ending inside a region) stays one node.
// Each cut line appears once per side in the result. Nodes keep their index where they are not
// copied; copies are appended.
struct CutMesh {
  io::HighOrderMesh mesh;
  std::vector<int> node_origin;  // per node of `mesh`, the node it copies
  std::vector<int> line_origin;  // per line of `mesh`, the input line
};
CutMesh cut_open(const io::HighOrderMesh& mesh, const std::vector<char>& cut);

}  // namespace curvemesh::fem
