// SVG elliptical arcs to cubics (SVG 1.1 Appendix F.6), each piece within kArcTolerance.
#include "svg/arc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace curvemesh::svg {

using geometry::CubicBezier;
using geometry::Vec2;

namespace {

constexpr double kHalfPi = std::numbers::pi / 2;

// (cos a, sin a), reduced by the nearest multiple q of π/2 first, so that it is exactly an axis
// direction at a = q·(π/2) as doubles compute it: there (a circle's extreme points, a rounded
// rect's sides) the tangent is exactly along the other axis and the join with the next quarter
// or with a straight side has no round-off angle at all.
Vec2 unit_point(double a) {
  const double q = std::round(a / kHalfPi);
  const double multiple = q * kHalfPi;
  const double r = a == multiple ? 0.0 : a - multiple;
  const double c = std::cos(r), s = std::sin(r);
  switch (((static_cast<long long>(q) % 4) + 4) % 4) {
    case 0: return {c, s};
    case 1: return {-s, c};
    case 2: return {-c, -s};
    default: return {s, -c};
  }
}

// Moves one coordinate of an interior joint p, and of the control arm d the two pieces meeting
// there share, onto the grid of g = 2·ulp(|p| + |d|): then p − d and p + d are doubles exactly,
// so the arm out of the joint and the arm into it are both exactly d as doubles — a tangent-
// continuous joint without even a round-off kink, which the features stage sees as one smooth
// curve. Moves p by at most ulp(|p| + |d|), far below kArcTolerance.
void snap_joint(double& p, double& d) {
  const double m = std::abs(p) + std::abs(d);
  if (!std::isfinite(m) || m == 0) return;
  const double g = std::ldexp(1.0, std::ilogb(m) - 51);
  if (!std::isnormal(g)) return;  // a joint of subnormal size: nothing to gain
  p = g * std::round(p / g);
  d = g * std::round(d / g);
}

}  // namespace

// The unit circle's cubic for the arc from −θ/2 to θ/2, with s = sin(θ/4), c = cos(θ/4), has
//   |B(t)|² − 1 = 16·s⁶/c² · t²(1−t)²(1−2t)²
// (expand B with the control arm k = 4/3·tan(θ/4)). It is ≥ 0: the cubic runs outside the circle
// and touches it at t = 0, 1/2, 1. t²(1−t)²(1−2t)² = u²(1 − 4u) with u = t(1−t) peaks at u = 1/6
// at 1/108, so |B|² − 1 ≤ 4s⁶/(27c²), and |B| − 1 ≤ (|B|² − 1)/2 = 2s⁶/(27c²). For small θ that
// is θ⁶/55296, within 1e-9 up to about 11.2° (the tests check the identity and that the bound is
// attained to its last step).
double arc_cubic_error(double theta) {
  const double quarter = std::abs(theta) / 4;
  if (!(quarter < kHalfPi)) return std::numeric_limits<double>::infinity();  // a turn or more, or NaN
  const double s = std::sin(quarter), c = std::cos(quarter);
  const double s2 = s * s;
  return 2 * s2 * s2 * s2 / (27 * c * c);
}

int arc_piece_count(double sweep) {
  const double a = std::abs(sweep);
  if (!(a > 0)) return 1;  // no sweep (or NaN: the caller draws a line)
  // The error grows with the angle: the first guess from its small-angle form θ⁶/55296, then the
  // exact fewest by the closed form itself (a step or two either way at most).
  const double guess = std::pow(55296 * kArcTolerance, 1.0 / 6);
  int n = std::max(1, static_cast<int>(std::ceil(std::min(a, 2 * std::numbers::pi) / guess)));
  while (arc_cubic_error(a / n) > kArcTolerance) ++n;
  while (n > 1 && arc_cubic_error(a / (n - 1)) <= kArcTolerance) --n;
  return n;
}

std::vector<CubicBezier> elliptic_arc_cubics(const EllipticArc& arc, const Vec2& from, const Vec2& to) {
  const double sweep = arc.end - arc.start;
  const int n = arc_piece_count(sweep);
  const double step = sweep / n;
  const double k = 4.0 / 3.0 * std::tan(step / 4);  // the control arm, signed with the step
  // The ellipse's linear part: a vector of the unit circle's frame to user space.
  auto linear = [&](const Vec2& u) {
    const double ex = arc.rx * u.x(), ey = arc.ry * u.y();
    return Vec2(arc.cos_phi * ex - arc.sin_phi * ey, arc.sin_phi * ex + arc.cos_phi * ey);
  };
  // Joint j at the parameter start + j·step, with its control arm k·(tangent): the piece before
  // it ends with joint − arm, the piece after it starts with joint + arm.
  std::vector<Vec2> joint(n + 1), arm(n + 1);
  for (int j = 0; j <= n; ++j) {
    const Vec2 u = unit_point(j == 0 ? arc.start : j == n ? arc.end : arc.start + j * step);
    arm[j] = linear(Vec2(-k * u.y(), k * u.x()));
    if (j == 0 || j == n) {
      joint[j] = j == 0 ? from : to;
    } else {
      joint[j] = arc.centre + linear(u);
      for (int c = 0; c < 2; ++c) snap_joint(joint[j][c], arm[j][c]);
    }
  }
  std::vector<CubicBezier> out;
  out.reserve(n);
  for (int j = 0; j < n; ++j) out.emplace_back(joint[j], joint[j] + arm[j], joint[j + 1] - arm[j + 1], joint[j + 1]);
  return out;
}

std::vector<CubicBezier> arc_to_cubics(const Vec2& from, double rx, double ry, double x_axis_rotation_deg,
                                       bool large_arc, bool sweep, const Vec2& to) {
  if (from == to) return {};  // F.6.2: the arc is omitted
  rx = std::abs(rx);
  ry = std::abs(ry);
  if (rx == 0 || ry == 0) return {CubicBezier::line(from, to)};  // F.6.2: a straight line

  const double phi = x_axis_rotation_deg * std::numbers::pi / 180.0;
  const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
  // F.6.5.1: the midpoint in the ellipse's axes.
  const Vec2 half = (from - to) / 2.0;
  const double x1 = cos_phi * half.x() + sin_phi * half.y();
  const double y1 = -sin_phi * half.x() + cos_phi * half.y();
  // F.6.6.2-3: radii too small to reach are scaled up uniformly.
  const double lambda = (x1 * x1) / (rx * rx) + (y1 * y1) / (ry * ry);
  if (lambda > 1) {
    const double s = std::sqrt(lambda);
    rx *= s;
    ry *= s;
  }
  // F.6.5.2: the centre in the ellipse's axes.
  const double rx2 = rx * rx, ry2 = ry * ry;
  const double num = rx2 * ry2 - rx2 * y1 * y1 - ry2 * x1 * x1;
  const double den = rx2 * y1 * y1 + ry2 * x1 * x1;
  double coef = den > 0 ? std::sqrt(std::max(0.0, num / den)) : 0.0;
  if (large_arc == sweep) coef = -coef;
  const double cxp = coef * rx * y1 / ry, cyp = -coef * ry * x1 / rx;
  // F.6.5.3: the centre in user space.
  const Vec2 mid = (from + to) / 2.0;
  const Vec2 centre(cos_phi * cxp - sin_phi * cyp + mid.x(), sin_phi * cxp + cos_phi * cyp + mid.y());
  // F.6.5.5-6: start angle and sweep on the unit circle.
  auto angle = [](double ux, double uy, double vx, double vy) {
    return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
  };
  const double ux = (x1 - cxp) / rx, uy = (y1 - cyp) / ry;
  const double vx = (-x1 - cxp) / rx, vy = (-y1 - cyp) / ry;
  const double theta1 = angle(1, 0, ux, uy);
  double delta = angle(ux, uy, vx, vy);
  if (!sweep && delta > 0) delta -= 2 * std::numbers::pi;
  if (sweep && delta < 0) delta += 2 * std::numbers::pi;
  if (!std::isfinite(delta) || !std::isfinite(theta1) || !std::isfinite(centre.x()) || !std::isfinite(centre.y()))
    return {CubicBezier::line(from, to)};
  return elliptic_arc_cubics({centre, rx, ry, cos_phi, sin_phi, theta1, theta1 + delta}, from, to);
}

}  // namespace curvemesh::svg
