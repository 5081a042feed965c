#pragma once
// The quadratic (P2) triangle map — Gmsh's 6-node triangle, element type 9 — and the certificate
// that it is a valid geometric map: det J > 0 on the whole reference triangle (§4.2, App. C, for
// degree 2 instead of 3). Node order, reference coordinates (u, v):
//   0 (0,0)     1 (1,0)     2 (0,1)       corners
//   3 (1/2,0)   4 (1/2,1/2) 5 (0,1/2)     middles of edges 0→1, 1→2, 2→0
// With barycentrics λ0 = 1 − u − v, λ1 = u, λ2 = v the Lagrange basis is λa (2λa − 1) at the
// corners and 4 λa λb at the middles. det J of a P2 map is a polynomial of degree 2: its six
// Bernstein coefficients (p3_triangle.hpp's triangular Bernstein form and order) all positive
// prove it positive on the closed triangle; otherwise the triangle is subdivided as for P3.
#include <gmpxx.h>

#include <Eigen/Core>
#include <array>
#include <limits>

#include "geometry/p3_triangle.hpp"
#include "geometry/vec2.hpp"

namespace curvemesh::geometry {

using P2Nodes = std::array<Vec2, 6>;
template <class T>
using P2NodesT = std::array<PointT<T>, 6>;

// Nodes of the straight triangle a, b, c: edge nodes at the middles.
P2Nodes p2_straight_nodes(const Vec2& a, const Vec2& b, const Vec2& c);

// The map x(u, v) = Σ N_i(u, v) node_i and its Jacobian [∂x/∂u ∂x/∂v] at a reference point.
Vec2 p2_map(const P2Nodes& nodes, double u, double v);
Eigen::Matrix2d p2_jacobian(const P2Nodes& nodes, double u, double v);

// The curved element's quality, as p3_max_amips for P3: the conformal AMIPS energy of the map
// (from the equilateral triangle), its largest value over the 28 points of the order-6 lattice,
// visited in the same order; with a `bound`, exact below it and at least it otherwise.
double p2_max_amips(const P2Nodes& nodes, double bound = std::numeric_limits<double>::infinity());
// The smallest det J and the largest AMIPS over the same 28 points, in one pass.
P3LatticeValues p2_lattice_values(const P2Nodes& nodes);

P2NodesT<mpq_class> to_exact(const P2Nodes& nodes);

// ---------------------------------------------------------------------------------------------
// Templates over the scalar type T: exact for mpq_class, ordinary rounding for double.

// The same map written with the ten nodes of a P3 triangle: the P2 map at the P3 reference nodes
// (edge nodes at thirds, the centre), exact for exact T.
template <class T>
P3NodesT<T> p2_as_p3(const P2NodesT<T>& n) {
  // At λ = (2/3, 1/3, 0): N = (2/9, −1/9, 0, 8/9, 0, 0); at the centre −1/9 per corner, 4/9 per middle.
  const auto at_third = [](const PointT<T>& near, const PointT<T>& mid, const PointT<T>& far) {
    PointT<T> p;
    for (int c = 0; c < 2; ++c) p[c] = T((T(2) * near[c] + T(8) * mid[c] - far[c]) / T(9));
    return p;
  };
  P3NodesT<T> out;
  out[0] = n[0], out[1] = n[1], out[2] = n[2];
  out[3] = at_third(n[0], n[3], n[1]);
  out[4] = at_third(n[1], n[3], n[0]);
  out[5] = at_third(n[1], n[4], n[2]);
  out[6] = at_third(n[2], n[4], n[1]);
  out[7] = at_third(n[2], n[5], n[0]);
  out[8] = at_third(n[0], n[5], n[2]);
  for (int c = 0; c < 2; ++c)
    out[9][c] = T((T(4) * (n[3][c] + n[4][c] + n[5][c]) - (n[0][c] + n[1][c] + n[2][c])) / T(9));
  return out;
}

// det J(u, v) from the Lagrange basis derivatives: the reference the Bernstein form is tested
// against.
template <class T>
T p2_jacobian_det(const P2NodesT<T>& n, const T& u, const T& v) {
  const T l0 = T(1) - u - v;
  const std::array<std::array<T, 2>, 6> d{{{T(T(1) - T(4) * l0), T(T(1) - T(4) * l0)},
                                           {T(T(4) * u - T(1)), T(0)},
                                           {T(0), T(T(4) * v - T(1))},
                                           {T(T(4) * (l0 - u)), T(T(-4) * u)},
                                           {T(T(4) * v), T(T(4) * u)},
                                           {T(T(-4) * v), T(T(4) * (l0 - v))}}};
  T xu(0), yu(0), xv(0), yv(0);
  for (int i = 0; i < 6; ++i) {
    xu += d[i][0] * n[i][0];
    yu += d[i][0] * n[i][1];
    xv += d[i][1] * n[i][0];
    yv += d[i][1] * n[i][1];
  }
  return T(xu * yv - yu * xv);
}

// det J as a degree-2 Bernstein polynomial (6 coefficients), exact for exact T. The control net
// of the map keeps the corners; along an edge A→B with middle node M the control point is
// 2M − (A + B)/2. ∂x/∂u = 2 Σ (P_β+e1 − P_β+e0) B¹_β and ∂x/∂v = 2 Σ (P_β+e2 − P_β+e0) B¹_β, and
// B¹_β B¹_γ = B²_β+γ / C(β+γ) with C the multinomial, so D_δ = 4 / C(δ) Σ_{β+γ=δ} U_β × V_γ.
// Gmsh node → control index (i, j, k): 0→200, 1→020, 2→002, 3→110, 4→011, 5→101.
template <class T>
constexpr std::array<T, 6> p2_jacobian_det_bernstein(const P2NodesT<T>& n) {
  const auto control = [](const PointT<T>& a, const PointT<T>& m, const PointT<T>& b) {
    PointT<T> p;
    for (int c = 0; c < 2; ++c) p[c] = T(T(2) * m[c] - (a[c] + b[c]) / T(2));
    return p;
  };
  std::array<PointT<T>, 6> P;
  P[bernstein_index(2, 0, 0)] = n[0];
  P[bernstein_index(2, 2, 0)] = n[1];
  P[bernstein_index(2, 0, 2)] = n[2];
  P[bernstein_index(2, 1, 0)] = control(n[0], n[3], n[1]);
  P[bernstein_index(2, 1, 1)] = control(n[1], n[4], n[2]);
  P[bernstein_index(2, 0, 1)] = control(n[2], n[5], n[0]);
  std::array<PointT<T>, 3> du, dv;  // degree-1 nets, without the factor 2
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j + k <= 1; ++j) {
      const auto& p0 = P[bernstein_index(2, j, k)];  // β + e0
      const auto& p1 = P[bernstein_index(2, j + 1, k)];
      const auto& p2 = P[bernstein_index(2, j, k + 1)];
      for (int c = 0; c < 2; ++c) {
        du[bernstein_index(1, j, k)][c] = T(p1[c] - p0[c]);
        dv[bernstein_index(1, j, k)][c] = T(p2[c] - p0[c]);
      }
    }
  std::array<T, 6> sum;
  sum.fill(T(0));
  for (int ka = 0; ka <= 1; ++ka)
    for (int ja = 0; ja + ka <= 1; ++ja)
      for (int kb = 0; kb <= 1; ++kb)
        for (int jb = 0; jb + kb <= 1; ++jb) {
          const auto& a = du[bernstein_index(1, ja, ka)];
          const auto& b = dv[bernstein_index(1, jb, kb)];
          sum[bernstein_index(2, ja + jb, ka + kb)] += T(a[0] * b[1] - a[1] * b[0]);
        }
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j + k <= 2; ++j) {
      T& s = sum[bernstein_index(2, j, k)];
      s = T(T(4) * s / T(multinomial(2 - j - k, j, k)));
    }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Certification of det J > 0 on the whole reference triangle: the P3 certificate's algorithm
// (certify_jacobian_exact, certify_jacobian) on the degree-2 polynomial.

// Exact: all 6 coefficients > 0 → positive; a value ≤ 0 at a corner of the element or of any
// sub-triangle examined → not_positive; otherwise split into 4 (exact de Casteljau subdivision)
// and recurse; undecided at the depth or work limit.
JacobianVerdict certify_jacobian_exact(const P2NodesT<mpq_class>& nodes, const JacobianCheckOptions& options = {});
JacobianVerdict certify_jacobian_exact(const P2Nodes& nodes, const JacobianCheckOptions& options = {});

// The same in doubles, every quantity with a rigorous bound on its rounding error, on the nodes
// taken relative to node 0: a verdict is never wrong, only possibly undecided. min_coefficient and
// max_coefficient are those of the 6 coefficients; min_value is over the 15 points of the
// degree-4 lattice (as for P3) and the sub-triangle corners visited.
JacobianCertificate certify_jacobian(const P2Nodes& nodes, const JacobianCheckOptions& options = {});

}  // namespace curvemesh::geometry
