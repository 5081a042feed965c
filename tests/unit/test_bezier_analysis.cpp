// Inflections, turning, the half-turning split, straight and degenerate tests, on curves whose
// answers are known in closed form (worked out in the comments) or by dense sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <numbers>

#include "geometry/bezier_analysis.hpp"

using namespace curvemesh::geometry;

namespace {

constexpr double kPi = std::numbers::pi;

// Turning by dense sampling: unwrapped tangent angle, summed absolute increments. Independent of
// the code under test; valid away from cusps.
double sampled_turning(const CubicBezier& c, double t0 = 0, double t1 = 1, int n = 100000) {
  double total = 0, prev = 0;
  for (int i = 0; i <= n; ++i) {
    const Vec2 d = c.derivative(t0 + (t1 - t0) * i / n);
    const double a = std::atan2(d.y(), d.x());
    if (i > 0) total += std::abs(std::remainder(a - prev, 2 * kPi));
    prev = a;
  }
  return total;
}

// One cubic for the circular arc of `theta` radians from angle 0 (the 4/3·tan(θ/4) construction).
CubicBezier arc(double theta) {
  const double k = 4.0 / 3.0 * std::tan(theta / 4);
  const Vec2 a(1, 0), b(std::cos(theta), std::sin(theta));
  return {a, a + k * Vec2(0, 1), b - k * Vec2(-std::sin(theta), std::cos(theta)), b};
}

}  // namespace

TEST(Inflections, SCurveHasOneInTheMiddle) {
  // a = (1,1), b = (0,-3), c = (0,6): det(c', c'') ∝ 6t - 3, one root at 1/2.
  const auto t = inflection_parameters({{0, 0}, {1, 1}, {2, -1}, {3, 0}});
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0], 0.5, 1e-15);
  // An asymmetric S.
  const CubicBezier s({0, 0}, {1, 2}, {3, -2}, {4, 2});
  const auto u = inflection_parameters(s);
  ASSERT_EQ(u.size(), 1u);
  // Check the root independently: the curvature changes sign across it.
  auto k = [&](double x) {
    const Vec2 d1 = s.derivative(x), d2 = s.second_derivative(x);
    return d1.x() * d2.y() - d1.y() * d2.x();
  };
  EXPECT_LT(k(u[0] - 1e-6) * k(u[0] + 1e-6), 0);
  EXPECT_NEAR(k(u[0]), 0, 1e-9);
}

TEST(Inflections, CurveWithoutAny) {
  // C: det ∝ -2t² + 2t - 1, negative discriminant.
  EXPECT_TRUE(inflection_parameters({{0, 0}, {0, 1}, {1, 1}, {1, 0}}).empty());
  // Loop: det ∝ 20t² - 20t + 6, negative discriminant.
  EXPECT_TRUE(inflection_parameters({{0, 0}, {2, 2}, {-1, 2}, {1, 0}}).empty());
  // Cusp at t = 1/2: det ∝ (2t - 1)², a double root, no sign change.
  EXPECT_TRUE(inflection_parameters({{0, 0}, {1, 1}, {0, 1}, {1, 0}}).empty());
}

TEST(Inflections, DegenerateInputsGiveNothingAndNoNaN) {
  EXPECT_TRUE(inflection_parameters(CubicBezier::line({0, 0}, {1, 2})).empty());
  EXPECT_TRUE(inflection_parameters({{1, 1}, {1, 1}, {1, 1}, {1, 1}}).empty());
  EXPECT_TRUE(inflection_parameters({{0, 0}, {1, 0}, {2, 0}, {-5, 0}}).empty());  // collinear, folds back
  for (const double scale : {1e-300, 1e-150, 1e150}) {
    const auto t = inflection_parameters({{0, 0}, {scale, scale}, {2 * scale, -scale}, {3 * scale, 0}});
    ASSERT_EQ(t.size(), 1u) << scale;
    EXPECT_NEAR(t[0], 0.5, 1e-12);
  }
}

TEST(Turning, QuarterCircle) {
  EXPECT_NEAR(turning_angle(arc(kPi / 2)), kPi / 2, 1e-12);
  EXPECT_NEAR(turning_angle(arc(kPi / 2), 0, 0.5), kPi / 4, 1e-3);  // symmetric: half the turning
  EXPECT_NEAR(turning_angle(CubicBezier::line({0, 0}, {3, 4})), 0, 1e-15);
}

TEST(Turning, CuspCountsHalfATurn) {
  // Tangent 45° -> 90° (left), flips to -90° at the cusp, then -90° -> -45°: 45 + 180 + 45.
  EXPECT_NEAR(turning_angle({{0, 0}, {1, 1}, {0, 1}, {1, 0}}), 1.5 * kPi, 1e-9);
}

TEST(Turning, MoreThanHalfATurnSplits) {
  // The loop turns from 45° counter-clockwise to -45°: 270°.
  const CubicBezier loop({0, 0}, {2, 2}, {-1, 2}, {1, 0});
  EXPECT_NEAR(turning_angle(loop), 1.5 * kPi, 1e-9);
  EXPECT_NEAR(sampled_turning(loop), 1.5 * kPi, 1e-6);
  const auto cuts = split_for_turning(loop, kPi);
  ASSERT_FALSE(cuts.empty());
  double sum = 0, lo = 0;
  std::vector<double> ends = cuts;
  ends.push_back(1);
  for (const double hi : ends) {
    const double piece = sampled_turning(loop, lo, hi);
    EXPECT_LT(piece, kPi) << "piece [" << lo << ", " << hi << "]";
    sum += piece;
    lo = hi;
  }
  EXPECT_NEAR(sum, 1.5 * kPi, 1e-6);
}

TEST(Turning, NearFullCircularArc) {
  // One cubic for a 340° arc: its tangent turns 340°, split into pieces under 180° each.
  const CubicBezier c = arc(340 * kPi / 180);
  EXPECT_NEAR(sampled_turning(c), 340 * kPi / 180, 1e-6);
  EXPECT_NEAR(turning_angle(c), 340 * kPi / 180, 1e-9);
  const auto cuts = split_for_turning(c, kPi);
  ASSERT_GE(cuts.size(), 1u);
  double lo = 0;
  std::vector<double> ends = cuts;
  ends.push_back(1);
  for (const double hi : ends) {
    EXPECT_LT(sampled_turning(c, lo, hi), kPi);
    lo = hi;
  }
  EXPECT_TRUE(split_for_turning(arc(kPi / 2), kPi).empty());
}

TEST(Turning, HalfTurningParameterHalves) {
  for (const CubicBezier& c : {arc(kPi / 2), arc(2.5), CubicBezier({0, 0}, {2, 2}, {-1, 2}, {1, 0}),
                               CubicBezier({0, 0}, {0, 2}, {2, 3}, {4, 3})}) {
    ASSERT_TRUE(inflection_parameters(c).empty());
    const double t = half_turning_parameter(c);
    ASSERT_GT(t, 0);
    ASSERT_LT(t, 1);
    const double whole = sampled_turning(c);
    EXPECT_NEAR(sampled_turning(c, 0, t), whole / 2, 1e-4 * whole);
  }
}

TEST(StraightAndDegenerate, Detection) {
  EXPECT_TRUE(is_degenerate({{1, 1}, {1 + 1e-9, 1}, {1, 1 - 1e-9}, {1, 1}}, 1e-8));
  EXPECT_FALSE(is_degenerate({{1, 1}, {1 + 1e-7, 1}, {1, 1}, {1, 1}}, 1e-8));
  EXPECT_TRUE(is_straight(CubicBezier::line({0, 0}, {3, 4}), 1e-12));
  EXPECT_TRUE(is_straight({{0, 0}, {5, 5}, {-1, -1}, {2, 2}}, 1e-12));  // collinear, folding back
  EXPECT_FALSE(is_straight({{0, 0}, {1, 1e-6}, {2, 0}, {3, 0}}, 1e-8));
  EXPECT_TRUE(is_straight({{0, 0}, {1, 1e-10}, {2, 0}, {3, 0}}, 1e-8));
  // Scaled copies behave the same when the tolerance scales with them.
  for (const double s : {1e-6, 1e6}) {
    EXPECT_TRUE(is_straight({{0, 0}, {s, 1e-10 * s}, {2 * s, 0}, {3 * s, 0}}, 1e-8 * s));
    EXPECT_FALSE(is_straight({{0, 0}, {s, 1e-6 * s}, {2 * s, 0}, {3 * s, 0}}, 1e-8 * s));
  }
}

TEST(Turning, EndTangentAngleIsTheTurningOfMonotonePieces) {
  // On pieces without inflection that turn less than π, the end-tangent angle is the turning on
  // every sub-interval (checked against dense sampling); elsewhere the pieces are not monotone.
  const CubicBezier pieces[] = {arc(kPi / 2), arc(0.9 * kPi), {{0, 0}, {1, 0}, {2, 1}, {2, 3}},
                                {{0, 0}, {5, 0}, {5, 1e-3}, {5, 2}}};
  for (const CubicBezier& c : pieces) {
    ASSERT_TRUE(turns_monotonically(c));
    for (double a : {0.0, 0.1, 0.37})
      for (double b : {0.5, 0.81, 1.0}) EXPECT_NEAR(end_tangent_angle(c, a, b), sampled_turning(c, a, b), 1e-6);
  }
  EXPECT_FALSE(turns_monotonically({{0, 0}, {1, 1}, {2, -1}, {3, 0}}));   // an S: one inflection
  EXPECT_FALSE(turns_monotonically({{0, 0}, {2, 2}, {-1, 2}, {1, 0}}));   // a loop: 270°
  EXPECT_NEAR(end_tangent_angle(CubicBezier::line({0, 0}, {3, 4}), 0.2, 0.9), 0.0, 1e-15);
}

TEST(Turning, PiecesSplitAtAnInflectionAreMonotone) {
  // The halves of S-curves split at their inflection: rounding may leave the inflection a hair
  // inside a half, which must not cost the half its monotone turning.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int split = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const CubicBezier c({0, 0}, {1 + u(rng), 1 + u(rng)}, {2 + u(rng), -1 + u(rng)}, {3, 0});
    const auto inflections = inflection_parameters(c);
    if (inflections.size() != 1 || turning_angle(c) >= kPi) continue;
    const auto [first, second] = c.split(inflections[0]);
    for (const CubicBezier& half : {first, second}) {
      if (turning_angle(half) >= kPi) continue;
      EXPECT_TRUE(turns_monotonically(half)) << "trial " << trial;
      for (double a : {0.0, 0.3})
        for (double b : {0.6, 1.0}) EXPECT_NEAR(end_tangent_angle(half, a, b), sampled_turning(half, a, b), 1e-6);
    }
    ++split;
  }
  EXPECT_GT(split, 100);
  // An inflection well inside still makes a piece non-monotone.
  EXPECT_FALSE(turns_monotonically(CubicBezier({0, 0}, {1, 1}, {2, -1}, {3, 0}).subcurve(0.0, 0.5 + 1e-6)));
}
