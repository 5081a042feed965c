#pragma once
// Internal to src/curve (never included from outside it): the state of one run of curve() and
// the steps that work on it. Builder's member functions are defined across the folder, one idea
// a file:
//   curve.cpp            the entry point, the order of the steps, the statistics, compaction;
//   split.cpp            step 1: splitting until every triangle has at most one primary edge;
//   nodes.cpp            steps 2 and 3: the P3 nodes of edges and centres, certification,
//                        straightening;
//   smooth.cpp           step 4: smoothing of corners and centres, projection onto curves;
//   local_operations.cpp step 4: swaps, collapses and splits on the curved mesh; step 6:
//                        coarsening along the curves;
//   fit.cpp              step 5: edges that could not follow their curve, the distances left;
//   guard.cpp            steps 4 and 5: the moves that may raise the worst energy, kept only if
//                        no worse (after a repair by step 4's operations);
//   tolerance.cpp        order 2: the distance from an edge to its curve, and the splits that
//                        bring the primary edges within the tolerance.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "curve/curve.hpp"
#include "geometry/p2_triangle.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/curved_element.hpp"
#include "mesh/invariants.hpp"
#include "mesh/operations.hpp"  // CollapseTest

namespace curvemesh::curve::detail {

using mesh::EdgeKind;
using mesh::TriMesh;

using mesh::followable;
using mesh::is_primary;
// How many of a triangle's edges are primary.
int primary_edges_of(const TriMesh& m, const mesh::Triangle& tri);

// Step 1 (split.cpp); returns the number of splits.
int split_until_one_primary_edge(TriMesh& m, const mesh::Constraints& c);
// Order 2, after step 1 (tolerance.cpp): the primary edges on their curve whose quadratic form
// would be beyond Options::tolerance are split as step 1 splits; returns the number of splits.
int split_beyond_tolerance(TriMesh& m, const mesh::Constraints& c, const Options& o);

// Steps 2 to 6 on the linear mesh after step 1 (out.linear, compacted).
class Builder {
 public:
  Builder(CurvedMesh& out, const mesh::Constraints& c, const Options& o, Stats& s)
      : out_(out),
        c_(c),
        o_(o),
        s_(s),
        nodes_(out.linear.journal()),
        triangle_nodes_(out.linear.journal()),
        vertex_node_(out.linear.journal()),
        first_node_(out.linear.journal()),
        curved_(out.linear.journal()),
        scaled_(out.linear.journal()),
        fitted_(out.linear.journal()) {}

  // Steps 2 to 6 and the statistics; out.nodes, out.triangles and out.lines are filled.
  void run();

 private:
  // Triangle t of the curved mesh is triangle slot t of out_.linear (compacted before curving;
  // step 4's operations add slots and leave dead ones, which finish() drops from both).

  // The node of vertex v (a corner).
  const Vec2& at(int v) const { return nodes_[vertex_node_[v]]; }

  // Triangle t's nodes: order 3's ten, order 2's six.
  geometry::P3Nodes nodes_of(int t) const {
    geometry::P3Nodes p;
    for (int i = 0; i < 10; ++i) p[i] = nodes_[triangle_nodes_[t][i]];
    return p;
  }
  geometry::P2Nodes p2_nodes_of(int t) const {
    geometry::P2Nodes p;
    for (int i = 0; i < 6; ++i) p[i] = nodes_[triangle_nodes_[t][i]];
    return p;
  }
  bool quadratic() const { return o_.order == 2; }
  // Triangle t's curved energy (geometry::p3_max_amips, p2_max_amips): exact below `bound`, at
  // least `bound` otherwise.
  double energy(int t, double bound = std::numeric_limits<double>::infinity()) const {
    return quadratic() ? geometry::p2_max_amips(p2_nodes_of(t), bound) : geometry::p3_max_amips(nodes_of(t), bound);
  }

  // ----- curve.cpp ------------------------------------------------------------------------------
  void place_nodes();
  void finish();
  void record_statistics();

  // ----- nodes.cpp: steps 2 and 3 ---------------------------------------------------------------
  void add_edge(int a, int b);
  void place_straight(int lo, int hi);
  void place_on_curve(int lo, int hi);
  void place_inner_nodes(int lo, int hi, const std::array<Vec2, 2>& inner);
  void straighten(int a, int b);
  std::array<int, 10> corner_and_edge_nodes(const mesh::Triangle& tri) const;
  std::pair<int, int> edge_nodes(int a, int b) const;
  int curved_edge_of(const mesh::Triangle& tri) const;
  geometry::P3Nodes element(const mesh::Triangle& tri) const;
  bool choose_centre(geometry::P3Nodes& p, int& choice, double& scaled) const;
  geometry::P2Nodes p2_element(const mesh::Triangle& tri) const;  // order 2's nodes_of, by corners
  double badness(int t) const;
  // Returns the chosen centre's energy(t) when every lattice point's det J is positive there
  // (badness is then that energy), else NaN.
  double choose_centre_of(int t);
  std::optional<double> certify(int t) const;
  bool certify_all(const std::vector<int>& triangles);
  // The nodes of some triangles, to put back when a move is refused.
  using Snapshot = std::vector<std::pair<int, Vec2>>;
  Snapshot snapshot(const std::vector<int>& triangles) const;
  void restore(const Snapshot& saved);

  // ----- smooth.cpp: step 4, smoothing ----------------------------------------------------------
  void smooth();
  std::vector<int> bad_triangles() const;
  int smooth_pass();
  int move_corner(int v);
  void place_corner(int v, const Vec2& p);
  // The two neighbours of primary vertex v along its section, and their parameters.
  struct CurveNeighbours {
    int x = -1, y = -1;
    double tx = 0, ty = 0;
  };
  void place_on_curve_at(int v, const CurveNeighbours& n, double t);
  bool curve_neighbours(int v, CurveNeighbours& n) const;
  int smooth_curve_corner(int v);
  int project(int v);
  int smooth_corner(int v);
  int smooth_centre(int t);

  // The largest of `measure(t, bound)` (energy, badness) over `triangles`, or over v's: exact
  // below `bound`, at least `bound` otherwise (it stops at the first triangle that reaches it).
  template <class Measure>
  double worst_over(const std::vector<int>& triangles, const Measure& measure,
                    double bound = std::numeric_limits<double>::infinity()) const {
    double worst = 0;
    for (int t : triangles) {
      worst = std::max(worst, measure(t, bound));
      if (worst >= bound) break;
    }
    return worst;
  }
  template <class Measure>
  double star_worst(int v, const Measure& measure,
                    double bound = std::numeric_limits<double>::infinity()) const {
    return worst_over(out_.linear.triangles_of(v), measure, bound);
  }

  // Where free corner v should go: compass search, from where it is and a first step of a quarter
  // of its shortest edge, on the worst `measure` around it (its nodes placed by place_corner);
  // positions that would turn a corner triangle over are out. Leaves every node as it was.
  template <class Measure>
  Vec2 search_corner(int v, const Measure& measure) {
    const TriMesh& m = out_.linear;
    double shortest = std::numeric_limits<double>::infinity();
    for (int w : m.neighbours(v)) shortest = std::min(shortest, (m.point(w) - m.point(v)).norm());
    const Snapshot saved = snapshot(m.triangles_of(v));
    return compass_search(at(v), 0.25 * shortest, [&](const Vec2& p, double bound) {
      if (!mesh::star_valid_at(m, v, p) || !mesh::secondary_edges_inside(m, c_, v, p))
        return std::numeric_limits<double>::infinity();
      place_corner(v, p);
      const double worst = star_worst(v, measure, bound);
      restore(saved);
      return worst;
    });
  }

  // Compass search: from x0 with the first step h, in 8 directions, halving h when none lowers
  // `objective`; returns the best point found. objective(x, bound) is called with the best value
  // so far as `bound` and need only be exact below it.
  template <class Objective>
  Vec2 compass_search(const Vec2& x0, double h, const Objective& objective) const {
    Vec2 x = x0;
    double best = objective(x0, std::numeric_limits<double>::infinity());
    for (int halvings = 0; halvings < 12;) {
      bool improved = false;
      for (int d = 0; d < 8; ++d) {
        const double angle = d * std::numbers::pi / 4;
        const Vec2 y = x + h * Vec2(std::cos(angle), std::sin(angle));
        const double e = objective(y, best);
        if (e < best) best = e, x = y, improved = true;
      }
      if (!improved) h *= 0.5, ++halvings;
    }
    return x;
  }

  // ----- local_operations.cpp: step 4, the operations of §4.1 on the curved mesh ---------------
  void improve();
  // Step 4's operations on triangle t, the first the mesh keeps (try_operation): a swap of one of
  // its edges, longest first; a collapse; the splits at a corner where curves meet; a split of one
  // edge; splits of two. Returns 1 if one was kept.
  int improve_triangle(int t);
  using Edges = std::array<std::array<int, 2>, 3>;
  Edges longest_first(const mesh::Triangle& tri) const;
  bool swap_one(const Edges& edges);
  bool collapse_one(const Edges& edges);
  bool split_at_junction(const mesh::Triangle& tri);
  bool split_one(const Edges& edges);
  bool cut_corner(const mesh::Triangle& tri);
  template <class Operation>
  bool try_operation(const std::vector<int>& before, const Operation& operation, const std::vector<int>& settle = {},
                     double accept_up_to = 0);
  bool judge_operation(const std::vector<int>& after, const std::vector<double>& known, bool settled,
                       double worst_before, int invalid_before, double accept_up_to);
  std::optional<std::vector<int>> collapse(int from, int to, const mesh::Constraints& constraints,
                                           const mesh::CollapseTest* also = nullptr);
  void coarsen();
  void settle_vertex(int v, const std::vector<int>& triangles);
  // The split of (a, b) at the middle of its parameter interval (mesh::split_edge), or −1 where
  // a new primary vertex would be left off its curve (the mesh is then changed: the caller's
  // try_operation takes it back).
  int split_on_curve(int a, int b);
  // try_operation with that split, kept when every triangle it changes is certified, whatever
  // their energy (order 2's meet_tolerance).
  bool split_certified(int a, int b);
  bool place_triangle(int t, double* known_energy = nullptr);

  // ----- guard.cpp: steps 4 and 5, moves kept only if no worse -------------------------------
  // The vertices within `rings` edges of the centres; the alive triangles at some vertices;
  // their worst energy (worst_over with energy).
  std::vector<int> vertices_near(const std::vector<int>& centres, int rings) const;
  std::vector<int> triangles_at(const std::vector<int>& vertices) const;
  double worst_of(const std::vector<int>& triangles, double bound = std::numeric_limits<double>::infinity()) const;
  bool keep_unless_worse(const std::vector<int>& centres, const std::function<bool()>& move,
                         const std::function<void()>& undo);

  // ----- tolerance.cpp: order 2 ----------------------------------------------------------------
  // The distance from primary edge (a, b) to its curve: quadratic_deviation where the edge is on
  // its curve, else edge_distance of its nodes (0 for order 3 on its curve).
  double deviation(int a, int b) const;
  // quadratic_deviation of the edge if it follows its curve (or will: followable), else 0.
  double curved_deviation(int a, int b) const;
  // Whether a primary edge that follows its curve is beyond the tolerance there (order 2).
  bool beyond_tolerance_if_curved(int a, int b) const;
  // The last step of order 2: splits of the edges still beyond the tolerance; returns how many.
  int meet_tolerance();

  // ----- fit.cpp: step 5 ------------------------------------------------------------------------
  void fit(int a, int b);
  bool on_fitted_edge(int v) const;
  int fitted_edge_of(const mesh::Triangle& tri) const;
  double distance_to_curve(int a, int b, const mesh::EdgeFeature& f, int first, int second) const;

  CurvedMesh& out_;
  const mesh::Constraints& c_;
  const Options& o_;
  Stats& s_;
  // The curved form of out_.linear, attached to its journal: whatever takes back a change of the
  // mesh takes back the nodes with it. Filled into out_.nodes and out_.triangles by finish().
  mesh::JournaledVector<Vec2> nodes_;  // vertices first (same indices), then the rest
  // Per triangle slot of out_.linear, its nodes (CurvedMesh::triangles' layout).
  mesh::JournaledVector<std::array<int, 10>> triangle_nodes_;
  // Where each vertex's node is in nodes_: the vertex's own index until step 4 adds vertices
  // (finish() puts the vertices first again).
  mesh::JournaledVector<int> vertex_node_;
  mesh::JournaledMap<std::uint64_t, int> first_node_;  // per edge, its first inner node
  mesh::JournaledMap<std::uint64_t, bool> curved_;     // per edge, whether it follows its curve
  mesh::JournaledVector<double> scaled_;  // per triangle: its scaled Jacobian, or −1 if not certified
  mesh::JournaledMap<std::uint64_t, bool> fitted_;  // primary edges fitted (step 5), not on their curve
};

}  // namespace curvemesh::curve::detail
