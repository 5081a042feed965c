#include "io/curved_mesh.hpp"

#include <span>

namespace curvemesh::io {

HighOrderMesh curved_mesh(const curve::CurvedMesh& m) {
  HighOrderMesh out;
  out.order = m.order;
  out.nodes = m.nodes;
  // CurvedMesh holds room for order 3's nodes; an order-2 element's are its first ones.
  const auto triangle_size = static_cast<std::size_t>(out.triangle_size());
  const auto line_size = static_cast<std::size_t>(out.line_size());
  for (const auto& t : m.triangles) out.add_triangle(std::span<const int>(t).first(triangle_size), kPhysicalDomain);
  for (const curve::FeatureLine& line : m.lines) {
    const int physical = line.kind == mesh::EdgeKind::primary     ? kPhysicalPrimary
                         : line.kind == mesh::EdgeKind::secondary ? kPhysicalSecondary
                                                                  : kPhysicalBoundary;
    out.add_line(std::span<const int>(line.nodes).first(line_size), physical);
  }
  return out;
}

}  // namespace curvemesh::io
