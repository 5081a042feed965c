#include "geometry/closest_point.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace curvemesh::geometry {

namespace {

// f(t) = (c(t) - p) · c'(t) and its derivative, for Newton.
struct Stationary {
  const CubicBezier& c;
  Vec2 p;
  double f(double t) const { return (c.eval(t) - p).dot(c.derivative(t)); }
  double df(double t) const {
    const Vec2 d = c.derivative(t);
    return d.squaredNorm() + (c.eval(t) - p).dot(c.second_derivative(t));
  }
};

// Newton on f within [lo, hi], falling back to bisection when a step leaves the bracket or f does
// not change sign there (then it only polishes).
double polish(const Stationary& s, double t, double lo, double hi) {
  lo = std::max(0.0, lo);
  hi = std::min(1.0, hi);
  double flo = s.f(lo), fhi = s.f(hi);
  const bool bracketed = (flo <= 0 && fhi >= 0) || (flo >= 0 && fhi <= 0);
  for (int it = 0; it < 60; ++it) {
    const double ft = s.f(t), dft = s.df(t);
    double next = dft != 0 ? t - ft / dft : t;
    if (!(next > lo && next < hi)) {
      if (!bracketed) break;
      next = 0.5 * (lo + hi);
    }
    if (bracketed) {
      if ((ft < 0) == (flo < 0)) lo = t, flo = ft;
      else hi = t, fhi = ft;
    }
    if (std::abs(next - t) <= 1e-15) {
      t = next;
      break;
    }
    t = next;
  }
  return std::clamp(t, 0.0, 1.0);
}

// Real roots in [0, 1] of the polynomial with coefficients k[0] + k[1] t + ... (degree ≤ 5).
std::vector<double> real_roots_in_unit(std::array<double, 6> k) {
  int degree = 5;
  double scale = 0;
  for (const double v : k) scale = std::max(scale, std::abs(v));
  if (scale == 0) return {};
  while (degree > 0 && std::abs(k[degree]) <= 1e-13 * scale) --degree;
  std::vector<double> roots;
  if (degree == 0) return roots;
  if (degree == 1) {
    roots.push_back(-k[0] / k[1]);
  } else {
    Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
    for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
    for (int i = 0; i < degree; ++i) companion(i, degree - 1) = -k[i] / k[degree];
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
    for (int i = 0; i < degree; ++i) {
      const std::complex<double> z = solver.eigenvalues()[i];
      if (std::abs(z.imag()) <= 1e-6 * (1 + std::abs(z.real()))) roots.push_back(z.real());
    }
  }
  std::vector<double> inside;
  for (const double t : roots)
    if (std::isfinite(t) && t > -1e-9 && t < 1 + 1e-9) inside.push_back(std::clamp(t, 0.0, 1.0));
  return inside;
}

}  // namespace

ClosestPoint closest_point(const CubicBezier& c, const Vec2& p) {
  // Scale-free frame: centred at p, unit size.
  double size = 0;
  for (const Vec2& q : c.p) size = std::max(size, (q - p).norm());
  ClosestPoint best{0.0, c.p[0], (c.p[0] - p).norm()};
  const ClosestPoint end{1.0, c.p[3], (c.p[3] - p).norm()};
  if (end.distance < best.distance) best = end;
  if (!(size > 0) || !std::isfinite(size)) return best;
  const CubicBezier n((c.p[0] - p) / size, (c.p[1] - p) / size, (c.p[2] - p) / size, (c.p[3] - p) / size);
  // Power basis of n(t) = d0 + d1 t + d2 t² + d3 t³ and of f(t) = n(t) · n'(t) (degree 5).
  const Vec2 d0 = n.p[0], d1 = 3.0 * (n.p[1] - n.p[0]), d2 = 3.0 * (n.p[2] - 2.0 * n.p[1] + n.p[0]),
             d3 = n.p[3] - 3.0 * n.p[2] + 3.0 * n.p[1] - n.p[0];
  const std::array<Vec2, 4> d{d0, d1, d2, d3};
  std::array<double, 6> k{};
  for (int i = 0; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j) k[i + j - 1] += j * d[i].dot(d[j]);

  const Stationary s{n, Vec2::Zero()};
  std::vector<std::pair<double, std::pair<double, double>>> candidates;  // t and its bracket
  for (const double t : real_roots_in_unit(k)) candidates.push_back({t, {t - 0.05, t + 0.05}});
  constexpr int kSamples = 64;
  std::array<double, kSamples + 1> dist{};
  for (int i = 0; i <= kSamples; ++i) dist[i] = n.eval(double(i) / kSamples).squaredNorm();
  for (int i = 1; i < kSamples; ++i)
    if (dist[i] <= dist[i - 1] && dist[i] <= dist[i + 1])
      candidates.push_back({double(i) / kSamples, {double(i - 1) / kSamples, double(i + 1) / kSamples}});

  for (const auto& [t0, bracket] : candidates) {
    const double t = polish(s, t0, bracket.first, bracket.second);
    const Vec2 q = c.eval(t);
    const double dq = (q - p).norm();
    if (dq < best.distance) best = {t, q, dq};
  }
  return best;
}

}  // namespace curvemesh::geometry
