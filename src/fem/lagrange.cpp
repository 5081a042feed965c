#include "fem/lagrange.hpp"

#include <cmath>
#include <stdexcept>

namespace curvemesh::fem {

std::vector<Vec2> reference_nodes(int order) {
  if (order < 1 || order > 3) throw std::invalid_argument("Lagrange order must be 1, 2 or 3");
  const Vec2 corners[3] = {{0, 0}, {1, 0}, {0, 1}};
  std::vector<Vec2> nodes(corners, corners + 3);
  for (int e = 0; e < 3; ++e)
    for (int k = 1; k < order; ++k) {
      const double s = double(k) / order;
      nodes.push_back((1 - s) * corners[e] + s * corners[(e + 1) % 3]);
    }
  if (order == 3) nodes.emplace_back(1.0 / 3, 1.0 / 3);
  return nodes;
}

namespace {

// The monomials ξ^a η^b (a + b <= order) and their derivatives, in a fixed order.
void monomials(int order, const Vec2& xi, Eigen::VectorXd& m, Eigen::MatrixX2d& dm) {
  const int n = (order + 1) * (order + 2) / 2;
  m.resize(n);
  dm.resize(n, 2);
  // Powers by multiplication (std::pow dominated the pixel-by-pixel inverse maps of pictures).
  const double px[4] = {1, xi.x(), xi.x() * xi.x(), xi.x() * xi.x() * xi.x()};
  const double py[4] = {1, xi.y(), xi.y() * xi.y(), xi.y() * xi.y() * xi.y()};
  int i = 0;
  for (int total = 0; total <= order; ++total)
    for (int a = total; a >= 0; --a, ++i) {
      const int b = total - a;
      m(i) = px[a] * py[b];
      dm(i, 0) = a == 0 ? 0.0 : a * px[a - 1] * py[b];
      dm(i, 1) = b == 0 ? 0.0 : b * px[a] * py[b - 1];
    }
}

}  // namespace

LagrangeBasis::LagrangeBasis(int order) : order_(order), nodes_(reference_nodes(order)) {
  // Vandermonde matrix V(i, j) = monomial j at node i; the basis is V⁻¹'s columns.
  const int n = size();
  Eigen::MatrixXd vandermonde(n, n);
  Eigen::VectorXd m;
  Eigen::MatrixX2d dm;
  for (int i = 0; i < n; ++i) {
    monomials(order_, nodes_[i], m, dm);
    vandermonde.row(i) = m.transpose();
  }
  coefficients_ = vandermonde.fullPivLu().inverse();
}

void LagrangeBasis::evaluate(const Vec2& xi, Eigen::VectorXd& values, Eigen::MatrixX2d& gradients) const {
  Eigen::VectorXd m;
  Eigen::MatrixX2d dm;
  monomials(order_, xi, m, dm);
  values = coefficients_.transpose() * m;
  gradients = coefficients_.transpose() * dm;
}

Eigen::VectorXd LagrangeBasis::values(const Vec2& xi) const {
  Eigen::VectorXd v;
  Eigen::MatrixX2d g;
  evaluate(xi, v, g);
  return v;
}

}  // namespace curvemesh::fem
