// Step 1 of curve(): splitting triangles until each has at most one primary edge.
#include "curve/steps.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve::detail {

int primary_edges_of(const TriMesh& m, const mesh::Triangle& tri) {
  int n = 0;
  for (int i = 0; i < 3; ++i) n += is_primary(m, tri[i], tri[(i + 1) % 3]);
  return n;
}

// Step 1. Splitting a non-primary edge of a triangle with two primary edges leaves one on each
// half; a triangle with three needs a primary split first. Interior midpoints always split
// validly; a split the invariants refuse is replaced by the next candidate edge.
int split_until_one_primary_edge(TriMesh& m, const mesh::Constraints& c) {
  int splits = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t) || primary_edges_of(m, m.triangle(t)) < 2) continue;
      const mesh::Triangle tri = m.triangle(t);
      std::array<std::array<int, 2>, 3> edges{{{tri[0], tri[1]}, {tri[1], tri[2]}, {tri[2], tri[0]}}};
      // Non-primary edges first, longer first.
      std::stable_sort(edges.begin(), edges.end(), [&](const auto& x, const auto& y) {
        const bool px = is_primary(m, x[0], x[1]), py = is_primary(m, y[0], y[1]);
        if (px != py) return !px;
        return (m.point(x[0]) - m.point(x[1])).squaredNorm() > (m.point(y[0]) - m.point(y[1])).squaredNorm();
      });
      for (const auto& [a, b] : edges) {
        if (mesh::split_edge(m, c, a, b, INFINITY) >= 0) {
          ++splits;
          changed = true;
          break;
        }
      }
    }
  }
  return splits;
}

}  // namespace curvemesh::curve::detail
