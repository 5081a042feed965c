#include "io/curved_mesh.hpp"

namespace curvemesh::io {

HighOrderMesh curved_mesh(const curve::CurvedMesh& m) {
  HighOrderMesh out;
  out.order = 3;
  out.nodes = m.nodes;
  for (const auto& t : m.triangles) out.add_triangle(t, kPhysicalDomain);
  for (const curve::FeatureLine& line : m.lines) {
    const int physical = line.kind == mesh::EdgeKind::primary     ? kPhysicalPrimary
                         : line.kind == mesh::EdgeKind::secondary ? kPhysicalSecondary
                                                                  : kPhysicalBoundary;
    out.add_line(line.nodes, physical);
  }
  return out;
}

}  // namespace curvemesh::io
