#pragma once
// Lagrange polynomials of order 1, 2 or 3 on the reference triangle (0,0), (1,0), (0,1), with
// the nodes in Gmsh's order (corners; the inner nodes of edge 0→1, 1→2, 2→0, each from its
// first corner on; the centre for order 3) — the order of io::HighOrderMesh.
#include <Eigen/Dense>
#include <vector>

#include "geometry/vec2.hpp"

namespace curvemesh::fem {

using geometry::Vec2;

class LagrangeBasis {
 public:
  explicit LagrangeBasis(int order);  // throws std::invalid_argument unless 1 <= order <= 3

  int order() const { return order_; }
  int size() const { return static_cast<int>(nodes_.size()); }
  const std::vector<Vec2>& nodes() const { return nodes_; }

  // Values (size()) and gradients with respect to (ξ, η) (size() × 2) at a reference point.
  void evaluate(const Vec2& xi, Eigen::VectorXd& values, Eigen::MatrixX2d& gradients) const;
  Eigen::VectorXd values(const Vec2& xi) const;

 private:
  int order_;
  std::vector<Vec2> nodes_;
  Eigen::MatrixXd coefficients_;  // column i: basis function i in the monomials ξ^a η^b, a + b <= order
};

// The reference nodes of order `order` in Gmsh's order.
std::vector<Vec2> reference_nodes(int order);

}  // namespace curvemesh::fem
