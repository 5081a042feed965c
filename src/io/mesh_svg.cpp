#include "io/mesh_svg.hpp"

#include "io/svg_writer.hpp"

namespace curvemesh::io {

std::string mesh_svg(const mesh::TriMesh& m) {
  geometry::Box2 box;
  for (int v = 0; v < m.vertex_count(); ++v) box.add(m.point(v));
  SvgWriter svg(box);
  // Each untagged edge once: from the triangle where it runs from the lower to the higher
  // vertex, or from its only triangle.
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (m.feature(a, b)) continue;
      if (a < b || m.edge_triangles(a, b).size() == 1) svg.segment(m.point(a), m.point(b), "#b0b0b0");
    }
  }
  for (const auto& [e, f] : m.sorted_features()) {
    const char* colour = f.kind == mesh::EdgeKind::primary ? "#d00000" : f.kind == mesh::EdgeKind::secondary ? "#00a000" : "#000000";
    svg.segment(m.point(e[0]), m.point(e[1]), colour);
  }
  for (int v = 0; v < m.vertex_count(); ++v)
    if (m.tag(v).isolated) svg.dot(m.point(v), "#0000d0");
  return svg.finish();
}

}  // namespace curvemesh::io
