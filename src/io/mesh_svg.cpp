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

// The Bézier pieces of polynomial edges through their nodes at equal steps of their parameter:
// the ends a and b and the inner nodes from a on. A P3 edge through m1, m2 is the cubic with
// control points (−5a + 18m1 − 9m2 + 2b)/6 and (2a − 9m1 + 18m2 − 5b)/6; a P2 edge through m is
// exactly the quadratic (SVG's Q) with control point 2m − (a + b)/2, drawn as such, not raised to
// a cubic.
BezierPiece cubic_through(const Vec2& a, const Vec2& m1, const Vec2& m2, const Vec2& b) {
  return {3, {a, (-5 * a + 18 * m1 - 9 * m2 + 2 * b) / 6, (2 * a - 9 * m1 + 18 * m2 - 5 * b) / 6, b}};
}
BezierPiece quadratic_through(const Vec2& a, const Vec2& m, const Vec2& b) {
  return {2, {a, 2 * m - (a + b) / 2, b, b}};
}
BezierPiece segment(const Vec2& a, const Vec2& b) {
  return {1, {a, b, b, b}};
}

// Edge i of a triangle (from corner i to corner i + 1) of `order`, from its node ids in Gmsh's
// order (edge i's inner nodes are 3 + (order − 1)i on).
template <class Ids>
BezierPiece triangle_edge(int order, const std::vector<Vec2>& nodes, const Ids& n, int i) {
  const Vec2 &a = nodes[n[i]], &b = nodes[n[(i + 1) % 3]];
  const int inner = 3 + (order - 1) * i;
  if (order == 3) return cubic_through(a, nodes[n[inner]], nodes[n[inner + 1]], b);
  return order == 2 ? quadratic_through(a, nodes[n[inner]], b) : segment(a, b);
}

// A feature line of `order` from its node ids: its ends, then its inner nodes.
template <class Ids>
BezierPiece line_piece(int order, const std::vector<Vec2>& nodes, const Ids& n) {
  const Vec2 &a = nodes[n[0]], &b = nodes[n[1]];
  if (order == 3) return cubic_through(a, nodes[n[2]], nodes[n[3]], b);
  return order == 2 ? quadratic_through(a, nodes[n[2]], b) : segment(a, b);
}

const char* line_colour(bool primary, bool secondary) {
  return primary ? "#d00000" : secondary ? "#00a000" : "#000000";
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
      if (a < b || m.edge_triangles(a, b).size() == 1) svg.piece(triangle_edge(cm.order, cm.nodes, n, i), "#b0b0b0");
    }
  }
  for (const curve::FeatureLine& line : cm.lines)
    svg.piece(line_piece(cm.order, cm.nodes, line.nodes),
              line_colour(line.kind == mesh::EdgeKind::primary, line.kind == mesh::EdgeKind::secondary));
  for (int v = 0; v < m.vertex_count(); ++v)
    if (m.tag(v).isolated) svg.dot(m.point(v), "#0000d0");
  return svg.finish();
}

std::string mesh_svg(const HighOrderMesh& m, const std::vector<std::string>& triangle_fill) {
  if (m.order < 1 || m.order > 3) throw std::logic_error("mesh_svg: triangles of order 1, 2 or 3 only");
  geometry::Box2 box;
  for (const Vec2& p : m.nodes) box.add(p);
  SvgWriter svg(box);
  std::vector<BezierPiece> boundary;
  for (int t = 0; t < m.triangle_count(); ++t) {
    if (triangle_fill.at(t).empty()) continue;
    const auto n = m.triangle(t);
    boundary.clear();
    for (int e = 0; e < 3; ++e) boundary.push_back(triangle_edge(m.order, m.nodes, n, e));
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
      svg.piece(triangle_edge(m.order, m.nodes, n, e), "#808080");
    }
  }
  for (int l = 0; l < m.line_count(); ++l) {
    const int physical = m.line_physical[l];
    svg.piece(line_piece(m.order, m.nodes, m.line(l)),
              line_colour(physical == kPhysicalPrimary, physical == kPhysicalSecondary));
  }
  return svg.finish();
}

}  // namespace curvemesh::io
