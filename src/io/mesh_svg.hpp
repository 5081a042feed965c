#pragma once
// A drawing of a mesh for inspection: every edge in thin grey, then the tagged edges on top —
// primary red, secondary green, box black (the colours of the paper's figures) — and isolated
// points as dots.
#include <string>
#include <vector>

#include "curve/curve.hpp"
#include "io/high_order_mesh.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::io {

std::string mesh_svg(const mesh::TriMesh& mesh);
// The same for a curved mesh: each edge as the SVG Bézier through its nodes (cubic: C; quadratic:
// Q).
std::string mesh_svg(const curve::CurvedMesh& mesh);
// A plain mesh (order 1, 2 or 3) with each triangle filled with its colour ("#rrggbb"; empty: not
// filled) under its edges: untagged edges grey, lines by their physical tag.
std::string mesh_svg(const HighOrderMesh& mesh, const std::vector<std::string>& triangle_fill);

}  // namespace curvemesh::io
