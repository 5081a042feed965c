// Arcs to cubics: the four flag combinations, radius correction, degenerate cases, and the
// stated error bound checked by dense sampling against the analytic ellipse.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "svg/arc.hpp"

using namespace curvemesh::svg;
using curvemesh::geometry::CubicBezier;
using curvemesh::geometry::Vec2;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kStatedBound = 2.8e-4;  // arc.hpp: times max(rx, ry)

// Radial error of a point against the ellipse (centre c, radii rx, ry, rotation phi): | |q| - 1 |
// for q the point in the ellipse's unit-circle frame. The distance to the ellipse is at most this
// times max(rx, ry), so checking it against the stated bound checks the bound.
double radial_error(const Vec2& p, const Vec2& c, double rx, double ry, double phi) {
  const Vec2 d = p - c;
  const double x = (std::cos(phi) * d.x() + std::sin(phi) * d.y()) / rx;
  const double y = (-std::sin(phi) * d.x() + std::cos(phi) * d.y()) / ry;
  return std::abs(std::hypot(x, y) - 1.0);
}

// Sweep of a piece seen from the centre (radians, signed).
double sweep_of(const CubicBezier& c, const Vec2& centre) {
  const Vec2 a = c.p[0] - centre, b = c.p[3] - centre;
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

void check_on_ellipse(const std::vector<CubicBezier>& pieces, const Vec2& c, double rx, double ry, double phi) {
  for (const CubicBezier& piece : pieces)
    for (int k = 0; k <= 200; ++k)
      EXPECT_LE(radial_error(piece.eval(k / 200.0), c, rx, ry, phi), kStatedBound);
  for (std::size_t i = 1; i < pieces.size(); ++i) EXPECT_EQ(pieces[i - 1].p[3], pieces[i].p[0]);
}

}  // namespace

TEST(Arc, FourFlagCombinations) {
  // From (0,0) to (2,0) with r = 2: centres at (1, ±√3); small arcs sweep 60°, large ones 300°.
  const Vec2 from(0, 0), to(2, 0);
  const double h = std::sqrt(3.0);
  struct Case {
    bool large, sweep;
    Vec2 centre;
    double sweep_deg;
  };
  const Case cases[] = {{false, true, {1, h}, 60}, {false, false, {1, -h}, -60},
                        {true, true, {1, -h}, 300}, {true, false, {1, h}, -300}};
  for (const Case& k : cases) {
    const auto pieces = arc_to_cubics(from, 2, 2, 0, k.large, k.sweep, to);
    ASSERT_FALSE(pieces.empty());
    EXPECT_EQ(pieces.front().p[0], from);
    EXPECT_EQ(pieces.back().p[3], to);
    check_on_ellipse(pieces, k.centre, 2, 2, 0);
    double total = 0;
    for (const auto& p : pieces) {
      const double s = sweep_of(p, k.centre);
      EXPECT_LE(std::abs(s), kPi / 2 + 1e-9);  // pieces of at most 90°
      total += s;
    }
    EXPECT_NEAR(total * 180 / kPi, k.sweep_deg, 1e-9) << "large " << k.large << " sweep " << k.sweep;
    EXPECT_EQ(pieces.size(), static_cast<std::size_t>(std::ceil(std::abs(k.sweep_deg) / 90 - 1e-9)));
  }
}

TEST(Arc, ExactQuarterIsOnePiece) {
  const auto pieces = arc_to_cubics({1, 0}, 1, 1, 0, false, true, {0, 1});
  ASSERT_EQ(pieces.size(), 1u);
  check_on_ellipse(pieces, {0, 0}, 1, 1, 0);
  // The classic control arm 4/3 (√2 − 1).
  EXPECT_NEAR(pieces[0].p[1].y(), 4.0 / 3.0 * (std::sqrt(2.0) - 1.0), 1e-12);
}

TEST(Arc, RotatedEllipse) {
  // An ellipse with radii 5 and 2, rotated 30°, centred at (10, 10): go between two of its points.
  const double phi = 30 * kPi / 180, rx = 5, ry = 2;
  const Vec2 c(10, 10);
  auto at = [&](double t) {
    const double x = rx * std::cos(t), y = ry * std::sin(t);
    return Vec2(c.x() + std::cos(phi) * x - std::sin(phi) * y, c.y() + std::sin(phi) * x + std::cos(phi) * y);
  };
  const auto pieces = arc_to_cubics(at(0.3), rx, ry, 30, true, true, at(0.1));
  EXPECT_EQ(pieces.size(), 4u);  // 360° − 11.5° in pieces of ≤ 90°
  check_on_ellipse(pieces, c, rx, ry, phi);
}

TEST(Arc, RadiiTooSmallAreScaledUp) {
  // Radius 1 cannot join points 4 apart: scaled to 2, the arc is a half circle centred at (2,0).
  const auto pieces = arc_to_cubics({0, 0}, 1, 1, 0, false, true, {4, 0});
  EXPECT_EQ(pieces.size(), 2u);
  check_on_ellipse(pieces, {2, 0}, 2, 2, 0);
  // Negative radii are taken as their absolute values.
  const auto neg = arc_to_cubics({0, 0}, -1, -1, 0, false, true, {4, 0});
  ASSERT_EQ(neg.size(), 2u);
  EXPECT_NEAR((neg[0].p[3] - pieces[0].p[3]).norm(), 0, 1e-12);
}

TEST(Arc, Degenerate) {
  EXPECT_TRUE(arc_to_cubics({1, 1}, 3, 3, 0, false, true, {1, 1}).empty());  // same endpoints
  const auto line = arc_to_cubics({0, 0}, 0, 3, 0, false, true, {3, 0});        // a zero radius
  ASSERT_EQ(line.size(), 1u);
  EXPECT_EQ(line[0].p[1], Vec2(1, 0));
  EXPECT_EQ(line[0].p[2], Vec2(2, 0));
}

TEST(Arc, BoundIsTight) {
  // The stated bound is a true bound, and not a loose one: a 90° piece nearly reaches it.
  const auto pieces = arc_to_cubics({1, 0}, 1, 1, 0, false, true, {0, 1});
  double worst = 0;
  for (int k = 0; k <= 10000; ++k) worst = std::max(worst, radial_error(pieces[0].eval(k / 1e4), {0, 0}, 1, 1, 0));
  EXPECT_LE(worst, kStatedBound);
  EXPECT_GE(worst, 0.9 * kStatedBound);
}
