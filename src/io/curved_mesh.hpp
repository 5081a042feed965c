#pragma once
// The curved mesh of §4.2 as a plain P3 (or P2) mesh for the writers: its nodes as they are (one
// per position, shared), the triangles in "domain", every feature edge as a 4-node (3-node) line
// in "primary", "secondary" or "boundary".
#include "curve/curve.hpp"
#include "io/high_order_mesh.hpp"

namespace curvemesh::io {

HighOrderMesh curved_mesh(const curve::CurvedMesh& mesh);

}  // namespace curvemesh::io
