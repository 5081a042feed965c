#include "geometry/p2_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/amips.hpp"
#include "geometry/bernstein_certificate.hpp"

namespace curvemesh::geometry {

P2Nodes p2_straight_nodes(const Vec2& a, const Vec2& b, const Vec2& c) {
  return {a, b, c, (a + b) / 2, (b + c) / 2, (c + a) / 2};
}

P2NodesT<mpq_class> to_exact(const P2Nodes& nodes) {
  P2NodesT<mpq_class> out;
  for (int i = 0; i < 6; ++i) out[i] = {mpq_class(nodes[i].x()), mpq_class(nodes[i].y())};
  return out;
}

namespace {

// ∂N_i/∂u and ∂N_i/∂v of the basis (λ0 = 1 − u − v).
using Gradients = std::array<std::array<double, 2>, 6>;
constexpr Gradients p2_basis_gradients(double u, double v) {
  const double l0 = 1 - u - v;
  return {{{1 - 4 * l0, 1 - 4 * l0},
           {4 * u - 1, 0},
           {0, 4 * v - 1},
           {4 * (l0 - u), -4 * u},
           {4 * v, 4 * u},
           {-4 * v, 4 * (l0 - v)}}};
}

// The gradients at the 28 points (j/6, k/6), j + k ≤ 6, in p3_max_amips's order, once.
using LatticeGradients = std::array<Gradients, 28>;
constexpr LatticeGradients lattice_gradients() {
  LatticeGradients g{};
  int n = 0;
  for (int j = 0; j <= 6; ++j)
    for (int k = 0; j + k <= 6; ++k) g[n++] = p2_basis_gradients(j / 6.0, k / 6.0);
  return g;
}
constexpr LatticeGradients kLatticeGradients = lattice_gradients();

struct Columns {
  Vec2 xu, xv;
};
Columns jacobian_columns(const P2Nodes& nodes, const Gradients& d) {
  double xu = 0, yu = 0, xv = 0, yv = 0;
  for (int i = 0; i < 6; ++i) {
    xu += nodes[i].x() * d[i][0];
    yu += nodes[i].y() * d[i][0];
    xv += nodes[i].x() * d[i][1];
    yv += nodes[i].y() * d[i][1];
  }
  return {Vec2(xu, yu), Vec2(xv, yv)};
}

}  // namespace

Vec2 p2_map(const P2Nodes& n, double u, double v) {
  const double l0 = 1 - u - v;
  return l0 * (2 * l0 - 1) * n[0] + u * (2 * u - 1) * n[1] + v * (2 * v - 1) * n[2] + 4 * l0 * u * n[3] +
         4 * u * v * n[4] + 4 * v * l0 * n[5];
}

Eigen::Matrix2d p2_jacobian(const P2Nodes& nodes, double u, double v) {
  const Columns J = jacobian_columns(nodes, p2_basis_gradients(u, v));
  Eigen::Matrix2d out;
  out << J.xu, J.xv;
  return out;
}

double p2_max_amips(const P2Nodes& nodes, double bound) {
  double e = 0;
  for (const auto& d : kLatticeGradients) {
    const Columns J = jacobian_columns(nodes, d);
    e = std::max(e, amips_of_edges(J.xu, J.xv));
    if (e >= bound) break;
  }
  return e;
}

P3LatticeValues p2_lattice_values(const P2Nodes& nodes) {
  P3LatticeValues out{std::numeric_limits<double>::infinity(), 0};
  for (const auto& d : kLatticeGradients) {
    const Columns J = jacobian_columns(nodes, d);
    out.min_det = std::min(out.min_det, cross(J.xu, J.xv));
    out.max_amips = std::max(out.max_amips, amips_of_edges(J.xu, J.xv));
  }
  return out;
}

JacobianVerdict certify_jacobian_exact(const P2NodesT<mpq_class>& nodes, const JacobianCheckOptions& options) {
  return detail::certify<2>(p2_jacobian_det_bernstein(nodes), options).verdict;
}

JacobianVerdict certify_jacobian_exact(const P2Nodes& nodes, const JacobianCheckOptions& options) {
  return certify_jacobian_exact(to_exact(nodes), options);
}

JacobianCertificate certify_jacobian(const P2Nodes& nodes, const JacobianCheckOptions& options) {
  return detail::certificate<2>(
      nodes, [](const auto& n) { return p2_jacobian_det_bernstein(n); },
      [](const P2NodesT<double>& n) {
        double m = std::numeric_limits<double>::infinity();
        for (int k = 0; k <= 4; ++k)
          for (int j = 0; j + k <= 4; ++j) m = std::min(m, p2_jacobian_det(n, j / 4.0, k / 4.0));
        return m;
      },
      options);
}

}  // namespace curvemesh::geometry
