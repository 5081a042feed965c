#include "fem/assembly.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace curvemesh::fem {

namespace {

template <class Local>
SparseMatrix assemble(const Geometry& geometry, const Space& space, int degree, Local local) {
  const Quadrature q = triangle_quadrature(degree);
  ElementValues ev;
  Triplets triplets;
  const int n = space.local_size();
  triplets.reserve(std::size_t(geometry.triangle_count()) * n * n);
  Eigen::MatrixXd k(n, n);
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, space, q, t);
    k.setZero();
    for (int p = 0; p < ev.points(); ++p) local(ev, p, k);
    const auto d = space.dofs(t);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) triplets.emplace_back(d[i], d[j], k(i, j));
  }
  SparseMatrix a(space.size(), space.size());
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

}  // namespace

SparseMatrix stiffness_matrix(const Geometry& geometry, const Space& space) {
  return assemble(geometry, space, quadrature_degree(geometry, space),
                  [](const ElementValues& ev, int p, Eigen::MatrixXd& k) {
                    k.noalias() += ev.weight[p] * ev.grad[p] * ev.grad[p].transpose();
                  });
}

SparseMatrix mass_matrix(const Geometry& geometry, const Space& space) {
  return assemble(geometry, space, quadrature_degree(geometry, space),
                  [](const ElementValues& ev, int p, Eigen::MatrixXd& k) {
                    k.noalias() += ev.weight[p] * ev.value[p] * ev.value[p].transpose();
                  });
}

Eigen::VectorXd load_vector(const Geometry& geometry, const Space& space, const ScalarFunction& f) {
  const Quadrature q = triangle_quadrature(quadrature_degree(geometry, space) + 2);
  ElementValues ev;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(space.size());
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, space, q, t);
    const auto d = space.dofs(t);
    for (int p = 0; p < ev.points(); ++p) {
      const double fw = f(ev.x[p]) * ev.weight[p];
      for (int i = 0; i < space.local_size(); ++i) b[d[i]] += fw * ev.value[p](i);
    }
  }
  return b;
}

int Dirichlet::fixed_count() const { return static_cast<int>(std::count(fixed.begin(), fixed.end(), 1)); }

Eigen::MatrixXd solve(const SparseMatrix& a, const Eigen::MatrixXd& b, const std::vector<char>& fixed,
                      const Eigen::MatrixXd& values, bool symmetric_positive) {
  const int n = static_cast<int>(a.rows());
  const auto k = b.cols();
  if (a.cols() != n || b.rows() != n || static_cast<int>(fixed.size()) != n || values.rows() != n ||
      values.cols() != k)
    throw std::invalid_argument("solve: sizes do not match");
  std::vector<int> free_index(n, -1);
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (!fixed[i]) free_index[i] = m++;
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(n, k);
  for (int i = 0; i < n; ++i)
    if (fixed[i]) x.row(i) = values.row(i);
  if (m == 0) return x;
  Eigen::MatrixXd rhs(m, k);
  for (int i = 0; i < n; ++i)
    if (free_index[i] >= 0) rhs.row(free_index[i]) = b.row(i);
  Triplets triplets;
  triplets.reserve(a.nonZeros());
  for (int col = 0; col < a.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(a, col); it; ++it) {
      const int r = static_cast<int>(it.row()), c = static_cast<int>(it.col());
      if (free_index[r] < 0) continue;
      if (free_index[c] >= 0)
        triplets.emplace_back(free_index[r], free_index[c], it.value());
      else
        rhs.row(free_index[r]) -= it.value() * x.row(c);
    }
  SparseMatrix reduced(m, m);
  reduced.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::MatrixXd y;
  if (symmetric_positive) {
    // LLᵀ always: CHOLMOD's automatic mode may choose LDLᵀ, which factors an indefinite matrix
    // without complaint; LLᵀ reports it.
    Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> chol;
    chol.compute(reduced);
    if (chol.info() != Eigen::Success) throw std::runtime_error("CHOLMOD could not factor the system (not positive definite)");
    y = chol.solve(rhs);
  } else {
    Eigen::UmfPackLU<SparseMatrix> lu;
    lu.compute(reduced);
    if (lu.info() != Eigen::Success) throw std::runtime_error("UMFPACK could not factor the system (singular)");
    y = lu.solve(rhs);
  }
  if (!y.allFinite()) throw std::runtime_error("the linear solve gave non-finite values (singular system)");
  for (int i = 0; i < n; ++i)
    if (free_index[i] >= 0) x.row(i) = y.row(free_index[i]);
  return x;
}

Eigen::VectorXd solve(const SparseMatrix& a, const Eigen::VectorXd& b, const Dirichlet& dirichlet,
                      bool symmetric_positive) {
  return solve(a, Eigen::MatrixXd(b), dirichlet.fixed, Eigen::MatrixXd(dirichlet.values), symmetric_positive)
      .col(0);
}

std::vector<std::pair<int, int>> boundary_edges(const io::HighOrderMesh& mesh) {
  std::map<std::pair<int, int>, int> count;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const int a = tri[e], b = tri[(e + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::pair<int, int>> out;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const int a = tri[e], b = tri[(e + 1) % 3];
      if (count[{std::min(a, b), std::max(a, b)}] == 1) out.emplace_back(t, e);
    }
  }
  return out;
}

void set_on_edges(const Geometry& geometry, const Space& space, const std::vector<std::pair<int, int>>& edges,
                  const ScalarFunction& g, Dirichlet& dirichlet) {
  for (const auto& [t, e] : edges) {
    const auto d = space.dofs(t);
    for (int i : space.edge_local_dofs(e)) dirichlet.set(d[i], g(geometry.map(t, space.reference_points()[i])));
  }
}

namespace {

template <class Integrand>
double integrate_error(const Geometry& geometry, const Space& space, int extra_degree, Integrand integrand) {
  const Quadrature q = triangle_quadrature(quadrature_degree(geometry, space) + extra_degree);
  ElementValues ev;
  double sum = 0;
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, space, q, t);
    const auto d = space.dofs(t);
    for (int p = 0; p < ev.points(); ++p) sum += ev.weight[p] * integrand(ev, p, d);
  }
  return std::sqrt(sum);
}

}  // namespace

double l2_error(const Geometry& geometry, const Space& space, const Eigen::VectorXd& uh, const ScalarFunction& u,
                int extra_degree) {
  return integrate_error(geometry, space, extra_degree, [&](const ElementValues& ev, int p, std::span<const int> d) {
    double v = 0;
    for (int i = 0; i < space.local_size(); ++i) v += uh[d[i]] * ev.value[p](i);
    const double diff = v - u(ev.x[p]);
    return diff * diff;
  });
}

double h1_error(const Geometry& geometry, const Space& space, const Eigen::VectorXd& uh, const GradientFunction& grad_u,
                int extra_degree) {
  return integrate_error(geometry, space, extra_degree, [&](const ElementValues& ev, int p, std::span<const int> d) {
    Vec2 g = Vec2::Zero();
    for (int i = 0; i < space.local_size(); ++i) g += uh[d[i]] * ev.grad[p].row(i).transpose();
    return (g - grad_u(ev.x[p])).squaredNorm();
  });
}

double area(const Geometry& geometry) {
  const Space p1(geometry.mesh(), 1);
  return std::pow(integrate_error(geometry, p1, 0, [](const ElementValues&, int, std::span<const int>) { return 1.0; }), 2);
}

}  // namespace curvemesh::fem
