#include "fem/space.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace curvemesh::fem {

io::HighOrderMesh straight_mesh(const io::HighOrderMesh& mesh) {
  io::HighOrderMesh out;
  out.order = 1;
  out.nodes = mesh.nodes;
  out.physical_names = mesh.physical_names;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    const int corners[3] = {tri[0], tri[1], tri[2]};
    out.add_triangle(corners, mesh.triangle_physical[t]);
  }
  for (int l = 0; l < mesh.line_count(); ++l) {
    const auto line = mesh.line(l);
    const int ends[2] = {line[0], line[1]};
    out.add_line(ends, mesh.line_physical[l]);
  }
  return out;
}

Geometry::Geometry(const io::HighOrderMesh& mesh) : mesh_(mesh), basis_(mesh.order) {}

void Geometry::map(int t, const Vec2& xi, Vec2& x, Eigen::Matrix2d& jacobian) const {
  Eigen::VectorXd n;
  Eigen::MatrixX2d dn;
  basis_.evaluate(xi, n, dn);
  map(t, n, dn, x, jacobian);
}

void Geometry::map(int t, const Eigen::VectorXd& n, const Eigen::MatrixX2d& dn, Vec2& x, Eigen::Matrix2d& jacobian) const {
  const auto tri = mesh_.triangle(t);
  x.setZero();
  jacobian.setZero();
  for (int i = 0; i < basis_.size(); ++i) {
    const Vec2& p = mesh_.nodes[tri[i]];
    x += n(i) * p;
    jacobian.col(0) += dn(i, 0) * p;
    jacobian.col(1) += dn(i, 1) * p;
  }
}

Vec2 Geometry::map(int t, const Vec2& xi) const {
  Vec2 x;
  Eigen::Matrix2d j;
  map(t, xi, x, j);
  return x;
}

bool Geometry::inverse(int t, const Vec2& x, Vec2& xi) const {
  xi = Vec2(1.0 / 3, 1.0 / 3);
  Vec2 y;
  Eigen::Matrix2d j;
  map(t, xi, y, j);
  const double scale = std::sqrt(std::abs(j.determinant()));
  for (int it = 0; it < 30; ++it) {
    const Vec2 r = x - y;
    if (r.norm() <= 1e-13 * scale) return true;
    const double det = j.determinant();
    if (!(std::abs(det) > 0)) return false;
    xi += j.inverse() * r;
    if (!xi.allFinite() || xi.norm() > 10) return false;
    if (order() == 1) {
      map(t, xi, y, j);
      return true;  // affine: one step is exact
    }
    map(t, xi, y, j);
  }
  return (x - y).norm() <= 1e-9 * scale;
}

Space::Space(const io::HighOrderMesh& mesh, int degree) : degree_(degree), basis_(degree) {
  if (degree != 1 && degree != 2) throw std::invalid_argument("solution spaces are P1 or P2");
  std::map<int, int> corner_dof;
  std::map<std::pair<int, int>, int> edge_dof;
  const int n = mesh.triangle_count();
  dofs_.resize(std::size_t(n) * local_size());
  // Corner unknowns first, in order of first use, then edge unknowns: the numbering depends only
  // on the mesh.
  for (int t = 0; t < n; ++t) {
    const auto tri = mesh.triangle(t);
    for (int c = 0; c < 3; ++c) {
      auto [it, inserted] = corner_dof.try_emplace(tri[c], dof_count_);
      if (inserted) ++dof_count_;
      dofs_[std::size_t(t) * local_size() + c] = it->second;
    }
  }
  if (degree == 2)
    for (int t = 0; t < n; ++t) {
      const auto tri = mesh.triangle(t);
      for (int e = 0; e < 3; ++e) {
        const int a = tri[e], b = tri[(e + 1) % 3];
        auto [it, inserted] = edge_dof.try_emplace({std::min(a, b), std::max(a, b)}, dof_count_);
        if (inserted) ++dof_count_;
        dofs_[std::size_t(t) * 6 + 3 + e] = it->second;
      }
    }
}

std::vector<int> Space::edge_local_dofs(int e) const {
  std::vector<int> local = {e, (e + 1) % 3};
  if (degree_ == 2) local.push_back(3 + e);
  return local;
}

std::vector<Vec2> Space::positions(const Geometry& geometry) const {
  std::vector<Vec2> out(dof_count_, Vec2::Zero());
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    const auto d = dofs(t);
    for (int i = 0; i < local_size(); ++i) out[d[i]] = geometry.map(t, basis_.nodes()[i]);
  }
  return out;
}

void ElementValues::compute(const Geometry& geometry, const Space& space, const Quadrature& q, int t) {
  const int n = q.size();
  x.resize(n);
  weight.resize(n);
  value.resize(n);
  grad.resize(n);
  det.resize(n);
  if (points_ != q.points || geometry_order_ != geometry.order() || space_degree_ != space.degree()) {
    points_ = q.points;
    geometry_order_ = geometry.order();
    space_degree_ = space.degree();
    geometry_value_.resize(n), geometry_grad_.resize(n), space_value_.resize(n), space_grad_.resize(n);
    for (int k = 0; k < n; ++k) {
      geometry.basis().evaluate(q.points[k], geometry_value_[k], geometry_grad_[k]);
      space.basis().evaluate(q.points[k], space_value_[k], space_grad_[k]);
    }
  }
  Eigen::Matrix2d j;
  for (int k = 0; k < n; ++k) {
    geometry.map(t, geometry_value_[k], geometry_grad_[k], x[k], j);
    det[k] = j.determinant();
    weight[k] = q.weights[k] * std::abs(det[k]);
    value[k] = space_value_[k];
    // ∇x φ = J⁻ᵀ ∇ξ φ: as rows, g · J⁻¹.
    grad[k].noalias() = space_grad_[k] * j.inverse();
  }
}

int quadrature_degree(const Geometry& geometry, const Space& space) {
  // Two basis functions: 2·degree, exact on straight maps. A cubic map adds its order − 1:
  // its integrands are not polynomials of a low degree (det J has degree 4, the stiffness
  // integrand is rational), and on the disk of fem/convergence.hpp two more degrees change no
  // error's fourth digit (degree 8 took 25 points per triangle where 6 takes 16).
  return 2 * space.degree() + (geometry.order() - 1);
}

}  // namespace curvemesh::fem
