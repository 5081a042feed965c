#include "mesh/curved_element.hpp"

#include <utility>

namespace curvemesh::mesh {

bool is_primary(const TriMesh& m, int a, int b) {
  const EdgeFeature* f = m.feature(a, b);
  return f && f->kind == EdgeKind::primary;
}

bool followable(const TriMesh& m, int a, int b) {
  if (!is_primary(m, a, b)) return false;
  for (int v : {a, b}) {
    const VertexTag& tag = m.tag(v);
    if (tag.kind == VertexKind::primary && !tag.on_curve) return false;
  }
  return true;
}

int followed_edge(const TriMesh& m, const Triangle& tri) {
  int primary = -1;
  for (int i = 0; i < 3; ++i) {
    if (!is_primary(m, tri[i], tri[(i + 1) % 3])) continue;
    if (primary >= 0) return -1;
    primary = i;
  }
  return primary >= 0 && followable(m, tri[primary], tri[(primary + 1) % 3]) ? primary : -1;
}

std::array<Vec2, 2> nodes_on_curve(const SectionCurve& curve, double t_lo, double t_hi, int order) {
  if (order == 2) return {curve.eval(0.5 * (t_lo + t_hi)), Vec2::Zero()};
  return {curve.eval((2 * t_lo + t_hi) / 3), curve.eval((t_lo + 2 * t_hi) / 3)};
}

std::array<Vec2, 2> nodes_on_chord(const Vec2& lo, const Vec2& hi, int order) {
  if (order == 2) return {(lo + hi) / 2, Vec2::Zero()};
  return {(2 * lo + hi) / 3, (lo + 2 * hi) / 3};
}

geometry::P3Nodes curved_element(const TriMesh& m, const Constraints& c, int t) {
  return curved_element(m, c, t, followed_edge(m, m.triangle(t)));
}

geometry::P3Nodes curved_element(const TriMesh& m, const Constraints& c, int t, int followed) {
  const Triangle& tri = m.triangle(t);
  geometry::P3Nodes p;
  for (int i = 0; i < 3; ++i) {
    const int a = tri[i], b = tri[(i + 1) % 3], lo = std::min(a, b), hi = std::max(a, b);
    p[i] = m.point(a);
    std::array<Vec2, 2> inner;
    if (i == followed) {
      const EdgeFeature& f = *m.feature(lo, hi);
      inner = nodes_on_curve(c.sections[f.source], f.t_lo, f.t_hi, 3);
    } else {
      inner = nodes_on_chord(m.point(lo), m.point(hi), 3);
    }
    if (a > b) std::swap(inner[0], inner[1]);
    p[3 + 2 * i] = inner[0];
    p[4 + 2 * i] = inner[1];
  }
  p[9] = (p[0] + p[1] + p[2]) / 3;
  return p;
}

}  // namespace curvemesh::mesh
