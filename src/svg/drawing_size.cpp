#include "svg/drawing_size.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace curvemesh::svg {

namespace {

std::string shown(double x) {
  std::ostringstream s;
  s.precision(2);
  s << x;
  return s.str();
}

}  // namespace

std::string drawing_size_problem(const geometry::Box2& box) {
  if (box.empty()) return {};
  const double far =
      std::max({std::abs(box.min.x()), std::abs(box.min.y()), std::abs(box.max.x()), std::abs(box.max.y())});
  if (!(far <= kMaxDrawingSize))
    return "the drawing reaches a coordinate of " + shown(far) + ", beyond " + shown(kMaxDrawingSize) +
           ": too large to mesh in double precision; scale it down";
  // Each side is at most twice kMaxDrawingSize, and std::hypot neither overflows nor underflows.
  const double across = std::hypot(box.max.x() - box.min.x(), box.max.y() - box.min.y());
  if (across > kMaxDrawingSize)
    return "the drawing is " + shown(across) + " across, larger than " + shown(kMaxDrawingSize) +
           ": too large to mesh in double precision; scale it down";
  if (across > 0 && across < kMinDrawingSize)
    return "the drawing is " + shown(across) + " across, smaller than " + shown(kMinDrawingSize) +
           ": too small to mesh in double precision; scale it up";
  return {};
}

}  // namespace curvemesh::svg
