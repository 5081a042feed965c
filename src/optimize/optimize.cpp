#include "optimize/optimize.hpp"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <queue>
#include <string>

#include "base/limits.hpp"
#include "base/parallel.hpp"
#include "geometry/amips.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/curved_element.hpp"
#include "mesh/operations.hpp"
#include "mesh/schedule.hpp"

namespace curvemesh::optimize {

using geometry::Vec2;
using mesh::TriMesh;

namespace {

struct Edge {
  int a, b;  // a < b
  double length;
  // For collapses: whether a may move onto b, whether b may move onto a (by the kinds).
  bool a_moves = false, b_moves = false;
  int order = 0;  // its place in edges_where's list: what breaks ties when sorting
};

// Triangles per part of the sweeps that collect edges: a count of the mesh's own, so that the
// parts, and the list, do not depend on the number of threads.
constexpr int kSweepPart = 4096;

// Every edge once, in triangle order (deterministic): an interior edge from the triangle in which
// it runs from its lower to its higher vertex, a hull edge from its only triangle; those that
// `keep` keeps. Whether an edge running downwards has a reverse (is inside) is asked only where
// both ends may lie on the hull: on the box, the only hull the optimizer's meshes have. Euler's
// formula checks that no hull edge was missed (a triangulated disk has V - E + T = 1); if one was
// (the mesh is not the box's, say), every downward edge is asked. Walking a star per edge was a
// cache miss or more each: a sixth of the optimization's time. The filter runs as the edges are
// found: a pass that wants few of them does not write them all first. The triangles are swept in
// parts side by side (keep must only read), the parts' lists joined in triangle order.
template <class Keep>
std::vector<Edge> edges_where(const TriMesh& m, const Keep& keep) {  // keep(Edge&) may fill it in
  const auto has_directed = [&](int a, int b) {
    for (int t : m.triangles_of(a)) {
      const auto& tri = m.triangle(t);
      if ((tri[0] == a && tri[1] == b) || (tri[1] == a && tri[2] == b) || (tri[2] == a && tri[0] == b))
        return true;
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
    const std::size_t parts = (static_cast<std::size_t>(m.triangle_slots()) + kSweepPart - 1) / kSweepPart;
    std::vector<std::vector<Edge>> found(parts);
    std::vector<long> counts(parts, 0);
    base::for_each_part(
        parts,
        [&](std::size_t part) {
          const int end = std::min(m.triangle_slots(), static_cast<int>((part + 1) * kSweepPart));
          for (int t = static_cast<int>(part * kSweepPart); t < end; ++t) {
            if (!m.alive(t)) continue;
            const auto& tri = m.triangle(t);
            for (int i = 0; i < 3; ++i) {
              const int a = tri[i], b = tri[(i + 1) % 3];
              if (a < b || ((all_downward || (on_box[a] && on_box[b])) && !has_directed(b, a))) {
                ++counts[part];
                Edge e{std::min(a, b), std::max(a, b), (m.point(a) - m.point(b)).norm()};
                if (keep(e)) found[part].push_back(e);
              }
            }
          }
        },
        1);
    edges.clear();
    for (const auto& f : found) edges.insert(edges.end(), f.begin(), f.end());
    for (std::size_t i = 0; i < edges.size(); ++i) edges[i].order = static_cast<int>(i);
    return std::accumulate(counts.begin(), counts.end(), 0L);
  };
  if (used_vertices - collect(false) + m.triangle_count() != 1) collect(true);
  return edges;
}

// Sorts edges_where's list by length, shortest first (`longest_first`: longest), ties in the
// list's order: a stable sort's result, sorted side by side.
void sort_by_length(std::vector<Edge>& edges, bool longest_first) {
  tbb::parallel_sort(edges.begin(), edges.end(), [longest_first](const Edge& x, const Edge& y) {
    if (x.length != y.length) return longest_first ? x.length > y.length : x.length < y.length;
    return x.order < y.order;
  });
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
  sort_by_length(edges, false);
  return edges;
}

// Collapses e, a onto b first (as the kinds allow), unless a collapse of this pass touched one of
// its ends; a collapse kept touches both.
template <class Collapse>
bool collapse_if_untouched(const Edge& e, std::vector<char>& touched, const Collapse& collapse) {
  if (touched[e.a] || touched[e.b]) return false;
  if (!(e.a_moves && collapse(e.a, e.b)) && !(e.b_moves && collapse(e.b, e.a))) return false;
  touched[e.a] = touched[e.b] = 1;
  return true;
}

// How many vertices a part of the mesh has at most when local operations run part by part
// (mesh::spatial_parts): a count of the mesh's own, so that the parts, and the result, do not
// depend on the number of threads. Parts of this size leave about a tenth of the operations on
// the first cut's borders, and one in fifty to seventy on the borders of both cuts, done one
// after another (old_truck_indana_model__01, mr_lakshman_poonyth_, hummer_01).
constexpr int kPartSize = 2048;

// The edges a swap pass looks at: every inner edge once (as its lower end sees it first, so hull
// edges, which never swap, come only the wrong way round and are left out), in triangle order, each
// with the triangle it came from as swap_edge's hint.
struct SwapCandidate {
  int a, b, t;
};
std::vector<SwapCandidate> swap_candidates(const TriMesh& m) {
  std::vector<SwapCandidate> candidates;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    const auto tri = m.triangle(t);
    if (tri[0] < 0) continue;
    for (int i = 0; i < 3; ++i)
      if (tri[i] < tri[(i + 1) % 3]) candidates.push_back({tri[i], tri[(i + 1) % 3], t});
  }
  return candidates;
}

// One swap pass over the whole mesh, one swap after another.
int swap_pass(TriMesh& m) {
  int swaps = 0;
  for (const SwapCandidate& e : swap_candidates(m)) swaps += mesh::swap_edge(m, e.a, e.b, 0, e.t);
  return swaps;
}

// The iterations' swap pass, part by part (mesh::for_each_in_parts): a swap of (a, b) reads and
// rewrites its two triangles and reads the stars of their corners, all in the stars of a and b.
int swap_pass_in_parts(TriMesh& m, mesh::Parts& parts) {
  const std::vector<SwapCandidate> candidates = swap_candidates(m);
  std::vector<char> swapped(candidates.size(), 0);
  mesh::for_each_in_parts(
      m, parts, candidates.size(),
      [&](std::size_t i) {
        return std::pair{candidates[i].a, candidates[i].b};
      },
      [&](std::size_t i) {
        swapped[i] = mesh::swap_edge(m, candidates[i].a, candidates[i].b, 0, candidates[i].t);
      });
  return static_cast<int>(std::count(swapped.begin(), swapped.end(), 1));
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
    const bool fixed_pair =
        m.tag(e.a).kind == mesh::VertexKind::fixed && m.tag(e.b).kind == mesh::VertexKind::fixed;
    if (curve_edge || fixed_pair) {
      size[e.a] = std::min(size[e.a], factor * e.length);
      size[e.b] = std::min(size[e.b], factor * e.length);
    }
  }
  grade(m, size, gradation);
  return size;
}

// The smallest angle of the triangles, in degrees (0 when there is none).
// `of(t)` for every alive triangle t (0 for a dead slot), computed side by side: what a sweep
// then adds up, in triangle order as before.
template <class Of>
std::vector<double> per_triangle(const TriMesh& m, const Of& of) {
  std::vector<double> value(m.triangle_slots(), 0.0);
  base::for_each_part(
      value.size(),
      [&](std::size_t t) {
        if (!m.alive(static_cast<int>(t))) return;
        const auto& tri = m.triangle(static_cast<int>(t));
        value[t] = of(m.point(tri[0]), m.point(tri[1]), m.point(tri[2]));
      },
      1024);
  return value;
}

std::vector<double> triangle_energies(const TriMesh& m) {
  return per_triangle(m,
                      [](const Vec2& a, const Vec2& b, const Vec2& c) { return geometry::amips(a, b, c); });
}

// The smallest angle of the triangles, in degrees (0 when there is none).
double min_angle_deg(const TriMesh& m) {
  const std::vector<double> angles = per_triangle(
      m, [](const Vec2& a, const Vec2& b, const Vec2& c) { return geometry::min_angle(a, b, c); });
  double min_angle = std::numbers::pi;
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t)) min_angle = std::min(min_angle, angles[t]);
  return m.triangle_count() ? min_angle * 180 / std::numbers::pi : 0;
}

// The vertices with a star that `wanted` wants, ascending.
template <class Wanted>
std::vector<int> vertices_where(const TriMesh& m, const Wanted& wanted) {
  std::vector<int> vertices;
  for (int v = 0; v < m.vertex_count(); ++v)
    if (!m.triangles_of(v).empty() && wanted(v)) vertices.push_back(v);
  return vertices;
}

}  // namespace

Quality measure(const TriMesh& m) {
  return measure(m, true);
}

Quality measure(const TriMesh& m, bool mean_edge_length) {
  Quality q;
  q.vertices = m.vertex_count();
  q.triangles = m.triangle_count();
  const std::vector<double> energies = triangle_energies(m);
  double max_e = 0, sum_e = 0;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    max_e = std::max(max_e, energies[t]);
    sum_e += energies[t];
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

// The energy triangle t would have once curved, as the curve stage first makes it
// (mesh::curved_element), with the best of the stage's three centres. 0 for a triangle the curve
// stage does not bend (mesh::followed_edge): the linear energy judges those.
double curved_energy(const TriMesh& m, const mesh::Constraints& c, int t) {
  const int followed = mesh::followed_edge(m, m.triangle(t));
  if (followed < 0) return 0;
  geometry::P3Nodes p = mesh::curved_element(m, c, t, followed);
  double best = std::numeric_limits<double>::infinity();
  for (const Vec2& centre : geometry::p3_centre_candidates(p)) {
    p[9] = centre;
    best = std::min(best, geometry::p3_max_amips(p, best));
  }
  return best;
}

}  // namespace

namespace {

// When each vertex's star last changed, counted in passes, so that the coarsening tries again
// only what changed: an operation's outcome depends on the stars it reads alone, so one tried on
// stars that have not changed since is refused again. `changed[v]`: one of v's triangles came or
// went, or a corner of one moved (a rollback counts: it may reorder the incidence lists, which the
// energies are summed in); `reshaped[v]`: one of its triangles came or went. A change is stamped
// with the pass it happened in, and stamps are only ever compared with when a pass began: parts
// of the mesh stamp their own vertices side by side, and the stamps do not depend on the order.
struct StarClock {
  long now = 1;
  std::vector<long> changed, reshaped;
  explicit StarClock(int vertices) : changed(vertices, 0), reshaped(vertices, 0) {}

  long begin_pass() { return ++now; }
  // v's star and its neighbours' stars changed in this pass.
  void star_changed(const TriMesh& m, int v, bool topology) {
    changed[v] = now;
    if (topology) reshaped[v] = now;
    for (int t : m.triangles_of(v))
      for (int w : m.triangle(t)) {
        changed[w] = now;
        if (topology) reshaped[w] = now;
      }
  }
  // After a compaction: the stamps follow the vertices' new numbers.
  void renumber(const std::vector<int>& remap, int vertices) {
    std::vector<long> kept_changed(vertices, 0), kept_reshaped(vertices, 0);
    for (std::size_t v = 0; v < remap.size(); ++v)
      if (remap[v] >= 0) kept_changed[remap[v]] = changed[v], kept_reshaped[remap[v]] = reshaped[v];
    changed = std::move(kept_changed);
    reshaped = std::move(kept_reshaped);
  }
};

// The curved pipeline's test of a collapse or swap of edge (a, b): `operation` is done under the
// journal and kept when `worst_after()` (the curved_energy of what it made) is at most the curved
// stop energy; else it is taken back (the rollback counts as a change of both ends' stars) and
// done again only if `worst_before()` (what it replaced, read after the rollback) was as bad. A
// coarser mesh beside a curve leaves the curved edge's bulge less room, and a swap can leave the
// bulge against the opposite corner: the curve stage cannot always undo either. (Judging the
// triangles along curves by their curved form alone, letting their linear energy rise to the
// curved stop energy, gives coarser meshes; but the curve stage does more than curved_energy
// foresees — splits triangles with two curved edges, projects late vertices, takes the first
// certified centre — and more meshes then end above the stop energy.)
template <class Operation, class After, class Before>
bool curved_test(TriMesh& m, const Options& o, StarClock& clock, int a, int b, const Operation& operation,
                 const After& worst_after, const Before& worst_before) {
  m.open_journal(a);
  if (!operation()) {
    m.commit(a);
    return false;
  }
  const double after = worst_after();
  if (after <= o.curved_stop_amips) {
    m.commit(a);
    return true;
  }
  m.rollback(a);
  clock.star_changed(m, a, true);
  clock.star_changed(m, b, true);
  return after <= worst_before() && operation();
}

// The worst of v's triangles once curved (curved_energy).
double star_curved(const TriMesh& m, const mesh::Constraints& c, int v) {
  double worst = 0;
  for (int t : m.triangles_of(v)) worst = std::max(worst, curved_energy(m, c, t));
  return worst;
}

// One round's collapses: every edge shorter than the target with an end whose star changed since
// the last round began, shortest first, each vertex touched once; every new triangle at most
// max(stop energy, the worst it replaces), as in the loop, and no new edge longer than 5/3 of the
// target; in the curved pipeline, curved_test too. Part by part, each part under a journal of its
// own (mesh::for_each_in_parts_journaled): a collapse reads the stars of its two ends and rewrites
// that of the one that goes, and stamps the stars of both. Returns the number kept.
long coarsening_collapses(TriMesh& m, const mesh::Constraints& c, const Options& o, mesh::Parts& parts,
                          StarClock& clock, long since) {
  const double target = o.edge_length;
  const mesh::CollapseTest short_enough = [&](int from, int to) {
    return mesh::collapse_keeps_edges_short(m, from, to,
                                            [&](int, int) { return mesh::kCoarseningScale * target; });
  };
  const auto collapse = [&](int from, int to) {
    const auto operation = [&] {
      return mesh::collapse_edge(m, c, from, to, o.stop_max_amips, short_enough);
    };
    if (!o.curved) return operation();
    return curved_test(
        m, o, clock, from, to, operation, [&] { return star_curved(m, c, to); },
        [&] { return std::max(star_curved(m, c, from), star_curved(m, c, to)); });
  };
  const std::vector<Edge> edges = collapse_candidates(
      m, [&](int, int) { return target; },
      [&](int a, int b) { return clock.changed[a] >= since || clock.changed[b] >= since; });
  std::vector<char> touched(m.vertex_count(), 0), kept(edges.size(), 0);
  mesh::for_each_in_parts_journaled(
      m, parts, edges.size(),
      [&](std::size_t i) {
        return std::pair{edges[i].a, edges[i].b};
      },
      [&](std::size_t i) {
        const Edge& e = edges[i];
        if (!collapse_if_untouched(e, touched, collapse)) return;
        kept[i] = 1;
        clock.star_changed(m, e.a, true);  // the one that stayed has the merged star; the other has none
        clock.star_changed(m, e.b, true);
      });
  return std::count(kept.begin(), kept.end(), 1);
}

// One round's swaps where they lower the larger energy of the two triangles; in the curved
// pipeline, curved_test too (the two triangles it makes at most the curved stop energy once
// curved, or no worse than the two it replaced). A swap of (a, b) reads its two triangles and the
// stars of the two opposite corners (is the other diagonal an edge already?): it is tried again
// when a corner of either triangle has a changed star, that is when a and b are both corners of
// such triangles (`near`). `since` is 0 on the first round: every edge is tried. Part by part,
// each part under a journal of its own.
int coarsening_swaps(TriMesh& m, const mesh::Constraints& c, const Options& o, mesh::Parts& parts,
                     StarClock& clock, long since) {
  std::vector<char> near(m.vertex_count(), since == 0);
  // A swap in a part marks the corners of the stars of its quad's corners, some of them on the
  // part's border and so in other parts' stars too: those are marked side by side (all with 1),
  // and read only by the operations on the borders, afterwards.
  const auto mark_near = [&](int v) {
    for (int t : m.triangles_of(v))
      for (int w : m.triangle(t)) std::atomic_ref<char>(near[w]).store(1, std::memory_order_relaxed);
  };
  if (since > 0)
    for (int v = 0; v < m.vertex_count(); ++v)
      if (clock.changed[v] >= since) mark_near(v);
  // The two triangles a swap rewrites keep their slots: after it they are the new diagonal's,
  // after a rollback the old ones again, so both energies are read from the slots swap_edge names
  // (no walk round a star before each swap tried).
  const auto swap = [&](int a, int b, int t) {
    std::array<int, 2> slots{-1, -1};
    const auto operation = [&] { return mesh::swap_edge(m, a, b, 0, t, &slots); };
    if (!o.curved) return operation();
    const auto worst_in_slots = [&] {
      return std::max(curved_energy(m, c, slots[0]), curved_energy(m, c, slots[1]));
    };
    return curved_test(m, o, clock, a, b, operation, worst_in_slots, worst_in_slots);
  };
  const std::vector<SwapCandidate> candidates = swap_candidates(m);
  std::vector<char> swapped(candidates.size(), 0);
  mesh::for_each_in_parts_journaled(
      m, parts, candidates.size(),
      [&](std::size_t i) {
        return std::pair{candidates[i].a, candidates[i].b};
      },
      [&](std::size_t i) {
        const auto [a, b, t] = candidates[i];
        if (!near[a] || !near[b] || !swap(a, b, t)) return;
        swapped[i] = 1;
        // The quad's corners are among the corners of a's and b's triangles now.
        for (int end : {a, b})
          for (int tri : m.triangles_of(end))
            for (int v : m.triangle(tri)) {
              clock.changed[v] = clock.reshaped[v] = clock.now;
              mark_near(v);
            }
      });
  return static_cast<int>(std::count(swapped.begin(), swapped.end(), 1));
}

// Smoothing where this round's collapses and swaps changed a star (the loop left the rest
// smoothed), part by part; returns the number of moves.
int smooth_reshaped(TriMesh& m, const mesh::Constraints& c, mesh::Parts& parts, StarClock& clock,
                    long round_start) {
  const std::vector<int> vertices = vertices_where(m, [&](int v) {
    return clock.reshaped[v] >= round_start && !m.has_exact(v) &&
           !(m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve);
  });
  std::vector<char> moved(m.vertex_count(), 0);
  mesh::for_each_vertex_in_parts(m, parts, vertices, [&](int v) { moved[v] = mesh::smooth_vertex(m, c, v); });
  int moves = 0;
  for (int v : vertices)
    if (moved[v]) {
      ++moves;
      clock.star_changed(m, v, false);
    }
  return moves;
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
// 0.93). After the first round, collapses and swaps are tried only where something changed since
// that pass last ran (StarClock).
void coarsen(TriMesh& m, const mesh::Constraints& c, const Options& o, Stats& s) {
  s.before_coarsening = m.triangle_count();
  StarClock clock(m.vertex_count());
  long collapse_start = 0, swap_start = 0;  // when each pass last began
  for (int round = 0; round < o.coarsening_rounds; ++round) {
    const long round_start = clock.begin_pass();
    // The collapses, swaps and smoothing part by part: the parts stay while no vertex is added.
    mesh::Parts parts = mesh::spatial_parts(m, kPartSize);
    const long collapsed = coarsening_collapses(m, c, o, parts, clock, collapse_start);
    collapse_start = round_start;
    s.coarsening_collapses += collapsed;
    const long since_swap = swap_start;
    swap_start = clock.begin_pass();
    s.swaps += coarsening_swaps(m, c, o, parts, clock, since_swap);
    s.smooths += smooth_reshaped(m, c, parts, clock, round_start);
    const std::vector<int> renumbered = m.compact();
    clock.renumber(renumbered, m.vertex_count());
    ++s.coarsening_rounds;
    if (o.log)
      *o.log << "optimize: coarsening round " << round + 1 << ": " << m.triangle_count() << " triangles, "
             << collapsed << " collapses\n";
    if (200 * collapsed <= m.triangle_count()) break;
  }
}

namespace {

// The sizing field (TetWild's adaptive sizing): the target edge length per vertex, small near
// features and graded away from them, halved around triangles that stay bad.
struct Sizing {
  std::vector<double> size;  // per vertex
  double edge(int a, int b) const { return 0.5 * (size[a] + size[b]); }
};

// Splits the edges longer than 4/3 of their target, longest first; returns the number of splits.
long split_long_edges(TriMesh& m, const mesh::Constraints& c, const Options& o, Sizing& sizing, Stats& s) {
  auto edges =
      edges_where(m, [&](const Edge& e) { return !(e.length <= mesh::kSplitAbove * sizing.edge(e.a, e.b)); });
  // Each split adds two triangles (one on the box's side): refused before the mesh grows.
  base::check_triangles(std::size_t(m.triangle_count()) + 2 * edges.size(), o.max_triangles,
                        "to meet the edge length, " + std::to_string(edges.size()) + " edges would be split");
  sort_by_length(edges, true);
  long splits = 0;
  for (const Edge& e : edges) {
    const int v = mesh::split_edge(m, c, e.a, e.b, o.stop_max_amips);
    if (v < 0) continue;
    // The sizing field at the middle: graded from the nearer end, up to the target. (The average
    // of the ends would keep the middle of a long edge between two small sizes small, and refine
    // a whole empty region to the size of the features around it.)
    sizing.size.push_back(
        std::min(o.edge_length, std::min(sizing.size[e.a], sizing.size[e.b]) + 0.5 * o.gradation * e.length));
    ++splits;
  }
  s.splits += splits;
  return splits;
}

// Collapses the edges shorter than 4/5 of their target, shortest first; an edge whose ends
// changed is looked at again in the next iteration. Returns the number of collapses.
long collapse_short_edges(TriMesh& m, const mesh::Constraints& c, const Options& o, const Sizing& sizing,
                          mesh::Parts& parts, Stats& s) {
  const auto edge_target = [&](int a, int b) { return sizing.edge(a, b); };
  // Which end may move along the edge, by the kinds, is asked once: the kinds stay while the
  // edge's ends are not touched, and a touched edge is not looked at again. An edge neither of
  // whose ends may move is not sorted (at 16,000 curves, half the refusals), and a direction the
  // kinds refuse is not tried.
  const std::vector<Edge> edges = collapse_candidates(
      m, [&](int a, int b) { return mesh::kCollapseBelow * edge_target(a, b); },
      [](int, int) { return true; });
  // The length test after the tests on tags and curves: they refuse most collapses (at 16,000
  // curves, every edge is shorter than the target, and most are on or next to a curve), and cost
  // least.
  const mesh::CollapseTest short_enough = [&](int from, int to) {
    return mesh::collapse_keeps_edges_short(m, from, to, edge_target);
  };
  // Part by part (mesh::for_each_in_parts): a collapse reads the stars of its two ends and
  // rewrites that of the one that goes; each vertex is touched once.
  std::vector<char> touched(m.vertex_count(), 0), kept(edges.size(), 0);
  mesh::for_each_in_parts(
      m, parts, edges.size(),
      [&](std::size_t i) {
        return std::pair{edges[i].a, edges[i].b};
      },
      [&](std::size_t i) {
        kept[i] = collapse_if_untouched(edges[i], touched, [&](int from, int to) {
          return mesh::collapse_edge(m, c, from, to, o.stop_max_amips, short_enough);
        });
      });
  const long collapses = std::count(kept.begin(), kept.end(), 1);
  s.collapses += collapses;
  return collapses;
}

// Every vertex smoothed, a feature vertex off its curve projected onto it (Fig. 8), an exact
// vertex rounded to doubles where that inverts nothing; part by part (each of these moves v
// alone, and retags v's own edges).
void smooth_all(TriMesh& m, const mesh::Constraints& c, const Options& o, mesh::Parts& parts,
                Stats& s) {
  enum : char { none, smoothed, projected };
  std::vector<char> what(m.vertex_count(), none);
  const auto move = [&](int v) {
    if (m.has_exact(v))
      mesh::round_vertex(m, c, v);
    else if (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve)
      what[v] = mesh::project_vertex(m, c, v, o.stop_max_amips) ? projected : none;
    else
      what[v] = mesh::smooth_vertex(m, c, v) ? smoothed : none;
  };
  mesh::for_each_vertex_in_parts(m, parts, vertices_where(m, [](int) { return true; }), move);
  s.smooths += std::count(what.begin(), what.end(), smoothed);
  s.projections += std::count(what.begin(), what.end(), projected);
}

// The vertices of the triangles that are still bad get more smoothing rounds of their own: one
// Newton step per pass lowers a sliver's energy by a constant factor only, and a sliver that
// starts at AMIPS 1e4 would otherwise cost a dozen passes over the whole mesh.
void smooth_bad_again(TriMesh& m, const mesh::Constraints& c, const Options& o, mesh::Parts& parts,
                      Stats& s) {
  std::vector<char> bad(m.vertex_count(), 0);
  const std::vector<double> energies = triangle_energies(m);
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t) && energies[t] > o.stop_max_amips)
      for (int v : m.triangle(t)) bad[v] = 1;
  const std::vector<int> vertices = vertices_where(m, [&](int v) {
    return bad[v] && !m.has_exact(v) && !(m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve);
  });
  for (int round = 0; round < o.extra_smoothing_rounds; ++round) {
    std::vector<char> moved(m.vertex_count(), 0);
    mesh::for_each_vertex_in_parts(m, parts, vertices, [&](int v) { moved[v] = mesh::smooth_vertex(m, c, v); });
    const long count = std::count(moved.begin(), moved.end(), 1);
    s.smooths += count;
    if (count == 0) break;
  }
}

// Secondary chords beside a path of feature edges, in triangles that stay bad: released. The same
// sweep measures the pass (the largest and the summed energy): releasing moves no vertex, and the
// compaction that follows keeps the triangles' order, so these are measure's after it.
std::pair<double, double> release_and_measure(TriMesh& m, const mesh::Constraints& c, const Options& o,
                                              Stats& s) {
  const std::vector<double> energies = triangle_energies(m);  // releasing moves no vertex
  double max_e = 0, sum_e = 0;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto tri = m.triangle(t);
    const double e = energies[t];
    max_e = std::max(max_e, e);
    sum_e += e;
    if (e <= o.stop_max_amips) continue;
    for (int i = 0; i < 3; ++i) s.released += mesh::release_secondary_edge(m, c, tri[i], tri[(i + 1) % 3]);
  }
  return {max_e, sum_e};
}

// Removed elements do not keep their memory; the sizing field follows the renumbering.
void compact(TriMesh& m, Sizing& sizing, double target) {
  const auto remap = m.compact();
  std::vector<double> resized(m.vertex_count(), target);
  for (std::size_t v = 0; v < remap.size(); ++v)
    if (remap[v] >= 0) resized[remap[v]] = sizing.size[v];
  sizing.size = std::move(resized);
}

// The stop rule of §4.1, and when to refine the sizing field instead (TetWild's adaptive sizing).
class StopRule {
 public:
  enum class Verdict { go_on, quality, no_improvement, refine };
  explicit StopRule(double initial_max) : best_max_(initial_max) {}

  Verdict judge(const Quality& q, long changes, const Options& o) {
    const bool good = q.min_angle_deg >= o.stop_min_angle_deg || q.max_amips <= o.stop_max_amips;
    // The rule applies once the sizes are met: little is left to split or collapse (2 % of the
    // triangles), or what is left no longer shrinks by a fifth per pass (the churn that smoothing
    // and swapping cause, not sizing work). A mesh that grew by more than a quarter in the pass is
    // still refining toward the target, not churning: with a small target every pass splits about
    // twice as many edges as the one before.
    const bool churn = previous_changes_ >= 0 && 5 * changes > 4 * previous_changes_ &&
                       4L * (q.triangles - previous_triangles_) <= previous_triangles_;
    const bool sizes_met = 50 * changes <= q.triangles || churn;
    previous_changes_ = changes;
    previous_triangles_ = q.triangles;
    if (good && sizes_met) return Verdict::quality;
    if (q.max_amips < best_max_ * (1 - 1e-2)) {
      best_max_ = q.max_amips;
      fruitless_refinements_ = 0;
      return Verdict::go_on;
    }
    if (good) return Verdict::go_on;
    // Refine around the worst triangles on the first pass that does not lower the worst energy;
    // give up when refining twice in a row brought nothing.
    return ++fruitless_refinements_ > 2 ? Verdict::no_improvement : Verdict::refine;
  }

 private:
  double best_max_;
  int fruitless_refinements_ = 0;
  long previous_changes_ = -1;  // none before the first iteration
  int previous_triangles_ = 0;
};

// Halves the target size at the corners of the triangles above the stop energy, then grades.
void refine_around_bad(const TriMesh& m, const Options& o, Sizing& sizing) {
  const std::vector<double> energies = triangle_energies(m);
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t) || energies[t] <= o.stop_max_amips) continue;
    for (int v : m.triangle(t)) sizing.size[v] = std::max(o.min_edge_length, 0.5 * sizing.size[v]);
  }
  grade(m, sizing.size, o.gradation);
}

// The pass's quality from release_and_measure's energies; the smallest angle matters to the stop
// rule only while the energy is above the bound.
Quality pass_quality(const TriMesh& m, const Options& o, std::pair<double, double> energies) {
  Quality q;
  q.vertices = m.vertex_count();
  q.triangles = m.triangle_count();
  q.max_amips = energies.first;
  q.mean_amips = q.triangles ? energies.second / q.triangles : 0;
  if (o.log || q.max_amips > o.stop_max_amips) q.min_angle_deg = min_angle_deg(m);
  return q;
}

void report_pass(const Options& o, int iteration, const Quality& q, long changes) {
  if (o.log)
    *o.log << "optimize: iteration " << iteration << ": " << q.triangles << " triangles, min angle "
           << q.min_angle_deg << ", max AMIPS " << q.max_amips << ", " << changes << " splits and collapses"
           << "\n";
  if (o.on_iteration) o.on_iteration(iteration, q.triangles, q.max_amips);
}

// Vertices that kept an exact position get one more chance, with the mesh as it is now; one that
// still cannot be rounded (it rounds onto a neighbour: features closer than a double can tell) is
// collapsed into its nearest neighbour that takes it, whatever the energy: a mesh with a vertex
// that has no double position cannot be written, and the curve stage's operations improve what the
// collapse leaves. When no neighbour takes it, what stops it is a neighbour flat with it to
// round-off (a free vertex lying on a secondary line through it, say): its free and secondary
// neighbours, nearest first, are collapsed into it, whatever the energy, until it rounds or goes.
// Returns whether anything was collapsed.
bool settle_exact_vertices(TriMesh& m, const mesh::Constraints& c, Stats& s) {
  const auto by_distance_to = [&](int v) {
    std::vector<int> near = m.neighbours(v);
    std::stable_sort(near.begin(), near.end(), [&](int x, int y) {
      return (m.point(x) - m.point(v)).squaredNorm() < (m.point(y) - m.point(v)).squaredNorm();
    });
    return near;
  };
  const double any = std::numeric_limits<double>::infinity();
  bool collapsed = false;
  const auto settle = [&](int v) {
    if (mesh::round_vertex(m, c, v)) return true;
    for (int w : by_distance_to(v))
      if (mesh::collapse_edge(m, c, v, w, any)) {
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
      if (!mesh::collapse_edge(m, c, w, v, any)) continue;
      ++s.collapses;
      collapsed = true;
      if (settle(v)) break;
    }
  }
  return collapsed;
}

// What settle_exact_vertices' collapses flattened (a vertex moved onto a secondary line with
// others on it to round-off), released and swapped as in the iterations; the collapsed vertices
// (and their exact positions) go.
void repair_after_settling(TriMesh& m, const mesh::Constraints& c, const Options& o, Stats& s) {
  release_and_measure(m, c, o, s);  // the energies are not needed here
  s.swaps += swap_pass(m);
  m.compact();
}

}  // namespace

// §4.1: TetWild's loop of splits, collapses, swaps and smoothing under the sizing field, until the
// stop rule holds; then the vertices left exact are settled and the mesh coarsened.
Stats optimize(TriMesh& m, const mesh::Constraints& c, const Options& o) {
  const auto start = std::chrono::steady_clock::now();
  Stats s;
  m.compact();
  s.initial = measure(m);
  Sizing sizing{initial_sizes(m, o.edge_length, o.pinned_size_factor, o.gradation)};
  StopRule stop(s.initial.max_amips);
  for (; s.iterations < o.max_iterations; ++s.iterations) {
    long changes = split_long_edges(m, c, o, sizing, s);  // the sizing work done in this iteration
    // The collapses, swaps and smoothing part by part: the parts stay while no vertex is added.
    mesh::Parts parts = mesh::spatial_parts(m, kPartSize);
    changes += collapse_short_edges(m, c, o, sizing, parts, s);
    // Swaps where they lower the larger energy of the two triangles.
    s.swaps += swap_pass_in_parts(m, parts);
    smooth_all(m, c, o, parts, s);
    smooth_bad_again(m, c, o, parts, s);
    const auto energies = release_and_measure(m, c, o, s);
    compact(m, sizing, o.edge_length);
    const Quality q = pass_quality(m, o, energies);
    report_pass(o, s.iterations + 1, q, changes);
    const StopRule::Verdict verdict = stop.judge(q, changes, o);
    if (verdict == StopRule::Verdict::quality || verdict == StopRule::Verdict::no_improvement) {
      s.stop_reason = verdict == StopRule::Verdict::quality ? "quality" : "no improvement";
      ++s.iterations;
      break;
    }
    if (verdict == StopRule::Verdict::refine) refine_around_bad(m, o, sizing);
  }
  if (s.stop_reason.empty()) s.stop_reason = "iteration limit";
  if (settle_exact_vertices(m, c, s)) repair_after_settling(m, c, o, s);
  if (o.coarsen) coarsen(m, c, o, s);
  s.exact_left = m.exact_vertex_count();
  for (int v = 0; v < m.vertex_count(); ++v)
    if (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve) ++s.unprojected;
  s.final = measure(m);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace curvemesh::optimize
