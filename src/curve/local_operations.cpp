// Step 4 of curve(), the local operations of §4.1 on the curved mesh: for triangles still above
// the stop energy after smoothing, a swap, a collapse or splits, each tried on the linear mesh
// under its journal and kept only if the curved triangles it changes get better.
#include <cmath>
#include <limits>

#include "curve/steps.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve::detail {

namespace {

using Edges = std::array<std::array<int, 2>, 3>;

// The union of two lists of ids, sorted, each once.
std::vector<int> sorted_union(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

// The split of (a, b) at the middle of its parameter interval (mesh::split_edge), or −1 where a
// new primary vertex would be left off its curve (the mesh is then changed: the caller's
// try_operation takes it back).
int split_on_curve(Curving& cv, int a, int b) {
  TriMesh& m = cv.mesh;
  const int mid = mesh::split_edge(m, cv.constraints, a, b, std::numeric_limits<double>::infinity());
  // A primary vertex left on the chord would leave its curve's edges straight.
  return mid >= 0 && !(m.tag(mid).kind == mesh::VertexKind::primary && !m.tag(mid).on_curve) ? mid : -1;
}

// The split of one edge, as an operation for try_operation.
Operation split_operation(Curving& cv, int a, int b) {
  return [&cv, a, b]() -> std::optional<std::vector<int>> {
    const int mid = split_on_curve(cv, a, b);
    if (mid < 0) return std::nullopt;
    return cv.mesh.triangles_of(mid);
  };
}

Edges longest_first(const Curving& cv, const mesh::Triangle& tri) {
  Edges edges{{{tri[0], tri[1]}, {tri[1], tri[2]}, {tri[2], tri[0]}}};
  std::stable_sort(edges.begin(), edges.end(), [&](const auto& x, const auto& y) {
    return (cv.form.at(x[0]) - cv.form.at(x[1])).squaredNorm() >
           (cv.form.at(y[0]) - cv.form.at(y[1])).squaredNorm();
  });
  return edges;
}

bool swap_one(Curving& cv, const Edges& edges) {
  TriMesh& m = cv.mesh;
  for (const auto& [a, b] : edges) {
    if (m.feature(a, b)) continue;
    const std::vector<int> changed = m.edge_triangles(a, b);
    if (try_operation(cv, changed, [&m, &changed, a = a, b = b]() -> std::optional<std::vector<int>> {
          if (!mesh::swap_edge(m, a, b, std::numeric_limits<double>::infinity())) return std::nullopt;
          return changed;
        })) {
      ++cv.stats.curved_swaps;
      return true;
    }
  }
  return false;
}

bool collapse_one(Curving& cv, const Edges& edges) {
  TriMesh& m = cv.mesh;
  for (const auto& edge : edges)
    for (const auto& [from, to] : {std::pair{edge[0], edge[1]}, std::pair{edge[1], edge[0]}}) {
      const std::vector<int> star = m.triangles_of(from);  // a copy: the collapse changes the list
      if (try_operation(cv, star,
                        [&cv, from = from, to = to] { return collapse(cv, from, to, cv.constraints); })) {
        ++cv.stats.curved_collapses;
        return true;
      }
    }
  return false;
}

// A fixed corner of the triangle where curves meet: every edge there split at once, its free
// neighbours then moved. Two curved edges leaving a vertex have at least two triangles between
// them (a triangle has one curved edge at most); where the curves bend towards each other, their
// sides bulge into those triangles, and no smoothing of a vertex between them undoes it. Halving
// the edges at the vertex grades the mesh towards it: the bulge of a curved edge shrinks like h²κ,
// and the triangles there approach straight wedges.
bool split_at_junction(Curving& cv, const mesh::Triangle& tri) {
  TriMesh& m = cv.mesh;
  for (int i = 0; i < 3; ++i) {
    const int v = tri[i];
    if (m.tag(v).kind != mesh::VertexKind::fixed) continue;
    int curves = 0;
    for (const mesh::TaggedEdge& e : m.tagged_edges(v)) curves += e.feature.kind == EdgeKind::primary;
    if (curves < 2) continue;
    const std::vector<int> ends = m.neighbours(v);
    std::vector<int> movable, before = sorted_union(m.triangles_of(v), {});
    for (int w : ends)
      if (m.tag(w).kind == mesh::VertexKind::free)
        movable.push_back(w), before = sorted_union(before, m.triangles_of(w));
    const auto split_all = [&]() -> std::optional<std::vector<int>> {
      std::vector<int> made;
      for (int w : ends) {
        const int mid = split_on_curve(cv, v, w);
        if (mid < 0) return std::nullopt;
        made = sorted_union(made, m.triangles_of(mid));
      }
      for (int w : movable) made = sorted_union(made, m.triangles_of(w));
      return made;
    };
    if (try_operation(cv, before, split_all, movable)) {
      cv.stats.curved_splits += static_cast<int>(ends.size());
      return true;
    }
  }
  return false;
}

// A split of one edge, its new vertex moved where its star is best before the outcome is judged.
bool split_one(Curving& cv, const Edges& edges) {
  for (const auto& [a, b] : edges)
    if (try_operation(cv, cv.mesh.edge_triangles(a, b), split_operation(cv, a, b))) {
      ++cv.stats.curved_splits;
      return true;
    }
  return false;
}

// Splits of two edges, the triangle's corner between them cut off: a thin corner between a curve
// and another feature needs both its sides shortened.
bool cut_corner(Curving& cv, const mesh::Triangle& tri) {
  TriMesh& m = cv.mesh;
  for (int i = 0; i < 3; ++i) {
    // The corner tri[i] between edges (tri[i], tri[i+1]) and (tri[i+2], tri[i]).
    const int a = tri[i], b = tri[(i + 1) % 3], c = tri[(i + 2) % 3];
    const std::vector<int> before = sorted_union(m.edge_triangles(a, b), m.edge_triangles(c, a));
    if (try_operation(cv, before, [&]() -> std::optional<std::vector<int>> {
          const int m1 = split_on_curve(cv, a, b);
          const int m2 = m1 < 0 ? -1 : split_on_curve(cv, c, a);
          if (m2 < 0) return std::nullopt;
          return sorted_union(m.triangles_of(m1), m.triangles_of(m2));
        })) {
      cv.stats.curved_splits += 2;
      return true;
    }
  }
  return false;
}

// Whether the triangles an operation made are kept (try_operation), their scaled Jacobians
// recorded if so. The energies first: where nothing before was uncertified, a triangle above both
// the worst before and accept_up_to refuses the operation, and no certificate need be made. Only
// whether the worst after is below the worst before or at most accept_up_to counts, so each
// energy need only be exact below the larger of the two.
bool judge_operation(Curving& cv, const std::vector<int>& after, const std::vector<double>& known,
                     bool settled, double worst_before, int invalid_before, double accept_up_to) {
  const double bound =
      std::nextafter(std::max(worst_before, accept_up_to), std::numeric_limits<double>::infinity());
  double worst_after = 0;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const int t = after[k];
    worst_after = std::max(worst_after, !settled && !std::isnan(known[k]) ? known[k] : cv.energy(t, bound));
    if (invalid_before == 0 && worst_after >= worst_before && worst_after > accept_up_to) return false;
  }
  int invalid_after = 0;
  std::vector<std::optional<double>> certified;
  for (int t : after) {
    certified.push_back(cv.certify(t));
    invalid_after += !certified.back();
  }
  if (!(invalid_after < invalid_before ||
        (invalid_after == 0 && (worst_after < worst_before || worst_after <= accept_up_to))))
    return false;
  for (std::size_t k = 0; k < after.size(); ++k) cv.form.set_scaled(after[k], certified[k].value_or(-1.0));
  return true;
}

// A vertex made by a split moves (move_corner), then the centres of `triangles` do.
void settle_vertex(Curving& cv, int v, const std::vector<int>& triangles) {
  move_corner(cv, v);
  for (int t : triangles) smooth_centre(cv, t);
}

}  // namespace

// Passes over the triangles still above the stop energy after smoothing: for each, the swap
// of one of its edges, else the collapse of one, else the split of every edge at a corner
// where curves meet, else the split of one edge (longer edges first) or two, whichever first
// lowers the worst energy of the triangles it changes with every changed triangle certified;
// then a smoothing pass. At most max_smoothing_passes passes.
void improve(Curving& cv) {
  for (int pass = 0; pass < cv.options.max_smoothing_passes; ++pass) {
    const std::vector<int> bad = bad_triangles(cv);
    if (bad.empty()) return;
    int changed = 0;
    for (int t : bad)
      if (cv.mesh.alive(t) && cv.energy(t) > cv.options.stop_amips) changed += improve_triangle(cv, t);
    changed += smooth_pass(cv);
    if (changed == 0) return;
  }
}

int improve_triangle(Curving& cv, int t) {
  const mesh::Triangle tri = cv.mesh.triangle(t);
  const Edges edges = longest_first(cv, tri);
  return swap_one(cv, edges) || collapse_one(cv, edges) || split_at_junction(cv, tri) ||
         split_one(cv, edges) || cut_corner(cv, tri);
}

// The operation's triangles get their nodes from the curved form (mesh::CurvedForm::adopt: new
// edges on their curve where they can follow it, centres chosen as in step 2), new vertices
// settle, then the vertices `settle` (existing ones, whose triangles must all be in `before` and
// in those returned); the operation is kept only if none of them has two primary edges and,
// compared with `before` (the triangles it replaces), fewer of them are uncertified (validity
// first: triangles flat to round-off leave a mesh that cannot be written), or all are certified
// and their worst energy is lower than before or at most `accept_up_to` (step 6's bound; 0 for
// step 4). Otherwise one rollback puts the mesh and its nodes back.
bool try_operation(Curving& cv, const std::vector<int>& before, const Operation& operation,
                   const std::vector<int>& settle, double accept_up_to) {
  TriMesh& m = cv.mesh;
  double worst_before = 0;
  int invalid_before = 0;
  std::vector<std::uint64_t> old_edges;
  for (int t : before) {
    worst_before = std::max(worst_before, cv.energy(t));
    invalid_before += cv.form.scaled(t) <= 0;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) old_edges.push_back(mesh::edge_key(tri[i], tri[(i + 1) % 3]));
  }
  const int vertices0 = m.vertex_count(), moves0 = cv.stats.smoothing_moves;
  m.open_journal();
  const std::optional<std::vector<int>> after = operation();
  // The energies placing the centres found (NaN where none), good while no vertex settles.
  std::vector<double> known;
  bool ok = after && cv.form.adopt(vertices0, *after, known);
  if (ok) {
    const bool settled = m.vertex_count() > vertices0 || !settle.empty();
    for (int v = vertices0; v < m.vertex_count(); ++v) settle_vertex(cv, v, *after);
    for (int v : settle) settle_vertex(cv, v, *after);
    ok = judge_operation(cv, *after, known, settled, worst_before, invalid_before, accept_up_to);
  }
  if (!ok) {
    m.rollback();
    cv.stats.smoothing_moves = moves0;
    return false;
  }
  m.commit();
  cv.form.forget_edges(old_edges);
  return true;
}

std::optional<std::vector<int>> collapse(Curving& cv, int from, int to, const mesh::Constraints& constraints,
                                         const mesh::CollapseTest* also) {
  TriMesh& m = cv.mesh;
  std::vector<int> kept;
  for (int u : m.triangles_of(from)) {
    const auto& corners = m.triangle(u);
    if (std::find(corners.begin(), corners.end(), to) == corners.end()) kept.push_back(u);
  }
  const double unbounded = std::numeric_limits<double>::infinity();
  if (!(also ? mesh::collapse_edge(m, constraints, from, to, unbounded, *also)
             : mesh::collapse_edge(m, constraints, from, to, unbounded)))
    return std::nullopt;
  // Order 2: an edge merged along its curve covers a longer interval, and may be beyond the
  // tolerance where the two were not.
  if (cv.form.quadratic())
    for (int u : kept)
      for (int i = 0; i < 3; ++i)
        if (const int a = m.triangle(u)[i], b = m.triangle(u)[(i + 1) % 3];
            is_primary(m, a, b) && beyond_tolerance_if_curved(cv, a, b))
          return std::nullopt;
  return kept;
}

bool split_certified(Curving& cv, int a, int b) {
  return try_operation(cv, cv.mesh.edge_triangles(a, b), split_operation(cv, a, b), {},
                       std::numeric_limits<double>::infinity());
}

}  // namespace curvemesh::curve::detail
