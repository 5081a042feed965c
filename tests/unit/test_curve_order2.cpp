// Curving with quadratic elements (curve::Options::order 2): checked from outside the stage —
// every element certified with exact rationals, middle nodes shared and on the curves, every
// primary edge within the tolerance of its curve, measured apart from the bound the stage uses —
// on whole drawings and on hand-made meshes where the tolerance forces splits or cannot be met.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "curve/curve.hpp"
#include "geometry/p2_triangle.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh {
namespace {

using geometry::Vec2;
using mesh::EdgeKind;

geometry::P2Nodes p2_nodes_of(const curve::CurvedMesh& c, std::size_t t) {
  geometry::P2Nodes p;
  for (int i = 0; i < 6; ++i) p[i] = c.nodes[c.triangles[t][i]];
  return p;
}

// The curve stage's options for order 2 on a hand-made mesh of unit size.
curve::Options quadratic(double tolerance) {
  curve::Options o = pipeline::resolve({}, 1).curve;
  o.order = 2;
  o.tolerance = tolerance;
  o.min_split_length = 1e-4;
  return o;
}

// The distance between the cubic and the quadratic through its points at s = 0, ½, 1, at equal
// parameters, by brute force: the bound quadratic_deviation is that maximum exactly.
TEST(QuadraticDeviation, IsTheLargestGapToTheInterpolatingQuadratic) {
  mesh::SectionCurve curve;
  curve.piece = geometry::CubicBezier({0, 0}, {0.2, 0.9}, {1.1, -0.4}, {1.5, 0.3});
  curve.t0 = 2, curve.t1 = 4;  // the section's parameters are not the piece's
  for (const auto& [ta, tb] : {std::pair{2.0, 4.0}, std::pair{2.5, 3.1}, std::pair{3.7, 2.2}}) {
    const Vec2 a = curve.eval(ta), m = curve.eval(0.5 * (ta + tb)), b = curve.eval(tb);
    double worst = 0;
    for (int i = 0; i <= 20000; ++i) {
      const double s = i / 20000.0;
      const Vec2 q = (1 - s) * (1 - 2 * s) * a + 4 * s * (1 - s) * m + s * (2 * s - 1) * b;
      worst = std::max(worst, (q - curve.eval(ta + s * (tb - ta))).norm());
    }
    const double bound = curve::quadratic_deviation(curve, ta, tb);
    EXPECT_GE(bound, worst * (1 - 1e-12));
    EXPECT_LE(bound, worst * (1 + 1e-6));
    // The distance as --stats measures it (to the nearest point of the curve) is at most that.
    EXPECT_LE(curve::edge_distance({a, b, m}, curve, ta, tb), bound * (1 + 1e-12));
  }
}

class CurveOrder2OnExamples : public testing::TestWithParam<std::string> {};

TEST_P(CurveOrder2OnExamples, CertifiedSharedOnTheCurvesAndWithinTheTolerance) {
  pipeline::Parameters p;
  p.order = 2;
  p.curve_tolerance_rel = 1e-6;  // far below what the linear mesh gives: the tolerance splits edges
  const pipeline::Result r = pipeline::run(pipeline::Source::file(std::string(CURVEMESH_EXAMPLES) + "/" + GetParam()), p);
  const curve::CurvedMesh& c = *r.curved;
  const curve::Stats& s = r.curve_stats;
  const double tolerance = 1e-6 * r.resolved.d;
  ASSERT_EQ(c.order, 2);
  ASSERT_GT(c.triangles.size(), 0u);
  EXPECT_GT(s.tolerance_splits, 0);
  EXPECT_EQ(s.beyond_tolerance, 0);
  EXPECT_EQ(s.invalid_triangles, 0);
  std::map<std::pair<int, int>, int> middle;  // (a, b) with a < b -> its middle node
  for (std::size_t t = 0; t < c.triangles.size(); ++t) {
    ASSERT_EQ(geometry::certify_jacobian_exact(p2_nodes_of(c, t)), geometry::JacobianVerdict::positive) << t;
    for (int i = 6; i < 10; ++i) EXPECT_EQ(c.triangles[t][i], -1);
    for (int i = 0; i < 3; ++i) {
      const int a = c.triangles[t][i], b = c.triangles[t][(i + 1) % 3];
      const auto [it, fresh] = middle.emplace(std::minmax(a, b), c.triangles[t][3 + i]);
      if (!fresh) {
        EXPECT_EQ(it->second, c.triangles[t][3 + i]) << "edge " << a << "-" << b << " has unshared nodes";
      }
    }
  }
  // No centre nodes: the vertices, then one node per edge.
  EXPECT_EQ(c.nodes.size(), static_cast<std::size_t>(c.linear.vertex_count()) + middle.size());
  int curved = 0;
  double farthest = 0;
  for (const curve::FeatureLine& line : c.lines) {
    EXPECT_EQ(line.nodes[3], -1);
    if (line.kind != EdgeKind::primary) continue;
    const int a = line.nodes[0], b = line.nodes[1];
    EXPECT_EQ(line.nodes[2], middle.at(std::minmax(a, b)));
    const mesh::EdgeFeature& f = *c.linear.feature(a, b);
    const mesh::SectionCurve& curve = r.constraints.sections[f.source];
    if (c.nodes[line.nodes[2]] == curve.eval(0.5 * (f.t_lo + f.t_hi))) ++curved;
    const double ta = a < b ? f.t_lo : f.t_hi, tb = a < b ? f.t_hi : f.t_lo;
    const double d = curve::edge_distance({c.nodes[a], c.nodes[b], c.nodes[line.nodes[2]]}, curve, ta, tb);
    EXPECT_LE(d, tolerance) << a << "-" << b;
    farthest = std::max(farthest, d);
  }
  EXPECT_EQ(curved, s.curved_edges);
  EXPECT_EQ(s.curved_edges, s.primary_edges);
  EXPECT_DOUBLE_EQ(curve::max_edge_distance(c, r.constraints), farthest);
  EXPECT_DOUBLE_EQ(r.stats["mesh"]["max_edge_distance"].get<double>(), farthest);
  EXPECT_GT(farthest, 0);
}

INSTANTIATE_TEST_SUITE_P(Examples, CurveOrder2OnExamples,
                         testing::Values("open-curves.svg", "overlapping-shapes.svg", "square-with-hole.svg"));

// A primary edge a-b (fixed ends) along a cubic bulging 3/4·`control` into triangle a-b-c (c at
// height 1, fixed), with fixed triangles below and around.
struct BulgingEdge {
  mesh::TriMesh m;
  mesh::Constraints constraints;
};
BulgingEdge bulging_edge(double control, double apex) {
  BulgingEdge e;
  e.constraints.max_turning = pipeline::resolve({}, 1).features.alpha_rad;
  mesh::VertexTag fixed;
  fixed.kind = mesh::VertexKind::fixed;
  auto& m = e.m;
  const int a = m.add_vertex({0, 0}, fixed), b = m.add_vertex({1, 0}, fixed);
  const int c = m.add_vertex({0.5, apex}, fixed), d = m.add_vertex({0.5, -1}, fixed);
  m.add_triangle(a, b, c);
  m.add_triangle(a, d, b);
  mesh::SectionCurve curve;
  curve.piece = geometry::CubicBezier({0, 0}, {0.2, control}, {0.7, control}, {1, 0});
  e.constraints.sections.push_back(curve);
  m.set_feature(a, b, {EdgeKind::primary, 0, 0, 0.0, 1.0});
  return e;
}

TEST(CurveOrder2, AnEdgeFartherThanTheToleranceIsSplitNotBent) {
  // An asymmetric bulge: the quadratic through the curve's middle misses it by about 0.024.
  auto [m, constraints] = bulging_edge(0.3, 1.0);
  const double gap = curve::quadratic_deviation(constraints.sections[0], 0, 1);
  ASSERT_GT(gap, 1e-3);
  curve::Stats loose, tight;
  const curve::CurvedMesh one = curve::curve(m, constraints, quadratic(2 * gap), &loose);
  EXPECT_EQ(loose.tolerance_splits, 0);
  EXPECT_EQ(loose.primary_edges, 1);
  // At equal parameters, 17 samples: about the bound itself.
  EXPECT_LE(loose.max_distance, gap);
  EXPECT_GT(loose.max_distance, 0.98 * gap);
  const curve::CurvedMesh many = curve::curve(m, constraints, quadratic(1e-5), &tight);
  EXPECT_GT(tight.tolerance_splits, 0);
  EXPECT_GE(tight.primary_edges, 16);  // a halving is 8 times nearer: 0.024 → 1e-5 takes 4 rounds
  EXPECT_EQ(tight.beyond_tolerance, 0);
  EXPECT_EQ(tight.curved_edges, tight.primary_edges);
  EXPECT_LE(tight.max_distance, 1e-5);
  EXPECT_LE(curve::max_edge_distance(many, constraints), 1e-5);
  for (const auto* out : {&one, &many})
    for (std::size_t t = 0; t < out->triangles.size(); ++t)
      EXPECT_EQ(geometry::certify_jacobian_exact(p2_nodes_of(*out, t)), geometry::JacobianVerdict::positive);
}

TEST(CurveOrder2, AnEdgeThatCannotBeSplitIsCountedBeyondTheTolerance) {
  // The curve bulges past the opposite corner (0.3 against 0.1): on its curve the edge folds its
  // triangle, and its middle point on the curve lies beyond that corner, so no split is valid. The
  // edge is fitted as far as certified, and the statistics say it is beyond the tolerance.
  auto [m, constraints] = bulging_edge(0.4, 0.1);
  curve::Stats s;
  const curve::CurvedMesh out = curve::curve(m, constraints, quadratic(1e-3), &s);
  EXPECT_EQ(s.primary_edges, 1);
  EXPECT_EQ(s.curved_edges, 0);
  EXPECT_EQ(s.beyond_tolerance, 1);
  EXPECT_GT(s.max_distance, 0.2);
  for (std::size_t t = 0; t < out.triangles.size(); ++t)
    EXPECT_EQ(geometry::certify_jacobian_exact(p2_nodes_of(out, t)), geometry::JacobianVerdict::positive);
}

TEST(CurveOrder2, CoarseningAlongACurveStopsAtTheTolerance) {
  // A circle meshed at order 2: coarsening merges edges along it only while each stays within the
  // tolerance, so a tighter tolerance keeps more edges on it.
  std::string svg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">)"
                    R"(<circle cx="50" cy="50" r="40" fill="none" stroke="black"/></svg>)";
  std::map<double, int> edges;
  for (const double tolerance : {1e-2, 1e-4, 1e-6}) {
    pipeline::Parameters p;
    p.order = 2;
    p.curve_tolerance_rel = tolerance;
    const pipeline::Result r = pipeline::run(pipeline::Source::svg(svg, "circle"), p);
    edges[tolerance] = r.curve_stats.primary_edges;
    EXPECT_EQ(r.curve_stats.beyond_tolerance, 0);
    EXPECT_LE(r.stats["mesh"]["max_edge_distance_rel"].get<double>(), tolerance);
  }
  EXPECT_LE(edges[1e-2], edges[1e-4]);
  EXPECT_LT(edges[1e-4], edges[1e-6]);
}

}  // namespace
}  // namespace curvemesh
