#pragma once
// The point of a cubic nearest to a given point (paper Appendix B), used to project feature
// vertices onto their curves.
#include "geometry/bezier.hpp"

namespace curvemesh::geometry {

struct ClosestPoint {
  double t = 0;        // parameter in [0, 1]
  Vec2 point = Vec2::Zero();
  double distance = 0;
};

// App. B: the stationary points of |c(t) - p|² are the roots of a quintic; we take the real
// eigenvalues of its companion matrix (in a frame scaled to the curve, and of lower degree when
// the leading coefficients vanish, as for straight curves), add the local minima of 64 samples
// as candidates so that no root the eigen-solver misses is lost, polish each with safeguarded
// Newton steps, and compare with both endpoints.
ClosestPoint closest_point(const CubicBezier& c, const Vec2& p);

}  // namespace curvemesh::geometry
