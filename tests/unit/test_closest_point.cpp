// Closest point on a cubic (paper App. B) against brute force on random curves and points.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <random>
#include <vector>

#include "geometry/closest_point.hpp"

using namespace curvemesh::geometry;

namespace {

// Dense sampling, then golden-section refinement around every sampled local minimum: an upper
// bound on the true distance that is independent of the code under test.
double brute_force_distance(const CubicBezier& c, const Vec2& p) {
  constexpr int n = 4000;
  std::vector<double> d(n + 1);
  for (int i = 0; i <= n; ++i) d[i] = (c.eval(double(i) / n) - p).norm();
  double best = *std::min_element(d.begin(), d.end());
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i <= n; ++i) {
    if ((i > 0 && d[i] > d[i - 1]) || (i < n && d[i] > d[i + 1])) continue;
    double lo = std::max(0.0, (i - 1.0) / n), hi = std::min(1.0, (i + 1.0) / n);
    for (int it = 0; it < 60; ++it) {
      const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
      if ((c.eval(a) - p).norm() < (c.eval(b) - p).norm()) hi = b;
      else lo = a;
    }
    best = std::min(best, (c.eval(0.5 * (lo + hi)) - p).norm());
  }
  return best;
}

}  // namespace

TEST(ClosestPoint, RandomQueriesAgainstBruteForce) {
  std::mt19937_64 rng(20191107);
  std::uniform_real_distribution<double> u(0.0, 1.0), q(-0.5, 1.5);
  int worse = 0;
  double worst = 0;
  for (int i = 0; i < 10000; ++i) {
    const CubicBezier c({u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)});
    const Vec2 p(q(rng), q(rng));
    Box2 box = c.bounds();
    box.add(p);
    const double d = box.diagonal();
    const ClosestPoint cp = closest_point(c, p);
    ASSERT_GE(cp.t, 0.0);
    ASSERT_LE(cp.t, 1.0);
    EXPECT_NEAR((c.eval(cp.t) - cp.point).norm(), 0.0, 1e-14);
    EXPECT_NEAR((cp.point - p).norm(), cp.distance, 1e-14);
    const double excess = cp.distance - brute_force_distance(c, p);
    worst = std::max(worst, excess / d);
    worse += excess > 1e-9 * d;
  }
  EXPECT_EQ(worse, 0) << "worst excess over brute force: " << worst << " d";
}

TEST(ClosestPoint, Endpoints) {
  const CubicBezier c({0, 0}, {1, 1}, {2, 1}, {3, 0});
  const ClosestPoint a = closest_point(c, {-1, -1});
  EXPECT_EQ(a.t, 0.0);
  EXPECT_NEAR(a.distance, std::sqrt(2.0), 1e-15);
  const ClosestPoint b = closest_point(c, {4, -1});
  EXPECT_EQ(b.t, 1.0);
  const ClosestPoint on = closest_point(c, c.eval(0.3));
  EXPECT_NEAR(on.t, 0.3, 1e-9);
  EXPECT_NEAR(on.distance, 0, 1e-12);
}

TEST(ClosestPoint, CuspStraightDegenerateAndFar) {
  const CubicBezier cusp({0, 0}, {1, 1}, {0, 1}, {1, 0});  // cusp at t = 1/2, at (0.5, 0.75)
  const ClosestPoint c = closest_point(cusp, {0.5, 0.9});
  EXPECT_NEAR(c.t, 0.5, 1e-6);
  EXPECT_NEAR(c.distance, brute_force_distance(cusp, {0.5, 0.9}), 1e-12);
  const CubicBezier line = CubicBezier::line({0, 0}, {4, 0});
  const ClosestPoint l = closest_point(line, {1, 3});
  EXPECT_NEAR(l.t, 0.25, 1e-12);
  EXPECT_NEAR(l.distance, 3, 1e-12);
  const CubicBezier dot({2, 2}, {2, 2}, {2, 2}, {2, 2});
  const ClosestPoint d = closest_point(dot, {5, 6});
  EXPECT_NEAR(d.distance, 5, 1e-12);
  const ClosestPoint far = closest_point(cusp, {1e6, -1e6});
  EXPECT_NEAR(far.distance, brute_force_distance(cusp, {1e6, -1e6}), 1e-6);
  EXPECT_TRUE(std::isfinite(far.t));
}
