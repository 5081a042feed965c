#pragma once
// What the invariants of §4.1 need to know about the input, independent of the features stage:
// the curve of each primary section, the ε-envelope of the secondary segments, the outer box.
#include <vector>

#include "geometry/bezier.hpp"
#include "geometry/envelope.hpp"

namespace curvemesh::mesh {

using geometry::Vec2;

// A primary section's curve, addressed by the parameter t of its soup curve (t0 <= t <= t1).
struct SectionCurve {
  geometry::CubicBezier piece;  // the soup curve restricted to [t0, t1]
  double t0 = 0, t1 = 1;
  bool monotone = false;  // no inflection, turning below π: the turning is the end-tangent angle

  double local(double t) const { return (t - t0) / (t1 - t0); }
  Vec2 eval(double t) const { return piece.eval(local(t)); }
  Vec2 derivative(double t) const { return piece.derivative(local(t)) / (t1 - t0); }
  Vec2 second_derivative(double t) const {
    return piece.second_derivative(local(t)) / ((t1 - t0) * (t1 - t0));
  }
  // Turning of the curve between two parameters (either order): invariant 3 bounds it by α.
  double turning(double ta, double tb) const;
};

struct Constraints {
  std::vector<SectionCurve> sections;  // indexed like the features' sections
  geometry::SegmentEnvelope envelope;  // the secondary input segments and ε (invariant 2)
  geometry::Box2 box;                  // the outer box the boundary edges lie on
  double max_turning = 0;              // α in radians (invariant 3)
};

}  // namespace curvemesh::mesh
