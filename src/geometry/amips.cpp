#include "geometry/amips.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curvemesh::geometry {

AmipsDerivatives& AmipsDerivatives::operator+=(const AmipsDerivatives& o) {
  energy += o.energy;
  gradient += o.gradient;
  hessian += o.hessian;
  return *this;
}

AmipsDerivatives amips_derivatives(const Vec2& a, const Vec2& b, const Vec2& c) {
  AmipsDerivatives d;
  const Vec2 e1 = b - a, e2 = c - a, f = 2 * e2 - e1;
  const double det = cross(e1, e2);
  if (!(det > 0)) {
    d.energy = std::numeric_limits<double>::infinity();
    return d;
  }
  // Moving a: de1/da = de2/da = df/da = -I. N is quadratic in a (Hessian 8 I), D is linear.
  const double n = 3 * e1.squaredNorm() + f.squaredNorm();
  const double den = kTwoSqrt3 * det;
  const Vec2 dn = -6 * e1 - 2 * f;
  const Vec2 dd = kTwoSqrt3 * Vec2(e1.y() - e2.y(), e2.x() - e1.x());  // ∂ det[b-a, c-a] / ∂a
  d.energy = n / den;
  d.gradient = dn / den - n * dd / (den * den);
  d.hessian = 8 * Eigen::Matrix2d::Identity() / den - (dn * dd.transpose() + dd * dn.transpose()) / (den * den) +
              2 * n * dd * dd.transpose() / (den * den * den);
  return d;
}

double min_angle(const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto angle = [](const Vec2& u, const Vec2& v) { return std::atan2(std::abs(cross(u, v)), u.dot(v)); };
  const Vec2 ab = b - a, bc = c - b, ca = a - c;
  if (cross(ab, -ca) == 0) return 0.0;
  // The smallest angle is the one opposite the shortest side.
  const double lab = ab.squaredNorm(), lbc = bc.squaredNorm(), lca = ca.squaredNorm();
  if (lbc <= lab && lbc <= lca) return angle(ab, -ca);  // at a
  if (lca <= lab) return angle(bc, -ab);                // at b
  return angle(ca, -bc);                                // at c
}

CurveDerivatives along_curve(const AmipsDerivatives& s, const Vec2& dc, const Vec2& ddc) {
  return {s.energy, s.gradient.dot(dc), dc.dot(s.hessian * dc) + s.gradient.dot(ddc)};
}

}  // namespace curvemesh::geometry
