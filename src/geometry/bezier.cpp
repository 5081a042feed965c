#include "geometry/bezier.hpp"

#include <cmath>

namespace curvemesh::geometry {

CubicBezier CubicBezier::line(const Vec2& a, const Vec2& b) {
  return {a, (2.0 * a + b) / 3.0, (a + 2.0 * b) / 3.0, b};
}

CubicBezier CubicBezier::from_quadratic(const Vec2& a, const Vec2& c, const Vec2& b) {
  return {a, a + 2.0 / 3.0 * (c - a), b + 2.0 / 3.0 * (c - b), b};
}

Vec2 CubicBezier::eval(double t) const {
  const double s = 1.0 - t;
  return s * s * s * p[0] + 3.0 * s * s * t * p[1] + 3.0 * s * t * t * p[2] + t * t * t * p[3];
}

Vec2 CubicBezier::derivative(double t) const {
  const double s = 1.0 - t;
  return 3.0 * (s * s * (p[1] - p[0]) + 2.0 * s * t * (p[2] - p[1]) + t * t * (p[3] - p[2]));
}

Vec2 CubicBezier::second_derivative(double t) const {
  return 6.0 * ((1.0 - t) * (p[2] - 2.0 * p[1] + p[0]) + t * (p[3] - 2.0 * p[2] + p[1]));
}

std::pair<CubicBezier, CubicBezier> CubicBezier::split(double t) const {
  const Vec2 a = p[0] + t * (p[1] - p[0]);
  const Vec2 b = p[1] + t * (p[2] - p[1]);
  const Vec2 c = p[2] + t * (p[3] - p[2]);
  const Vec2 ab = a + t * (b - a);
  const Vec2 bc = b + t * (c - b);
  const Vec2 m = ab + t * (bc - ab);
  return {CubicBezier(p[0], a, ab, m), CubicBezier(m, bc, c, p[3])};
}

CubicBezier CubicBezier::subcurve(double t0, double t1) const {
  if (t0 <= 0.0 && t1 >= 1.0) return *this;
  CubicBezier right = t0 > 0.0 ? split(t0).second : *this;
  if (t1 >= 1.0) return right;
  const double u = (t1 - t0) / (1.0 - t0);
  CubicBezier piece = right.split(u).first;
  piece.p[0] = eval(t0);  // exact endpoints where they are known
  piece.p[3] = eval(t1);
  return piece;
}

Box2 CubicBezier::control_bounds() const {
  Box2 b;
  for (const auto& q : p) b.add(q);
  return b;
}

Box2 CubicBezier::bounds() const {
  Box2 b;
  b.add(p[0]);
  b.add(p[3]);
  // c'(t)/3 = a t^2 + b t + c per coordinate, in the power basis.
  for (int k = 0; k < 2; ++k) {
    const double d0 = p[1][k] - p[0][k], d1 = p[2][k] - p[1][k], d2 = p[3][k] - p[2][k];
    const double qa = d0 - 2.0 * d1 + d2, qb = 2.0 * (d1 - d0), qc = d0;
    auto consider = [&](double t) {
      if (t > 0.0 && t < 1.0) b.add(eval(t));
    };
    const double scale = std::abs(d0) + std::abs(d1) + std::abs(d2);
    if (std::abs(qa) <= 1e-14 * scale) {
      if (qb != 0.0) consider(-qc / qb);
      continue;
    }
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) continue;
    const double sq = std::sqrt(disc);
    // Numerically stable roots of the quadratic.
    const double q = -0.5 * (qb + std::copysign(sq, qb));
    if (q != 0.0) consider(qc / q);
    consider(q / qa);
  }
  return b;
}

namespace {
// 8-point Gauss–Legendre on [0, 1].
constexpr std::array<double, 8> kGaussX = {0.019855071751231856, 0.10166676129318664, 0.2372337950418355,
                                           0.4082826787521751,   0.5917173212478249,  0.7627662049581645,
                                           0.8983332387068134,   0.9801449282487681};
constexpr std::array<double, 8> kGaussW = {0.05061426814518813, 0.11119051722668724, 0.15685332293894363,
                                           0.18134189168918100, 0.18134189168918100, 0.15685332293894363,
                                           0.11119051722668724, 0.05061426814518813};

double gauss_length(const CubicBezier& c, double a, double b) {
  double sum = 0.0;
  for (size_t i = 0; i < kGaussX.size(); ++i) sum += kGaussW[i] * c.derivative(a + (b - a) * kGaussX[i]).norm();
  return sum * (b - a);
}

// `tolerance` is absolute (a fraction of the whole curve's length), so only the pieces that hold
// a cusp, where |c'| has a kink, keep subdividing: the recursion stays linear in the depth.
double adaptive_length(const CubicBezier& c, double a, double b, double whole, double tolerance, int depth) {
  const double m = 0.5 * (a + b);
  const double left = gauss_length(c, a, m), right = gauss_length(c, m, b);
  if (depth >= 40 || std::abs(left + right - whole) <= tolerance) return left + right;
  return adaptive_length(c, a, m, left, 0.5 * tolerance, depth + 1) +
         adaptive_length(c, m, b, right, 0.5 * tolerance, depth + 1);
}
}  // namespace

double CubicBezier::length() const {
  const double estimate = gauss_length(*this, 0.0, 1.0);
  return adaptive_length(*this, 0.0, 1.0, estimate, 1e-13 * estimate, 0);
}

}  // namespace curvemesh::geometry
