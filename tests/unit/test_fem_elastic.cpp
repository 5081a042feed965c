// Neo-Hookean elasticity (fem/elastic.hpp): the stress is the derivative of the energy density
// and the tangent that of the stress; assembled, the residual is the gradient of the total
// energy and the tangent its Hessian (finite differences on curved and straight meshes); Newton
// converges quadratically on the paper's hung square with a hole; no load gives no
// displacement; small loads give linear elasticity's answer (assembled here independently);
// the body hangs from its top; the deformed mesh is exactly x + u.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "fem/domain.hpp"
#include "fem/drawing.hpp"
#include "fem/elastic.hpp"
#include "fem/output.hpp"
#include "pipeline/output.hpp"

namespace curvemesh::fem {
namespace {

using Eigen::Matrix2d;
using Eigen::VectorXd;

// The unit square in cells × cells squares cut by a diagonal, triangles of order `order` with
// their nodes on the lattice, every node then moved by `warp` (a smooth map bends every edge of
// a cubic mesh; a straight one keeps its corners only).
template <class Warp>
io::HighOrderMesh grid(int order, int cells, Warp warp) {
  io::HighOrderMesh m;
  m.order = order;
  const int n = cells * order;  // lattice points per side, minus one
  std::map<std::pair<int, int>, int> index;
  auto node = [&](int i, int j) {
    auto [it, added] = index.try_emplace({i, j}, static_cast<int>(m.nodes.size()));
    if (added) m.nodes.push_back(warp(Vec2(double(i) / n, double(j) / n)));
    return it->second;
  };
  auto triangle = [&](std::array<std::array<int, 2>, 3> c) {
    std::vector<int> ids;
    for (const auto& q : c) ids.push_back(node(q[0], q[1]));
    for (int e = 0; e < 3; ++e)
      for (int k = 1; k < order; ++k)
        ids.push_back(node((c[e][0] * (order - k) + c[(e + 1) % 3][0] * k) / order,
                           (c[e][1] * (order - k) + c[(e + 1) % 3][1] * k) / order));
    if (order == 3) ids.push_back(node((c[0][0] + c[1][0] + c[2][0]) / 3, (c[0][1] + c[1][1] + c[2][1]) / 3));
    m.add_triangle(ids);
  };
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b) {
      const int i = a * order, j = b * order, s = order;
      triangle({{{i, j}, {i + s, j}, {i + s, j + s}}});
      triangle({{{i, j}, {i + s, j + s}, {i, j + s}}});
    }
  return m;
}

Vec2 bend(const Vec2& p) {
  return {p.x() + 0.08 * std::sin(std::numbers::pi * p.y()), p.y() + 0.08 * std::sin(std::numbers::pi * p.x())};
}

VectorXd random_vector(int n, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
  VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = uniform(rng);
  return v;
}

// Zero where clamped, as the solver's iterates are.
VectorXd clamp(const NeoHookean& problem, VectorXd v) {
  for (int i = 0; i < problem.size(); ++i)
    if (problem.fixed(i)) v[i] = 0;
  return v;
}

TEST(Elastic, LameParametersOfYoungsModulusAndPoissonsRatio) {
  const Lame m = lame_parameters(1.0, 0.25);
  EXPECT_DOUBLE_EQ(m.mu, 0.4);
  EXPECT_DOUBLE_EQ(m.lambda, 0.4);
  EXPECT_THROW(lame_parameters(1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(lame_parameters(0.0, 0.3), std::invalid_argument);
}

TEST(Elastic, StressIsTheEnergyDerivativeAndTheTangentTheStressDerivative) {
  const Lame m{0.7, 2.3};
  EXPECT_NEAR(neo_hookean_energy(m, Matrix2d::Identity()), 0.0, 1e-15);
  EXPECT_NEAR(neo_hookean_stress(m, Matrix2d::Identity()).norm(), 0.0, 1e-15);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-0.4, 0.4);
  const double h = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    Matrix2d f = Matrix2d::Identity(), df;
    for (int k = 0; k < 4; ++k) f(k / 2, k % 2) += uniform(rng), df(k / 2, k % 2) = uniform(rng);
    ASSERT_GT(f.determinant(), 0);
    const Matrix2d p = neo_hookean_stress(m, f);
    const double dw = (neo_hookean_energy(m, f + h * df) - neo_hookean_energy(m, f - h * df)) / (2 * h);
    EXPECT_NEAR(dw, p.cwiseProduct(df).sum(), 1e-8 * (1 + p.norm()));
    const Matrix2d dp = (neo_hookean_stress(m, f + h * df) - neo_hookean_stress(m, f - h * df)) / (2 * h);
    EXPECT_LT((dp - neo_hookean_stress_derivative(m, f, df)).norm(), 1e-7 * (1 + dp.norm()));
  }
}

// The assembled residual is the gradient of the energy and the tangent its Hessian: central
// differences along random directions, at a random displacement that strains the mesh by up to
// about 30 %.
void check_derivatives(const io::HighOrderMesh& mesh) {
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  ElasticOptions options;
  options.material = lame_parameters(10.0, 0.4);
  options.body_force = Vec2(0.3, 1.1);
  const NeoHookean problem(geometry, space, hang_from_top(geometry, space, 1e-9), options);
  const VectorXd u = clamp(problem, random_vector(problem.size(), 0.02, 1));
  ASSERT_TRUE(problem.admissible(u));
  const VectorXd r = problem.residual(u);
  const SparseMatrix k = problem.tangent(u);
  EXPECT_LT((SparseMatrix(k.transpose()) - k).norm(), 1e-12 * k.norm());
  const double h = 1e-6;
  for (unsigned seed = 2; seed < 6; ++seed) {
    const VectorXd v = random_vector(problem.size(), 1.0, seed);
    const double de = (problem.energy(u + h * v) - problem.energy(u - h * v)) / (2 * h);
    EXPECT_NEAR(de, r.dot(v), 1e-7 * r.norm() * v.norm());
    const VectorXd dr = (problem.residual(u + h * v) - problem.residual(u - h * v)) / (2 * h);
    const VectorXd kv = k * v;
    EXPECT_LT((dr - kv).norm(), 1e-6 * kv.norm()) << "relative error " << (dr - kv).norm() / kv.norm();
  }
}

TEST(Elastic, TangentIsTheResidualDerivativeOnACurvedMesh) { check_derivatives(grid(3, 3, bend)); }
TEST(Elastic, TangentIsTheResidualDerivativeOnAStraightMesh) { check_derivatives(grid(1, 3, bend)); }

TEST(Elastic, InvertedElementsHaveInfiniteEnergy) {
  const io::HighOrderMesh mesh = grid(3, 2, bend);
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  const NeoHookean problem(geometry, space, std::vector<char>(space.size(), 0));
  // u = (−2x, 0): F = diag(−1, 1), a mirror image, det F = −1.
  VectorXd u(problem.size());
  const std::vector<Vec2> x = space.positions(geometry);
  for (int i = 0; i < space.size(); ++i) u[2 * i] = -2 * x[i].x(), u[2 * i + 1] = 0;
  EXPECT_FALSE(problem.admissible(u));
  EXPECT_EQ(problem.energy(u), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(problem.admissible(0.2 * u));
}

TEST(Elastic, HangsFromTheTopSideOrFromTheEdgesAtATopCorner) {
  // The square's top side is y = 0 (smallest y): its 2·cells + 1 P2 unknowns.
  const io::HighOrderMesh square = grid(3, 3, [](const Vec2& p) { return p; });
  const Geometry g1(square);
  const Space s1(square, 2);
  const std::vector<char> top = hang_from_top(g1, s1, 1e-9);
  const std::vector<Vec2> x1 = s1.positions(g1);
  EXPECT_EQ(std::count(top.begin(), top.end(), 1), 7);
  for (int i = 0; i < s1.size(); ++i) EXPECT_EQ(top[i] != 0, x1[i].y() < 1e-12) << i;
  // Turned by 45°, the top is a corner: the two border edges through it are clamped (5 unknowns).
  const io::HighOrderMesh diamond = grid(3, 3, [](const Vec2& p) { return Vec2(p.x() - p.y(), p.x() + p.y()); });
  const Geometry g2(diamond);
  const Space s2(diamond, 2);
  const std::vector<char> corner = hang_from_top(g2, s2, 1e-9);
  const std::vector<Vec2> x2 = s2.positions(g2);
  EXPECT_EQ(std::count(corner.begin(), corner.end(), 1), 5);
  for (int i = 0; i < s2.size(); ++i) {
    if (corner[i]) {
      EXPECT_NEAR(std::abs(x2[i].x()), x2[i].y(), 1e-12) << "clamped off the two top edges: " << i;
    }
  }
}

TEST(Elastic, HangsARoundedTopByTheEdgesAtItsTopmostPoint) {
  // The top side bent down away from x = 1/2, more steeply on the left: a band of 0.02 holds the
  // top corner and the middle of the edge on its right (y = 0.019) only, no whole edge, and
  // would let the body pivot about them. The two edges through the corner are clamped as well.
  auto top = [](double x) { return x >= 0.5 ? 0.3 * (x - 0.5) * (x - 0.5) : 0.6 * (x - 0.5) * (x - 0.5); };
  const io::HighOrderMesh mesh =
      grid(3, 2, [&](const Vec2& p) { return Vec2(p.x(), p.y() + top(p.x()) * (1 - p.y())); });
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  const std::vector<char> clamped = hang_from_top(geometry, space, 0.02);
  const std::vector<Vec2> x = space.positions(geometry);
  ASSERT_EQ(std::count_if(x.begin(), x.end(), [](const Vec2& p) { return p.y() <= 0.02; }), 2);
  // Two cells across: the two edges are the whole top side, the unknowns with y < 0.2 (the next
  // row of the grid is at 0.25 and below).
  EXPECT_EQ(std::count(clamped.begin(), clamped.end(), 1), 5);
  for (int i = 0; i < space.size(); ++i) EXPECT_EQ(clamped[i] != 0, x[i].y() < 0.2) << "(" << x[i].transpose() << ")";
}

TEST(Elastic, NoLoadNoDisplacement) {
  const io::HighOrderMesh mesh = grid(3, 3, bend);
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  ElasticOptions options;
  options.body_force = Vec2(0, 0);
  const NeoHookean problem(geometry, space, hang_from_top(geometry, space, 1e-9), options);
  // The reference configuration is stress-free: no residual, no energy.
  EXPECT_LT(problem.residual(VectorXd::Zero(problem.size())).norm(), 1e-14);
  EXPECT_EQ(problem.energy(VectorXd::Zero(problem.size())), 0.0);
  const ElasticResult r = problem.solve();
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.displacement.size(), problem.size());
  EXPECT_EQ(r.displacement.norm(), 0.0);
}

// The paper's set-up, meshed coarsely: the square with a hole, hung at its top side.
struct HungRing {
  MeshedDrawing drawing;
  io::HighOrderMesh mesh;
  explicit HungRing(double edge_length_rel) {
    pipeline::Parameters p;
    p.edge_length_rel = edge_length_rel;
    drawing = pipeline::mesh_drawing(pipeline::Source::file(std::string(CURVEMESH_EXAMPLES) + "/square-with-hole.svg"), p);
    const std::vector<char> keep =
        regions::domain_triangles({regions::find_faces(drawing.mesh), {}, {}}, regions::Domain::evenodd);
    mesh = submesh(drawing.mesh, keep);
  }
};

TEST(Elastic, NewtonConvergesQuadraticallyNearTheSolution) {
  const HungRing ring(0.1);
  const Geometry geometry(ring.mesh);
  const Space space(ring.mesh, 2);
  ElasticOptions options;
  options.material = lame_parameters(100.0, 0.3);
  // Heavy enough for a large deformation (the bottom sags by about a tenth of the side) that
  // takes Newton several iterations from u = 0.
  options.body_force = Vec2(0, 40.0 / ring.drawing.diagonal);
  // Above the round-off of the residual's sums (about 5e-14 of the load on this mesh), which
  // would end the quadratic decrease.
  options.tolerance = 1e-10;
  const NeoHookean problem(geometry, space, hang_from_top(geometry, space, 1e-3 * ring.drawing.diagonal), options);
  const ElasticResult r = problem.solve();
  ASSERT_TRUE(r.converged) << r.failure;
  const int n = static_cast<int>(r.iterations.size());
  ASSERT_GE(n, 6) << "the test needs a problem that takes several iterations";
  std::vector<double> rel;  // residuals relative to the load
  for (const auto& it : r.iterations) rel.push_back(it.residual / r.initial_residual);
  std::string trace;
  for (int k = 0; k < n; ++k)
    trace += std::to_string(k) + ": " + testing::PrintToString(rel[k]) + " alpha " +
             testing::PrintToString(r.iterations[k].step_length) + "\n";
  // The last three steps are full Newton steps on the exact tangent, over residuals that span
  // several orders of magnitude.
  for (int k = n - 4; k < n - 1; ++k) {
    EXPECT_EQ(r.iterations[k].step_length, 1.0) << trace;
    EXPECT_EQ(r.iterations[k].shift, 0.0) << trace;
  }
  EXPECT_GT(rel[n - 4] / rel[n - 1], 1e6) << trace;
  // Over them the contraction r_{k+1} / r_k falls towards 0, by at least ten times a step ...
  for (int k = n - 4; k < n - 2; ++k) EXPECT_LT(rel[k + 2] / rel[k + 1], 0.1 * (rel[k + 1] / rel[k])) << trace;
  EXPECT_LT(rel[n - 1] / rel[n - 2], 1e-3) << trace;
  // ... and r_{k+1} <= C r_k² with C = 10 in units of the load (measured: 0.04 to 1.3). Linear
  // or superlinear convergence would make r_{k+1} / r_k² grow like 1 / r_k, past 1e4 here.
  for (int k = n - 4; k < n - 1; ++k) EXPECT_LE(rel[k + 1], 10 * rel[k] * rel[k]) << trace;
}

// Linear elasticity (σ = λ tr ε I + 2μ ε, plane strain) assembled directly from the basis
// gradients: the linearization of Neo-Hookean at u = 0.
SparseMatrix linear_elasticity(const Geometry& geometry, const Space& space, const Lame& m) {
  const Quadrature q = triangle_quadrature(quadrature_degree(geometry, space));
  ElementValues ev;
  Triplets triplets;
  const int n = space.local_size();
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, space, q, t);
    const auto d = space.dofs(t);
    for (int p = 0; p < ev.points(); ++p) {
      // B: the strain (ε_xx, ε_yy, 2 ε_xy) of each local unknown.
      Eigen::MatrixXd b = Eigen::MatrixXd::Zero(3, 2 * n);
      for (int a = 0; a < n; ++a) {
        const double gx = ev.grad[p](a, 0), gy = ev.grad[p](a, 1);
        b(0, 2 * a) = gx, b(1, 2 * a + 1) = gy, b(2, 2 * a) = gy, b(2, 2 * a + 1) = gx;
      }
      Eigen::Matrix3d c;
      c << m.lambda + 2 * m.mu, m.lambda, 0, m.lambda, m.lambda + 2 * m.mu, 0, 0, 0, m.mu;
      const Eigen::MatrixXd k = ev.weight[p] * b.transpose() * c * b;
      for (int i = 0; i < 2 * n; ++i)
        for (int j = 0; j < 2 * n; ++j) triplets.emplace_back(2 * d[i / 2] + i % 2, 2 * d[j / 2] + j % 2, k(i, j));
    }
  }
  SparseMatrix a(2 * space.size(), 2 * space.size());
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

TEST(Elastic, SmallLoadsGiveLinearElasticity) {
  const io::HighOrderMesh mesh = grid(3, 4, bend);
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  const std::vector<char> clamped = hang_from_top(geometry, space, 1e-9);
  const Lame material = lame_parameters(1.0, 0.3);
  const Vec2 gravity(0.2, 1.0);
  // The linear answer per unit load.
  Dirichlet dirichlet(2 * space.size());
  for (int i = 0; i < space.size(); ++i)
    if (clamped[i]) dirichlet.set(2 * i, 0), dirichlet.set(2 * i + 1, 0);
  ElasticOptions unit;
  unit.material = material;
  unit.body_force = gravity;
  const NeoHookean unit_problem(geometry, space, clamped, unit);
  const VectorXd f = -unit_problem.residual(VectorXd::Zero(unit_problem.size()));  // ∫ f·φ
  const VectorXd linear = solve(linear_elasticity(geometry, space, material), f, dirichlet, true);
  ASSERT_GT(linear.norm(), 0);
  std::vector<double> gap;
  for (double scale : {1e-2, 1e-3}) {
    ElasticOptions options = unit;
    options.body_force = scale * gravity;
    options.tolerance = 1e-12;
    const ElasticResult r = NeoHookean(geometry, space, clamped, options).solve();
    ASSERT_TRUE(r.converged) << r.failure;
    gap.push_back((r.displacement / scale - linear).norm() / linear.norm());
  }
  // The gap is the nonlinear part: first order in the load.
  EXPECT_LT(gap[0], 0.1);
  EXPECT_GT(gap[0] / gap[1], 7.0);
  EXPECT_LT(gap[0] / gap[1], 13.0);
}

TEST(Elastic, LoadStepsReachTheSameEquilibrium) {
  const io::HighOrderMesh mesh = grid(3, 3, bend);
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  ElasticOptions options;
  options.material = lame_parameters(1.0, 0.3);
  options.body_force = Vec2(0, 0.3);
  options.tolerance = 1e-12;
  const std::vector<char> clamped = hang_from_top(geometry, space, 1e-9);
  const ElasticResult one = NeoHookean(geometry, space, clamped, options).solve();
  options.load_steps = 4;
  const ElasticResult four = NeoHookean(geometry, space, clamped, options).solve();
  ASSERT_TRUE(one.converged && four.converged);
  EXPECT_EQ(four.iterations.back().load_step, 4);
  EXPECT_LT((one.displacement - four.displacement).norm(), 1e-9 * one.displacement.norm());
  // Hanging sags: every free point moves down (+y), nothing clamped moves.
  for (int i = 0; i < space.size(); ++i) {
    if (clamped[i])
      EXPECT_EQ(one.displacement.segment<2>(2 * i).norm(), 0.0);
    else
      EXPECT_GT(one.displacement[2 * i + 1], 0.0);
  }
}

// A slender column clamped at its top and pushed up by a load far beyond its buckling load: the
// straight column is an unstable equilibrium, where the tangent is indefinite. Newton must shift
// the tangent there, never raise the energy, and end on a buckled (bent sideways) equilibrium
// with the exact tangent, positive definite, converging quadratically.
TEST(Elastic, PastBucklingTheShiftedTangentFindsAStableEquilibrium) {
  const io::HighOrderMesh mesh = grid(3, 4, [](const Vec2& p) { return Vec2(0.25 * p.x(), p.y()); });
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  ElasticOptions options;
  options.material = lame_parameters(1.0, 0.3);
  options.body_force = Vec2(0.0, -0.5);  // about 40 times the self-weight buckling load 7.84 EI / L³
  const ElasticResult r = NeoHookean(geometry, space, hang_from_top(geometry, space, 1e-9), options).solve();
  ASSERT_TRUE(r.converged) << r.failure;
  const auto& its = r.iterations;
  EXPECT_TRUE(std::any_of(its.begin(), its.end(), [](const NewtonIteration& it) { return it.shift > 0; }));
  // (Near the solution a step may raise the energy within its round-off, 1e-12 relative.)
  for (std::size_t k = 1; k < its.size(); ++k)
    EXPECT_LE(its[k].energy, its[k - 1].energy + 1e-12 * std::abs(its[k - 1].energy)) << k;
  const int n = static_cast<int>(its.size());
  for (int k = n - 4; k < n - 1; ++k) EXPECT_EQ(its[k].shift, 0.0) << k;
  EXPECT_LT(its[n - 1].residual, 1e-3 * its[n - 2].residual);
  double sideways = 0;
  for (int i = 0; i < space.size(); ++i) sideways = std::max(sideways, std::abs(r.displacement[2 * i]));
  EXPECT_GT(sideways, 0.1) << "the column did not buckle";
}

TEST(Elastic, DeformedMeshIsExactlyTheMovedMap) {
  for (int order : {1, 3}) {
    const io::HighOrderMesh mesh = grid(order, 2, bend);
    const Geometry geometry(mesh);
    const Space space(mesh, 2);
    const VectorXd u = random_vector(2 * space.size(), 0.05, 11);
    const DeformedMesh moved = deformed_mesh(geometry, space, u);
    EXPECT_EQ(moved.mesh.order, std::max(order, 2));
    const Geometry moved_geometry(moved.mesh);
    for (int t = 0; t < mesh.triangle_count(); ++t)
      for (const Vec2& xi : {Vec2(0.2, 0.3), Vec2(0.7, 0.1), Vec2(0.05, 0.9)}) {
        const Vec2 expected =
            geometry.map(t, xi) + Vec2(value_at(space, u, t, xi, 2, 0), value_at(space, u, t, xi, 2, 1));
        EXPECT_LT((moved_geometry.map(t, xi) - expected).norm(), 1e-14) << "order " << order << ", triangle " << t;
      }
  }
}

TEST(Elastic, DisplacementAtAPointOfACurvedMesh) {
  const io::HighOrderMesh mesh = grid(3, 3, bend);
  const Geometry geometry(mesh);
  const Space space(mesh, 2);
  const VectorXd u = random_vector(2 * space.size(), 1.0, 5);
  // Points given by their triangle and reference point: inside, on an inner edge, on the curved border.
  const std::pair<int, Vec2> where[] = {{4, Vec2(0.2, 0.3)}, {7, Vec2(0.5, 0.5)}, {0, Vec2(0.4, 0.0)}};
  for (const auto& [t, xi] : where) {
    Vec2 value;
    ASSERT_TRUE(displacement_at(geometry, space, u, geometry.map(t, xi), value)) << t;
    EXPECT_LT((value - Vec2(value_at(space, u, t, xi, 2, 0), value_at(space, u, t, xi, 2, 1))).norm(), 1e-10) << t;
  }
  Vec2 value;
  EXPECT_FALSE(displacement_at(geometry, space, u, Vec2(2, 2), value));
}

}  // namespace
}  // namespace curvemesh::fem

