#pragma once
// The cubic (P3) triangle map of a curved element (paper §4.2, Appendix C) and the certificate
// that it is a valid geometric map: det J > 0 everywhere on the reference triangle (DESIGN §3.5).
//
// Node order is Gmsh's 10-node triangle (element type 21), checked against
// gmsh.model.mesh.getElementProperties(21). Reference coordinates (u, v):
//   0 (0,0)     1 (1,0)     2 (0,1)                       corners
//   3 (1/3,0)   4 (2/3,0)                                 edge 0→1, 3 nearer 0
//   5 (2/3,1/3) 6 (1/3,2/3)                               edge 1→2, 5 nearer 1
//   7 (0,2/3)   8 (0,1/3)                                 edge 2→0, 7 nearer 2
//   9 (1/3,1/3)                                           centre
// The paper's Lagrange basis ℓ0..ℓ9 (Appendix C, x = u, y = v) uses the same order.
//
// Triangular Bernstein form of degree n. With barycentrics λ0 = 1 − u − v, λ1 = u, λ2 = v,
//   B_ijk(u, v) = n! / (i! j! k!) λ0^i λ1^j λ2^k,   i + j + k = n,
// so c_n00 sits at corner 0, c_0n0 at corner 1, c_00n at corner 2, and those three coefficients
// equal the polynomial's values there. Coefficients are stored by rows of equal k, within a row
// by increasing j: flat index bernstein_index(n, j, k) = k (2n + 3 − k) / 2 + j.
#include <gmpxx.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>

#include "geometry/vec2.hpp"

namespace curvemesh::geometry {

using P3Nodes = std::array<Vec2, 10>;

// A point with coordinates in any field T (double, mpq_class, ...), for the exact templates.
template <class T>
using PointT = std::array<T, 2>;
template <class T>
using P3NodesT = std::array<PointT<T>, 10>;

// Number of coefficients of a degree-n triangular Bernstein polynomial.
constexpr std::size_t bernstein_count(int n) {
  return static_cast<std::size_t>((n + 1) * (n + 2) / 2);
}
constexpr std::size_t bernstein_index(int n, int j, int k) {
  return static_cast<std::size_t>(k * (2 * n + 3 - k) / 2 + j);
}

// Reference coordinates (u, v) of node i, times 3 (so exact in integers).
constexpr std::array<std::array<int, 2>, 10> kP3ReferenceNodesTimes3{
    {{0, 0}, {3, 0}, {0, 3}, {1, 0}, {2, 0}, {2, 1}, {1, 2}, {0, 2}, {0, 1}, {1, 1}}};
Vec2 p3_reference_node(int i);

// Nodes of the straight triangle a, b, c: edge nodes at thirds, centre at the centroid.
P3Nodes p3_straight_nodes(const Vec2& a, const Vec2& b, const Vec2& c);

// The same nodes computed exactly and each coordinate rounded toward zero, as mpq_class::get_d
// rounds the rationals of p3_straight_nodes' exact map (the nodes on which `curvemesh check` has
// always measured a linear element's scaled Jacobian), without rationals but where the result
// would be subnormal.
P3Nodes p3_straight_nodes_truncated(const Vec2& a, const Vec2& b, const Vec2& c);

// Centres for the corner and edge nodes of `nodes` (its centre is not read), in the order the
// curve stage tries them: the one that reproduces quadratic maps exactly (the map's cubic part as
// small as the edges allow), the paper's (the average of the other nine nodes), the corners'
// centroid.
std::array<Vec2, 3> p3_centre_candidates(const P3Nodes& nodes);

// The map x(u, v) = Σ ℓ_i(u, v) node_i and its Jacobian [∂x/∂u ∂x/∂v] at a reference point.
Vec2 p3_map(const P3Nodes& nodes, double u, double v);
Eigen::Matrix2d p3_jacobian(const P3Nodes& nodes, double u, double v);

// The conformal AMIPS energy of the map at a reference point: ‖J‖²/det J with J the Jacobian
// taken from the equilateral reference triangle, so 2 where the map is conformal and +∞ where
// det J ≤ 0; for straight nodes it equals geometry::amips of the corners everywhere.
double p3_amips(const P3Nodes& nodes, double u, double v);
// Its largest value over the 28 points of the order-6 lattice (corners, edges and inside): the
// quality measure of a curved triangle (validity is certify_jacobian's business, not this one's).
// With a `bound`, it may stop at the first value not below the bound and return that value: the
// result is exact when below the bound and at least the bound otherwise, which is all a search
// that only keeps improvements on the bound needs.
double p3_max_amips(const P3Nodes& nodes, double bound = std::numeric_limits<double>::infinity());
// The smallest det J and the largest AMIPS over the same 28 points, in one pass.
struct P3LatticeValues {
  double min_det = 0, max_amips = 0;
};
P3LatticeValues p3_lattice_values(const P3Nodes& nodes);

// Exact conversion of double nodes to rationals (every finite double is rational).
P3NodesT<mpq_class> to_exact(const P3Nodes& nodes);
P3NodesT<double> to_array(const P3Nodes& nodes);

// ---------------------------------------------------------------------------------------------
// Templates over the scalar type T: exact for mpq_class, ordinary rounding for double.

// The Lagrange basis ℓ0..ℓ9 of Appendix C at (u, v), with s = u + v.
template <class T>
std::array<T, 10> p3_basis(const T& u, const T& v) {
  const T s = u + v, one(1), n9h = T(9) / T(2);
  return {T(-(T(3) * s - one) * (s - one) * (T(3) * s - T(2)) / T(2)),
          T(u * (T(3) * u - one) * (T(3) * u - T(2)) / T(2)),
          T(v * (T(3) * v - one) * (T(3) * v - T(2)) / T(2)),
          T(n9h * u * (s - one) * (T(3) * s - T(2))),
          T(-n9h * u * (T(3) * u - one) * (s - one)),
          T(n9h * u * v * (T(3) * u - one)),
          T(n9h * u * v * (T(3) * v - one)),
          T(-n9h * v * (T(3) * v - one) * (s - one)),
          T(n9h * v * (s - one) * (T(3) * s - T(2))),
          T(T(-27) * u * v * (s - one))};
}

// x(u, v) = Σ ℓ_i(u, v) node_i.
template <class T>
PointT<T> p3_map(const P3NodesT<T>& nodes, const T& u, const T& v) {
  const auto l = p3_basis(u, v);
  PointT<T> x{T(0), T(0)};
  for (int i = 0; i < 10; ++i)
    for (int c = 0; c < 2; ++c) x[c] += l[i] * nodes[i][c];
  return x;
}

// ∂ℓ_i/∂u and ∂ℓ_i/∂v of Appendix C's basis, with s = u + v.
template <class T>
constexpr std::array<std::array<T, 2>, 10> p3_basis_gradients(const T& u, const T& v) {
  const T s = u + v, one(1), half = T(1) / T(2), n9h = T(9) / T(2);
  const T g = T(3) * s * s - T(5) * s + T(2);  // (s − 1)(3s − 2)
  const T dg = T(6) * s - T(5);
  const T d0 = -half * (T(27) * s * s - T(36) * s + T(11));  // ℓ0 = −½ (3s−1)(s−1)(3s−2)
  std::array<std::array<T, 2>, 10> d{};
  d[0] = {d0, d0};
  d[1] = {half * (T(27) * u * u - T(18) * u + T(2)), T(0)};
  d[2] = {T(0), half * (T(27) * v * v - T(18) * v + T(2))};
  d[3] = {n9h * (g + u * dg), n9h * u * dg};                             // ½·9 u g(s)
  d[4] = {-n9h * ((T(6) * u - one) * (s - one) + u * (T(3) * u - one)),  // −½·9 u (3u−1)(s−1)
          -n9h * u * (T(3) * u - one)};
  d[5] = {n9h * v * (T(6) * u - one), n9h * u * (T(3) * u - one)};  // ½·9 u v (3u−1)
  d[6] = {n9h * v * (T(3) * v - one), n9h * u * (T(6) * v - one)};  // ½·9 u v (3v−1)
  d[7] = {-n9h * v * (T(3) * v - one),                              // −½·9 v (3v−1)(s−1)
          -n9h * ((T(6) * v - one) * (s - one) + v * (T(3) * v - one))};
  d[8] = {n9h * v * dg, n9h * (g + v * dg)};                                      // ½·9 v g(s)
  d[9] = {T(-27) * v * (T(2) * u + v - one), T(-27) * u * (u + T(2) * v - one)};  // −27 u v (s−1)
  return d;
}

// det J(u, v) from the Lagrange basis derivatives: the reference formula the Bernstein form is
// tested against.
template <class T>
T p3_jacobian_det(const P3NodesT<T>& nodes, const T& u, const T& v) {
  const auto d = p3_basis_gradients(u, v);
  T xu(0), yu(0), xv(0), yv(0);
  for (int i = 0; i < 10; ++i) {
    xu += d[i][0] * nodes[i][0];
    yu += d[i][0] * nodes[i][1];
    xv += d[i][1] * nodes[i][0];
    yv += d[i][1] * nodes[i][1];
  }
  return T(xu * yv - yu * xv);
}

// The Bézier control net of the map (degree 3, in the Bernstein order above). Corners are
// shared; along an edge A→B with Lagrange nodes L_a (at 1/3) and L_b (at 2/3) the cubic
// interpolation conditions give the control point next to A as (−5A + 18L_a − 9L_b + 2B) / 6;
// the centre follows from x(⅓,⅓) = (Σ corners + 3 Σ edge controls + 6 P_111) / 27.
// Gmsh node → control index (i, j, k): 0→300, 1→030, 2→003, 3→210, 4→120, 5→021, 6→012,
// 7→102, 8→201, 9→111.
template <class T>
constexpr std::array<PointT<T>, 10> p3_control_net(const P3NodesT<T>& n) {
  auto near_a = [](const PointT<T>& a, const PointT<T>& la, const PointT<T>& lb, const PointT<T>& b) {
    PointT<T> p;
    for (int c = 0; c < 2; ++c) p[c] = T((T(-5) * a[c] + T(18) * la[c] - T(9) * lb[c] + T(2) * b[c]) / T(6));
    return p;
  };
  std::array<PointT<T>, 10> P;
  // at(i, j, k) names the control point by its full index; i = 3 − j − k is implied.
  auto at = [&]([[maybe_unused]] int i, int j, int k) -> PointT<T>& { return P[bernstein_index(3, j, k)]; };
  at(3, 0, 0) = n[0];
  at(0, 3, 0) = n[1];
  at(0, 0, 3) = n[2];
  at(2, 1, 0) = near_a(n[0], n[3], n[4], n[1]);
  at(1, 2, 0) = near_a(n[1], n[4], n[3], n[0]);
  at(0, 2, 1) = near_a(n[1], n[5], n[6], n[2]);
  at(0, 1, 2) = near_a(n[2], n[6], n[5], n[1]);
  at(1, 0, 2) = near_a(n[2], n[7], n[8], n[0]);
  at(2, 0, 1) = near_a(n[0], n[8], n[7], n[2]);
  for (int c = 0; c < 2; ++c) {
    T rest = n[0][c] + n[1][c] + n[2][c];
    for (const PointT<T>* e :
         {&at(2, 1, 0), &at(1, 2, 0), &at(0, 2, 1), &at(0, 1, 2), &at(1, 0, 2), &at(2, 0, 1)})
      rest += T(3) * (*e)[c];
    at(1, 1, 1)[c] = T((T(27) * n[9][c] - rest) / T(6));
  }
  return P;
}

// Multinomial n! / (i! j! k!) for n ≤ 4.
constexpr int multinomial(int i, int j, int k) {
  constexpr int f[5] = {1, 1, 2, 6, 24};
  return f[i + j + k] / (f[i] * f[j] * f[k]);
}

// The products of the two degree-2 nets that make det J's coefficients, in the order of the loops
// ka, ja, kb, jb (each coefficient sums its terms in that order): du index, dv index, coefficient
// index and the multinomial weight C(α) C(β). Listed once so that the sum unrolls with constant
// indices.
struct ProductTerm {
  std::size_t a, b, sum;
  int weight;
};
constexpr std::array<ProductTerm, 36> p3_product_terms() {
  std::array<ProductTerm, 36> out{};
  std::size_t n = 0;
  for (int ka = 0; ka <= 2; ++ka)
    for (int ja = 0; ja + ka <= 2; ++ja)
      for (int kb = 0; kb <= 2; ++kb)
        for (int jb = 0; jb + kb <= 2; ++jb)
          out[n++] = {bernstein_index(2, ja, ka), bernstein_index(2, jb, kb), bernstein_index(4, ja + jb, ka + kb),
                      multinomial(2 - ja - ka, ja, ka) * multinomial(2 - jb - kb, jb, kb)};
  return out;
}
inline constexpr std::array<ProductTerm, 36> kP3ProductTerms = p3_product_terms();
constexpr std::array<int, 15> p3_multinomials() {
  std::array<int, 15> out{};
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j + k <= 4; ++j) out[bernstein_index(4, j, k)] = multinomial(4 - j - k, j, k);
  return out;
}
inline constexpr std::array<int, 15> kP3Multinomials = p3_multinomials();

// det J as a degree-4 Bernstein polynomial (15 coefficients), exact for exact T.
// ∂x/∂u = 3 Σ (P_α+e1 − P_α+e0) B²_α and ∂x/∂v = 3 Σ (P_α+e2 − P_α+e0) B²_α; the product
// B²_α B²_β = [C(α) C(β) / C(α+β)] B⁴_α+β with C the multinomial.
template <class T>
constexpr std::array<T, 15> p3_jacobian_det_bernstein(const P3NodesT<T>& nodes) {
  const auto P = p3_control_net(nodes);
  std::array<PointT<T>, 6> du, dv;  // degree-2 nets, without the factor 3
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j + k <= 2; ++j) {
      const auto& p0 = P[bernstein_index(3, j, k)];  // α + e0
      const auto& p1 = P[bernstein_index(3, j + 1, k)];
      const auto& p2 = P[bernstein_index(3, j, k + 1)];
      for (int c = 0; c < 2; ++c) {
        du[bernstein_index(2, j, k)][c] = T(p1[c] - p0[c]);
        dv[bernstein_index(2, j, k)][c] = T(p2[c] - p0[c]);
      }
    }
  std::array<T, 15> sum;
  sum.fill(T(0));
#pragma GCC unroll 36
  for (const ProductTerm& e : kP3ProductTerms) {
    const auto& a = du[e.a];
    const auto& b = dv[e.b];
    sum[e.sum] += T(e.weight) * T(a[0] * b[1] - a[1] * b[0]);
  }
#pragma GCC unroll 15
  for (std::size_t i = 0; i < 15; ++i) sum[i] = T(T(9) * sum[i] / T(kP3Multinomials[i]));
  return sum;
}

// Value of a degree-n Bernstein polynomial at (u, v), by de Casteljau's algorithm.
template <class T, std::size_t N>
T bernstein_eval(const std::array<T, N>& c, int n, const T& u, const T& v) {
  std::array<T, N> net = c;
  const T l0 = T(1) - u - v;
  for (int m = n; m > 0; --m)  // degree m → m − 1, in place (row-major order keeps reads ahead)
    for (int k = 0; k < m; ++k)
      for (int j = 0; j + k < m; ++j)
        net[bernstein_index(m - 1, j, k)] =
            T(l0 * net[bernstein_index(m, j, k)] + u * net[bernstein_index(m, j + 1, k)] +
              v * net[bernstein_index(m, j, k + 1)]);
  return net[0];
}

// ---------------------------------------------------------------------------------------------
// Certification of det J > 0 on the whole reference triangle.

enum class JacobianVerdict { positive, not_positive, undecided };

struct JacobianCheckOptions {
  int max_depth = 10;           // levels of 4-way subdivision before giving up
  int max_subtriangles = 4096;  // work budget: sub-triangles examined before giving up
};

// Exact: all 15 Bernstein coefficients > 0 → positive; a value ≤ 0 at a corner of the element or
// of any sub-triangle examined → not_positive; otherwise split into 4 at the edge midpoints (exact
// de Casteljau subdivision) and recurse; undecided when the depth or work limit is reached.
JacobianVerdict certify_jacobian_exact(const P3NodesT<mpq_class>& nodes,
                                       const JacobianCheckOptions& options = {});
JacobianVerdict certify_jacobian_exact(const P3Nodes& nodes, const JacobianCheckOptions& options = {});

struct JacobianCertificate {
  JacobianVerdict verdict = JacobianVerdict::undecided;
  double min_coefficient = 0;  // smallest of the element's coefficients (15; 6 for P2): a lower bound on det J
  double max_coefficient = 0;  // largest of them: an upper bound on det J
  double min_value = 0;        // smallest det J found (15 lattice points, sub-triangle corners):
                               // an upper bound on min det J
  double scaled_jacobian = 0;  // min_value / max_coefficient (1 for a straight triangle, ≤ 0 when
                               // invalid; −∞ when max_coefficient ≤ 0)
  int subtriangles = 0;        // sub-triangles examined, the element itself included
};

// The same algorithm in double, conservative both ways: every quantity carries a rigorous bound
// on its accumulated rounding error, computed from the magnitudes involved, so a coefficient is
// positive only when it exceeds its own error bound (and a value is ≤ 0 only when it is below
// minus its bound). The nodes are first taken relative to node 0, so the bounds scale with the
// element's size squared: the verdict does not depend on where the element is or on its scale.
JacobianCertificate certify_jacobian(const P3Nodes& nodes, const JacobianCheckOptions& options = {});

// A straight triangle a, b, c, i.e. the exact map of p3_straight_nodes: its 15 coefficients all
// equal (b − a) × (c − a), so certify_jacobian_exact says positive when that is > 0 and
// not_positive otherwise. The same sign in doubles with certify_jacobian's error bound: that
// verdict when the bound decides it, undecided when it does not.
JacobianVerdict certify_jacobian_linear(const Vec2& a, const Vec2& b, const Vec2& c);

}  // namespace curvemesh::geometry
