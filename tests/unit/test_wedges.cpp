// The wedges at fixed vertices (curve/wedges.cpp): the bound an angle between two tagged lines
// puts on the triangles between them, checked against the energy of real triangles, and the
// statistics of hand-made sharp junctions meshed by the whole pipeline.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "curve/curve.hpp"
#include "geometry/amips.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/tri_mesh.hpp"
#include "pipeline/pipeline.hpp"
#include "tangent_junction.hpp"

namespace {

using curvemesh::geometry::Vec2;
namespace curve = curvemesh::curve;
namespace pipeline = curvemesh::pipeline;

constexpr double kDegree = std::numbers::pi / 180;

// The energy of the isosceles triangle with apex `angle` and unit legs, as the meshes measure it.
double isosceles(double angle) {
  return curvemesh::geometry::amips(Vec2(0, 0), Vec2(1, 0), Vec2(std::cos(angle), std::sin(angle)));
}

// Each element's energy, recomputed from its P3 nodes.
std::vector<double> element_energies(const curve::CurvedMesh& mesh) {
  std::vector<double> amips;
  for (const auto& ids : mesh.triangles) {
    curvemesh::geometry::P3Nodes nodes;
    for (int i = 0; i < 10; ++i) nodes[i] = mesh.nodes[ids[i]];
    amips.push_back(curvemesh::geometry::p3_max_amips(nodes));
  }
  return amips;
}

double worst_energy(const curve::CurvedMesh& mesh) {
  const std::vector<double> amips = element_energies(mesh);
  return amips.empty() ? 0.0 : *std::max_element(amips.begin(), amips.end());
}

TEST(WedgeBound, IsTheBestFanOfIsoscelesTriangles) {
  // The figures the bound is quoted with.
  EXPECT_NEAR(curve::wedge_amips_bound(10 * kDegree), 6.75, 0.01);
  EXPECT_NEAR(curve::wedge_amips_bound(5 * kDegree), 13.3, 0.05);
  EXPECT_NEAR(curve::wedge_amips_bound(3.3 * kDegree), 20.0, 0.3);
  // Below 60° one triangle is best: the bound is that triangle's energy.
  for (double a : {1.0, 4.0, 17.0, 45.0, 60.0})
    EXPECT_NEAR(curve::wedge_amips_bound(a * kDegree), isosceles(a * kDegree), 1e-9) << a << "°";
  // Wider wedges are split: 120° into two equilateral triangles, 90° at best into two of 45°
  // or one right angle.
  EXPECT_NEAR(curve::wedge_amips_bound(120 * kDegree), 2.0, 1e-9);
  EXPECT_NEAR(curve::wedge_amips_bound(90 * kDegree), std::min(isosceles(90 * kDegree), isosceles(45 * kDegree)),
              1e-9);
  // No fan of k triangles does better than the bound (their angles sum to the wedge).
  for (double w : {2.0, 7.0, 50.0, 100.0, 200.0, 350.0})
    for (int k = 1; k <= 12; ++k) {
      double worst = isosceles(w * kDegree / k);
      EXPECT_GE(worst, curve::wedge_amips_bound(w * kDegree) - 1e-9) << w << "° in " << k;
    }
  EXPECT_TRUE(std::isinf(curve::wedge_amips_bound(0)));
}

// Two segments leaving (0, 0) at `angle` from each other, with a square around them: the only
// wedge smaller than 90° is at their common end.
pipeline::Result junction(double angle) {
  const auto segment = [](const Vec2& a, const Vec2& b) {
    return std::array<Vec2, 4>{a, (2 * a + b) / 3, (a + 2 * b) / 3, b};
  };
  const Vec2 o(0, 0), x(1, 0), y(std::cos(angle), std::sin(angle));
  std::vector<std::array<Vec2, 4>> curves = {segment(o, x), segment(o, y)};
  const Vec2 c[4] = {{-0.5, -0.5}, {1.5, -0.5}, {1.5, 1.5}, {-0.5, 1.5}};
  for (int i = 0; i < 4; ++i) curves.push_back(segment(c[i], c[(i + 1) % 4]));
  return pipeline::run(pipeline::Source::beziers(curves, "junction"), {});
}

TEST(WedgeStats, AJunctionIsMeasuredOnTheCurvedMesh) {
  // Above the junction angle the two segments stay apart: the wedge is theirs, and a mesh
  // always has a triangle in it, so its worst energy is at least the bound.
  for (double degrees : {12.0, 20.0}) {
    SCOPED_TRACE(testing::Message() << degrees << "°");
    const pipeline::Result r = junction(degrees * kDegree);
    const curve::Stats& s = r.curve_stats;
    EXPECT_NEAR(s.wedges.smallest_wedge / kDegree, degrees, 1e-6);
    EXPECT_DOUBLE_EQ(s.wedges.smallest_wedge_bound, curve::wedge_amips_bound(s.wedges.smallest_wedge));
    EXPECT_GE(s.max_amips, s.wedges.smallest_wedge_bound * (1 - 1e-9));
    EXPECT_EQ(s.wedges.sharp_triangles, 0);
    EXPECT_EQ(s.wedges.max_amips_elsewhere, s.max_amips);
  }
}

TEST(WedgeStats, ATriangleInASharpWedgeIsCountedApart) {
  // A hand-made mesh: two tagged lines leave fixed vertex o at 2° with one triangle between
  // them (o, p, q), and one triangle on either side. Nothing can move (every vertex is fixed).
  const double angle = 2 * kDegree;
  curvemesh::mesh::TriMesh m;
  curvemesh::mesh::VertexTag fixed;
  fixed.kind = curvemesh::mesh::VertexKind::fixed;
  const int o = m.add_vertex({0, 0}, fixed), p = m.add_vertex({1, 0}, fixed);
  const int q = m.add_vertex({std::cos(angle), std::sin(angle)}, fixed);
  const int below = m.add_vertex({0.5, -1}, fixed), above = m.add_vertex({0, 1}, fixed);
  m.add_triangle(o, p, q);
  m.add_triangle(o, below, p);
  m.add_triangle(o, q, above);
  m.set_feature(o, p, {curvemesh::mesh::EdgeKind::boundary});
  m.set_feature(o, q, {curvemesh::mesh::EdgeKind::boundary});
  const pipeline::Resolved paper = pipeline::resolve({}, 1);
  curve::Stats s;
  const curve::CurvedMesh out = curve::curve(m, {}, paper.curve, &s);
  ASSERT_EQ(out.triangles.size(), 3u);
  EXPECT_NEAR(s.wedges.smallest_wedge, angle, 1e-9);
  EXPECT_GT(s.wedges.smallest_wedge_bound, 30.0);  // 33.1 at 2°
  EXPECT_EQ(s.wedges.sharp_triangles, 1);
  // The sliver is the worst element and at least the bound; the others are measured apart.
  const std::vector<double> amips = element_energies(out);
  std::size_t sliver = 0;
  for (std::size_t t = 0; t < out.triangles.size(); ++t)
    if (std::count(out.triangles[t].begin(), out.triangles[t].begin() + 3, p) &&
        std::count(out.triangles[t].begin(), out.triangles[t].begin() + 3, q))
      sliver = t;
  EXPECT_GE(amips[sliver], s.wedges.smallest_wedge_bound * (1 - 1e-9));
  EXPECT_EQ(s.max_amips, amips[sliver]);
  double elsewhere = 0;
  for (std::size_t t = 0; t < amips.size(); ++t)
    if (t != sliver) elsewhere = std::max(elsewhere, amips[t]);
  EXPECT_EQ(s.wedges.max_amips_elsewhere, elsewhere);
  EXPECT_LT(s.wedges.max_amips_elsewhere, 20.0);
}

TEST(WedgeStats, CurvesLeavingAJunctionAtAFewDegreesEndUnder20) {
  // Two arcs leave (0, 0) at 4° and turn apart; their chords open wider than the junction angle.
  // Two curved edges leaving there at 4° would need a triangle between them for each (a triangle
  // has at most one curved edge): two wedges of 2°, whose triangles are at best 33 at that
  // corner. One of the curves is secondary at the junction instead (a straight edge along its
  // chord), and the fan around (0, 0) ends within the curved stop energy.
  for (double degrees : {3.0, 4.0, 6.0}) {
    SCOPED_TRACE(testing::Message() << degrees << "°");
    const pipeline::Result r =
        pipeline::run(pipeline::Source::beziers(curvemesh::testing_support::tangent_junction(degrees), "junction"), {});
    const curve::Stats& s = r.curve_stats;
    EXPECT_LE(s.wedges.smallest_wedge_bound, 20.0);
    ASSERT_TRUE(r.curved.has_value());
    const double worst = worst_energy(*r.curved);
    EXPECT_EQ(worst, s.max_amips);
    EXPECT_LE(worst, 20.0);
    EXPECT_EQ(s.invalid_triangles, 0);
  }
}

// A heart of four cubics, as playing cards draw it: its two lobes leave the cusp at (0, 0) a
// few degrees either side of straight up (the first control points `handle` above the cusp,
// `lean` · `handle` to the side) and at once turn apart, so that the chords of edges at the
// cusp open much wider than the curves' tangents.
std::vector<std::array<Vec2, 4>> heart(double handle, double lean) {
  const std::array<Vec2, 7> right{Vec2(0, 0),   Vec2(lean * handle, -handle), Vec2(6.5, -28), Vec2(31, -20),
                                  Vec2(62, -4), Vec2(22, 30),                 Vec2(0, 58)};
  std::array<Vec2, 7> left;
  for (int i = 0; i < 7; ++i) left[i] = Vec2(-right[i].x(), right[i].y());
  return {{right[0], right[1], right[2], right[3]},
          {right[3], right[4], right[5], right[6]},
          {left[6], left[5], left[4], left[3]},
          {left[3], left[2], left[1], left[0]}};
}

TEST(WedgeStats, CurvesTurningApartAtACuspEndUnder20) {
  // Both curves at the cusp stay primary (their tangents meet at 11° to 14°, above the junction
  // angle), and their first edges bulge into the triangles between them: without edges graded
  // towards the cusp, those end at 23 to 31 here. The wedge bound allows less than 20.
  for (const auto& [handle, lean] : {std::pair{0.5, 0.1}, std::pair{0.6, 0.12}, std::pair{0.75, 0.12}}) {
    SCOPED_TRACE(testing::Message() << "handle " << handle << ", lean " << lean);
    const pipeline::Result r = pipeline::run(pipeline::Source::beziers(heart(handle, lean), "heart"), {});
    ASSERT_TRUE(r.curved.has_value());
    const curve::CurvedMesh& c = *r.curved;
    const curve::Stats& s = r.curve_stats;
    // The premise: two primary curves leave the cusp, at a wedge the bound allows under 20.
    int primary_at_cusp = 0;
    for (const curve::FeatureLine& line : c.lines)
      if (line.kind == curvemesh::mesh::EdgeKind::primary)
        for (int end : {line.nodes[0], line.nodes[1]}) primary_at_cusp += c.nodes[end].norm() == 0;
    EXPECT_EQ(primary_at_cusp, 2);
    EXPECT_GT(s.wedges.smallest_wedge / kDegree, 10);
    EXPECT_LT(s.wedges.smallest_wedge / kDegree, 15);
    const double worst = worst_energy(c);
    EXPECT_LE(worst, 20.0);
    EXPECT_EQ(s.invalid_triangles, 0);
    // The corners of the curved mesh are the linear mesh's vertices, where the operations tried
    // and taken back left them too.
    int moved = 0;
    for (int v = 0; v < c.linear.vertex_count(); ++v) moved += c.nodes[v] != c.linear.point(v);
    EXPECT_EQ(moved, 0);
  }
}

TEST(WedgeStats, NoSharpWedgeInASquare) {
  const auto segment = [](const Vec2& a, const Vec2& b) {
    return std::array<Vec2, 4>{a, (2 * a + b) / 3, (a + 2 * b) / 3, b};
  };
  const Vec2 c[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<std::array<Vec2, 4>> curves;
  for (int i = 0; i < 4; ++i) curves.push_back(segment(c[i], c[(i + 1) % 4]));
  const pipeline::Result r = pipeline::run(pipeline::Source::beziers(curves, "square"), {});
  const curve::Stats& s = r.curve_stats;
  EXPECT_GE(s.wedges.smallest_wedge / kDegree, 90 - 1e-6);
  EXPECT_EQ(s.wedges.sharp_triangles, 0);
  EXPECT_EQ(s.wedges.max_amips_elsewhere, s.max_amips);
}

}  // namespace
