// Coarsening (optimize::coarsen, the last step of the linear optimization): on random meshes with
// every kind of tag it keeps every invariant (checked as in test_mesh_operations, orientation with
// GMP rationals computed here) and the energy bounds, the linear pipeline's and the curved one's
// (triangles along curves judged once curved), and removes what the target length does not need;
// through the pipeline, linear and curved, `-l` keeps its meaning away from the features for small
// and large l.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "geometry/amips.hpp"
#include "geometry/p3_triangle.hpp"
#include "grid_fixture.hpp"
#include "mesh/operations.hpp"
#include "optimize/optimize.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh {
namespace {

using geometry::Vec2;
using mesh::TriMesh;
using mesh::VertexKind;

double worst_energy(const TriMesh& m) {
  double worst = 0;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    worst = std::max(worst, geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])));
  }
  return worst;
}

// Coarsens grid f with o, then checks every invariant. coarsen compacts: the fixed vertices are
// renumbered, but none may be removed or moved (the invariants check compares them by position,
// so the fixture's record of them is renumbered first).
void coarsen_and_check(mesh::fixture::Fixture& f, const optimize::Options& o, optimize::Stats& s,
                       const char* what) {
  optimize::coarsen(f.mesh, f.constraints, o, s);
  std::map<int, Vec2> fixed;
  for (int v = 0; v < f.mesh.vertex_count(); ++v)
    if (f.mesh.tag(v).kind == VertexKind::fixed) fixed[v] = f.mesh.point(v);
  ASSERT_EQ(fixed.size(), f.fixed_positions.size());
  std::set<std::pair<double, double>> was, is;
  for (const auto& [v, p] : f.fixed_positions) was.insert({p.x(), p.y()});
  for (const auto& [v, p] : fixed) is.insert({p.x(), p.y()});
  EXPECT_EQ(was, is);
  f.fixed_positions = fixed;
  mesh::fixture::expect_invariants(f, what);
}

TEST(Coarsen, RandomMeshesKeepEveryInvariantAndTheEnergyBound) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    // A grid of edges 1/24 against a target of 1/4: nearly every edge is short.
    mesh::fixture::Fixture f = mesh::fixture::make_grid(24, seed);
    const int before = f.mesh.triangle_count();
    const double worst_before = worst_energy(f.mesh);
    optimize::Options o;
    o.edge_length = 0.25;
    o.stop_max_amips = 10;
    optimize::Stats s;
    coarsen_and_check(f, o, s, "coarsening");
    if (HasFatalFailure()) return;

    EXPECT_EQ(s.before_coarsening, before);
    EXPECT_GT(s.coarsening_collapses, 0);
    // What the target length does not need goes: at most a third of the triangles stay.
    EXPECT_LT(3 * f.mesh.triangle_count(), before);
    // No triangle above the stop energy or the worst before (the grid's jitter stays below 10).
    EXPECT_LE(worst_energy(f.mesh), std::max(o.stop_max_amips, worst_before));
    // The target length keeps its meaning: the mean edge is within [0.8, 1.25] of it. (Each
    // collapse makes no edge longer than 5/3 of it; the swaps after may choose a diagonal a
    // little longer, as in the loop.)
    double sum = 0;
    int edges = 0;
    for (int t = 0; t < f.mesh.triangle_slots(); ++t) {
      if (!f.mesh.alive(t)) continue;
      const auto& tri = f.mesh.triangle(t);
      for (int i = 0; i < 3; ++i, ++edges) sum += (f.mesh.point(tri[i]) - f.mesh.point(tri[(i + 1) % 3])).norm();
    }
    EXPECT_GE(sum / edges, 0.8 * o.edge_length);
    EXPECT_LE(sum / edges, 1.25 * o.edge_length);
  }
}

// The energy of triangle t once curved, as the curve stage first makes it, computed here: with
// exactly one primary edge whose ends are on their curve, the cubic triangle with that edge's
// nodes on the curve at the thirds of its parameter interval and the best of the stage's centre
// candidates; 0 for any other triangle (it stays straight, its linear energy judges it).
double curved_form_energy(const TriMesh& m, const mesh::Constraints& c, int t) {
  const auto& tri = m.triangle(t);
  int primary = -1, count = 0;
  for (int i = 0; i < 3; ++i) {
    const mesh::EdgeFeature* f = m.feature(tri[i], tri[(i + 1) % 3]);
    if (f && f->kind == mesh::EdgeKind::primary) {
      primary = i;
      ++count;
    }
  }
  if (count != 1) return 0;
  const int a = tri[primary], b = tri[(primary + 1) % 3], o = tri[(primary + 2) % 3];
  for (int v : {a, b})
    if (m.tag(v).kind == VertexKind::primary && !m.tag(v).on_curve) return 0;
  const mesh::EdgeFeature& f = *m.feature(a, b);
  const double ta = a < b ? f.t_lo : f.t_hi, tb = a < b ? f.t_hi : f.t_lo;
  geometry::P3Nodes p = geometry::p3_straight_nodes(m.point(a), m.point(b), m.point(o));
  p[3] = c.sections[f.source].eval(ta + (tb - ta) / 3);
  p[4] = c.sections[f.source].eval(ta + 2 * (tb - ta) / 3);
  double best = std::numeric_limits<double>::infinity();
  for (const Vec2& centre : geometry::p3_centre_candidates(p)) {
    p[9] = centre;
    best = std::min(best, geometry::p3_max_amips(p));
  }
  return best;
}

double worst_curved(const TriMesh& m, const mesh::Constraints& c) {
  double worst = 0;
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t)) worst = std::max(worst, curved_form_energy(m, c, t));
  return worst;
}

TEST(Coarsen, InTheCurvedPipelineTrianglesAlongCurvesKeepTheCurvedBound) {
  // The same random meshes, coarsened for the curved pipeline: every invariant, no triangle above
  // the stop energy (or the worst before), and no triangle along the curve above the curved stop
  // energy once curved (or the worst curved one before).
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    mesh::fixture::Fixture f = mesh::fixture::make_grid(24, seed);
    const double linear_before = worst_energy(f.mesh);
    const double curved_before = worst_curved(f.mesh, f.constraints);
    optimize::Options o;
    o.edge_length = 0.25;
    o.stop_max_amips = 10;
    o.curved = true;
    o.curved_stop_amips = 20;
    optimize::Stats s;
    coarsen_and_check(f, o, s, "coarsening for the curved pipeline");
    if (HasFatalFailure()) return;
    EXPECT_GT(s.coarsening_collapses, 0);
    EXPECT_LE(worst_energy(f.mesh), std::max(o.stop_max_amips, linear_before));
    const double curved_after = worst_curved(f.mesh, f.constraints);
    EXPECT_GT(curved_after, 0) << "the curve is still meshed";
    EXPECT_LE(curved_after, std::max(o.curved_stop_amips, curved_before));
  }
}

TEST(Coarsen, OffByOptionTheMeshIsTheLoopsAndOnItIsCoarser) {
  // The same grid, optimized with and without the step: with it, fewer triangles, and the worst
  // energy still within the stop energy.
  mesh::fixture::Fixture with = mesh::fixture::make_grid(20, 7), without = mesh::fixture::make_grid(20, 7);
  optimize::Options o;
  o.edge_length = 0.2;
  o.min_edge_length = 1e-4;
  o.max_iterations = 80;
  o.stop_min_angle_deg = 10;
  o.stop_max_amips = 10;
  const optimize::Stats s_with = optimize::optimize(with.mesh, with.constraints, o);
  o.coarsen = false;
  const optimize::Stats s_without = optimize::optimize(without.mesh, without.constraints, o);
  EXPECT_EQ(s_without.coarsening_rounds, 0);
  EXPECT_EQ(s_with.before_coarsening, s_without.final.triangles);
  EXPECT_LT(s_with.final.triangles, s_without.final.triangles);
  EXPECT_LE(s_with.final.max_amips, std::max(10.0, s_without.final.max_amips));
}

// Two small rings at opposite corners of a drawing: the box between them is empty, the mesh there
// is sized by l alone.
std::string two_rings() {
  const auto ring = [](double cx, double cy) {
    const double r = 5;
    std::string s = "<circle cx=\"" + std::to_string(cx) + "\" cy=\"" + std::to_string(cy) + "\" r=\"" +
                    std::to_string(r) + "\" fill=\"none\" stroke=\"black\"/>";
    return s;
  };
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 400 300\">" + ring(10, 10) + ring(390, 290) +
         "</svg>";
}

// The mean length of the edges away from the features: both ends neither on a feature nor next
// to a vertex on one.
double mean_edge_away_from_features(const TriMesh& m, int* count) {
  std::vector<char> near(m.vertex_count(), 0);
  const auto on_feature = [&](int v) {
    const VertexKind k = m.tag(v).kind;
    return k == VertexKind::primary || k == VertexKind::secondary ||
           (k == VertexKind::fixed && !m.tagged_edges(v).empty() &&
            std::any_of(m.tagged_edges(v).begin(), m.tagged_edges(v).end(),
                        [](const mesh::TaggedEdge& e) { return e.feature.kind != mesh::EdgeKind::boundary; }));
  };
  for (int v = 0; v < m.vertex_count(); ++v)
    if (on_feature(v)) {
      near[v] = 1;
      for (int w : m.neighbours(v)) near[w] = 1;
    }
  double sum = 0;
  *count = 0;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (near[a] || near[b]) continue;
      // Each inner edge twice (once from each side), each box edge once: the box's edges count
      // half as much, which does not move a mean of edges all sized alike.
      sum += (m.point(a) - m.point(b)).norm();
      ++*count;
    }
  }
  return *count ? sum / *count : 0;
}

TEST(Coarsen, TheTargetLengthKeepsItsMeaningForSmallAndLargeL) {
  for (const bool linear : {true, false})
    for (const double l : {0.01, 0.02, 0.05, 0.1, 0.2}) {
      SCOPED_TRACE((linear ? "linear, l = " : "curved, l = ") + std::to_string(l));
      Parameters p;
      p.edge_length_rel = l;
      p.order = linear ? 1 : 3;
      const pipeline::Result r = pipeline::run(pipeline::Source::svg(two_rings(), "two rings"), p);
      int count = 0;
      const double mean = mean_edge_away_from_features(r.corners(), &count);
      const double target = r.resolved.optimize.edge_length;
      ASSERT_GT(count, 10) << "too few edges away from the features to measure";
      EXPECT_GE(mean, 0.8 * target);
      EXPECT_LE(mean, 1.25 * target);
    }
}

}  // namespace
}  // namespace curvemesh
