#include "geometry/bezier_analysis.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace curvemesh::geometry {

namespace {

constexpr double kPi = std::numbers::pi;

// stableNorm: the squares of coordinates near 1e-300 would underflow.
double polygon_size(const CubicBezier& c) {
  return (c.p[1] - c.p[0]).stableNorm() + (c.p[2] - c.p[1]).stableNorm() + (c.p[3] - c.p[2]).stableNorm();
}

// c'(t)/3 = a + 2 b t + c t² in the power basis (a = p1 - p0, b = p2 - 2 p1 + p0, c = ...).
struct Hodograph {
  Vec2 a, b, c;
  explicit Hodograph(const CubicBezier& k)
      : a(k.p[1] - k.p[0]), b(k.p[2] - 2.0 * k.p[1] + k.p[0]), c(k.p[3] - 3.0 * k.p[2] + 3.0 * k.p[1] - k.p[0]) {}
};

// Roots in (0, 1) of q2 t² + q1 t + q0 where the sign changes; |coefficients| ≤ zero count as 0.
std::vector<double> sign_changes(double q2, double q1, double q0, double zero) {
  std::vector<double> roots;
  if (std::abs(q2) <= zero) {
    if (std::abs(q1) > zero) roots.push_back(-q0 / q1);
  } else {
    const double disc = q1 * q1 - 4.0 * q2 * q0;
    if (disc > 0) {  // a double root (disc = 0) is a touch, not a sign change
      const double s = std::sqrt(disc);
      const double q = -0.5 * (q1 + std::copysign(s, q1));
      roots.push_back(q / q2);
      if (q != 0) roots.push_back(q0 / q);
    }
  }
  std::vector<double> inside;
  for (const double t : roots)
    if (std::isfinite(t) && t > 0.0 && t < 1.0) inside.push_back(t);
  std::sort(inside.begin(), inside.end());
  inside.erase(std::unique(inside.begin(), inside.end()), inside.end());
  return inside;
}

// unit_tangent, for callers that have the control polygon's size already.
Vec2 tangent(const CubicBezier& c, double t, double lo, double hi, double size) {
  Vec2 d = c.derivative(t);
  const bool look_above = (t - lo) <= (hi - t);
  for (double step = 1e-9; d.norm() <= 1e-12 * size && step <= 0.5; step *= 10) {
    const double s = look_above ? std::min(hi, t + step * (hi - lo)) : std::max(lo, t - step * (hi - lo));
    d = c.derivative(s);
  }
  const double n = d.norm();
  return n > 0 ? Vec2(d / n) : Vec2(1, 0);
}

double angle_between(const Vec2& u, const Vec2& v) { return std::abs(std::atan2(cross(u, v), u.dot(v))); }

}  // namespace

Vec2 unit_tangent(const CubicBezier& c, double t, double lo, double hi) {
  return tangent(c, t, lo, hi, polygon_size(c));
}

Vec2 unit_tangent(const CubicBezier& c, double t, double lo, double hi, double size) {
  return tangent(c, t, lo, hi, size);
}

double control_polygon_size(const CubicBezier& c) { return polygon_size(c); }

std::vector<double> inflection_parameters(const CubicBezier& k, double tolerance_rel) {
  const double size = polygon_size(k);
  if (!(size > 0) || !std::isfinite(size)) return {};
  // Work in a frame scaled to the curve so the tolerance is relative and nothing overflows.
  const Hodograph h(CubicBezier((k.p[0] - k.p[0]) / size, (k.p[1] - k.p[0]) / size, (k.p[2] - k.p[0]) / size,
                                (k.p[3] - k.p[0]) / size));
  // det(c', c'') ∝ det(b, c) t² + det(a, c) t + det(a, b)  (§4, eq. 1)
  std::vector<double> out;
  for (const double t : sign_changes(cross(h.b, h.c), cross(h.a, h.c), cross(h.a, h.b), tolerance_rel)) {
    if (k.derivative(t).stableNorm() > 1e-9 * size) out.push_back(t);  // a cusp is not an inflection
  }
  return out;
}

double turning_angle(const CubicBezier& c, double t0, double t1) {
  if (!(t1 > t0)) return 0.0;
  const double size = polygon_size(c);
  if (!(size > 0)) return 0.0;
  constexpr int kSamples = 32;
  std::vector<double> ts;
  ts.reserve(kSamples + 3);
  for (int i = 0; i <= kSamples; ++i) ts.push_back(t0 + (t1 - t0) * i / kSamples);
  // Inflections inside: the tangent turns back there, which samples alone could miss.
  for (const double t : inflection_parameters(c))
    if (t > t0 && t < t1) ts.push_back(t);
  std::sort(ts.begin(), ts.end());
  // Per interval, the tangent at its start (from above) and at its end (from below); a cusp at a
  // sample shows as the angle between one interval's end and the next one's start. Away from a
  // cusp both are c' there, normalized: the same vector, whose angle to itself is exactly 0
  // (cross(u, u) is 0 in doubles too), so it is computed once and its angle not at all.
  double total = 0.0;
  Vec2 previous_end(0, 0);
  bool first = true, previous_regular = false;
  double previous_b = 0;
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    const double a = ts[i], b = ts[i + 1];
    if (b <= a) continue;
    const bool reuse = previous_regular && previous_b == a;
    const Vec2 start = reuse ? previous_end : tangent(c, a, a, b, size);
    const Vec2 d = c.derivative(b);
    const bool regular = d.norm() > 1e-12 * size;
    const Vec2 end = regular ? Vec2(d / d.norm()) : tangent(c, b, a, b, size);
    if (!first && !reuse) total += angle_between(previous_end, start);
    total += angle_between(start, end);
    previous_end = end;
    previous_regular = regular;
    previous_b = b;
    first = false;
  }
  return total;
}

double end_tangent_angle(const CubicBezier& c, double t0, double t1) {
  if (!(t1 > t0)) return 0.0;
  const double size = polygon_size(c);
  if (!(size > 0)) return 0.0;
  return angle_between(tangent(c, t0, t0, t1, size), tangent(c, t1, t0, t1, size));
}

bool turns_monotonically(const CubicBezier& c) {
  const double whole = turning_angle(c);
  if (!(whole < kPi)) return false;
  // A piece split off at an inflection keeps it, by rounding, within ~1e-12 of its end: harmless,
  // as long as the curve turns by next to nothing there, which the last test makes sure of.
  constexpr double kEndMargin = 1e-9;
  for (const double t : inflection_parameters(c))
    if (t > kEndMargin && t < 1 - kEndMargin) return false;
  return std::abs(whole - end_tangent_angle(c, 0.0, 1.0)) <= 1e-10;
}

double half_turning_parameter(const CubicBezier& c) {
  const double size = polygon_size(c);
  if (!(size > 0)) return 0.5;
  const Vec2 u = tangent(c, 0.0, 0.0, 1.0, size), v = tangent(c, 1.0, 0.0, 1.0, size);
  Vec2 m = u + v;
  // Beyond π the average of the end tangents points backwards: use its opposite (§4).
  if (turning_angle(c) > kPi) m = -m;
  if (m.norm() < 1e-12) m = Vec2(-u.y(), u.x());  // ends exactly opposite: the perpendicular
  // det(m, c'(t)/3) = det(m, a) + 2 det(m, b) t + det(m, c) t²
  const Hodograph h(c);
  const double scale = size * size;
  const std::vector<double> roots =
      sign_changes(cross(m, h.c) / scale, 2.0 * cross(m, h.b) / scale, cross(m, h.a) / scale, 1e-14);
  // Several candidates: keep the one where the tangent really points along m and that best halves.
  double best = 0.5, best_error = INFINITY;
  const double whole = turning_angle(c);
  for (const double t : roots) {
    if (c.derivative(t).dot(m) <= 0) continue;
    const double error = std::abs(turning_angle(c, 0.0, t) - 0.5 * whole);
    if (error < best_error) best = t, best_error = error;
  }
  return best;
}

namespace {
void split_recursive(const CubicBezier& c, double lo, double hi, double max_turning, int depth,
                     std::vector<double>& out) {
  const CubicBezier piece = c.subcurve(lo, hi);
  if (depth >= 8 || turning_angle(piece) < max_turning) return;
  const double s = half_turning_parameter(piece);
  const double t = lo + s * (hi - lo);
  if (!(t > lo && t < hi)) return;
  split_recursive(c, lo, t, max_turning, depth + 1, out);
  out.push_back(t);
  split_recursive(c, t, hi, max_turning, depth + 1, out);
}
}  // namespace

std::vector<double> split_for_turning(const CubicBezier& c, double max_turning) {
  std::vector<double> out;
  split_recursive(c, 0.0, 1.0, max_turning, 0, out);
  return out;
}

bool is_degenerate(const CubicBezier& c, double eps) {
  const Vec2 centre = (c.p[0] + c.p[1] + c.p[2] + c.p[3]) / 4.0;
  return std::all_of(c.p.begin(), c.p.end(), [&](const Vec2& q) { return (q - centre).norm() <= eps; });
}

bool is_straight(const CubicBezier& c, double eps) {
  const Vec2 centre = (c.p[0] + c.p[1] + c.p[2] + c.p[3]) / 4.0;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec2& q : c.p) cov += (q - centre) * (q - centre).transpose();
  // The least-squares line runs along the principal eigenvector of the scatter matrix.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(cov);
  const Vec2 direction = solver.eigenvectors().col(1);
  double sum = 0;
  for (const Vec2& q : c.p) sum += std::abs(cross(direction, q - centre));
  return sum < eps;
}

}  // namespace curvemesh::geometry
