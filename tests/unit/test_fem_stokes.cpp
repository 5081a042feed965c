// Stokes flow with Taylor–Hood elements (fem/stokes.hpp). Poiseuille flow in a straight channel,
//   u = (G / 2μ · y (H − y), 0),   p = G (L − x),
// has a quadratic velocity and a linear pressure, so P2–P1 on an affine map holds it exactly:
// the discrete solution must match it to round-off on any straight triangulation of the
// channel, and on cubic triangles whose nodes sit where the affine map puts them. Cubic
// triangles that are really curved (the channel's inside bent by a smooth map, its sides kept
// straight) leave the exact solution out of the space: then what must hold is ∫ q div u_h = 0 for
// every P1 q, hence the inflow's flux reaching the outlet exactly, and the optimal convergence
// rates. Where the velocity is given all around, one pressure is held and the flow still solves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "fem/assembly.hpp"
#include "fem/convergence.hpp"
#include "fem/stokes.hpp"

namespace curvemesh::fem {
namespace {

constexpr double kLength = 3, kHeight = 1, kViscosity = 0.7, kGradient = 2;

Vec2 poiseuille_velocity(const Vec2& x) {
  return {kGradient / (2 * kViscosity) * x.y() * (kHeight - x.y()), 0};
}
double poiseuille_pressure(const Vec2& x) {
  return kGradient * (kLength - x.x());
}
// ∫₀ᴴ u_x dy.
constexpr double kFlux = kGradient * kHeight * kHeight * kHeight / (12 * kViscosity);

// The rectangle [x0, x0 + length] × [0, H] as nx × ny squares cut by alternating diagonals, of
// order 1 or 3, every node (corners and inner nodes alike) then moved by the smooth field
//   d(x) = bend · sin(π (x − x0) / length) · sin(π y / H) · (1, 1) / √2,
// which vanishes on the border: the domain stays the rectangle with straight sides, and with
// bend ≠ 0 the cubic triangles are curved (the interpolant of a smooth non-affine map) while
// the straight ones are a less regular triangulation.
io::HighOrderMesh channel(int nx, int ny, int order, double bend = 0, double x0 = 0,
                          double length = kLength) {
  io::HighOrderMesh m;
  m.order = order;
  const double hx = length / nx, hy = kHeight / ny;
  auto corner = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(x0 + i * hx, j * hy);
  auto add = [&](const Vec2& x) {
    m.nodes.push_back(x);
    return static_cast<int>(m.nodes.size()) - 1;
  };
  std::map<std::pair<int, int>, std::array<int, 2>> edge_nodes;  // from the lower corner on
  auto edge = [&](int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = edge_nodes.find(key);
    if (it == edge_nodes.end()) {
      const Vec2 p = m.nodes[key.first], q = m.nodes[key.second];
      const int n1 = add((2 * p + q) / 3);
      const int n2 = add((p + 2 * q) / 3);
      it = edge_nodes.emplace(key, std::array<int, 2>{n1, n2}).first;
    }
    return a < b ? it->second : std::array<int, 2>{it->second[1], it->second[0]};
  };
  auto triangle = [&](int a, int b, int c) {
    std::vector<int> nodes = {a, b, c};
    if (order == 3) {
      for (const auto& [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
        for (int n : edge(p, q)) nodes.push_back(n);
      nodes.push_back(add((m.nodes[a] + m.nodes[b] + m.nodes[c]) / 3));
    }
    m.add_triangle(nodes);
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1), d = corner(i, j + 1);
      if ((i + j) % 2 == 0)
        triangle(a, b, c), triangle(a, c, d);
      else
        triangle(a, b, d), triangle(b, c, d);
    }
  for (Vec2& x : m.nodes)
    x += bend * std::sin(M_PI * (x.x() - x0) / length) * std::sin(M_PI * x.y() / kHeight) * Vec2(1, 1) /
         std::sqrt(2.0);
  return m;
}

// The border edges of the mesh whose two corners and midpoint satisfy `where`.
std::vector<std::pair<int, int>> edges_where(const io::HighOrderMesh& mesh,
                                             const std::function<bool(const Vec2&)>& where) {
  std::vector<std::pair<int, int>> out;
  for (const auto& [t, e] : boundary_edges(mesh)) {
    const auto tri = mesh.triangle(t);
    const Vec2 a = mesh.nodes[tri[e]], b = mesh.nodes[tri[(e + 1) % 3]];
    if (where(a) && where(b) && where((a + b) / 2)) out.emplace_back(t, e);
  }
  return out;
}

// Poiseuille's boundary conditions on the channel from x0 to x1: the exact profile at the
// inlet, no slip on the walls, nothing at the outlet.
std::vector<VelocityCondition> poiseuille_conditions(const io::HighOrderMesh& mesh, double x0 = 0) {
  VelocityCondition inflow{edges_where(mesh, [x0](const Vec2& x) { return std::abs(x.x() - x0) < 1e-12; }),
                           poiseuille_velocity};
  VelocityCondition walls{
      edges_where(mesh,
                  [](const Vec2& x) { return std::abs(x.y()) < 1e-12 || std::abs(x.y() - kHeight) < 1e-12; }),
      [](const Vec2&) { return Vec2(0, 0); }};
  return {inflow, walls};
}

struct Errors {
  double velocity = 0, pressure = 0;  // largest difference at the unknowns, relative to the largest value
};

Errors nodal_errors(const Geometry& geometry, const Space& velocity, const Space& pressure,
                    const StokesResult& r) {
  Errors e;
  double umax = 0, pmax = 0;
  const auto xv = velocity.positions(geometry);
  for (int i = 0; i < velocity.size(); ++i) {
    const Vec2 u = poiseuille_velocity(xv[i]);
    e.velocity = std::max(e.velocity, (Vec2(r.velocity[2 * i], r.velocity[2 * i + 1]) - u).norm());
    umax = std::max(umax, u.norm());
  }
  const auto xp = pressure.positions(geometry);
  for (int i = 0; i < pressure.size(); ++i) {
    e.pressure = std::max(e.pressure, std::abs(r.pressure[i] - poiseuille_pressure(xp[i])));
    pmax = std::max(pmax, std::abs(poiseuille_pressure(xp[i])));
  }
  e.velocity /= umax, e.pressure /= pmax;
  return e;
}

// ∫ q div u_h for every P1 function q (independently of the solver's assembly, with a rule
// exact for the polynomial integrand q · (adj J ∇ξ u) on a cubic map), and the scale to judge
// it by: the same sums of absolute values.
std::pair<Eigen::VectorXd, double> divergence_moments(const Geometry& geometry, const Space& velocity,
                                                      const Space& pressure, const Eigen::VectorXd& u) {
  const Quadrature q = triangle_quadrature(6);
  ElementValues ev;
  Eigen::VectorXd moments = Eigen::VectorXd::Zero(pressure.size());
  double scale = 0;
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, velocity, q, t);
    const auto dv = velocity.dofs(t);
    const auto dp = pressure.dofs(t);
    for (int p = 0; p < ev.points(); ++p) {
      double div = 0, size = 0;
      for (int i = 0; i < 6; ++i)
        for (int c = 0; c < 2; ++c) {
          div += u[2 * dv[i] + c] * ev.grad[p](i, c);
          size += std::abs(u[2 * dv[i] + c] * ev.grad[p](i, c));
        }
      const Eigen::VectorXd psi = pressure.basis().values(q.points[p]);
      for (int j = 0; j < 3; ++j) moments[dp[j]] += ev.weight[p] * psi(j) * div;
      scale += ev.weight[p] * size;
    }
  }
  return {moments, scale};
}

// ∫ u_h · n over the border edges with both corners at x = x_side (n = +x).
double flux_through(const Geometry& geometry, const Space& velocity, const Eigen::VectorXd& u,
                    double x_side) {
  const io::HighOrderMesh& mesh = geometry.mesh();
  const Quadrature line = interval_quadrature(10);
  const std::array<Vec2, 3> corners = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  double flux = 0;
  for (const auto& [t, e] :
       edges_where(mesh, [x_side](const Vec2& x) { return std::abs(x.x() - x_side) < 1e-12; })) {
    const auto d = velocity.dofs(t);
    const Vec2 a = corners[e], b = corners[(e + 1) % 3];
    for (int k = 0; k < line.size(); ++k) {
      const Vec2 xi = a + line.points[k].x() * (b - a);
      Vec2 x;
      Eigen::Matrix2d j;
      geometry.map(t, xi, x, j);
      const Eigen::VectorXd phi = velocity.basis().values(xi);
      double ux = 0;
      for (int i = 0; i < 6; ++i) ux += u[2 * d[i]] * phi(i);
      flux += line.weights[k] * ux * (j * (b - a)).norm();
    }
  }
  return flux;
}

StokesResult solve_poiseuille(const io::HighOrderMesh& mesh, const Geometry& geometry, const Space& velocity,
                              const Space& pressure) {
  return stokes(geometry, velocity, pressure, poiseuille_conditions(mesh), {.viscosity = kViscosity});
}

TEST(StokesTest, PoiseuilleFlowIsExactOnStraightTriangles) {
  const io::HighOrderMesh mesh = channel(6, 3, 1, 0.2);
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  const StokesResult r = solve_poiseuille(mesh, geometry, velocity, pressure);
  EXPECT_EQ(r.velocity_unknowns, 2 * velocity.size());
  EXPECT_EQ(r.pressure_unknowns, pressure.size());
  EXPECT_EQ(r.closed_parts, 0);  // the outlet fixes the pressure's level
  const Errors e = nodal_errors(geometry, velocity, pressure, r);
  EXPECT_LT(e.velocity, 1e-10);
  EXPECT_LT(e.pressure, 1e-10);
  // The solution is not trivially zero: the errors are relative to a nonzero field.
  EXPECT_GT(r.velocity.cwiseAbs().maxCoeff(), 0.3);
  EXPECT_NEAR(flux_through(geometry, velocity, r.velocity, kLength), kFlux, 1e-12);
}

TEST(StokesTest, PoiseuilleFlowIsExactOnACubicMapThatIsAffine) {
  // Cubic triangles whose inner nodes sit where the straight map puts them: the same map.
  const io::HighOrderMesh mesh = channel(6, 3, 3);
  ASSERT_EQ(mesh.order, 3);
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  const Errors e =
      nodal_errors(geometry, velocity, pressure, solve_poiseuille(mesh, geometry, velocity, pressure));
  EXPECT_LT(e.velocity, 1e-10);
  EXPECT_LT(e.pressure, 1e-10);
}

TEST(StokesTest, PoiseuilleFlowIsExactUnderViscosityAndSpeedScaling) {
  // Doubling μ with the same inflow halves the pressure gradient: p = G/2 (L − x) with μ' = 2μ.
  const io::HighOrderMesh mesh = channel(4, 2, 1);
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  const StokesResult r1 =
      stokes(geometry, velocity, pressure, poiseuille_conditions(mesh), {.viscosity = kViscosity});
  const StokesResult r2 =
      stokes(geometry, velocity, pressure, poiseuille_conditions(mesh), {.viscosity = 2 * kViscosity});
  EXPECT_LT((r2.velocity - r1.velocity).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((r2.pressure - 2 * r1.pressure).cwiseAbs().maxCoeff(), 1e-10 * r1.pressure.cwiseAbs().maxCoeff());
}

TEST(StokesTest, CurvedMapConservesMassAndConverges) {
  // The bent channel's cubic triangles are valid (det J > 0 at the quadrature points, checked),
  // their map is not affine, and Poiseuille flow is no longer in the space. The meshes are the
  // interpolants of one smooth map at shrinking h, a regular family of curved triangles: the
  // errors fall at the optimal rates, h³ for the velocity and h² for the pressure in L2.
  std::vector<double> h, velocity_errors, pressure_errors;
  for (int level : {1, 2, 4}) {
    const io::HighOrderMesh mesh = channel(6 * level, 3 * level, 3, 0.2);
    const Geometry geometry(mesh);
    const Space velocity(mesh, 2), pressure(mesh, 1);
    const Quadrature q = triangle_quadrature(quadrature_degree(geometry, velocity));
    ElementValues ev;
    double min_det = INFINITY;
    for (int t = 0; t < geometry.triangle_count(); ++t) {
      ev.compute(geometry, velocity, q, t);
      min_det = std::min(min_det, *std::min_element(ev.det.begin(), ev.det.end()));
    }
    ASSERT_GT(min_det, 0);
    EXPECT_NEAR(area(geometry), kLength * kHeight, 1e-12);

    const StokesResult r = solve_poiseuille(mesh, geometry, velocity, pressure);
    const auto [moments, scale] = divergence_moments(geometry, velocity, pressure, r.velocity);
    EXPECT_LT(moments.cwiseAbs().maxCoeff(), 1e-13 * scale) << "level " << level;
    // Σ q_j = 1, so the moments sum to ∫ div u_h = the flux out minus the flux in.
    EXPECT_NEAR(flux_through(geometry, velocity, r.velocity, kLength), kFlux, 1e-12 * kFlux)
        << "level " << level;
    Eigen::VectorXd ux(velocity.size()), uy(velocity.size());
    for (int i = 0; i < velocity.size(); ++i) ux[i] = r.velocity[2 * i], uy[i] = r.velocity[2 * i + 1];
    h.push_back(1.0 / level);
    velocity_errors.push_back(
        std::hypot(l2_error(geometry, velocity, ux, [](const Vec2& x) { return poiseuille_velocity(x).x(); }),
                   l2_error(geometry, velocity, uy, [](const Vec2&) { return 0.0; })));
    pressure_errors.push_back(l2_error(geometry, pressure, r.pressure, poiseuille_pressure));
  }
  // Not exact: the test would not notice a solver that ignored the map otherwise.
  EXPECT_GT(velocity_errors[0], 1e-4);
  EXPECT_GT(pressure_errors[0], 1e-3);
  EXPECT_GT(convergence_rate(h, velocity_errors), 2.8);
  EXPECT_GT(convergence_rate(h, pressure_errors), 1.8);
}

TEST(StokesTest, DrivenCavityHoldsOnePressureAndIsDivergenceFree) {
  // The velocity is given on the whole border (a lid moving along the top, no slip elsewhere):
  // the pressure is defined up to a constant, one unknown is held, and the divergence
  // condition still holds for every q, the held one's too, since the border flux is zero.
  const io::HighOrderMesh mesh = channel(5, 5, 3, 0.2);
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  VelocityCondition lid{edges_where(mesh, [](const Vec2& x) { return std::abs(x.y() - kHeight) < 1e-12; }),
                        [](const Vec2& x) { return Vec2(x.x() * (kLength - x.x()), 0); }};
  VelocityCondition walls{boundary_edges(mesh), [](const Vec2&) { return Vec2(0, 0); }};
  const StokesResult r = stokes(geometry, velocity, pressure, {walls, lid});  // the lid holds on its edges
  EXPECT_EQ(r.closed_parts, 1);
  EXPECT_EQ(r.pressure[0], 0.0);  // the held unknown: the lowest of its part
  EXPECT_TRUE(r.velocity.allFinite() && r.pressure.allFinite());
  EXPECT_GT(r.pressure.cwiseAbs().maxCoeff(), 0.1);  // the lid drives a flow
  const auto [moments, scale] = divergence_moments(geometry, velocity, pressure, r.velocity);
  EXPECT_LT(moments.cwiseAbs().maxCoeff(), 1e-13 * scale);
}

TEST(StokesTest, ClosedPartAtRestBesideAChannel) {
  // Two pieces: the channel, and a box beside it with no slip all around. The box gets its own
  // pressure reference and holds fluid at rest; the channel's flow is still exact.
  io::HighOrderMesh mesh = channel(6, 3, 1);
  const io::HighOrderMesh box = channel(2, 2, 1, 0, kLength + 1, 1);
  const int offset = static_cast<int>(mesh.nodes.size());
  mesh.nodes.insert(mesh.nodes.end(), box.nodes.begin(), box.nodes.end());
  for (int t = 0; t < box.triangle_count(); ++t) {
    std::vector<int> nodes;
    for (int n : box.triangle(t)) nodes.push_back(n + offset);
    mesh.add_triangle(nodes);
  }
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  std::vector<VelocityCondition> conditions = poiseuille_conditions(mesh);
  for (const auto& edge : edges_where(mesh, [](const Vec2& x) { return x.x() > kLength + 0.5; }))
    conditions[1].edges.push_back(edge);
  const StokesResult r = stokes(geometry, velocity, pressure, conditions, {.viscosity = kViscosity});
  EXPECT_EQ(r.closed_parts, 1);
  const auto xv = velocity.positions(geometry);
  const auto xp = pressure.positions(geometry);
  double channel_error = 0, box_speed = 0, box_pressure = 0;
  for (int i = 0; i < velocity.size(); ++i) {
    const Vec2 u(r.velocity[2 * i], r.velocity[2 * i + 1]);
    if (xv[i].x() > kLength + 0.5)
      box_speed = std::max(box_speed, u.norm());
    else
      channel_error = std::max(channel_error, (u - poiseuille_velocity(xv[i])).norm());
  }
  for (int i = 0; i < pressure.size(); ++i)
    if (xp[i].x() > kLength + 0.5) box_pressure = std::max(box_pressure, std::abs(r.pressure[i]));
  EXPECT_LT(channel_error, 1e-10);
  EXPECT_EQ(box_speed, 0.0);
  EXPECT_LT(box_pressure, 1e-12);
}

TEST(StokesTest, PocketOfTwoTrianglesHoldsItsUnseenPressures) {
  // A square of two triangles with no slip all around: four pressures, and the only free
  // velocity is the diagonal's midpoint (two unknowns). One pressure is held for the constant,
  // one more for the mode the two free velocities cannot see; the fluid is at rest.
  const io::HighOrderMesh mesh = channel(1, 1, 1, 0, 0, 1);
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  ASSERT_EQ(pressure.size(), 4);
  ASSERT_EQ(velocity.size(), 9);
  const StokesResult r =
      stokes(geometry, velocity, pressure, {{boundary_edges(mesh), [](const Vec2&) { return Vec2(0, 0); }}});
  EXPECT_EQ(r.fixed_velocities, 16);
  EXPECT_EQ(r.closed_parts, 1);
  EXPECT_EQ(r.dependent_pressures, 1);
  EXPECT_EQ(r.velocity.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(r.pressure.cwiseAbs().maxCoeff(), 0.0);
  // Without the check before the solve, the singular system fails to factor, and the sparse
  // check of every group after it finds the same mode.
  const StokesResult late =
      stokes(geometry, velocity, pressure, {{boundary_edges(mesh), [](const Vec2&) { return Vec2(0, 0); }}},
             {.dense_group_limit = 0});
  EXPECT_EQ(late.closed_parts, 1);
  EXPECT_EQ(late.dependent_pressures, 1);
  EXPECT_EQ(late.velocity.cwiseAbs().maxCoeff(), 0.0);
}

TEST(StokesTest, PoiseuilleFlowIsExactInAChannelOneTriangleThick) {
  // Every corner on a wall, the inlet or the outlet (Taylor–Hood's stability argument does not
  // cover such a mesh): the exact solution is in the space and its data are compatible with
  // every equation, so the discrete solution is still exact.
  const io::HighOrderMesh mesh = channel(6, 1, 1);
  const Geometry geometry(mesh);
  const Space velocity(mesh, 2), pressure(mesh, 1);
  const StokesResult r = solve_poiseuille(mesh, geometry, velocity, pressure);
  EXPECT_EQ(r.closed_parts + r.dependent_pressures, 0);
  const Errors e = nodal_errors(geometry, velocity, pressure, r);
  EXPECT_LT(e.velocity, 1e-10);
  EXPECT_LT(e.pressure, 1e-10);
}

TEST(StokesTest, PoiseuilleVelocityIsExactWithTheWholeBorderGiven) {
  // The exact velocity at the outlet too: the pressure's level is free, one pressure is held (and
  // in the channel one square long, another one no free velocity sees); the data let as much
  // fluid out as in, so the velocity is still exact, and the pressure exact up to its level
  // where nothing else was held.
  for (int n : {1, 6}) {
    const io::HighOrderMesh mesh = channel(n, 1, 1);
    const Geometry geometry(mesh);
    const Space velocity(mesh, 2), pressure(mesh, 1);
    std::vector<VelocityCondition> conditions = poiseuille_conditions(mesh);
    conditions[0].edges = edges_where(
        mesh, [](const Vec2& x) { return std::abs(x.x()) < 1e-12 || std::abs(x.x() - kLength) < 1e-12; });
    const StokesResult r = stokes(geometry, velocity, pressure, conditions, {.viscosity = kViscosity});
    EXPECT_EQ(r.closed_parts, 1) << n;
    EXPECT_EQ(r.dependent_pressures, n == 1 ? 1 : 0) << n;
    const Errors e = nodal_errors(geometry, velocity, pressure, r);
    EXPECT_LT(e.velocity, 1e-10) << n;
    if (r.dependent_pressures > 0) continue;
    // The held pressure is the lowest unknown, 0.
    const auto xp = pressure.positions(geometry);
    EXPECT_EQ(r.pressure[0], 0.0);
    for (int j = 0; j < pressure.size(); ++j)
      EXPECT_NEAR(r.pressure[j], poiseuille_pressure(xp[j]) - poiseuille_pressure(xp[0]),
                  1e-10 * kGradient * kLength);
  }
}

TEST(StokesTest, RefusesWrongSpacesAndViscosity) {
  const io::HighOrderMesh mesh = channel(2, 1, 1);
  const Geometry geometry(mesh);
  const Space p1(mesh, 1), p2(mesh, 2);
  EXPECT_THROW(stokes(geometry, p1, p1, {}), std::invalid_argument);
  EXPECT_THROW(stokes(geometry, p2, p2, {}), std::invalid_argument);
  EXPECT_THROW(stokes(geometry, p2, p1, {}, {.viscosity = 0}), std::invalid_argument);
  EXPECT_THROW(stokes(geometry, p2, p1, {}, {.viscosity = NAN}), std::invalid_argument);
  EXPECT_THROW(stokes(geometry, p2, p1, {}, {.dense_group_limit = -1}), std::invalid_argument);
}

}  // namespace
}  // namespace curvemesh::fem
