#pragma once
// Internal to src/curve (never included from outside it): the steps of curve() (curve.hpp), as
// functions on the mesh and its curved form (mesh/curved_form.hpp), one idea a file:
//   curve.cpp            the schedule of the stage and its statistics;
//   split.cpp            step 1: splitting until every triangle has at most one primary edge;
//   nodes.cpp            steps 2 and 3: certification of the placed nodes, straightening;
//   smooth.cpp           step 4: smoothing of corners and centres, projection onto curves;
//   local_operations.cpp step 4: swaps, collapses and splits on the curved mesh;
//   coarsen.cpp          step 6: coarsening along the curves;
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
#include "mesh/curved_element.hpp"
#include "mesh/curved_form.hpp"
#include "mesh/invariants.hpp"
#include "mesh/operations.hpp"  // CollapseTest

namespace curvemesh::curve::detail {

using mesh::CurvedForm;
using mesh::EdgeKind;
using mesh::TriMesh;

using mesh::followable;
using mesh::is_primary;

// What every step works on: the linear mesh after step 1 with its curved form attached, the
// input's constraints, the options and the statistics.
struct Curving {
  TriMesh& mesh;
  CurvedForm& form;
  const mesh::Constraints& constraints;
  const Options& options;
  Stats& stats;
  double energy(int t, double bound = std::numeric_limits<double>::infinity()) const {
    return form.energy(t, bound);
  }
  std::optional<double> certify(int t) const { return form.certify(t, options.certificate_depth); }
};

// How many of a triangle's edges are primary.
int primary_edges_of(const TriMesh& m, const mesh::Triangle& tri);

// ----- split.cpp, tolerance.cpp: on the linear mesh, before the nodes --------------------------
// Step 1; returns the number of splits.
int split_until_one_primary_edge(TriMesh& m, const mesh::Constraints& c);
// Order 2, after step 1: the primary edges on their curve whose quadratic form would be beyond
// Options::tolerance are split as step 1 splits; returns the number of splits.
int split_beyond_tolerance(TriMesh& m, const mesh::Constraints& c, const Options& o);

// ----- nodes.cpp: steps 2 and 3 ---------------------------------------------------------------
// Each triangle with a curved edge certified (order 3: with the first certified centre
// candidate), its curved edge straightened where none is; then every triangle's nodes.
void certify_placed_nodes(Curving& cv);
// Certifies every one of `triangles`; only if all are certified, records their scaled
// Jacobians and returns true.
bool certify_all(Curving& cv, const std::vector<int>& triangles);

// ----- smooth.cpp: step 4, smoothing ----------------------------------------------------------
void smooth(Curving& cv);
// The energy of every alive triangle slot (0 for a dead one), computed in parallel.
std::vector<double> energies(const Curving& cv);
std::vector<int> bad_triangles(const Curving& cv);  // above the stop energy, worst first
int smooth_pass(Curving& cv);
int move_corner(Curving& cv, int v);
int smooth_centre(Curving& cv, int t);
// Primary vertices the linear optimization could not bring onto their curve (Fig. 8), brought
// there where nothing around them ends worse; returns how many.
int project_late(Curving& cv);

// The largest of `measure(t, bound)` (energy, badness) over `triangles`, or over v's: exact
// below `bound`, at least `bound` otherwise (it stops at the first triangle that reaches it).
template <class Measure>
double worst_over(const std::vector<int>& triangles, const Measure& measure,
                  double bound = std::numeric_limits<double>::infinity()) {
  double worst = 0;
  for (int t : triangles) {
    worst = std::max(worst, measure(t, bound));
    if (worst >= bound) break;
  }
  return worst;
}
template <class Measure>
double star_worst(const Curving& cv, int v, const Measure& measure,
                  double bound = std::numeric_limits<double>::infinity()) {
  return worst_over(cv.mesh.triangles_of(v), measure, bound);
}

// Compass search: from x0 with the first step h, in 8 directions, halving h when none lowers
// `objective`; returns the best point found. objective(x, bound) is called with the best value
// so far as `bound` and need only be exact below it.
template <class Objective>
Vec2 compass_search(const Vec2& x0, double h, const Objective& objective) {
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

// Compass search for a free or secondary corner v, from `start` (where it is) with a first step
// of a quarter of its shortest edge; positions that would turn a triangle of its star over or
// take one of its secondary edges out of the ε-envelope are out. objective(p, bound) as
// compass_search's.
template <class Objective>
Vec2 search_in_plane(const Curving& cv, int v, const Vec2& start, const Objective& objective) {
  const TriMesh& m = cv.mesh;
  double shortest = std::numeric_limits<double>::infinity();
  for (int w : m.neighbours(v)) shortest = std::min(shortest, (m.point(w) - m.point(v)).norm());
  return compass_search(start, 0.25 * shortest, [&](const Vec2& p, double bound) {
    if (!mesh::star_valid_at(m, v, p) || !mesh::secondary_edges_inside(m, cv.constraints, v, p))
      return std::numeric_limits<double>::infinity();
    return objective(p, bound);
  });
}

// Where free corner v should go: search_in_plane on the worst `measure` around it (its nodes
// placed by place_corner). Leaves every node as it was.
template <class Measure>
Vec2 search_corner(Curving& cv, int v, const Measure& measure) {
  const CurvedForm::Snapshot saved = cv.form.snapshot(cv.mesh.triangles_of(v));
  return search_in_plane(cv, v, cv.form.at(v), [&](const Vec2& p, double bound) {
    cv.form.place_corner(v, p);
    const double worst = star_worst(cv, v, measure, bound);
    cv.form.restore(saved);
    return worst;
  });
}

// ----- local_operations.cpp: step 4, the operations of §4.1 on the curved mesh ---------------
void improve(Curving& cv);
// Step 4's operations on triangle t, the first the mesh keeps: a swap of one of its edges,
// longest first; a collapse; the splits at a corner where curves meet; a split of one edge;
// splits of two. Returns 1 if one was kept.
int improve_triangle(Curving& cv, int t);
// A local operation of the linear mesh tried on the curved mesh (local_operations.cpp says how
// it is judged): `operation` changes the mesh under its journal and returns the triangles it
// changed or made, or nothing if it refused.
using Operation = std::function<std::optional<std::vector<int>>()>;
bool try_operation(Curving& cv, const std::vector<int>& before, const Operation& operation,
                   const std::vector<int>& settle = {}, double accept_up_to = 0);
// Collapses `from` onto `to` under `constraints` (and the caller's test `also`, if any), as an
// operation for try_operation: the triangles of from's star that stay, or nothing if refused.
std::optional<std::vector<int>> collapse(Curving& cv, int from, int to, const mesh::Constraints& constraints,
                                         const mesh::CollapseTest* also = nullptr);
// try_operation with the split of (a, b) on its curve, kept when every triangle it changes is
// certified, whatever their energy (order 2's meet_tolerance).
bool split_certified(Curving& cv, int a, int b);

// ----- coarsen.cpp: step 6 --------------------------------------------------------------------
void coarsen(Curving& cv);

// ----- guard.cpp: steps 4 and 5, moves kept only if no worse -------------------------------
// The vertices within `rings` edges of the centres; the alive triangles at some vertices;
// their worst energy (worst_over with energy).
std::vector<int> vertices_near(const TriMesh& m, const std::vector<int>& centres, int rings);
std::vector<int> triangles_at(const TriMesh& m, const std::vector<int>& vertices);
double worst_of(const Curving& cv, const std::vector<int>& triangles,
                double bound = std::numeric_limits<double>::infinity());
bool keep_unless_worse(Curving& cv, const std::vector<int>& centres, const std::function<bool()>& move,
                       const std::function<void()>& undo);

// ----- tolerance.cpp: order 2 ----------------------------------------------------------------
// The distance from primary edge (a, b) to its curve: quadratic_deviation where the edge is on
// its curve, else edge_distance of its nodes (0 for order 3 on its curve).
double deviation(const Curving& cv, int a, int b);
// Whether a primary edge that follows its curve (or will: followable) is beyond the tolerance
// there (order 2).
bool beyond_tolerance_if_curved(const Curving& cv, int a, int b);
// The last step of order 2: splits of the edges still beyond the tolerance; returns how many.
int meet_tolerance(Curving& cv);

// ----- fit.cpp: step 5 ------------------------------------------------------------------------
// The primary edges still straight, on their curve where nothing around them ends worse, else
// fitted towards it.
void fit_straight_edges(Curving& cv);
// An upper bound of the distance from primary edge (a, b) to its curve (statistics).
double distance_to_curve(const Curving& cv, int a, int b, const mesh::EdgeFeature& f);

}  // namespace curvemesh::curve::detail
