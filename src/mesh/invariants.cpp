// The checks of the invariants of §4.1 that both the linear operations and the curved mesh use.
#include "mesh/invariants.hpp"

namespace curvemesh::mesh {

namespace {

// Floating-point slack on the turning bound: the features stage measured the same turning.
constexpr double kTurningSlack = 1e-9;

}  // namespace

bool star_valid_at(const TriMesh& m, int v, const Vec2& p) {
  for (int t : m.triangles_of(v)) {
    const auto& tri = m.triangle(t);
    if (m.orientation_with(tri[0], tri[1], tri[2], v, p) <= 0) return false;
  }
  return true;
}

bool secondary_edges_inside(const TriMesh& m, const Constraints& c, int v, const Vec2& p) {
  if (m.tag(v).kind == VertexKind::free) return true;  // no tagged edge at all
  for (const TaggedEdge& e : m.tagged_edges(v))
    if (e.feature.kind == EdgeKind::secondary && !c.envelope.contains(p, m.point(e.other), e.feature.curve))
      return false;
  return true;
}

double turning_limit(const Constraints& c) {
  return c.max_turning + kTurningSlack;
}

bool edge_satisfies_invariants(const TriMesh& m, const Constraints& c, int a, int b) {
  const EdgeFeature* f = m.feature(a, b);
  if (!f) return true;
  if (f->kind == EdgeKind::secondary) return c.envelope.contains(m.point(a), m.point(b), f->curve);
  if (f->kind == EdgeKind::primary)
    return c.sections[f->source].turning(f->t_lo, f->t_hi) <= turning_limit(c);
  return true;
}

}  // namespace curvemesh::mesh
