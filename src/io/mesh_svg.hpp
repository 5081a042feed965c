#pragma once
// A drawing of a mesh for inspection: every edge in thin grey, then the tagged edges on top —
// primary red, secondary green, box black (the colours of the paper's figures) — and isolated
// points as dots.
#include <string>

#include "curve/curve.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::io {

std::string mesh_svg(const mesh::TriMesh& mesh);
// The same for a curved mesh: each edge as the SVG cubic Bézier through its four nodes.
std::string mesh_svg(const curve::CurvedMesh& mesh);

}  // namespace curvemesh::io
