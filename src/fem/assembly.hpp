#pragma once
// Assembly of the scalar matrices and vectors most problems are made of, the error norms of a
// solution against a known function, and the sparse direct solves (SuiteSparse: CHOLMOD for
// symmetric positive definite systems, UMFPACK for the rest) with Dirichlet unknowns eliminated.
#include <Eigen/Sparse>
#include <functional>
#include <vector>

#include "fem/space.hpp"

namespace curvemesh::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;
using ScalarFunction = std::function<double(const Vec2&)>;
using GradientFunction = std::function<Vec2(const Vec2&)>;

SparseMatrix stiffness_matrix(const Geometry& geometry, const Space& space);  // ∫ ∇φi·∇φj
SparseMatrix mass_matrix(const Geometry& geometry, const Space& space);       // ∫ φi φj
Eigen::VectorXd load_vector(const Geometry& geometry, const Space& space, const ScalarFunction& f);  // ∫ f φi

// Unknowns held at given values; the others are solved for.
struct Dirichlet {
  std::vector<char> fixed;  // one per unknown
  Eigen::VectorXd values;   // one per unknown; read where fixed

  explicit Dirichlet(int size) : fixed(size, 0), values(Eigen::VectorXd::Zero(size)) {}
  void set(int dof, double value) { fixed[dof] = 1, values[dof] = value; }
  int fixed_count() const;
};

// Solves A x = b for the free unknowns (the rows of fixed ones are dropped, their columns moved
// to the right-hand side); x takes the fixed values elsewhere. `symmetric_positive`: CHOLMOD,
// else UMFPACK. Throws std::runtime_error when the factorization fails (a singular system).
Eigen::VectorXd solve(const SparseMatrix& a, const Eigen::VectorXd& b, const Dirichlet& dirichlet,
                      bool symmetric_positive);

// The same for several problems that share the matrix and which unknowns are fixed: column k of b
// and of `values` (read where fixed) is problem k, column k of the result its solution. One
// factorization serves them all.
Eigen::MatrixXd solve(const SparseMatrix& a, const Eigen::MatrixXd& b, const std::vector<char>& fixed,
                      const Eigen::MatrixXd& values, bool symmetric_positive);

// The domain's triangles whose edges are on no other triangle of the mesh: (triangle, local edge).
std::vector<std::pair<int, int>> boundary_edges(const io::HighOrderMesh& mesh);

// The unknowns of `space` on the given edges, set to g at their positions on `geometry`.
void set_on_edges(const Geometry& geometry, const Space& space, const std::vector<std::pair<int, int>>& edges,
                  const ScalarFunction& g, Dirichlet& dirichlet);

// ‖u_h − u‖ in L2 and |u_h − u| in H1 over the mesh (on its own geometry).
double l2_error(const Geometry& geometry, const Space& space, const Eigen::VectorXd& uh, const ScalarFunction& u,
                int extra_degree = 4);
double h1_error(const Geometry& geometry, const Space& space, const Eigen::VectorXd& uh, const GradientFunction& grad_u,
                int extra_degree = 4);

double area(const Geometry& geometry);

}  // namespace curvemesh::fem
