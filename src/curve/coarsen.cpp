// Step 6 of curve(): coarsening along the curves, once the triangles are curved and certified.
#include "curve/steps.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve::detail {

namespace {

// The primary edges shorter than l that follow their curve and have an end in `changed`,
// shortest first.
std::vector<std::pair<double, std::array<int, 2>>> short_curved_edges(const Curving& cv,
                                                                      const std::vector<char>& changed,
                                                                      double l) {
  const TriMesh& m = cv.mesh;
  std::vector<std::pair<double, std::array<int, 2>>> edges;
  for (const auto& [edge, f] : m.sorted_features()) {
    const int a = edge[0], b = edge[1];
    if (f.kind != EdgeKind::primary || !cv.form.follows(a, b) || !(changed[a] || changed[b])) continue;
    if (const double len = (m.point(a) - m.point(b)).squaredNorm(); len < l * l)
      edges.push_back({len, {a, b}});
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// The collapse of `from` onto `to` along their curve, tried as step 6 allows it: the merged edge
// follows its curve like the one it replaces (a new primary edge left straight would be a step
// back), no new edge is longer than 5/3 l, the changed triangles certified and at most
// max(coarsen_amips, the worst they replace).
bool collapse_along_curve(Curving& cv, int from, int to, const mesh::Constraints& relaxed) {
  TriMesh& m = cv.mesh;
  const double l = cv.options.coarsen_edge_length;
  const mesh::CollapseTest short_new_edges = [&](int a, int b) {
    return mesh::collapse_keeps_edges_short(m, a, b, [&](int, int) { return mesh::kCoarseningScale * l; });
  };
  const std::vector<int> star = m.triangles_of(from);
  if (std::any_of(star.begin(), star.end(), [&](int t) { return cv.form.scaled(t) <= 0; })) return false;
  return try_operation(
      cv, star,
      [&]() -> std::optional<std::vector<int>> {
        const std::optional<std::vector<int>> left = collapse(cv, from, to, relaxed, &short_new_edges);
        if (!left) return std::nullopt;
        for (int u : *left)
          for (int i = 0; i < 3; ++i) {
            const int a = m.triangle(u)[i], b = m.triangle(u)[(i + 1) % 3];
            if (is_primary(m, a, b) && !followable(m, a, b)) return std::nullopt;
          }
        return left;
      },
      {}, cv.options.coarsen_amips);
}

}  // namespace

// Invariant 3 (a primary edge turns at most α) is what lets the linear mesh be curved at all
// (Theorem 3.4); once the triangles are curved and certified it is not needed any more (§4.2,
// Curved Mesh Optimization), and it is what keeps a curve's edges short where the curve bends: a
// circle of any size gets 36 edges. So here a primary edge may cover any interval of its section
// (no inflection, turning below π: the cubic through its nodes is the curve's own piece). In
// rounds, the primary edges shorter than l, shortest first, are collapsed along their curve
// (collapse_along_curve). Fitted and straight edges stay as they are. After the first round only
// edges at a vertex whose star the last round changed are tried: a collapse reads the star of the
// vertex it removes alone, so one refused on unchanged stars is refused again.
void coarsen(Curving& cv) {
  const double l = cv.options.coarsen_edge_length;
  if (!(l > 0)) return;
  TriMesh& m = cv.mesh;
  mesh::Constraints relaxed = cv.constraints;
  relaxed.max_turning = std::numbers::pi;
  std::vector<char> changed(m.vertex_count(), 1);
  for (;;) {
    const auto edges = short_curved_edges(cv, changed, l);
    std::fill(changed.begin(), changed.end(), 0);
    int made = 0;
    for (const auto& [len, e] : edges)
      for (const auto& [from, to] : {std::pair{e[0], e[1]}, std::pair{e[1], e[0]}}) {
        // An earlier collapse of the round may have removed the edge or bent one beside it.
        if (!is_primary(m, from, to) || !cv.form.follows(from, to) ||
            !mesh::collapse_allowed_by_kind(m, from, to))
          continue;
        if (cv.form.on_fitted_edge(from) || cv.form.on_fitted_edge(to)) continue;
        if (!collapse_along_curve(cv, from, to, relaxed)) continue;
        for (int u : m.triangles_of(to))
          for (int w : m.triangle(u)) changed[w] = 1;
        ++made;
        ++cv.stats.coarsening_collapses;
        break;
      }
    if (made == 0) break;
  }
}

}  // namespace curvemesh::curve::detail
