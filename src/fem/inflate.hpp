#pragma once
// Surface inflation (paper §5.1, after Joshi & Carr's Repoussé with a constant load): the
// bi-Laplace equation Δ²u = f on the domain, clamped at its border (u = 0, ∂u/∂n = 0), in the
// mixed form of Ciarlet and Raviart: w = −Δu and u are both P2 unknowns,
//   ∫ w ψ − ∫ ∇u·∇ψ = 0   for every ψ,
//   −∫ ∇w·∇φ = −∫ f φ     for every φ vanishing on the border,
// a symmetric indefinite system solved by UMFPACK.
#include <Eigen/Dense>

#include "fem/space.hpp"

namespace curvemesh::fem {

struct InflateResult {
  Eigen::VectorXd height;  // u, one value per unknown of the space
  Eigen::VectorXd w;       // −Δu
  int unknowns = 0;        // of the saddle-point system
  double assembly_seconds = 0, solve_seconds = 0;
};

InflateResult inflate(const Geometry& geometry, const Space& space, double load = 1);

}  // namespace curvemesh::fem
