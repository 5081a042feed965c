// The AMIPS energy against its definition and its derivatives against finite differences,
// at the scales drawings come in.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/LU>

#include "geometry/amips.hpp"

namespace curvemesh::geometry {
namespace {

Vec2 rotate(const Vec2& p, double angle) {
  return {std::cos(angle) * p.x() - std::sin(angle) * p.y(), std::sin(angle) * p.x() + std::cos(angle) * p.y()};
}

TEST(Amips, EquilateralIsTwoAtAnySizeAndPlace) {
  for (double scale : {1e-6, 1.0, 1e6})
    for (double angle : {0.0, 0.3, 2.0})
      for (const Vec2& shift : {Vec2(0, 0), Vec2(3, -7)}) {
        const Vec2 a = shift * scale, b = a + rotate(Vec2(scale, 0), angle),
                   c = a + rotate(Vec2(0.5 * scale, std::sqrt(3.0) / 2 * scale), angle);
        EXPECT_NEAR(amips(a, b, c), 2.0, 1e-9) << scale << " " << angle;
      }
}

TEST(Amips, RightIsoscelesAndInverted) {
  // ‖J‖² = 1 + |(-1, 2)|²/3 = 8/3, det J = 2/√3: E = 4/√3.
  EXPECT_NEAR(amips(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)), 4 / std::sqrt(3.0), 1e-14);
  EXPECT_TRUE(std::isinf(amips(Vec2(0, 0), Vec2(0, 1), Vec2(1, 0))));
  EXPECT_TRUE(std::isinf(amips(Vec2(0, 0), Vec2(1, 1), Vec2(2, 2))));
  EXPECT_TRUE(std::isinf(amips_derivatives(Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)).energy));
}

TEST(Amips, FlatteningGrowsWithoutBound) {
  double last = 0;
  for (double h : {1.0, 0.1, 0.01, 0.001}) {
    const double e = amips(Vec2(0, 0), Vec2(1, 0), Vec2(0.5, h));
    EXPECT_GT(e, last);
    last = e;
  }
  EXPECT_GT(last, 500);
}

TEST(Amips, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  for (double scale : {1e-6, 1.0, 1e6})
    for (int k = 0; k < 200; ++k) {
      const Vec2 a(u(rng), u(rng)), b(u(rng), u(rng)), c(u(rng), u(rng));
      if (amips(a, b, c) > 20) continue;  // well-shaped and counter-clockwise only
      const Vec2 sa = a * scale, sb = b * scale, sc = c * scale;
      const auto d = amips_derivatives(sa, sb, sc);
      EXPECT_NEAR(d.energy, amips(sa, sb, sc), 1e-12 * d.energy);
      const double h = 1e-5 * scale;
      for (int i = 0; i < 2; ++i) {
        Vec2 dx = Vec2::Zero();
        dx[i] = h;
        const double fd = (amips(sa + dx, sb, sc) - amips(sa - dx, sb, sc)) / (2 * h);
        EXPECT_NEAR(d.gradient[i], fd, 1e-5 * (std::abs(fd) + d.energy / scale));
        const Vec2 gfd = (amips_derivatives(sa + dx, sb, sc).gradient - amips_derivatives(sa - dx, sb, sc).gradient) / (2 * h);
        for (int j = 0; j < 2; ++j)
          EXPECT_NEAR(d.hessian(j, i), gfd[j], 1e-5 * (std::abs(gfd[j]) + d.energy / (scale * scale)));
      }
      ++tested;
    }
  EXPECT_GT(tested, 100);
}

TEST(Amips, EquilateralVertexIsAMinimiser) {
  const Vec2 b(1, 0), c(0.5, std::sqrt(3.0) / 2);
  const auto d = amips_derivatives(Vec2(0, 0), b, c);
  EXPECT_NEAR(d.gradient.norm(), 0, 1e-12);
  // Positive definite there.
  EXPECT_GT(d.hessian.determinant(), 0);
  EXPECT_GT(d.hessian.trace(), 0);
}

TEST(Amips, AlongCurveMatchesFiniteDifferences) {
  const Vec2 b(1, 0.1), c(0.4, 0.9);
  // The parabola a(t) = (0.1 + t, 0.2 t²) passes through the vertex at t = 0.05.
  const auto at = [](double t) { return Vec2(0.1 + t, 0.2 * t * t); };
  const double t = 0.05, h = 1e-5;
  const auto g = along_curve(amips_derivatives(at(t), b, c), Vec2(1, 0.4 * t), Vec2(0, 0.4));
  const double e0 = amips(at(t - h), b, c), e1 = amips(at(t), b, c), e2 = amips(at(t + h), b, c);
  EXPECT_NEAR(g.energy, e1, 1e-14);
  EXPECT_NEAR(g.first, (e2 - e0) / (2 * h), 1e-6);
  EXPECT_NEAR(g.second, (e2 - 2 * e1 + e0) / (h * h), 1e-3);
}

TEST(Amips, SumsAccumulate) {
  AmipsDerivatives s;
  s += amips_derivatives(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  s += amips_derivatives(Vec2(0, 0), Vec2(0, 1), Vec2(-1, 0));
  EXPECT_NEAR(s.energy, 8 / std::sqrt(3.0), 1e-13);
}

TEST(MinAngle, KnownTriangles) {
  EXPECT_NEAR(min_angle(Vec2(0, 0), Vec2(1, 0), Vec2(0.5, std::sqrt(3.0) / 2)), M_PI / 3, 1e-14);
  EXPECT_NEAR(min_angle(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)), M_PI / 4, 1e-14);
  EXPECT_NEAR(min_angle(Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)), M_PI / 4, 1e-14);  // clockwise
  const double ten = M_PI / 18;  // an isosceles triangle with a 20° apex
  EXPECT_NEAR(min_angle(Vec2(0, 0), Vec2(std::cos(ten), -std::sin(ten)), Vec2(std::cos(ten), std::sin(ten))), M_PI / 9, 1e-12);
  EXPECT_EQ(min_angle(Vec2(0, 0), Vec2(1, 1), Vec2(2, 2)), 0.0);
}

// min_angle measures only the angle opposite the shortest side: it must be the least of all three.
TEST(MinAngle, IsTheLeastOfTheThreeAngles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto angle = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // at p, by the law of cosines
    const double a = (q - r).norm(), b = (p - r).norm(), c = (p - q).norm();
    return std::acos(std::clamp((b * b + c * c - a * a) / (2 * b * c), -1.0, 1.0));
  };
  for (int trial = 0; trial < 10000; ++trial) {
    const Vec2 a(u(rng), u(rng)), b(u(rng), u(rng)), c(trial % 3 ? Vec2(u(rng), u(rng)) : Vec2(a + 1e-3 * (b - a) + Vec2(0, 1e-9)));
    const double expected = std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
    EXPECT_NEAR(min_angle(a, b, c), expected, 1e-6) << "trial " << trial;
  }
}

}  // namespace
}  // namespace curvemesh::geometry
