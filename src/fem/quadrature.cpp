#include "fem/quadrature.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace curvemesh::fem {

namespace {

// n-point Gauss–Legendre on [0, 1]: the nodes are the eigenvalues of the symmetric tridiagonal
// Jacobi matrix of the Legendre polynomials, the weights the squared first components of its
// eigenvectors (Golub & Welsch 1969).
Quadrature gauss_legendre(int n) {
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    const double beta = k / std::sqrt(4.0 * k * k - 1.0);
    jacobi(k, k - 1) = jacobi(k - 1, k) = beta;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jacobi);
  Quadrature q;
  for (int i = 0; i < n; ++i) {
    const double v0 = eig.eigenvectors()(0, i);
    q.points.emplace_back((eig.eigenvalues()(i) + 1) / 2, 0.0);
    q.weights.push_back(v0 * v0);  // 2 v0² on [-1, 1], halved for [0, 1]
  }
  return q;
}

int points_for(int degree) {
  if (degree < 0) throw std::invalid_argument("quadrature degree must be >= 0");
  return std::max(1, (degree + 2) / 2);  // 2n - 1 >= degree
}

}  // namespace

Quadrature interval_quadrature(int degree) { return gauss_legendre(points_for(degree)); }

Quadrature triangle_quadrature(int degree) {
  // (u, v) in the unit square -> (ξ, η) = (u (1 - v), v), Jacobian (1 - v): the integrand
  // gains one degree in v.
  const Quadrature gu = gauss_legendre(points_for(degree));
  const Quadrature gv = gauss_legendre(points_for(degree + 1));
  Quadrature q;
  for (int j = 0; j < gv.size(); ++j)
    for (int i = 0; i < gu.size(); ++i) {
      const double u = gu.points[i].x(), v = gv.points[j].x();
      q.points.emplace_back(u * (1 - v), v);
      q.weights.push_back(gu.weights[i] * gv.weights[j] * (1 - v));
    }
  return q;
}

}  // namespace curvemesh::fem
