#pragma once
// Plane vectors and axis-aligned boxes: the smallest types every stage shares.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace curvemesh::geometry {

using Vec2 = Eigen::Vector2d;

// The cross product of two plane vectors (the z of their 3D one): u.x·v.y − u.y·v.x, the signed
// area of the parallelogram they span. In doubles: where a sign decides topology (orientation,
// intersection), geometry/predicates decides it exactly instead.
inline double cross(const Vec2& u, const Vec2& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// An axis-aligned box; empty until the first point is added.
struct Box2 {
  Vec2 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};

  bool empty() const { return !(min.x() <= max.x() && min.y() <= max.y()); }
  void add(const Vec2& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const Box2& b) {
    if (b.empty()) return;
    add(b.min);
    add(b.max);
  }
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
  // The squared distance from p to the box (0 inside it or on its border).
  double squared_distance(const Vec2& p) const {
    const double dx = std::max({min.x() - p.x(), 0.0, p.x() - max.x()});
    const double dy = std::max({min.y() - p.y(), 0.0, p.y() - max.y()});
    return dx * dx + dy * dy;
  }
  double width() const { return empty() ? 0.0 : max.x() - min.x(); }
  double height() const { return empty() ? 0.0 : max.y() - min.y(); }
};

}  // namespace curvemesh::geometry
