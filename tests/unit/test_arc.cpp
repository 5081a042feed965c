// Arcs to cubics: the error identity behind the construction's bound, the number of pieces the
// bound asks for, and every piece of circles, ellipses, rounded rects and SVG arcs within
// kArcTolerance of its conic — proved exactly (GMP) where the conic's equation has rational
// coefficients (axis-aligned ellipses), by dense sampling everywhere; endpoints exactly where the
// SVG spec puts them, pieces joined tangent-continuously.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "svg/arc.hpp"
#include "svg/shapes.hpp"

using namespace curvemesh::svg;
using curvemesh::geometry::CubicBezier;
using curvemesh::geometry::Vec2;

namespace {

constexpr double kPi = std::numbers::pi;

struct Ellipse {
  Vec2 c;
  double rx, ry, phi = 0;  // phi: rotation of the x axis, radians
};

long double point_on_piece_error(const CubicBezier& b, long double t, const Ellipse& e) {
  // The piece evaluated in long double from its (double) control points.
  const long double s = 1 - t;
  const long double w[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
  long double x = 0, y = 0;
  for (int i = 0; i < 4; ++i) x += w[i] * b.p[i].x(), y += w[i] * b.p[i].y();
  const long double cp = std::cos((long double)e.phi), sp = std::sin((long double)e.phi);
  const long double dx = x - e.c.x(), dy = y - e.c.y();
  const long double u = (cp * dx + sp * dy) / e.rx, v = (-sp * dx + cp * dy) / e.ry;
  return std::abs(std::sqrt(u * u + v * v) - 1.0L);
}

// The largest radial error over 2001 parameters of each piece.
long double sampled_error(const std::vector<CubicBezier>& pieces, const Ellipse& e) {
  long double worst = 0;
  for (const CubicBezier& b : pieces)
    for (int k = 0; k <= 2000; ++k) worst = std::max(worst, point_on_piece_error(b, k / 2000.0L, e));
  return worst;
}

// ---- Exact: f(t) = ((x(t) − cx)/rx)² + ((y(t) − cy)/ry)² − 1 as a Bernstein polynomial of
// degree 6 in rationals (the doubles taken exactly). |q| − 1 ∈ [−tol, tol] is
// f ∈ [(1 − tol)² − 1, (1 + tol)² − 1]; Bernstein coefficients bound the polynomial on [0, 1]
// (convex hull), and halving (de Casteljau) tightens them until they prove it.
using Poly6 = std::array<mpq_class, 7>;

Poly6 square(const std::array<mpq_class, 4>& a) {
  static constexpr int kC3[4] = {1, 3, 3, 1};
  static constexpr int kC6[7] = {1, 6, 15, 20, 15, 6, 1};
  Poly6 out;
  for (auto& q : out) q = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i + j] += mpq_class(kC3[i] * kC3[j], kC6[i + j]) * a[i] * a[j];
  return out;
}

Poly6 conic_polynomial(const CubicBezier& b, const Ellipse& e) {
  std::array<mpq_class, 4> x, y;
  for (int i = 0; i < 4; ++i) {
    x[i] = (mpq_class(b.p[i].x()) - mpq_class(e.c.x())) / mpq_class(e.rx);
    y[i] = (mpq_class(b.p[i].y()) - mpq_class(e.c.y())) / mpq_class(e.ry);
  }
  Poly6 f = square(x), g = square(y);
  for (int k = 0; k <= 6; ++k) f[k] += g[k] - 1;  // the Bernstein basis sums to 1
  return f;
}

std::pair<Poly6, Poly6> halve(Poly6 f) {
  Poly6 left, right;
  for (int level = 0; level <= 6; ++level) {
    left[level] = f[0];
    right[6 - level] = f[6 - level];
    for (int k = 0; k < 6 - level; ++k) f[k] = (f[k] + f[k + 1]) / 2;
  }
  return {left, right};
}

bool proved_within(const Poly6& f, const mpq_class& lo, const mpq_class& hi, int depth) {
  bool all = true;
  for (const mpq_class& q : f) all = all && q >= lo && q <= hi;
  if (all) return true;
  if (depth == 0 || f[0] < lo || f[0] > hi || f[6] < lo || f[6] > hi) return false;  // the ends are values
  const auto [left, right] = halve(f);
  return proved_within(left, lo, hi, depth - 1) && proved_within(right, lo, hi, depth - 1);
}

// Every piece within kArcTolerance of the axis-aligned ellipse e, proved in rationals.
void expect_proved_on_ellipse(const std::vector<CubicBezier>& pieces, const Ellipse& e) {
  const mpq_class tol(1, 1000000000);
  static_assert(kArcTolerance == 1e-9);
  const mpq_class lo = (1 - tol) * (1 - tol) - 1, hi = (1 + tol) * (1 + tol) - 1;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    EXPECT_TRUE(proved_within(conic_polynomial(pieces[i], e), lo, hi, 12)) << "piece " << i;
}

// Consecutive pieces share their endpoint exactly and leave it along one line, the same way.
void expect_joined_tangentially(const std::vector<CubicBezier>& pieces) {
  for (std::size_t i = 1; i < pieces.size(); ++i) {
    const CubicBezier &a = pieces[i - 1], &b = pieces[i];
    EXPECT_EQ(a.p[3], b.p[0]) << i;
    const Vec2 in = a.p[3] - a.p[2], out = b.p[1] - b.p[0];
    const double sine = (in.x() * out.y() - in.y() * out.x()) / (in.norm() * out.norm());
    EXPECT_LE(std::abs(sine), 1e-14) << i;
    EXPECT_GT(in.dot(out), 0) << i;
  }
}

std::vector<CubicBezier> segments_of(const std::vector<Subpath>& subpaths) {
  EXPECT_EQ(subpaths.size(), 1u);
  return subpaths.empty() ? std::vector<CubicBezier>{} : subpaths[0].segments;
}

// Sweep of a piece seen from the centre (radians, signed).
double sweep_of(const CubicBezier& c, const Vec2& centre) {
  const Vec2 a = c.p[0] - centre, b = c.p[3] - centre;
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

}  // namespace

// The identity the bound rests on (arc.cpp): |B(t)|² − 1 = 16 sin⁶(θ/4)/cos²(θ/4)·t²(1−t)²(1−2t)²
// for the unit circle's cubic of angle θ, and the largest radial error is the stated bound to
// within its last step (√(1 + x) − 1 ≤ x/2).
TEST(Arc, ErrorIdentityAndBound) {
  for (const double degrees : {8.0, 11.0, 30.0, 90.0, 120.0, 180.0}) {
    const double theta = degrees * kPi / 180, h = theta / 2;
    const double k = 4.0 / 3.0 * std::tan(theta / 4);
    const Vec2 p0(std::cos(h), -std::sin(h)), p3(std::cos(h), std::sin(h));
    const CubicBezier b(p0, p0 + k * Vec2(std::sin(h), std::cos(h)), p3 + k * Vec2(std::sin(h), -std::cos(h)), p3);
    const double s = std::sin(theta / 4), c = std::cos(theta / 4);
    const double scale = 16 * std::pow(s, 6) / (c * c);
    long double worst = 0;
    for (int i = 0; i <= 4000; ++i) {
      const long double t = i / 4000.0L;
      const long double u = 1 - t;
      const long double w[4] = {u * u * u, 3 * u * u * t, 3 * u * t * t, t * t * t};
      long double x = 0, y = 0;
      for (int j = 0; j < 4; ++j) x += w[j] * b.p[j].x(), y += w[j] * b.p[j].y();
      const long double identity = scale * t * t * u * u * (1 - 2 * t) * (1 - 2 * t);
      EXPECT_NEAR(double(x * x + y * y - 1), double(identity), 1e-6 * scale / 108 + 1e-15) << degrees << "° t " << double(t);
      worst = std::max(worst, std::abs(std::sqrt(x * x + y * y) - 1));
    }
    EXPECT_LE(double(worst), arc_cubic_error(theta)) << degrees;
    EXPECT_GE(double(worst), (1 - 2e-5) * arc_cubic_error(theta) * (1 - arc_cubic_error(theta))) << degrees;
  }
  EXPECT_NEAR(arc_cubic_error(kPi / 2), 2.7257e-4, 1e-8);  // the classic quarter's error
}

TEST(Arc, PieceCountIsTheFewestWithinTheTolerance) {
  EXPECT_EQ(arc_piece_count(2 * kPi), 33);
  EXPECT_EQ(arc_piece_count(-2 * kPi), 33);
  EXPECT_EQ(arc_piece_count(kPi / 2), 9);
  EXPECT_EQ(arc_piece_count(1e-3), 1);
  EXPECT_EQ(arc_piece_count(0), 1);
  for (int i = 1; i <= 1000; ++i) {
    const double sweep = 2 * kPi * i / 1000;
    const int n = arc_piece_count(sweep);
    EXPECT_LE(arc_cubic_error(sweep / n), kArcTolerance) << sweep;
    if (n > 1) {
      EXPECT_GT(arc_cubic_error(sweep / (n - 1)), kArcTolerance) << sweep;
    }
  }
}

TEST(Arc, CircleIsWithinTheToleranceEndsOnItsAxesAndCloses) {
  const Ellipse e{{5, 5}, 2, 2};
  const std::vector<Subpath> subpaths = ellipse_subpaths(5, 5, 2, 2);
  const std::vector<CubicBezier> pieces = segments_of(subpaths);
  ASSERT_EQ(pieces.size(), 36u);  // four quarters of nine pieces
  ASSERT_TRUE(subpaths[0].closed);
  EXPECT_EQ(subpaths[0].start, Vec2(7, 5));
  // SVG 2 §10.4: from (cx + r, cy) through (cx, cy + r), (cx − r, cy), (cx, cy − r), back to the start.
  EXPECT_EQ(pieces[0].p[0], Vec2(7, 5));
  EXPECT_EQ(pieces[9].p[0], Vec2(5, 7));
  EXPECT_EQ(pieces[18].p[0], Vec2(3, 5));
  EXPECT_EQ(pieces[27].p[0], Vec2(5, 3));
  EXPECT_EQ(pieces.back().p[3], subpaths[0].start);
  expect_joined_tangentially(pieces);
  expect_proved_on_ellipse(pieces, e);
  const long double worst = sampled_error(pieces, e);
  EXPECT_LE(worst, kArcTolerance);
  EXPECT_NEAR(double(worst), arc_cubic_error(kPi / 18), 1e-3 * arc_cubic_error(kPi / 18));  // 10° pieces
  for (const CubicBezier& b : pieces) EXPECT_NEAR(sweep_of(b, e.c), kPi / 18, 1e-12);  // clockwise on screen
}

TEST(Arc, EllipsesOfHighEccentricity) {
  for (const Ellipse& e : {Ellipse{{0, 0}, 1000, 0.5}, Ellipse{{-3, 7}, 1e-3, 10}, Ellipse{{1e3, -1e3}, 250, 1}}) {
    const std::vector<Subpath> subpaths = ellipse_subpaths(e.c.x(), e.c.y(), e.rx, e.ry);
    const std::vector<CubicBezier> pieces = segments_of(subpaths);
    ASSERT_EQ(pieces.size(), 36u);
    EXPECT_EQ(pieces[9].p[0], Vec2(e.c.x(), e.c.y() + e.ry));
    EXPECT_EQ(pieces[18].p[0], Vec2(e.c.x() - e.rx, e.c.y()));
    EXPECT_EQ(pieces.back().p[3], subpaths[0].start);
    expect_joined_tangentially(pieces);
    expect_proved_on_ellipse(pieces, e);
    EXPECT_LE(sampled_error(pieces, e), kArcTolerance);
  }
}

TEST(Arc, RoundedRectCornersAreQuarterEllipsesBetweenExactSides) {
  // Sides of length 4 and 1, corners of radii 3 and 1.5.
  const double x = 1, y = 2, w = 10, h = 4, rx = 3, ry = 1.5;
  const std::vector<CubicBezier> s = segments_of(rect_subpaths(x, y, w, h, rx, ry));
  ASSERT_EQ(s.size(), 4u + 36u);
  const Ellipse corners[4] = {{{x + w - rx, y + ry}, rx, ry}, {{x + w - rx, y + h - ry}, rx, ry},
                              {{x + rx, y + h - ry}, rx, ry}, {{x + rx, y + ry}, rx, ry}};
  // SVG 2 §10.2: from (x + rx, y), a side, then each corner's arc between the sides' ends.
  const Vec2 side_ends[4][2] = {{{x + rx, y}, {x + w - rx, y}},
                                {{x + w, y + ry}, {x + w, y + h - ry}},
                                {{x + w - rx, y + h}, {x + rx, y + h}},
                                {{x, y + h - ry}, {x, y + ry}}};
  for (int i = 0; i < 4; ++i) {
    const CubicBezier& side = s[10 * i];
    EXPECT_EQ(side.p[0], side_ends[i][0]) << i;
    EXPECT_EQ(side.p[3], side_ends[i][1]) << i;
    const std::vector<CubicBezier> arc(s.begin() + 10 * i + 1, s.begin() + 10 * i + 10);
    EXPECT_EQ(arc.front().p[0], side_ends[i][1]) << i;
    EXPECT_EQ(arc.back().p[3], side_ends[(i + 1) % 4][0]) << i;
    expect_joined_tangentially(arc);
    expect_proved_on_ellipse(arc, corners[i]);
    EXPECT_LE(sampled_error(arc, corners[i]), kArcTolerance);
  }
  EXPECT_EQ(s.back().p[3], s.front().p[0]);  // closed exactly
  // The sides leave the corners along the arcs' tangents.
  expect_joined_tangentially(s);
}

TEST(Arc, RoundedRectWithoutSidesHasNoSegmentOfRoundOffLength) {
  // rx = w/2 and ry = h/2 leave no straight side: the outline is an ellipse of four corner arcs,
  // whatever x + w − rx rounds to (0.1 + 0.7 − 0.35 is not 0.1 + 0.35 in doubles).
  const double x = 0.1, y = 0.3, w = 0.7, h = 0.9;
  const std::vector<Subpath> subpaths = rect_subpaths(x, y, w, h, 0.35, 0.45);
  const std::vector<CubicBezier> s = segments_of(subpaths);
  ASSERT_EQ(s.size(), 36u);
  expect_joined_tangentially(s);
  EXPECT_EQ(s.back().p[3], subpaths[0].start);
  // Radii larger than half the sides are clamped to them (§9.2).
  EXPECT_EQ(segments_of(rect_subpaths(x, y, w, h, 5, 5)).size(), 36u);
}

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
    ASSERT_EQ(static_cast<int>(pieces.size()), arc_piece_count(k.sweep_deg * kPi / 180));
    EXPECT_EQ(pieces.front().p[0], from);
    EXPECT_EQ(pieces.back().p[3], to);
    expect_joined_tangentially(pieces);
    EXPECT_LE(sampled_error(pieces, {k.centre, 2, 2}), kArcTolerance);
    double total = 0;
    for (const auto& p : pieces) total += sweep_of(p, k.centre);
    EXPECT_NEAR(total * 180 / kPi, k.sweep_deg, 1e-9) << "large " << k.large << " sweep " << k.sweep;
  }
}

TEST(Arc, RotatedEllipticArcs) {
  // Radii 5 and 0.05, rotated 30°, centred at (10, 10): from its point at parameter 0.3 to the one
  // at 0.1, all four ways. Two of them run on this ellipse; the other two on its reflection
  // through the chord's midpoint (same radii and rotation, centre from + to − c).
  const Ellipse e{{10, 10}, 5, 0.05, 30 * kPi / 180};
  auto at = [&](double t) {
    const double x = e.rx * std::cos(t), y = e.ry * std::sin(t);
    return Vec2(e.c.x() + std::cos(e.phi) * x - std::sin(e.phi) * y, e.c.y() + std::sin(e.phi) * x + std::cos(e.phi) * y);
  };
  const Vec2 from = at(0.3), to = at(0.1);
  for (const bool large : {false, true})
    for (const bool sweep : {false, true}) {
      const auto pieces = arc_to_cubics(from, e.rx, e.ry, 30, large, sweep, to);
      const double swept = large ? 2 * kPi - 0.2 : 0.2;  // of the ellipse's parameter
      EXPECT_EQ(static_cast<int>(pieces.size()), arc_piece_count(swept)) << large << sweep;
      EXPECT_EQ(pieces.front().p[0], from);
      EXPECT_EQ(pieces.back().p[3], to);
      expect_joined_tangentially(pieces);
      Ellipse on = e;
      if (large != sweep) on.c = from + to - e.c;
      // The centre is recomputed from the endpoints (F.6.5): the ellipse is the arc's to round-off.
      EXPECT_LE(sampled_error(pieces, on), kArcTolerance + 1e-13) << large << sweep;
    }
}

TEST(Arc, RadiiTooSmallAreScaledUp) {
  // Radius 1 cannot join points 4 apart: scaled to 2, the arc is a half circle centred at (2,0).
  const auto pieces = arc_to_cubics({0, 0}, 1, 1, 0, false, true, {4, 0});
  EXPECT_EQ(static_cast<int>(pieces.size()), arc_piece_count(kPi));
  EXPECT_LE(sampled_error(pieces, {{2, 0}, 2, 2}), kArcTolerance);
  // Negative radii are taken as their absolute values.
  const auto neg = arc_to_cubics({0, 0}, -1, -1, 0, false, true, {4, 0});
  ASSERT_EQ(neg.size(), pieces.size());
  for (std::size_t i = 0; i < neg.size(); ++i) EXPECT_EQ(neg[i].p[3], pieces[i].p[3]);
}

TEST(Arc, Degenerate) {
  EXPECT_TRUE(arc_to_cubics({1, 1}, 3, 3, 0, false, true, {1, 1}).empty());  // same endpoints
  const auto line = arc_to_cubics({0, 0}, 0, 3, 0, false, true, {3, 0});        // a zero radius
  ASSERT_EQ(line.size(), 1u);
  EXPECT_EQ(line[0].p[1], Vec2(1, 0));
  EXPECT_EQ(line[0].p[2], Vec2(2, 0));
}

// Round-off kinks are ruled out, not only bounded: at every joint the control arm into it and the
// arm out of it are parallel as doubles (their cross product exactly 0), wherever the arc lies
// (far from the origin, rotated, very eccentric), so that no later stage sees a corner there.
TEST(Arc, ArmsAtJointsAreExactlyOpposite) {
  int joints = 0;
  for (int i = 0; i < 200; ++i) {
    const double cx = std::ldexp(1.0 + 0.37 * i, i % 20), cy = -0.7 * cx;
    const double rx = std::ldexp(1.3 + 0.01 * i, (7 * i) % 30 - 15), ry = rx * std::ldexp(1.1, (3 * i) % 20 - 10);
    std::vector<std::vector<CubicBezier>> arcs;
    arcs.push_back(segments_of(ellipse_subpaths(cx, cy, rx, ry)));
    arcs.push_back(arc_to_cubics({cx, cy}, rx, ry, 0.77 * i, i % 2, i % 3 == 0, {cx + 0.3 * rx, cy - 0.2 * ry}));
    for (const auto& pieces : arcs)
      for (std::size_t k = 1; k < pieces.size(); ++k, ++joints) {
        ASSERT_EQ(pieces[k - 1].p[3], pieces[k].p[0]);
        const Vec2 in = pieces[k - 1].p[3] - pieces[k - 1].p[2], out = pieces[k].p[1] - pieces[k].p[0];
        ASSERT_EQ(in.x() * out.y(), in.y() * out.x()) << i << " joint " << k;
        ASSERT_GT(in.dot(out), 0) << i << " joint " << k;
      }
  }
  EXPECT_GT(joints, 200 * 35);
}
