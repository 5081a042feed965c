#pragma once
// Steady Stokes flow (paper §5.1): the velocity u and pressure p of a slow viscous fluid,
//   −μ Δu + ∇p = 0,   div u = 0,
// with Taylor–Hood elements: continuous P2 velocity (two components) and continuous P1 pressure,
// on a straight or cubic map. The weak form
//   μ ∫ ∇u : ∇v − ∫ p div v = 0   for every v vanishing where u is given,
//   −∫ q div u = 0                for every q,
// is a symmetric indefinite (saddle-point) system, solved by UMFPACK. The velocity is given on
// some border edges (walls, inflow); on the other border edges the natural condition of this
// form holds, μ ∂u/∂n − p n = 0 ("do nothing" outflow), under which Poiseuille flow is exact.
//
// Where a connected part of the domain has the velocity given on its whole border, the pressure
// is determined only up to a constant there (and the data must let as much fluid out as in):
// one pressure unknown of each such part is held at 0. Where triangles have all their corners on
// the border (pockets and slivers between curves), Taylor–Hood can have more pressure modes that
// no free velocity sees; they are found by rank-revealing QR and held at 0 too. Either way the
// velocity is the same and the system is nonsingular.
#include <Eigen/Dense>
#include <functional>
#include <utility>
#include <vector>

#include "fem/space.hpp"

namespace curvemesh::fem {

using VectorFunction = std::function<Vec2(const Vec2&)>;

// The velocity held at `velocity` on border edges (triangle, local edge).
struct VelocityCondition {
  std::vector<std::pair<int, int>> edges;
  VectorFunction velocity;
};

struct StokesOptions {
  double viscosity = 1;  // μ > 0
  // Groups of pressures that share free velocities (see stokes.cpp) up to this size are checked
  // for modes no free velocity sees before the solve, with a dense QR each; larger groups only
  // if the solve fails, with a sparse QR (slower than the solve, and rarely needed).
  int dense_group_limit = 64;
};

struct StokesResult {
  Eigen::VectorXd velocity;     // per unknown i of the P2 space: x at 2i, y at 2i + 1
  Eigen::VectorXd pressure;     // per unknown of the P1 space
  int velocity_unknowns = 0;    // 2 × the P2 space's size
  int pressure_unknowns = 0;    // the P1 space's size
  int fixed_velocities = 0;     // velocity unknowns held by the conditions
  int closed_parts = 0;         // connected parts with no natural border, one pressure held in each
  int dependent_pressures = 0;  // more pressures held: local modes the velocity cannot see
  // Assembly includes finding the pressures to hold; the solve, a second one if the first fails.
  double assembly_seconds = 0, solve_seconds = 0;
};

// `velocity` must be a P2 and `pressure` a P1 space of the geometry's mesh. Conditions are
// applied in order: where edges of two conditions share a node, the later one holds (list the
// walls last for no-slip at the corners). Throws std::invalid_argument on bad spaces or options
// and std::runtime_error when the solve fails.
StokesResult stokes(const Geometry& geometry, const Space& velocity, const Space& pressure,
                    const std::vector<VelocityCondition>& conditions, const StokesOptions& options = {});

}  // namespace curvemesh::fem
