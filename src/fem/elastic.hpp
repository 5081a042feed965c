#pragma once
// Compressible Neo-Hookean hyperelasticity under gravity (paper §5.1, "Elasticity"), in plane
// strain: a P2 displacement u (two components) on a straight or cubic Geometry minimises the
// total potential energy
//
//   Π(u) = ∫ W(F) − ∫ f·u,   F = I + ∇u,  J = det F,
//   W(F) = μ/2 (tr FᵀF − 2) − μ ln J + λ/2 (ln J)²,
//
// whose first Piola stress is the paper's σ = ∂W/∂F = μ (F − F⁻ᵀ) + λ ln J F⁻ᵀ, so that the
// Euler–Lagrange equation is −div σ = f. The body force f = ρ g points along +y: the drawing's
// coordinates have y pointing down (SVG), so +y is "down" on the picture.
//
// Newton's method with the exact tangent ∂σ/∂F (the Hessian of Π): each step solves K d = −R by
// CHOLMOD (LLᵀ). The tangent is positive definite near a stable equilibrium; where it is not (far
// from one, or on an unstable branch such as a column pushed past buckling) the LLᵀ fails, or its
// step is no descent direction, and the step is taken with K + τ diag(K) instead, τ growing
// tenfold until it is, which keeps d a descent direction. A backtracking line search on Π accepts
// the step once the energy has dropped enough (Armijo) and never lets det F ≤ 0 at a quadrature
// point (Π = +∞ there). Gravity can be applied in load steps, each solved from the previous one's
// solution.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "fem/assembly.hpp"
#include "fem/space.hpp"

namespace curvemesh::fem {

struct Lame {
  double mu = 0, lambda = 0;
};

// Lamé parameters of Young's modulus E > 0 and Poisson's ratio −1 < ν < 1/2 (the 3D ones, as
// plane strain uses them).
Lame lame_parameters(double youngs_modulus, double poisson_ratio);

struct ElasticOptions {
  Lame material = lame_parameters(100.0, 0.3);
  Vec2 body_force = Vec2(0, 9.81);  // f = ρ g per unit area, in the mesh's coordinates (+y is down in a drawing)
  int load_steps = 1;               // gravity applied as f·s/steps, s = 1..steps
  double tolerance = 1e-10;         // stop when ‖R‖ <= tolerance · ‖R(0)‖ at full load (free unknowns)
  int max_iterations = 50;          // Newton iterations per load step
  int max_backtracks = 40;          // halvings of the step before the line search gives up
  double armijo = 1e-4;             // sufficient decrease: Π(u + αd) <= Π(u) + armijo · α ∇Π·d
  int quadrature_degree = 0;        // 0: fem::quadrature_degree(geometry, space)
};

// One Newton iteration: the state it started from and the step it took.
struct NewtonIteration {
  int load_step = 0;         // 1-based
  int iteration = 0;         // 0-based within the load step
  double residual = 0;       // ‖R(u_k)‖ over the free unknowns
  double energy = 0;         // Π(u_k) at this load step's load
  double step_length = 0;    // α taken (0 on the last record of a load step: converged, no step)
  int backtracks = 0;        // halvings before α was accepted
  double shift = 0;          // τ of K + τ diag(K) (0: the exact tangent's step was taken)
};

struct ElasticResult {
  Eigen::VectorXd displacement;  // component c of unknown i at 2i + c
  std::vector<NewtonIteration> iterations;
  bool converged = false;
  std::string failure;           // why not, when not converged
  double energy = 0;             // Π at the end
  double initial_residual = 0;   // ‖R(0)‖ at full load, the scale of `tolerance`
  int unknowns = 0;              // 2 × scalar unknowns, fixed ones included
  int free_unknowns = 0;
  double seconds = 0;            // the whole solve
  double assembly_seconds = 0;   // residuals, tangents and line-search energies
  double factor_seconds = 0;     // CHOLMOD analysis, factorisations and solves
};

// The hyperelastic problem on a mesh: energy, residual (its gradient) and tangent (its Hessian)
// as functions of the displacement, with some scalar unknowns clamped (u = 0 in both components).
class NeoHookean {
 public:
  // `clamped`: one flag per unknown of `space`. The geometry and space must outlive this.
  NeoHookean(const Geometry& geometry, const Space& space, std::vector<char> clamped, ElasticOptions options = {});

  int size() const { return 2 * space_.size(); }
  const ElasticOptions& options() const { return options_; }
  bool fixed(int k) const { return clamped_[k / 2] != 0; }

  // Π(u) with the body force scaled by `load`; +∞ if det F <= 0 at some quadrature point.
  double energy(const Eigen::VectorXd& u, double load = 1) const;
  // ∇Π(u) (all unknowns; the rows of clamped ones included).
  Eigen::VectorXd residual(const Eigen::VectorXd& u, double load = 1) const;
  // The Hessian of Π at u, all unknowns (symmetric).
  SparseMatrix tangent(const Eigen::VectorXd& u) const;
  // det F at every quadrature point is positive.
  bool admissible(const Eigen::VectorXd& u) const;

  ElasticResult solve() const;

 private:
  // Calls visit(t, weight, G, F) at every quadrature point (G: the local basis gradients in x,
  // one row per local unknown; F = I + ∇u); stops and returns false at a point with det F <= 0.
  template <class Visit>
  bool for_each_point(const Eigen::VectorXd& u, Visit visit) const;
  SparseMatrix assemble_tangent(const Eigen::VectorXd& u, const std::vector<int>& index, int size) const;

  const Geometry& geometry_;
  const Space& space_;
  std::vector<char> clamped_;
  ElasticOptions options_;
  Quadrature quadrature_;
  // The reference gradients of the geometry's basis and of the space's basis at the quadrature
  // points: the same on every triangle, so evaluated once.
  std::vector<Eigen::MatrixX2d> map_gradients_, basis_gradients_;
  Eigen::VectorXd load_;  // ∫ f·φ for every unknown, at full load
};

// Stored energy density W(F) and first Piola stress P(F) = ∂W/∂F; the tangent ∂P/∂F applied to
// dF. Exposed for tests.
double neo_hookean_energy(const Lame& m, const Eigen::Matrix2d& f);
Eigen::Matrix2d neo_hookean_stress(const Lame& m, const Eigen::Matrix2d& f);
Eigen::Matrix2d neo_hookean_stress_derivative(const Lame& m, const Eigen::Matrix2d& f, const Eigen::Matrix2d& df);

// How a body hangs: its border unknowns within `band` of the top (smallest y) of each piece of
// the mesh (triangles connected through edges), plus, where these hold no whole border edge (a
// rounded or pointed top), the unknowns of the border edges through the piece's topmost point,
// so that no piece can swing. One flag per unknown of `space`.
std::vector<char> hang_from_top(const Geometry& geometry, const Space& space, double band);

// The value of the displacement at a point x of the domain (located through the inverse of the
// triangles' maps); false when x lies in no triangle.
bool displacement_at(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u, const Vec2& x,
                     Vec2& value);

// ‖u‖ in L2 over the mesh.
double displacement_l2_norm(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u);

// The mesh moved by u: the same triangles with every node at x + u(x), of the geometry's order
// when it is at least 2 and of order 2 for a straight one (x + u is then quadratic, and its
// corners alone would lose it), so that the moved map is exactly x + u for a P2 (or P1) u.
struct DeformedMesh {
  io::HighOrderMesh mesh;
  std::vector<double> displacement;  // u at each node of `mesh`, 3 per node (z = 0)
};
DeformedMesh deformed_mesh(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u);

}  // namespace curvemesh::fem
