// SVG elliptical arcs to cubics (SVG 1.1 Appendix F.6).
#include "svg/arc.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace curvemesh::svg {

using geometry::CubicBezier;
using geometry::Vec2;

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

  // Pieces of at most 90°; the small slack keeps an exact quarter from becoming two pieces.
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(delta) / (std::numbers::pi / 2) - 1e-9)));
  const double step = delta / n;
  const double k = 4.0 / 3.0 * std::tan(step / 4);
  // Maps a point of the unit circle frame to user space.
  auto map = [&](double px, double py) {
    const double ex = rx * px, ey = ry * py;
    return Vec2(cos_phi * ex - sin_phi * ey + centre.x(), sin_phi * ex + cos_phi * ey + centre.y());
  };
  std::vector<CubicBezier> out;
  out.reserve(n);
  Vec2 start = from;
  for (int i = 0; i < n; ++i) {
    const double a0 = theta1 + i * step, a1 = a0 + step;
    const double c0 = std::cos(a0), s0 = std::sin(a0), c1 = std::cos(a1), s1 = std::sin(a1);
    const Vec2 end = i + 1 == n ? to : map(c1, s1);  // the last piece ends exactly at `to`
    out.emplace_back(start, map(c0 - k * s0, s0 + k * c0), map(c1 + k * s1, s1 - k * c1), end);
    start = end;
  }
  return out;
}

}  // namespace curvemesh::svg
