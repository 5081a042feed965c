// Step 4 of curve(), the local operations of §4.1 on the curved mesh: for triangles still above
// the stop energy after smoothing, a swap, a collapse or splits, each tried on the linear mesh
// under its journal and kept only if the curved triangles it changes get better.
#include <cmath>
#include <limits>

#include "curve/builder.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve::detail {

namespace {

// The union of two lists of ids, sorted, each once.
std::vector<int> sorted_union(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

}  // namespace

// Passes over the triangles still above the stop energy after smoothing: for each, the swap
// of one of its edges, else the collapse of one, else the split of every edge at a corner
// where curves meet, else the split of one edge (longer edges first) or two, whichever first
// lowers the worst energy of the triangles it changes with every changed triangle certified;
// then a smoothing pass. At most max_smoothing_passes passes.
void Builder::improve() {
  for (int pass = 0; pass < o_.max_smoothing_passes; ++pass) {
    const std::vector<int> bad = bad_triangles();
    if (bad.empty()) return;
    int changed = 0;
    for (int t : bad)
      if (out_.linear.alive(t) && energy(t) > o_.stop_amips) changed += improve_triangle(t);
    changed += smooth_pass();
    if (changed == 0) return;
  }
}

int Builder::improve_triangle(int t) {
  const mesh::Triangle tri = out_.linear.triangle(t);
  const Edges edges = longest_first(tri);
  return swap_one(edges) || collapse_one(edges) || split_at_junction(tri) || split_one(edges) || cut_corner(tri);
}

Builder::Edges Builder::longest_first(const mesh::Triangle& tri) const {
  Edges edges{{{tri[0], tri[1]}, {tri[1], tri[2]}, {tri[2], tri[0]}}};
  std::stable_sort(edges.begin(), edges.end(), [&](const auto& x, const auto& y) {
    return (at(x[0]) - at(x[1])).squaredNorm() > (at(y[0]) - at(y[1])).squaredNorm();
  });
  return edges;
}

// The loops below name the ends without structured bindings: the lambdas use them, which clang
// before 16 refuses.
bool Builder::swap_one(const Edges& edges) {
  TriMesh& m = out_.linear;
  for (const auto& edge : edges) {
    const int a = edge[0], b = edge[1];
    if (m.feature(a, b)) continue;
    if (try_operation(m.edge_triangles(a, b), [&]() -> std::optional<std::vector<int>> {
          std::vector<int> changed = m.edge_triangles(a, b);
          if (!mesh::swap_edge(m, a, b, std::numeric_limits<double>::infinity())) return std::nullopt;
          return changed;
        })) {
      ++s_.curved_swaps;
      return true;
    }
  }
  return false;
}

bool Builder::collapse_one(const Edges& edges) {
  TriMesh& m = out_.linear;
  for (const auto& edge : edges)
    for (const auto& ends : {std::pair{edge[0], edge[1]}, std::pair{edge[1], edge[0]}}) {
      const int from = ends.first, to = ends.second;
      const std::vector<int> star = m.triangles_of(from);  // a copy: the collapse changes the list
      if (try_operation(star, [&] { return collapse(from, to, c_); })) {
        ++s_.curved_collapses;
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
bool Builder::split_at_junction(const mesh::Triangle& tri) {
  TriMesh& m = out_.linear;
  for (int i = 0; i < 3; ++i) {
    const int v = tri[i];
    if (m.tag(v).kind != mesh::VertexKind::fixed) continue;
    int curves = 0;
    for (const mesh::TaggedEdge& e : m.tagged_edges(v)) curves += e.feature.kind == EdgeKind::primary;
    if (curves < 2) continue;
    const std::vector<int> ends = m.neighbours(v);
    std::vector<int> movable, before = sorted_union(m.triangles_of(v), {});
    for (int w : ends)
      if (m.tag(w).kind == mesh::VertexKind::free) movable.push_back(w), before = sorted_union(before, m.triangles_of(w));
    const auto split_all = [&]() -> std::optional<std::vector<int>> {
      std::vector<int> made;
      for (int w : ends) {
        const int mid = split_on_curve(v, w);
        if (mid < 0) return std::nullopt;
        made = sorted_union(made, m.triangles_of(mid));
      }
      for (int w : movable) made = sorted_union(made, m.triangles_of(w));
      return made;
    };
    if (try_operation(before, split_all, movable)) {
      s_.curved_splits += static_cast<int>(ends.size());
      return true;
    }
  }
  return false;
}

// A split of one edge, its new vertex moved where its star is best before the outcome is judged.
bool Builder::split_one(const Edges& edges) {
  TriMesh& m = out_.linear;
  for (const auto& edge : edges) {
    const int a = edge[0], b = edge[1];
    if (try_operation(m.edge_triangles(a, b), [&]() -> std::optional<std::vector<int>> {
          const int mid = split_on_curve(a, b);
          if (mid < 0) return std::nullopt;
          return m.triangles_of(mid);
        })) {
      ++s_.curved_splits;
      return true;
    }
  }
  return false;
}

// Splits of two edges, the triangle's corner between them cut off: a thin corner between a curve
// and another feature needs both its sides shortened.
bool Builder::cut_corner(const mesh::Triangle& tri) {
  TriMesh& m = out_.linear;
  for (int i = 0; i < 3; ++i) {
    // The corner tri[i] between edges (tri[i], tri[i+1]) and (tri[i+2], tri[i]).
    const int a = tri[i], b = tri[(i + 1) % 3], c = tri[(i + 2) % 3];
    const std::vector<int> before = sorted_union(m.edge_triangles(a, b), m.edge_triangles(c, a));
    if (try_operation(before, [&]() -> std::optional<std::vector<int>> {
          const int m1 = split_on_curve(a, b);
          const int m2 = m1 < 0 ? -1 : split_on_curve(c, a);
          if (m2 < 0) return std::nullopt;
          return sorted_union(m.triangles_of(m1), m.triangles_of(m2));
        })) {
      s_.curved_splits += 2;
      return true;
    }
  }
  return false;
}

// Tries a local operation of the linear mesh on the curved mesh. `operation` changes
// out_.linear (under its journal) and returns the triangles it changed or made, or nothing if
// it refused. Those triangles get their P3 nodes (new edges on their curve where they can
// follow it, centres chosen as in step 2), new vertices settle, then the vertices `settle`
// (existing ones, whose triangles must all be in `before` and in those returned); the
// operation is kept only if none of them has two primary edges and, compared with `before`
// (the triangles it replaces), fewer of them are uncertified (validity first: triangles flat
// to round-off leave a mesh that cannot be written), or all are certified and their worst
// energy is lower than before or at most `accept_up_to` (step 6's bound; 0 for step 4).
// Otherwise everything is put back.
template <class Operation>
bool Builder::try_operation(const std::vector<int>& before, const Operation& operation,
                            const std::vector<int>& settle, double accept_up_to) {
  TriMesh& m = out_.linear;
  double worst_before = 0;
  int invalid_before = 0;
  std::vector<std::uint64_t> old_edges;
  for (int t : before) {
    worst_before = std::max(worst_before, energy(t));
    invalid_before += scaled_[t] <= 0;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) old_edges.push_back(mesh::edge_key(tri[i], tri[(i + 1) % 3]));
  }
  const int vertices0 = m.vertex_count(), moves0 = s_.smoothing_moves;
  // The journal takes back the mesh and its nodes alike: those of the new triangles and
  // vertices, and the existing ones the vertices in `settle` move (their own, their edges').
  m.open_journal();
  const std::optional<std::vector<int>> after = operation();
  bool ok = after.has_value();
  if (ok) {
    for (int v = vertices0; v < m.vertex_count(); ++v) {
      vertex_node_.push_back(static_cast<int>(nodes_.size()));
      nodes_.push_back(m.point(v));
    }
    triangle_nodes_.resize(m.triangle_slots());
    scaled_.resize(m.triangle_slots(), -1.0);
    // The energies placing the centres found (NaN where none), good while no vertex settles.
    std::vector<double> known(after->size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < after->size(); ++k) ok = ok && place_triangle((*after)[k], &known[k]);
    const bool settled = m.vertex_count() > vertices0 || !settle.empty();
    for (int v = vertices0; ok && v < m.vertex_count(); ++v) settle_vertex(v, *after);
    for (int v : settle)
      if (ok) settle_vertex(v, *after);
    ok = ok && judge_operation(*after, known, settled, worst_before, invalid_before, accept_up_to);
  }
  if (!ok) {
    m.rollback();
    s_.smoothing_moves = moves0;
    return false;
  }
  m.commit();
  // Edges the operation removed lose their nodes (a later operation may make them again).
  for (const auto key : old_edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (m.edge_triangles(a, b).empty()) first_node_.erase(key), curved_.erase(key), fitted_.erase(key);
  }
  return true;
}

// Whether the triangles an operation made are kept (try_operation), their scaled Jacobians
// recorded if so. The energies first: where nothing before was uncertified, a triangle above both
// the worst before and accept_up_to refuses the operation, and no certificate need be made. Only
// whether the worst after is below the worst before or at most accept_up_to counts, so each
// energy need only be exact below the larger of the two.
bool Builder::judge_operation(const std::vector<int>& after, const std::vector<double>& known, bool settled,
                              double worst_before, int invalid_before, double accept_up_to) {
  const double bound = std::nextafter(std::max(worst_before, accept_up_to), std::numeric_limits<double>::infinity());
  double worst_after = 0;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const int t = after[k];
    worst_after = std::max(worst_after, !settled && !std::isnan(known[k]) ? known[k] : energy(t, bound));
    if (invalid_before == 0 && worst_after >= worst_before && worst_after > accept_up_to) return false;
  }
  int invalid_after = 0;
  std::vector<std::optional<double>> certified;
  for (int t : after) {
    certified.push_back(certify(t));
    invalid_after += !certified.back();
  }
  if (!(invalid_after < invalid_before ||
        (invalid_after == 0 && (worst_after < worst_before || worst_after <= accept_up_to))))
    return false;
  for (std::size_t k = 0; k < after.size(); ++k) scaled_.set(after[k], certified[k].value_or(-1.0));
  return true;
}

int Builder::split_on_curve(int a, int b) {
  TriMesh& m = out_.linear;
  const int mid = mesh::split_edge(m, c_, a, b, std::numeric_limits<double>::infinity());
  // A primary vertex left on the chord would leave its curve's edges straight.
  return mid >= 0 && !(m.tag(mid).kind == mesh::VertexKind::primary && !m.tag(mid).on_curve) ? mid : -1;
}

bool Builder::split_certified(int a, int b) {
  TriMesh& m = out_.linear;
  return try_operation(
      m.edge_triangles(a, b),
      [&]() -> std::optional<std::vector<int>> {
        const int mid = split_on_curve(a, b);
        if (mid < 0) return std::nullopt;
        return m.triangles_of(mid);
      },
      {}, std::numeric_limits<double>::infinity());
}

// A vertex made by a split moves (move_corner), then the centres of `triangles` do.
void Builder::settle_vertex(int v, const std::vector<int>& triangles) {
  move_corner(v);
  for (int t : triangles) smooth_centre(t);
}

// Gives triangle t (changed by an operation) its nodes: its edges' (made where new), a new
// centre (none for order 2). False if it has two primary edges (step 1 gave every triangle at
// most one).
bool Builder::place_triangle(int t, double* known_energy) {
  const TriMesh& m = out_.linear;
  const mesh::Triangle tri = m.triangle(t);
  if (primary_edges_of(m, tri) > 1) return false;
  for (int i = 0; i < 3; ++i) add_edge(tri[i], tri[(i + 1) % 3]);
  std::array<int, 10> ids = corner_and_edge_nodes(tri);
  if (!quadratic()) {
    ids[9] = static_cast<int>(nodes_.size());
    nodes_.push_back((at(tri[0]) + at(tri[1]) + at(tri[2])) / 3);
  }
  triangle_nodes_.set(t, ids);
  const double e = curved_edge_of(tri) >= 0 ? choose_centre_of(t) : std::numeric_limits<double>::quiet_NaN();
  if (known_energy) *known_energy = e;
  return true;
}

// Collapses `from` onto `to` under `constraints` (and the caller's test `also`, if any), as an
// operation for try_operation: the triangles of from's star that stay (those without `to`), or
// nothing if the collapse is refused.
std::optional<std::vector<int>> Builder::collapse(int from, int to, const mesh::Constraints& constraints,
                                                  const mesh::CollapseTest* also) {
  TriMesh& m = out_.linear;
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
  if (quadratic())
    for (int u : kept)
      for (int i = 0; i < 3; ++i)
        if (const int a = m.triangle(u)[i], b = m.triangle(u)[(i + 1) % 3];
            is_primary(m, a, b) && beyond_tolerance_if_curved(a, b))
          return std::nullopt;
  return kept;
}

// Step 6: coarsening along the curves. Invariant 3 (a primary edge turns at most α) is what lets
// the linear mesh be curved at all (Theorem 3.4); once the triangles are curved and certified it
// is not needed any more (§4.2, Curved Mesh Optimization), and it is what keeps a curve's edges
// short where the curve bends: a circle of any size gets 36 edges. So here a primary edge may
// cover any interval of its section (no inflection, turning below π: the cubic through its nodes
// is the curve's own piece). In rounds, the primary edges shorter than l, shortest first, are
// collapsed along their curve when every triangle the collapse changes is certified, no new
// edge is longer than 5/3 of l (the linear coarsening's bound) and their worst energy is at most
// max(coarsen_amips, the worst they replace). Fitted and straight edges stay as they are.
void Builder::coarsen() {
  const double l = o_.coarsen_edge_length;
  if (!(l > 0)) return;
  TriMesh& m = out_.linear;
  mesh::Constraints relaxed = c_;
  relaxed.max_turning = std::numbers::pi;
  const mesh::CollapseTest short_new_edges = [&](int from, int to) {
    return mesh::collapse_keeps_edges_short(m, from, to, [&](int, int) { return mesh::kCoarseningScale * l; });
  };
  const auto curved = [&](int a, int b) {
    const bool* c = curved_.find(mesh::edge_key(a, b));
    return c && *c;
  };
  // After the first round only edges at a vertex whose star the last round changed: a collapse
  // reads the star of the vertex it removes alone, so one refused on unchanged stars is refused
  // again.
  std::vector<char> changed(m.vertex_count(), 1);
  for (;;) {
    std::vector<std::pair<double, std::array<int, 2>>> edges;
    for (const auto& [edge, f] : m.sorted_features()) {
      const int a = edge[0], b = edge[1];
      if (f.kind != EdgeKind::primary || !curved(a, b) || !(changed[a] || changed[b])) continue;
      if (const double len = (m.point(a) - m.point(b)).squaredNorm(); len < l * l)
        edges.push_back({len, {a, b}});
    }
    std::sort(edges.begin(), edges.end());
    std::fill(changed.begin(), changed.end(), 0);
    int made = 0;
    for (const auto& [len, e] : edges)
      for (const auto& ends : {std::pair{e[0], e[1]}, std::pair{e[1], e[0]}}) {
        const int from = ends.first, to = ends.second;
        // An earlier collapse of the round may have removed the edge or bent one beside it.
        if (!is_primary(m, from, to) || !curved(from, to) || !mesh::collapse_allowed_by_kind(m, from, to))
          continue;
        if (on_fitted_edge(from) || on_fitted_edge(to)) continue;
        const std::vector<int> star = m.triangles_of(from);
        if (std::any_of(star.begin(), star.end(), [&](int t) { return scaled_[t] <= 0; })) continue;
        const bool kept = try_operation(
            star,
            [&]() -> std::optional<std::vector<int>> {
              const std::optional<std::vector<int>> left = collapse(from, to, relaxed, &short_new_edges);
              if (!left) return std::nullopt;
              // The merged edge follows its curve like the one it replaces (a new primary edge
              // left straight would be a step back).
              for (int u : *left)
                for (int i = 0; i < 3; ++i) {
                  const int a = m.triangle(u)[i], b = m.triangle(u)[(i + 1) % 3];
                  if (is_primary(m, a, b) && !followable(m, a, b)) return std::nullopt;
                }
              return left;
            },
            {}, o_.coarsen_amips);
        if (kept) {
          for (int u : m.triangles_of(to))
            for (int w : m.triangle(u)) changed[w] = 1;
          ++made;
          ++s_.coarsening_collapses;
          break;
        }
      }
    if (made == 0) break;
  }
}

}  // namespace curvemesh::curve::detail
