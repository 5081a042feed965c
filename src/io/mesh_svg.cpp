#include "io/mesh_svg.hpp"

#include "io/svg_writer.hpp"

#include <algorithm>
#include <set>
#include <span>
#include <stdexcept>
#include <utility>

using curvemesh::geometry::Vec2;

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

namespace {

// The cubic Bézier through four points at parameters 0, 1/3, 2/3, 1 (a P3 edge).
geometry::CubicBezier bezier_through(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  return {p0, (-5 * p0 + 18 * p1 - 9 * p2 + 2 * p3) / 6, (2 * p0 - 9 * p1 + 18 * p2 - 5 * p3) / 6, p3};
}

}  // namespace

std::string mesh_svg(const curve::CurvedMesh& cm) {
  const mesh::TriMesh& m = cm.linear;
  geometry::Box2 box;
  for (const Vec2& p : cm.nodes) box.add(p);
  SvgWriter svg(box);
  for (std::size_t k = 0; k < cm.triangles.size(); ++k) {
    const auto& n = cm.triangles[k];
    for (int i = 0; i < 3; ++i) {
      const int a = n[i], b = n[(i + 1) % 3];
      if (m.feature(a, b)) continue;
      if (a < b || m.edge_triangles(a, b).size() == 1)
        svg.cubic(bezier_through(cm.nodes[a], cm.nodes[n[3 + 2 * i]], cm.nodes[n[4 + 2 * i]], cm.nodes[b]), "#b0b0b0");
    }
  }
  for (const curve::FeatureLine& line : cm.lines) {
    const char* colour = line.kind == mesh::EdgeKind::primary ? "#d00000" : line.kind == mesh::EdgeKind::secondary ? "#00a000" : "#000000";
    const auto& n = line.nodes;
    svg.cubic(bezier_through(cm.nodes[n[0]], cm.nodes[n[2]], cm.nodes[n[3]], cm.nodes[n[1]]), colour);
  }
  for (int v = 0; v < m.vertex_count(); ++v)
    if (m.tag(v).isolated) svg.dot(m.point(v), "#0000d0");
  return svg.finish();
}

namespace {

// Edge e of triangle t (or line l) as a cubic Bézier, from its nodes in Gmsh's order.
geometry::CubicBezier edge_bezier(const HighOrderMesh& m, std::span<const int> n, int a, int b, int e) {
  if (m.order == 3)
    return bezier_through(m.nodes[n[a]], m.nodes[n[3 + 2 * e]], m.nodes[n[4 + 2 * e]], m.nodes[n[b]]);
  return geometry::CubicBezier::line(m.nodes[n[a]], m.nodes[n[b]]);
}

}  // namespace

std::string mesh_svg(const HighOrderMesh& m, const std::vector<std::string>& triangle_fill) {
  if (m.order != 1 && m.order != 3) throw std::logic_error("mesh_svg: triangles of order 1 or 3 only");
  geometry::Box2 box;
  for (const Vec2& p : m.nodes) box.add(p);
  SvgWriter svg(box);
  std::vector<geometry::CubicBezier> boundary;
  for (int t = 0; t < m.triangle_count(); ++t) {
    if (triangle_fill.at(t).empty()) continue;
    const auto n = m.triangle(t);
    boundary.clear();
    for (int e = 0; e < 3; ++e) boundary.push_back(edge_bezier(m, n, e, (e + 1) % 3, e));
    svg.filled(boundary, triangle_fill[t]);
  }
  // Each edge once, lines last (on top) in their colours.
  std::set<std::pair<int, int>> lines;
  for (int l = 0; l < m.line_count(); ++l) lines.emplace(std::min(m.line(l)[0], m.line(l)[1]), std::max(m.line(l)[0], m.line(l)[1]));
  std::set<std::pair<int, int>> drawn;
  for (int t = 0; t < m.triangle_count(); ++t) {
    const auto n = m.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const int a = n[e], b = n[(e + 1) % 3];
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      if (lines.count(key) || !drawn.insert(key).second) continue;
      svg.cubic(edge_bezier(m, n, e, (e + 1) % 3, e), "#808080");
    }
  }
  for (int l = 0; l < m.line_count(); ++l) {
    const auto n = m.line(l);
    const int physical = m.line_physical[l];
    const char* colour = physical == kPhysicalPrimary ? "#d00000" : physical == kPhysicalSecondary ? "#00a000" : "#000000";
    svg.cubic(m.order == 3 ? bezier_through(m.nodes[n[0]], m.nodes[n[2]], m.nodes[n[3]], m.nodes[n[1]])
                           : geometry::CubicBezier::line(m.nodes[n[0]], m.nodes[n[1]]),
              colour);
  }
  return svg.finish();
}

}  // namespace curvemesh::io
