#include "geometry/p3_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "geometry/amips.hpp"
#include "geometry/bernstein_certificate.hpp"

namespace curvemesh::geometry {

Vec2 p3_reference_node(int i) {
  return Vec2(kP3ReferenceNodesTimes3[i][0], kP3ReferenceNodesTimes3[i][1]) / 3.0;
}

P3Nodes p3_straight_nodes(const Vec2& a, const Vec2& b, const Vec2& c) {
  auto third = [](const Vec2& p, const Vec2& q) -> Vec2 { return (2 * p + q) / 3; };  // 1/3 from p
  return {a,           b,           c,           third(a, b), third(b, a),
          third(b, c), third(c, b), third(c, a), third(a, c), (a + b + c) / 3};
}

namespace {

// (w0 x0 + w1 x1 + w2 x2) / 3 rounded toward zero, for small integer weights w: mpq_get_d of the
// exact rational, computed on integers. Each nonzero x is an integer M of 53 bits times 2^E;
// with e the smallest such E, the sum is n 2^e for the integer n = Σ w M 2^(E − e). The integer
// quotient of n 2^64 by 3, which has more than 53 bits (|n| ≥ 1), truncated to 53 bits by
// mpz_get_d_2exp, is the real quotient truncated to 53 bits: at 2^62 and above every double is
// an integer. The scaling by 2^(e − 64) is then exact unless the result is subnormal, where
// ldexp would round to nearest: that case is left to mpq.
double third_truncated(const std::array<int, 3>& w, const std::array<double, 3>& x) {
  std::array<long, 3> m{};
  std::array<int, 3> exponent{};
  int e = std::numeric_limits<int>::max();
  for (int k = 0; k < 3; ++k) {
    int q = 0;
    m[k] = w[k] ? static_cast<long>(std::ldexp(std::frexp(x[k], &q), 53)) : 0;
    exponent[k] = q - 53;
    if (m[k]) e = std::min(e, exponent[k]);
  }
  if (e == std::numeric_limits<int>::max()) return 0.0;
  mpz_class n(0);
  for (int k = 0; k < 3; ++k)
    if (m[k]) n += mpz_class(m[k] * w[k]) << static_cast<mp_bitcnt_t>(exponent[k] - e);
  if (n == 0) return 0.0;
  n <<= 64;
  mpz_tdiv_q_ui(n.get_mpz_t(), n.get_mpz_t(), 3);
  long scale = 0;
  const double d = mpz_get_d_2exp(&scale, n.get_mpz_t());  // |d| in [0.5, 1), toward zero
  scale += e - 64;
  if (scale - 1 < std::numeric_limits<double>::min_exponent - 1) {
    mpq_class exact(0);
    for (int k = 0; k < 3; ++k) exact += mpq_class(w[k]) * mpq_class(x[k]);
    return mpq_class(exact / 3).get_d();
  }
  return std::ldexp(d, static_cast<int>(scale));
}

}  // namespace

P3Nodes p3_straight_nodes_truncated(const Vec2& a, const Vec2& b, const Vec2& c) {
  P3Nodes out;
  // The corners are exact; + 0.0 turns −0 into +0, as a rational has no sign of zero.
  const Vec2 zero = Vec2::Zero();
  out[0] = a + zero, out[1] = b + zero, out[2] = c + zero;
  for (int i = 3; i < 10; ++i) {
    const int u3 = kP3ReferenceNodesTimes3[i][0], v3 = kP3ReferenceNodesTimes3[i][1];
    const std::array<int, 3> w{3 - u3 - v3, u3, v3};
    out[i] = Vec2(third_truncated(w, {a.x(), b.x(), c.x()}), third_truncated(w, {a.y(), b.y(), c.y()}));
  }
  return out;
}

std::array<Vec2, 3> p3_centre_candidates(const P3Nodes& p) {
  const Vec2 sum_corners = p[0] + p[1] + p[2];
  Vec2 sum_edges = Vec2::Zero();
  for (int i = 3; i < 9; ++i) sum_edges += p[i];
  return {sum_edges / 4 - sum_corners / 6, (sum_corners + sum_edges) / 9, sum_corners / 3};
}

P3NodesT<mpq_class> to_exact(const P3Nodes& nodes) {
  P3NodesT<mpq_class> out;
  for (int i = 0; i < 10; ++i) out[i] = {mpq_class(nodes[i].x()), mpq_class(nodes[i].y())};
  return out;
}

P3NodesT<double> to_array(const P3Nodes& nodes) {
  P3NodesT<double> out;
  for (int i = 0; i < 10; ++i) out[i] = {nodes[i].x(), nodes[i].y()};
  return out;
}

Vec2 p3_map(const P3Nodes& nodes, double u, double v) {
  const auto x = p3_map(to_array(nodes), u, v);
  return {x[0], x[1]};
}

Eigen::Matrix2d p3_jacobian(const P3Nodes& nodes, double u, double v) {
  const auto d = p3_basis_gradients(u, v);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 10; ++i) J += nodes[i] * Eigen::RowVector2d(d[i][0], d[i][1]);
  return J;
}

double p3_amips(const P3Nodes& nodes, double u, double v) {
  const Eigen::Matrix2d J = p3_jacobian(nodes, u, v);  // [x_u x_v]
  return amips_of_edges(J.col(0), J.col(1));
}

namespace {

// The basis gradients at the 28 points (j/6, k/6), j + k ≤ 6, of the order-6 lattice, in the
// order p3_max_amips visits them: evaluated once, at compile time, with the same arithmetic as at
// run time, so the energies are bit for bit those of p3_amips at the same points.
using LatticeGradients = std::array<std::array<std::array<double, 2>, 10>, 28>;
constexpr LatticeGradients lattice_gradients() {
  LatticeGradients g{};
  int n = 0;
  for (int j = 0; j <= 6; ++j)
    for (int k = 0; j + k <= 6; ++k) g[n++] = p3_basis_gradients(j / 6.0, k / 6.0);
  return g;
}
constexpr LatticeGradients kLatticeGradients = lattice_gradients();

// The basis gradients at the 15 points (j/4, k/4) the certificate estimates min det J at, in
// bernstein_index(4, j, k) order, likewise, laid out point by point (padded to 16) so that the
// sums over the nodes run for all points at once: each point's sum in p3_jacobian_det's order,
// hence its values bit for bit.
struct QuarterGradients {
  alignas(32) std::array<std::array<double, 16>, 10> du{}, dv{};
};
constexpr QuarterGradients quarter_gradients() {
  QuarterGradients g;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j + k <= 4; ++j) {
      const auto d = p3_basis_gradients(j / 4.0, k / 4.0);
      for (int i = 0; i < 10; ++i) {
        g.du[i][bernstein_index(4, j, k)] = d[i][0];
        g.dv[i][bernstein_index(4, j, k)] = d[i][1];
      }
    }
  return g;
}
constexpr QuarterGradients kQuarterGradients = quarter_gradients();

// Four points at a time, in the four lanes of one vector (the same operations as one at a time);
// with AVX where the processor has it (no FMA: a fused product would round differently).
__attribute__((target_clones("avx2", "default"))) double quarter_lattice_min_det(const P3NodesT<double>& n) {
  using Quad = double __attribute__((vector_size(32)));
  std::array<double, 16> det;
  for (std::size_t p = 0; p < 16; p += 4) {
    Quad xu{0, 0, 0, 0}, yu{0, 0, 0, 0}, xv{0, 0, 0, 0}, yv{0, 0, 0, 0};
    for (int i = 0; i < 10; ++i) {
      Quad du, dv;
      std::memcpy(&du, &kQuarterGradients.du[i][p], sizeof du);
      std::memcpy(&dv, &kQuarterGradients.dv[i][p], sizeof dv);
      xu += du * n[i][0];
      yu += du * n[i][1];
      xv += dv * n[i][0];
      yv += dv * n[i][1];
    }
    const Quad d = xu * yv - yu * xv;
    std::memcpy(&det[p], &d, sizeof d);
  }
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < 15; ++p) m = std::min(m, det[p]);
  return m;
}

// J = Σ node_i ⊗ ∇ℓ_i at a lattice point, summed in p3_jacobian's order; its columns x_u, x_v.
struct LatticeJacobian {
  Vec2 xu, xv;
};
LatticeJacobian lattice_jacobian(const P3Nodes& nodes, const std::array<std::array<double, 2>, 10>& d) {
  double xu = 0, yu = 0, xv = 0, yv = 0;
  for (int i = 0; i < 10; ++i) {
    xu += nodes[i].x() * d[i][0];
    yu += nodes[i].y() * d[i][0];
    xv += nodes[i].x() * d[i][1];
    yv += nodes[i].y() * d[i][1];
  }
  return {Vec2(xu, yu), Vec2(xv, yv)};
}

}  // namespace

double p3_max_amips(const P3Nodes& nodes, double bound) {
  double e = 0;
  for (const auto& d : kLatticeGradients) {
    const LatticeJacobian J = lattice_jacobian(nodes, d);
    e = std::max(e, amips_of_edges(J.xu, J.xv));
    if (e >= bound) break;
  }
  return e;
}

P3LatticeValues p3_lattice_values(const P3Nodes& nodes) {
  P3LatticeValues out{std::numeric_limits<double>::infinity(), 0};
  for (const auto& d : kLatticeGradients) {
    const LatticeJacobian J = lattice_jacobian(nodes, d);
    out.min_det = std::min(out.min_det, cross(J.xu, J.xv));
    out.max_amips = std::max(out.max_amips, amips_of_edges(J.xu, J.xv));
  }
  return out;
}

JacobianVerdict certify_jacobian_exact(const P3NodesT<mpq_class>& nodes,
                                       const JacobianCheckOptions& options) {
  return detail::certify<4>(p3_jacobian_det_bernstein(nodes), options).verdict;
}

JacobianVerdict certify_jacobian_exact(const P3Nodes& nodes, const JacobianCheckOptions& options) {
  return certify_jacobian_exact(to_exact(nodes), options);
}

JacobianCertificate certify_jacobian(const P3Nodes& nodes, const JacobianCheckOptions& options) {
  return detail::certificate<4>(
      nodes, [](const auto& n) { return p3_jacobian_det_bernstein(n); },
      quarter_lattice_min_det, options);
}

JacobianVerdict certify_jacobian_linear(const Vec2& a, const Vec2& b, const Vec2& c) {
  using detail::ErrorBounded;
  const auto edge = [](double to, double from) { return ErrorBounded(to, 0) - ErrorBounded(from, 0); };
  const ErrorBounded det = edge(b.x(), a.x()) * edge(c.y(), a.y()) - edge(b.y(), a.y()) * edge(c.x(), a.x());
  if (detail::certainly_positive(det)) return JacobianVerdict::positive;
  if (detail::certainly_nonpositive(det)) return JacobianVerdict::not_positive;
  return JacobianVerdict::undecided;
}

}  // namespace curvemesh::geometry
