#pragma once
// Cubic Bézier curves: the one curve type of the pipeline (paper §3.1: lines, quadratics and
// arcs are all turned into cubics on input).
#include <array>

#include "geometry/vec2.hpp"

namespace curvemesh::geometry {

struct CubicBezier {
  std::array<Vec2, 4> p;  // control points p0..p3

  CubicBezier() : p{Vec2::Zero(), Vec2::Zero(), Vec2::Zero(), Vec2::Zero()} {}
  CubicBezier(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3) : p{p0, p1, p2, p3} {}

  // The straight segment a -> b with control points at thirds (a degree-elevated line).
  static CubicBezier line(const Vec2& a, const Vec2& b);
  // Exact degree elevation of the quadratic with control points a, c, b.
  static CubicBezier from_quadratic(const Vec2& a, const Vec2& c, const Vec2& b);

  Vec2 eval(double t) const;
  Vec2 derivative(double t) const;         // c'(t)
  Vec2 second_derivative(double t) const;  // c''(t)

  // de Casteljau split at t: the first piece covers [0, t], the second [t, 1].
  std::pair<CubicBezier, CubicBezier> split(double t) const;
  // The piece covering [t0, t1] reparametrised to [0, 1].
  CubicBezier subcurve(double t0, double t1) const;

  // Tight bounding box (endpoints and interior extrema), not the control polygon's.
  Box2 bounds() const;
  // Box of the four control points: contains the curve (convex hull property).
  Box2 control_bounds() const;
  // Arc length by adaptive Gauss–Legendre quadrature, relative accuracy about 1e-12.
  double length() const;
};

}  // namespace curvemesh::geometry
