#pragma once
// Exact geometric signs. Every orientation that decides topology goes through here: on doubles
// with CGAL's filtered exact predicate (exact for any finite input), on rationals with GMP.
#include <gmpxx.h>

#include "geometry/vec2.hpp"

namespace curvemesh::geometry {

// A point with rational coordinates: an intersection of input segments before it is rounded.
struct ExactPoint {
  mpq_class x, y;
  ExactPoint() = default;
  ExactPoint(mpq_class x_, mpq_class y_) : x(std::move(x_)), y(std::move(y_)) {}
  explicit ExactPoint(const Vec2& p) : x(p.x()), y(p.y()) {}  // every finite double is rational
  Vec2 to_double() const { return {x.get_d(), y.get_d()}; }  // nearest-ish double (GMP truncates)
};

// Sign of the signed area of (a, b, c): +1 counter-clockwise, -1 clockwise, 0 collinear. Exact.
int orientation(const Vec2& a, const Vec2& b, const Vec2& c);
int orientation(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c);

// The double nearest to a rational (round to nearest, ties to even), unlike mpq's get_d.
double nearest_double(const mpq_class& q);
Vec2 nearest_double(const ExactPoint& p);

}  // namespace curvemesh::geometry
