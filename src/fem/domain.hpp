#pragma once
// Cutting a mesh open along curves. Which part of a meshed drawing a problem lives on is the
// drawing's faces and regions (regions/faces.hpp), the same classification `curvemesh mesh
// --domain` makes.
#include <vector>

#include "io/high_order_mesh.hpp"
#include "regions/faces.hpp"

namespace curvemesh::fem {

using regions::edge_lines;
using regions::edge_triangles;
using regions::submesh;

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
