#include "geometry/p3_triangle.hpp"

#include <algorithm>
#include <cmath>
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
      [](const auto& n, double u, double v) { return p3_jacobian_det(n, u, v); }, options);
}

}  // namespace curvemesh::geometry
