#pragma once
// The geometric map of a triangle mesh (P1 straight or P3 curved triangles of an
// io::HighOrderMesh) and the Lagrange solution spaces P1 and P2 on it (paper §5.1: P2 on P3
// geometry; the same mesh with its straight P1 map for comparison).
#include <Eigen/Dense>
#include <array>
#include <span>
#include <vector>

#include "fem/lagrange.hpp"
#include "fem/quadrature.hpp"
#include "io/high_order_mesh.hpp"

namespace curvemesh::fem {

// The same mesh with straight triangles: only the corners (same node indices), lines by their
// ends. Replacing the cubic map by this one is the paper's straight comparison.
io::HighOrderMesh straight_mesh(const io::HighOrderMesh& mesh);

class Geometry {
 public:
  explicit Geometry(const io::HighOrderMesh& mesh);  // keeps a reference: the mesh must outlive it
  const io::HighOrderMesh& mesh() const { return mesh_; }
  int order() const { return mesh_.order; }
  int triangle_count() const { return mesh_.triangle_count(); }

  const LagrangeBasis& basis() const { return basis_; }
  Vec2 map(int t, const Vec2& xi) const;
  // The same from the geometric basis' values and reference gradients at ξ (see basis()).
  void map(int t, const Eigen::VectorXd& n, const Eigen::MatrixX2d& dn, Vec2& x, Eigen::Matrix2d& jacobian) const;
  // Position and Jacobian ∂x/∂ξ at a reference point.
  void map(int t, const Vec2& xi, Vec2& x, Eigen::Matrix2d& jacobian) const;
  // The reference point of triangle t that maps to x (Newton from the centroid), or nothing if
  // it does not converge. Whether x lies in the triangle is for the caller to decide from ξ.
  bool inverse(int t, const Vec2& x, Vec2& xi) const;

 private:
  const io::HighOrderMesh& mesh_;
  LagrangeBasis basis_;
};

// P1 or P2 Lagrange functions, continuous across triangles that share corner nodes: one
// unknown per corner node and, for P2, one per edge (a pair of corner nodes). A mesh cut open
// (fem/domain.hpp) has distinct nodes on the two sides of the cut, hence independent unknowns.
class Space {
 public:
  Space(const io::HighOrderMesh& mesh, int degree);

  int degree() const { return degree_; }
  int size() const { return dof_count_; }
  int local_size() const { return degree_ == 1 ? 3 : 6; }
  // The unknowns of triangle t in Gmsh's order (corners, then edges 0→1, 1→2, 2→0).
  std::span<const int> dofs(int t) const {
    return std::span<const int>(dofs_).subspan(std::size_t(t) * local_size(), local_size());
  }
  // The local unknowns on local edge e (its two corners, then the edge's own for P2).
  std::vector<int> edge_local_dofs(int e) const;
  const LagrangeBasis& basis() const { return basis_; }
  // The reference point of each local unknown.
  const std::vector<Vec2>& reference_points() const { return basis_.nodes(); }
  // Where each unknown sits on a geometry of the same mesh (the map at its reference point).
  std::vector<Vec2> positions(const Geometry& geometry) const;

 private:
  int degree_;
  int dof_count_ = 0;
  std::vector<int> dofs_;
  LagrangeBasis basis_;
};

// Basis values and physical gradients of one triangle at the quadrature points.
struct ElementValues {
  std::vector<Vec2> x;                 // mapped points
  std::vector<double> weight;          // quadrature weight × |det J|
  std::vector<Eigen::VectorXd> value;  // per point: the local basis values
  std::vector<Eigen::MatrixX2d> grad;  // per point: the local basis gradients in x
  std::vector<double> det;             // det J per point (positive in a valid mesh)

  void compute(const Geometry& geometry, const Space& space, const Quadrature& q, int t);
  int points() const { return static_cast<int>(weight.size()); }

 private:
  // The reference values of both bases at the quadrature points, computed once per rule and
  // pair of orders rather than once per triangle.
  std::vector<Vec2> points_;
  int geometry_order_ = 0, space_degree_ = 0;
  std::vector<Eigen::VectorXd> geometry_value_, space_value_;
  std::vector<Eigen::MatrixX2d> geometry_grad_, space_grad_;
};

// The quadrature degree for integrands of two basis functions of `space` on `geometry`: exact on
// straight maps, two degrees more on cubic ones (their integrands are rational).
int quadrature_degree(const Geometry& geometry, const Space& space);

}  // namespace curvemesh::fem
