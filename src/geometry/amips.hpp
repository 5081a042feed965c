#pragma once
// The conformal AMIPS energy of a triangle (TetWild; TriWild App. A) and what smoothing needs of
// it: derivatives with respect to one vertex, and their restriction to a curve through it.
//
// With J = [b - a, c - a] W⁻¹, W the equilateral reference [[1, 1/2], [0, √3/2]],
// E = ‖J‖²_F / det J. E = 2 for every equilateral triangle and grows without bound as the triangle
// flattens; it does not depend on size, position or rotation. Counter-clockwise is valid: E = +∞
// when det J <= 0.
#include <Eigen/Core>
#include <limits>

#include "geometry/vec2.hpp"

namespace curvemesh::geometry {

// The same energy of the linear map that takes the reference triangle (0,0), (1,0), (0,1) to
// edges e1 and e2: amips(a, b, c) is amips_of_edges(b - a, c - a); a curved element's energy at a
// point is that of its Jacobian's columns.
// With f = 2 e2 − e1, J's columns are e1 and f / √3, so ‖J‖² = |e1|² + |f|²/3 and
// det J = (2/√3) det[e1 e2]: E = N / D with N = 3|e1|² + |f|² and D = 2√3 det[e1 e2]. Everything
// is computed from differences, so it is as accurate at 1e-6 as at 1e6. Inline: the curved
// energy evaluates it at 28 points per triangle.
inline constexpr double kTwoSqrt3 = 3.4641016151377544;  // 2√3
inline double amips_of_edges(const Vec2& e1, const Vec2& e2) {
  const Vec2 f = 2 * e2 - e1;
  const double det = cross(e1, e2);
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  return (3 * e1.squaredNorm() + f.squaredNorm()) / (kTwoSqrt3 * det);
}
// Inline as well: the optimizer asks for it in every star it looks at, tens of millions of times.
inline double amips(const Vec2& a, const Vec2& b, const Vec2& c) { return amips_of_edges(b - a, c - a); }

struct AmipsDerivatives {
  double energy = 0;
  Vec2 gradient = Vec2::Zero();                       // dE/da
  Eigen::Matrix2d hessian = Eigen::Matrix2d::Zero();  // d²E/da²
  AmipsDerivatives& operator+=(const AmipsDerivatives& o);
};

// Energy, gradient and Hessian with respect to the first vertex a (b and c fixed), analytic.
// For det J <= 0: energy +∞, gradient and Hessian zero.
AmipsDerivatives amips_derivatives(const Vec2& a, const Vec2& b, const Vec2& c);

// The smallest interior angle in radians (0 for a degenerate triangle; either orientation).
double min_angle(const Vec2& a, const Vec2& b, const Vec2& c);

// A summed star energy restricted to a curve c(t) through the vertex (App. A): with g and H the
// gradient and Hessian at the vertex, dc = c'(t), ddc = c''(t):
// first = g·dc, second = dcᵀ H dc + g·ddc.
struct CurveDerivatives {
  double energy = 0, first = 0, second = 0;
};
CurveDerivatives along_curve(const AmipsDerivatives& summed, const Vec2& dc, const Vec2& ddc);

}  // namespace curvemesh::geometry
