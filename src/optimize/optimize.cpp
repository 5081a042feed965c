#include "optimize/optimize.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>
#include <string>

#include "base/limits.hpp"
#include "geometry/amips.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::optimize {

using mesh::TriMesh;
using geometry::Vec2;

namespace {


struct Edge {
  int a, b;  // a < b
  double length;
  // For collapses: whether a may move onto b, whether b may move onto a (by the kinds).
  bool a_moves = false, b_moves = false;
};

// Every edge once, in triangle order (deterministic): an interior edge from the triangle in which
// it runs from its lower to its higher vertex, a hull edge from its only triangle; those that
// `keep` keeps. Whether an edge running downwards has a reverse (is inside) is asked only where
// both ends may lie on the hull: on the box, the only hull the optimizer's meshes have. Euler's
// formula checks that no hull edge was missed (a triangulated disk has V - E + T = 1); if one was
// (the mesh is not the box's, say), every downward edge is asked. Walking a star per edge was a
// cache miss or more each: a sixth of the optimization's time. The filter runs as the edges are
// found: a pass that wants few of them does not write them all first.
template <class Keep>
std::vector<Edge> edges_where(const TriMesh& m, const Keep& keep) {  // keep(Edge&) may fill it in
  const auto has_directed = [&](int a, int b) {
    for (int t : m.triangles_of(a)) {
      const auto& tri = m.triangle(t);
      if ((tri[0] == a && tri[1] == b) || (tri[1] == a && tri[2] == b) || (tri[2] == a && tri[0] == b)) return true;
    }
    return false;
  };
  // Which vertices are on the box, read in one sweep over the tags rather than once per downward
  // edge (a cache miss each), and how many vertices the triangles use.
  std::vector<char> on_box(m.vertex_count(), 0);
  long used_vertices = 0;
  for (int v = 0; v < m.vertex_count(); ++v) {
    const mesh::VertexKind k = m.tag(v).kind;
    on_box[v] = k == mesh::VertexKind::boundary || k == mesh::VertexKind::fixed;
    used_vertices += !m.triangles_of(v).empty();
  }
  std::vector<Edge> edges;
  const auto collect = [&](bool all_downward) {
    edges.clear();
    long count = 0;
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t)) continue;
      const auto& tri = m.triangle(t);
      for (int i = 0; i < 3; ++i) {
        const int a = tri[i], b = tri[(i + 1) % 3];
        if (a < b || ((all_downward || (on_box[a] && on_box[b])) && !has_directed(b, a))) {
          ++count;
          Edge e{std::min(a, b), std::max(a, b), (m.point(a) - m.point(b)).norm()};
          if (keep(e)) edges.push_back(e);
        }
      }
    }
    return count;
  };
  if (used_vertices - collect(false) + m.triangle_count() != 1) collect(true);
  return edges;
}

std::vector<Edge> all_edges(const TriMesh& m) {
  return edges_where(m, [](const Edge&) { return true; });
}

// The edges shorter than below(a, b) that the kinds let collapse one way or the other (which ends
// may move filled in) and that `wanted(a, b)`, shortest first, in triangle order among equals.
template <class Below, class Wanted>
std::vector<Edge> collapse_candidates(const TriMesh& m, const Below& below, const Wanted& wanted) {
  auto edges = edges_where(m, [&](Edge& e) {
    if (e.length >= below(e.a, e.b) || !wanted(e.a, e.b)) return false;
    e.a_moves = mesh::collapse_allowed_by_kind(m, e.a, e.b);
    e.b_moves = mesh::collapse_allowed_by_kind(m, e.b, e.a);
    return e.a_moves || e.b_moves;
  });
  std::stable_sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.length < y.length; });
  return edges;
}

// One swap pass: every inner edge once, in the order of all_edges as the pass starts (hull edges
// never swap), each with the triangle it came from as the hint. The corners are copied first: the
// swaps rewrite triangles as the pass goes.
// `wanted(a, b)` may leave out edges whose swap is known to be refused; `swap(a, b, t)` swaps
// (mesh::swap_edge with t as the hint, or a stricter test of it); `swapped(a, b)` hears of each
// swap of (a, b), after it.
template <class Wanted, class Swap, class Swapped>
int swap_pass(TriMesh& m, const Wanted& wanted, const Swap& swap, const Swapped& swapped) {
  std::vector<mesh::Triangle> corners(m.triangle_slots());
  for (int t = 0; t < m.triangle_slots(); ++t) corners[t] = m.triangle(t);
  int swaps = 0;
  for (int t = 0; t < static_cast<int>(corners.size()); ++t) {
    const auto& tri = corners[t];
    if (tri[0] < 0) continue;
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (a < b && wanted(a, b) && swap(a, b, t)) {
        ++swaps;
        swapped(a, b);
      }
    }
  }
  return swaps;
}

int swap_pass(TriMesh& m) {
  return swap_pass(
      m, [](int, int) { return true; }, [&](int a, int b, int t) { return mesh::swap_edge(m, a, b, 0, t); },
      [](int, int) {});
}

// Lipschitz grading of a per-vertex sizing field over the mesh edges: no vertex asks for more
// than its neighbour's size plus `gradation` times their distance (Dijkstra from the smallest).
void grade(const TriMesh& m, std::vector<double>& size, double gradation) {
  using Item = std::pair<double, int>;
  // A vertex at the largest size lowers no neighbour (its bound is at least that size): it need
  // not be looked at. The queue orders by size, then vertex, so the heap is built at once.
  const double largest = size.empty() ? 0 : *std::max_element(size.begin(), size.end());
  std::vector<Item> items;
  for (int v = 0; v < m.vertex_count(); ++v)
    if (size[v] < largest) items.emplace_back(size[v], v);
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue(std::greater<>{}, std::move(items));
  while (!queue.empty()) {
    const auto [s, v] = queue.top();
    queue.pop();
    if (s > size[v]) continue;
    // The star's corners, an inner neighbour twice: the second look changes nothing, and the
    // result does not depend on the order (the queue orders by size, then vertex).
    for (int t : m.triangles_of(v))
      for (int w : m.triangle(t)) {
        if (w == v) continue;
        const double bound = s + gradation * (m.point(v) - m.point(w)).norm();
        if (bound < size[w]) {
          size[w] = bound;
          queue.emplace(bound, w);
        }
      }
  }
}

// The initial sizing field: the target length, except where two vertices that can never merge
// are closer (the edges of a tight bend of a curve, two section ends of a curve): there the mesh
// must be about as fine as their distance (`factor` times it), and grows from there. Without this
// the optimizer would find out by stalling and halving, many times over.
std::vector<double> initial_sizes(const TriMesh& m, double target, double factor, double gradation) {
  std::vector<double> size(m.vertex_count(), target);
  const auto pinned = [&](int v) {
    const auto& t = m.tag(v);
    return t.kind == mesh::VertexKind::fixed || (t.kind == mesh::VertexKind::primary && t.on_curve);
  };
  for (const Edge& e : all_edges(m)) {
    const mesh::EdgeFeature* f = m.feature(e.a, e.b);
    const bool curve_edge = f && f->kind == mesh::EdgeKind::primary && pinned(e.a) && pinned(e.b);
    const bool fixed_pair = m.tag(e.a).kind == mesh::VertexKind::fixed && m.tag(e.b).kind == mesh::VertexKind::fixed;
    if (curve_edge || fixed_pair) {
      size[e.a] = std::min(size[e.a], factor * e.length);
      size[e.b] = std::min(size[e.b], factor * e.length);
    }
  }
  grade(m, size, gradation);
  return size;
}

// The smallest angle of the triangles, in degrees (0 when there is none).
double min_angle_deg(const TriMesh& m) {
  double min_angle = std::numbers::pi;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    min_angle = std::min(min_angle, geometry::min_angle(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])));
  }
  return m.triangle_count() ? min_angle * 180 / std::numbers::pi : 0;
}

}  // namespace

Quality measure(const TriMesh& m) { return measure(m, true); }

Quality measure(const TriMesh& m, bool mean_edge_length) {
  Quality q;
  q.vertices = m.vertex_count();
  q.triangles = m.triangle_count();
  double max_e = 0, sum_e = 0;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    const double e = geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2]));
    max_e = std::max(max_e, e);
    sum_e += e;
  }
  q.max_amips = max_e;
  q.mean_amips = q.triangles ? sum_e / q.triangles : 0;
  q.min_angle_deg = min_angle_deg(m);
  if (!mean_edge_length) return q;
  const auto edges = all_edges(m);
  double sum_l = 0;
  for (const Edge& e : edges) sum_l += e.length;
  q.mean_edge_length = edges.empty() ? 0 : sum_l / static_cast<double>(edges.size());
  return q;
}

namespace {

// The energy triangle t would have once curved, as the curve stage first makes it: its primary
// edge on the curve (nodes at the thirds of its parameter interval), the best of the stage's
// three centres. 0 for a triangle with no primary edge, or more than one (the curve stage splits
// it), or one with an end off its curve (the stage leaves that edge straight): the linear energy
// judges those.
double curved_energy(const TriMesh& m, const mesh::Constraints& c, int t) {
  const mesh::Triangle& tri = m.triangle(t);
  int curved = -1;
  for (int i = 0; i < 3; ++i) {
    const mesh::EdgeFeature* f = m.feature(tri[i], tri[(i + 1) % 3]);
    if (!f || f->kind != mesh::EdgeKind::primary) continue;
    if (curved >= 0) return 0;
    curved = i;
  }
  if (curved < 0) return 0;
  const int a = tri[curved], b = tri[(curved + 1) % 3];
  for (int v : {a, b})
    if (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve) return 0;
  const mesh::EdgeFeature& f = *m.feature(a, b);
  const double ta = a < b ? f.t_lo : f.t_hi, tb = a < b ? f.t_hi : f.t_lo;
  // The corners turned so that the curved edge is the first (nodes 3 and 4).
  geometry::P3Nodes p = geometry::p3_straight_nodes(m.point(a), m.point(b), m.point(tri[(curved + 2) % 3]));
  const mesh::SectionCurve& s = c.sections[f.source];
  p[3] = s.eval(ta + (tb - ta) / 3);
  p[4] = s.eval(ta + 2 * (tb - ta) / 3);
  double best = std::numeric_limits<double>::infinity();
  for (const Vec2& centre : geometry::p3_centre_candidates(p)) {
    p[9] = centre;
    best = std::min(best, geometry::p3_max_amips(p, best));
  }
  return best;
}

}  // namespace

// The sizing field (small near features, halved where quality stalled) asked for more vertices
// than quality needs in the end: the loop refines where it must, and what it refined stays. Each
// round tries every edge shorter than the target again, against the target length alone (no new
// edge longer than 5/3 of it); rounds go on while they remove more than 0.5 % of the triangles. A
// collapse changes only its own star, so one round touches each vertex once (as in the loop). The
// loop collapses below 4/5 of its target and up to 4/3 of it only (TetWild's rule, so that its
// splits and collapses do not undo each other); no split follows here, and these bounds leave a
// mean edge of about 1.1 times the target where the features leave room (the loop's bounds left
// 0.93).
//
// Smoothing goes only where collapses and swaps changed the mesh (the loop left the rest
// smoothed). After the first round, collapses and swaps are tried only where something changed
// since that pass last ran: an operation's outcome depends on the stars it reads alone, so one
// tried on stars that have not changed since is refused again. `changed[v]` is the last time v's
// star changed: one of its triangles came or went, or a corner of one moved (a rollback counts:
// it may reorder the incidence lists, which the energies are summed in); `reshaped[v]`, the last
// time one of its triangles came or went.
void coarsen(TriMesh& m, const mesh::Constraints& c, const Options& o, Stats& s) {
  s.before_coarsening = m.triangle_count();
  const double target = o.edge_length;
  const bool curved = o.curved_stop_amips > 0;
  long clock = 1;
  std::vector<long> changed(m.vertex_count(), 0), reshaped(m.vertex_count(), 0);
  long collapse_start = 0, swap_start = 0;  // when each pass last began
  const auto star_changed = [&](int v, bool topology) {  // v's star and its neighbours' stars
    changed[v] = clock;
    if (topology) reshaped[v] = clock;
    for (int t : m.triangles_of(v))
      for (int w : m.triangle(t)) {
        changed[w] = clock;
        if (topology) reshaped[w] = clock;
      }
  };
  const auto star_curved = [&](int v) {  // the worst of v's triangles once curved (curved_energy)
    double worst = 0;
    for (int t : m.triangles_of(v)) worst = std::max(worst, curved_energy(m, c, t));
    return worst;
  };
  const mesh::CollapseTest short_enough = [&](int from, int to) {
    return mesh::collapse_keeps_edges_short(m, from, to, [&](int, int) { return mesh::kCoarseningScale * target; });
  };
  // A collapse: every new triangle at most max(stop energy, the worst it replaces), as in the
  // loop. In the curved pipeline it is also taken back when a triangle it leaves is above the
  // curved stop energy once curved (curved_energy), and redone only if none is above the worst of
  // both stars before: a coarser mesh beside a curve leaves the curved edge's bulge less room,
  // and the curve stage cannot always undo it. (Letting the linear energy of the triangles along
  // curves rise to the curved stop energy, judged by their curved form alone, made meshes a tenth
  // coarser still, but the curve stage does more than curved_energy foresees — splits triangles
  // with two curved edges, projects late vertices, takes the first certified centre: `mechorse`
  // ended at 158.9 and 16 of the collection's first 2,249 drawings above 20, 3 before; at three
  // quarters of it, `gis-computer_glenn_rolla_01` ended at 32.4.)
  // The curved pipeline's test of a collapse or swap of edge (a, b), shared by both: `operation`
  // is done under the journal and kept when `worst_after()` (the curved_energy of what it made)
  // is at most the curved stop energy; else it is taken back (the rollback counts as a change of
  // both ends' stars) and done again if `worst_before()` (what it replaced, read after the
  // rollback) was as bad.
  const auto curved_test = [&](int a, int b, const auto& operation, const auto& worst_after, const auto& worst_before) {
    m.open_journal();
    if (!operation()) {
      m.commit();
      return false;
    }
    const double after = worst_after();
    if (after <= o.curved_stop_amips) {
      m.commit();
      return true;
    }
    m.rollback();
    ++clock;
    star_changed(a, true);
    star_changed(b, true);
    return after <= worst_before() && operation();
  };
  const auto collapse = [&](int from, int to) {
    const auto operation = [&] { return mesh::collapse_edge(m, c, from, to, o.stop_max_amips, short_enough); };
    if (!curved) return operation();
    return curved_test(
        from, to, operation, [&] { return star_curved(to); },
        [&] { return std::max(star_curved(from), star_curved(to)); });
  };
  for (int round = 0; round < o.coarsening_rounds; ++round) {
    const long round_start = ++clock;
    // A collapse reads the stars of both ends.
    const long since_collapse = collapse_start;
    collapse_start = round_start;
    const std::vector<Edge> edges = collapse_candidates(
        m, [&](int, int) { return target; },
        [&](int a, int b) { return changed[a] >= since_collapse || changed[b] >= since_collapse; });
    std::vector<char> touched(m.vertex_count(), 0);
    long collapsed = 0;
    for (const Edge& e : edges) {
      if (touched[e.a] || touched[e.b]) continue;
      if ((e.a_moves && collapse(e.a, e.b)) || (e.b_moves && collapse(e.b, e.a))) {
        ++collapsed;
        touched[e.a] = touched[e.b] = 1;
        ++clock;
        star_changed(e.a, true);  // the one that stayed has the merged star; the other has none
        star_changed(e.b, true);
      }
    }
    s.coarsening_collapses += collapsed;

    // A swap of (a, b) reads its two triangles and the stars of the two opposite corners (is the
    // other diagonal an edge already?): it is tried again when a corner of either triangle has a
    // changed star, that is when a and b are both corners of such triangles (`near`).
    const long since_swap = swap_start;
    swap_start = ++clock;
    std::vector<char> near(m.vertex_count(), since_swap == 0);
    const auto mark_near = [&](int v) {
      for (int t : m.triangles_of(v))
        for (int w : m.triangle(t)) near[w] = 1;
    };
    if (since_swap > 0)
      for (int v = 0; v < m.vertex_count(); ++v)
        if (changed[v] >= since_swap) mark_near(v);
    // In the curved pipeline a swap is kept only if the two triangles it makes are at most the
    // curved stop energy once curved (curved_energy), or no worse than the two it replaced: above
    // the stop energy it is taken back (the rollback counts as a change of both ends' stars) and
    // redone if those were as bad, as the collapses. A swap beside a curve can leave the curved
    // edge's bulge against the opposite corner: `harp_mo_01` had a triangle at 16 once curved
    // before its first swap pass and 36.8 after it, and ended at 28.2. (The same test on the
    // smoothing moves cost 7.5 % more instructions on `old_truck` and changed no tail.)
    // The two triangles a swap rewrites keep their slots: after it they are the new diagonal's,
    // after a rollback the old ones again, so both energies are read from the slots swap_edge
    // names (no walk round a star before each swap tried).
    const auto swap = [&](int a, int b, int t) {
      std::array<int, 2> slots{-1, -1};
      const auto operation = [&] { return mesh::swap_edge(m, a, b, 0, t, &slots); };
      if (!curved) return operation();
      const auto worst_in_slots = [&] { return std::max(curved_energy(m, c, slots[0]), curved_energy(m, c, slots[1])); };
      return curved_test(a, b, operation, worst_in_slots, worst_in_slots);
    };
    s.swaps += swap_pass(
        m, [&](int a, int b) { return near[a] && near[b]; }, swap,
        [&](int a, int b) {  // the quad's corners are among the corners of a's and b's triangles now
          ++clock;
          for (int end : {a, b})
            for (int t : m.triangles_of(end))
              for (int v : m.triangle(t)) {
                changed[v] = reshaped[v] = clock;
                mark_near(v);
              }
        });

    // Smoothing, where this round's collapses and swaps changed a star.
    for (int v = 0; v < m.vertex_count(); ++v)
      if (reshaped[v] >= round_start && !m.triangles_of(v).empty() && !m.has_exact(v) &&
          !(m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve) && mesh::smooth_vertex(m, c, v)) {
        ++s.smooths;
        ++clock;
        star_changed(v, false);
      }

    const std::vector<int> renumbered = m.compact();
    std::vector<long> kept_changed(m.vertex_count(), 0), kept_reshaped(m.vertex_count(), 0);
    for (std::size_t v = 0; v < renumbered.size(); ++v)
      if (renumbered[v] >= 0) {
        kept_changed[renumbered[v]] = changed[v];
        kept_reshaped[renumbered[v]] = reshaped[v];
      }
    changed = std::move(kept_changed);
    reshaped = std::move(kept_reshaped);
    ++s.coarsening_rounds;
    if (o.log)
      *o.log << "optimize: coarsening round " << round + 1 << ": " << m.triangle_count() << " triangles, "
             << collapsed << " collapses\n";
    if (200 * collapsed <= m.triangle_count()) break;
  }
}

Stats optimize(TriMesh& m, const mesh::Constraints& c, const Options& o) {
  const auto start = std::chrono::steady_clock::now();
  Stats s;
  m.compact();
  s.initial = measure(m);
  const double target = o.edge_length, smallest = o.min_edge_length;
  std::vector<double> size = initial_sizes(m, target, o.pinned_size_factor, o.gradation);  // the sizing field, per vertex
  const auto edge_target = [&](int a, int b) { return 0.5 * (size[a] + size[b]); };
  double best_max = s.initial.max_amips;
  int fruitless_refinements = 0;
  long previous_changes = -1;  // none before the first iteration
  int previous_triangles = 0;

  for (; s.iterations < o.max_iterations; ++s.iterations) {
    long changes = 0;  // splits and collapses: the sizing work done in this iteration
    // Split long edges, longest first.
    {
      auto edges = edges_where(m, [&](const Edge& e) { return !(e.length <= mesh::kSplitAbove * edge_target(e.a, e.b)); });
      // Each split adds two triangles (one on the box's side): refused before the mesh grows.
      base::check_triangles(std::size_t(m.triangle_count()) + 2 * edges.size(), o.max_triangles,
                            "to meet the edge length, " + std::to_string(edges.size()) + " edges would be split");
      std::stable_sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.length > y.length; });
      for (const Edge& e : edges) {
        const int v = mesh::split_edge(m, c, e.a, e.b, o.stop_max_amips);
        if (v < 0) continue;
        // The sizing field at the middle: graded from the nearer end, up to the target. (The
        // average of the ends would keep the middle of a long edge between two small sizes small,
        // and refine a whole empty region to the size of the features around it.)
        size.push_back(std::min(target, std::min(size[e.a], size[e.b]) + 0.5 * o.gradation * e.length));
        ++s.splits, ++changes;
      }
    }
    // Collapse short edges, shortest first; an edge whose ends changed is looked at again later.
    {
      // Which end may move along the edge, by the kinds, is asked once: the kinds stay while the
      // edge's ends are not touched, and a touched edge is not looked at again. An edge neither
      // of whose ends may move is not sorted (at 16,000 curves, half the refusals), and a
      // direction the kinds refuse is not tried.
      const std::vector<Edge> edges =
          collapse_candidates(m, [&](int a, int b) { return mesh::kCollapseBelow * edge_target(a, b); }, [](int, int) { return true; });
      std::vector<char> touched(m.vertex_count(), 0);
      // The length test after the tests on tags and curves: they refuse most collapses (at 16,000
      // curves, every edge is shorter than the target, and most are on or next to a curve), and
      // cost least.
      const mesh::CollapseTest short_enough = [&](int from, int to) {
        return mesh::collapse_keeps_edges_short(m, from, to, edge_target);
      };
      const auto collapse = [&](int from, int to) {
        return mesh::collapse_edge(m, c, from, to, o.stop_max_amips, short_enough);
      };
      // An edge whose ends are untouched is still there: a collapse rewrites only the triangles of
      // the vertex that goes (those it keeps get the other end instead), so it removes or adds
      // edges only at its two ends. (collapse_edge refuses a pair that is no edge anyway.)
      for (const Edge& e : edges) {
        if (touched[e.a] || touched[e.b]) continue;
        if ((e.a_moves && collapse(e.a, e.b)) || (e.b_moves && collapse(e.b, e.a))) {
          ++s.collapses, ++changes;
          touched[e.a] = touched[e.b] = 1;
        }
      }
    }
    // Swap where it lowers the larger energy of the two triangles (an edge an earlier swap
    // removed has no triangle on either side: swap_edge refuses it).
    s.swaps += swap_pass(m);
    // Smooth, project feature vertices onto their curves (Fig. 8), round exact vertices.
    for (int v = 0; v < m.vertex_count(); ++v) {
      if (m.triangles_of(v).empty()) continue;
      if (m.has_exact(v)) {
        mesh::round_vertex(m, c, v);
      } else if (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve) {
        if (mesh::project_vertex(m, c, v, o.stop_max_amips)) ++s.projections;
      } else if (mesh::smooth_vertex(m, c, v)) {
        ++s.smooths;
      }
    }
    // The vertices of the triangles that are still bad get more smoothing rounds of their own: one
    // Newton step per pass lowers a sliver's energy by a constant factor only, and a sliver that
    // starts at AMIPS 1e4 would otherwise cost a dozen passes over the whole mesh.
    {
      std::vector<int> bad;
      for (int t = 0; t < m.triangle_slots(); ++t) {
        if (!m.alive(t)) continue;
        const auto& tri = m.triangle(t);
        if (geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])) > o.stop_max_amips)
          bad.insert(bad.end(), tri.begin(), tri.end());
      }
      std::sort(bad.begin(), bad.end());
      bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
      std::erase_if(bad, [&](int v) {
        return m.has_exact(v) || (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve);
      });
      for (int round = 0; round < o.extra_smoothing_rounds; ++round) {
        int moved = 0;
        for (int v : bad) moved += mesh::smooth_vertex(m, c, v);
        s.smooths += moved;
        if (moved == 0) break;
      }
    }
    // Secondary chords beside a path of feature edges, in triangles that stay bad: released. The
    // same sweep measures the pass: releasing moves no vertex, and compacting below keeps the
    // triangles' order, so the energies and their sum are measure's after it.
    double max_e = 0, sum_e = 0;
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t)) continue;
      const auto tri = m.triangle(t);
      const double e = geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2]));
      max_e = std::max(max_e, e);
      sum_e += e;
      if (e <= o.stop_max_amips) continue;
      for (int i = 0; i < 3; ++i) s.released += mesh::release_secondary_edge(m, c, tri[i], tri[(i + 1) % 3]);
    }
    // Compact: removed elements do not keep their memory.
    const auto remap = m.compact();
    std::vector<double> resized(m.vertex_count(), target);
    for (std::size_t v = 0; v < remap.size(); ++v)
      if (remap[v] >= 0) resized[remap[v]] = size[v];
    size = std::move(resized);

    Quality q;
    q.vertices = m.vertex_count();
    q.triangles = m.triangle_count();
    q.max_amips = max_e;
    q.mean_amips = q.triangles ? sum_e / q.triangles : 0;
    // The smallest angle matters to the stop rule only while the energy is above the bound.
    if (o.log || q.max_amips > o.stop_max_amips) q.min_angle_deg = min_angle_deg(m);
    if (o.log)
      *o.log << "optimize: iteration " << s.iterations + 1 << ": " << q.triangles << " triangles, min angle "
             << q.min_angle_deg << ", max AMIPS " << q.max_amips << ", " << changes << " splits and collapses" << "\n";
    if (o.on_iteration) o.on_iteration(s.iterations + 1, q.triangles, q.max_amips);
    const bool good = q.min_angle_deg >= o.stop_min_angle_deg || q.max_amips <= o.stop_max_amips;
    // The stop rule of §4.1 applies once the sizes are met: little is left to split or collapse
    // (2 % of the triangles), or what is left no longer shrinks by a fifth per pass (the churn
    // that smoothing and swapping cause, not sizing work). A mesh that grew by more than a
    // quarter in the pass is still refining toward the target, not churning: with a small target
    // every pass splits about twice as many edges as the one before.
    const bool churn = previous_changes >= 0 && 5 * changes > 4 * previous_changes &&
                       4L * (q.triangles - previous_triangles) <= previous_triangles;
    const bool sizes_met = 50 * changes <= q.triangles || churn;
    previous_changes = changes;
    previous_triangles = q.triangles;
    if (good && sizes_met) {
      s.stop_reason = "quality";
      ++s.iterations;
      break;
    }
    if (q.max_amips < best_max * (1 - 1e-2)) {
      best_max = q.max_amips;
      fruitless_refinements = 0;
    } else if (!good) {
      // Adaptive sizing (TetWild): refine around the worst triangles on the first pass that does
      // not lower the worst energy, and give up when refining twice in a row brought nothing.
      if (++fruitless_refinements > 2) {
        s.stop_reason = "no improvement";
        ++s.iterations;
        break;
      }
      for (int t = 0; t < m.triangle_slots(); ++t) {
        const auto& tri = m.triangle(t);
        if (geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])) <= o.stop_max_amips) continue;
        for (int v : tri) size[v] = std::max(smallest, 0.5 * size[v]);
      }
      grade(m, size, o.gradation);
    }
  }
  if (s.stop_reason.empty()) s.stop_reason = "iteration limit";

  // Vertices that kept an exact position get one more chance, with the mesh as it is now; one
  // that still cannot be rounded (it rounds onto a neighbour: features closer than a double can
  // tell) is collapsed into its nearest neighbour that takes it, whatever the energy: a mesh with
  // a vertex that has no double position cannot be written, and the curve stage's operations
  // improve what the collapse leaves. When no neighbour takes it, what stops it is a neighbour
  // flat with it to round-off (a free vertex lying on a secondary line through it, say): its free
  // and secondary neighbours, nearest first, are collapsed into it, whatever the energy, until it
  // rounds or goes.
  const auto by_distance_to = [&](int v) {
    std::vector<int> near = m.neighbours(v);
    std::stable_sort(near.begin(), near.end(), [&](int x, int y) {
      return (m.point(x) - m.point(v)).squaredNorm() < (m.point(y) - m.point(v)).squaredNorm();
    });
    return near;
  };
  bool collapsed = false;
  const auto settle = [&](int v) {
    if (mesh::round_vertex(m, c, v)) return true;
    for (int w : by_distance_to(v))
      if (mesh::collapse_edge(m, c, v, w, std::numeric_limits<double>::infinity())) {
        ++s.collapses;
        collapsed = true;
        return true;
      }
    return false;
  };
  for (int v = 0; v < m.vertex_count(); ++v) {
    if (!m.has_exact(v) || m.triangles_of(v).empty() || settle(v)) continue;
    for (int w : by_distance_to(v)) {
      const mesh::VertexKind k = m.tag(w).kind;
      if (k != mesh::VertexKind::free && k != mesh::VertexKind::secondary) continue;
      if (!mesh::collapse_edge(m, c, w, v, std::numeric_limits<double>::infinity())) continue;
      ++s.collapses;
      collapsed = true;
      if (settle(v)) break;
    }
  }
  if (collapsed) {
    // What those collapses flattened (a vertex moved onto a secondary line with others on it to
    // round-off), released and swapped as in the iterations.
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t)) continue;
      const auto tri = m.triangle(t);
      if (geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])) <= o.stop_max_amips) continue;
      for (int i = 0; i < 3; ++i) s.released += mesh::release_secondary_edge(m, c, tri[i], tri[(i + 1) % 3]);
    }
    s.swaps += swap_pass(m);
    m.compact();  // the collapsed vertices (and their exact positions) go
  }
  if (o.coarsen) coarsen(m, c, o, s);
  s.exact_left = m.exact_vertex_count();
  for (int v = 0; v < m.vertex_count(); ++v)
    if (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve) ++s.unprojected;
  s.final = measure(m);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace curvemesh::optimize
