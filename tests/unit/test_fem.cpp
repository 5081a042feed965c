// The finite element layer: quadrature, Lagrange bases, maps, spaces, assembly and solves,
// regions and cuts. Checked against closed forms (monomial integrals, polynomial solutions that
// P2 must reproduce, areas) rather than against itself.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "fem/assembly.hpp"
#include "fem/convergence.hpp"
#include "fem/domain.hpp"
#include "fem/drawing.hpp"
#include "fem/inflate.hpp"
#include "fem/output.hpp"
#include "pipeline/output.hpp"

namespace curvemesh::fem {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

TEST(Quadrature, IntegratesMonomialsExactlyUpToItsDegree) {
  for (int degree = 0; degree <= 12; ++degree) {
    const Quadrature q = triangle_quadrature(degree);
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b) {
        double sum = 0;
        for (int k = 0; k < q.size(); ++k) sum += q.weights[k] * std::pow(q.points[k].x(), a) * std::pow(q.points[k].y(), b);
        const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
        EXPECT_NEAR(sum, exact, 1e-14) << "degree " << degree << " x^" << a << " y^" << b;
      }
    const Quadrature line = interval_quadrature(degree);
    for (int a = 0; a <= degree; ++a) {
      double sum = 0;
      for (int k = 0; k < line.size(); ++k) sum += line.weights[k] * std::pow(line.points[k].x(), a);
      EXPECT_NEAR(sum, 1.0 / (a + 1), 1e-14);
    }
  }
  // And not beyond: the 1-point rule misses x².
  const Quadrature q1 = triangle_quadrature(1);
  double sum = 0;
  for (int k = 0; k < q1.size(); ++k) sum += q1.weights[k] * q1.points[k].x() * q1.points[k].x();
  EXPECT_GT(std::abs(sum - 1.0 / 12), 1e-3);
}

TEST(Lagrange, NodalPartitionOfUnityAndGradients) {
  for (int order = 1; order <= 3; ++order) {
    const LagrangeBasis basis(order);
    ASSERT_EQ(basis.size(), (order + 1) * (order + 2) / 2);
    for (int j = 0; j < basis.size(); ++j) {
      const Eigen::VectorXd v = basis.values(basis.nodes()[j]);
      for (int i = 0; i < basis.size(); ++i) EXPECT_NEAR(v(i), i == j ? 1.0 : 0.0, 1e-12);
    }
    const Vec2 xi(0.23, 0.41);
    Eigen::VectorXd v;
    Eigen::MatrixX2d g;
    basis.evaluate(xi, v, g);
    EXPECT_NEAR(v.sum(), 1.0, 1e-13);
    EXPECT_NEAR(g.col(0).sum(), 0.0, 1e-12);
    const double h = 1e-6;
    const Eigen::VectorXd fd = (basis.values(xi + Vec2(h, 0)) - basis.values(xi - Vec2(h, 0))) / (2 * h);
    for (int i = 0; i < basis.size(); ++i) EXPECT_NEAR(g(i, 0), fd(i), 1e-7);
  }
  // Gmsh's node order: edge 1→2 of the cubic element starts at corner 1.
  EXPECT_NEAR(LagrangeBasis(3).nodes()[5].x(), 2.0 / 3, 1e-15);
  EXPECT_NEAR(LagrangeBasis(3).nodes()[7].y(), 2.0 / 3, 1e-15);
}

io::HighOrderMesh unit_square(int n, int order) {
  // n × n squares, each split into two triangles, with nodes of the given order on straight edges.
  io::HighOrderMesh m;
  m.order = order;
  std::map<std::pair<int, int>, int> index;  // lattice point (in units of 1/(n·order)) -> node
  auto node = [&](int i, int j) {
    auto [it, inserted] = index.try_emplace({i, j}, static_cast<int>(m.nodes.size()));
    if (inserted) m.nodes.emplace_back(double(i) / (n * order), double(j) / (n * order));
    return it->second;
  };
  const std::vector<Vec2> ref = reference_nodes(order);
  auto add = [&](std::array<int, 2> a, std::array<int, 2> b, std::array<int, 2> c) {
    std::vector<int> ids;
    for (const Vec2& r : ref) {
      const double s = r.x(), t = r.y();
      ids.push_back(node(static_cast<int>(std::lround(a[0] + s * (b[0] - a[0]) + t * (c[0] - a[0]))),
                         static_cast<int>(std::lround(a[1] + s * (b[1] - a[1]) + t * (c[1] - a[1])))));
    }
    m.add_triangle(ids);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int k = order;
      add({i * k, j * k}, {(i + 1) * k, j * k}, {(i + 1) * k, (j + 1) * k});
      add({i * k, j * k}, {(i + 1) * k, (j + 1) * k}, {i * k, (j + 1) * k});
    }
  return m;
}

TEST(Space, CountsUnknownsByCornersAndEdges) {
  const io::HighOrderMesh m = unit_square(3, 1);
  EXPECT_EQ(Space(m, 1).size(), 16);
  EXPECT_EQ(Space(m, 2).size(), 16 + 33);  // 3·3·3 + 2·3 edges
  EXPECT_THROW(Space(m, 3), std::invalid_argument);
}

// P2 contains every quadratic: with its values on the border and its (constant) −Δ as load, the
// discrete solution is the quadratic itself, on the straight and on the cubic (straight-sided)
// map alike.
TEST(Poisson, ReproducesQuadraticsExactly) {
  auto u = [](const Vec2& p) { return 1 + 2 * p.x() - p.y() + 3 * p.x() * p.x() + p.x() * p.y() - 2 * p.y() * p.y(); };
  for (int order : {1, 3}) {
    const io::HighOrderMesh m = unit_square(4, order);
    const Geometry g(m);
    const Space s(m, 2);
    const SparseMatrix k = stiffness_matrix(g, s);
    const Eigen::VectorXd b = load_vector(g, s, [](const Vec2&) { return -(6.0 - 4.0); });
    Dirichlet d(s.size());
    set_on_edges(g, s, boundary_edges(m), u, d);
    EXPECT_EQ(boundary_edges(m).size(), 16u);
    const Eigen::VectorXd x = solve(k, b, d, true);
    EXPECT_LT(l2_error(g, s, x, u), 1e-12) << "geometry order " << order;
    EXPECT_NEAR(area(g), 1.0, 1e-14);
    // P1 cannot: the same problem leaves an error.
    const Space p1(m, 1);
    Dirichlet d1(p1.size());
    set_on_edges(g, p1, boundary_edges(m), u, d1);
    const Eigen::VectorXd x1 = solve(stiffness_matrix(g, p1), load_vector(g, p1, [](const Vec2&) { return -2.0; }), d1, true);
    EXPECT_GT(l2_error(g, p1, x1, u), 1e-4);
  }
}

// Two problems with one matrix and one set of held unknowns, solved together: each column is
// its own quadratic (so columns are neither mixed nor shifted), with either factorization.
TEST(Poisson, SeveralProblemsShareOneFactorization) {
  const std::array<ScalarFunction, 2> u{
      [](const Vec2& p) {
        return 1 + 2 * p.x() - p.y() + 3 * p.x() * p.x() + p.x() * p.y() - 2 * p.y() * p.y();
      },
      [](const Vec2& p) { return -4 + p.y() + 0.5 * p.x() * p.x() + 2 * p.y() * p.y(); }};
  const std::array<double, 2> minus_laplacian{-(6.0 - 4.0), -(1.0 + 4.0)};
  const io::HighOrderMesh m = unit_square(4, 3);
  const Geometry g(m);
  const Space s(m, 2);
  const SparseMatrix k = stiffness_matrix(g, s);
  Eigen::MatrixXd b(s.size(), 2), values(s.size(), 2);
  std::vector<char> fixed;
  for (int c = 0; c < 2; ++c) {
    b.col(c) = load_vector(g, s, [&](const Vec2&) { return minus_laplacian[c]; });
    Dirichlet d(s.size());
    set_on_edges(g, s, boundary_edges(m), u[c], d);
    values.col(c) = d.values;
    if (c == 0) fixed = d.fixed;
    ASSERT_EQ(d.fixed, fixed);
  }
  for (bool cholmod : {true, false}) {
    const Eigen::MatrixXd x = solve(k, b, fixed, values, cholmod);
    ASSERT_EQ(x.cols(), 2);
    for (int c = 0; c < 2; ++c) {
      EXPECT_LT(l2_error(g, s, x.col(c), u[c]), 1e-12)
          << "column " << c << (cholmod ? ", CHOLMOD" : ", UMFPACK");
      EXPECT_GT(l2_error(g, s, x.col(c), u[1 - c]), 1e-2) << "column " << c;
    }
  }
  EXPECT_THROW(solve(k, b, fixed, values.leftCols(1), true), std::invalid_argument);
}

TEST(Geometry, InverseFindsTheReferencePointOfACurvedTriangle) {
  io::HighOrderMesh m = unit_square(1, 3);
  // Bend the diagonal's inner nodes (shared by both triangles) a little.
  const auto t0 = m.triangle(0);
  m.nodes[t0[7]] += Vec2(0.05, -0.05);  // edge 2→0 of the first triangle is the diagonal
  m.nodes[t0[8]] += Vec2(0.05, -0.05);
  const Geometry g(m);
  for (const Vec2& xi : {Vec2(0.2, 0.3), Vec2(0.6, 0.35), Vec2(0.05, 0.9)}) {
    Vec2 back;
    ASSERT_TRUE(g.inverse(0, g.map(0, xi), back));
    EXPECT_NEAR((back - xi).norm(), 0.0, 1e-12);
  }
  // The area is still 1: the bend moves area from one triangle to the other.
  EXPECT_NEAR(area(g), 1.0, 1e-13);
}

MeshedDrawing disk(double l) {
  pipeline::Parameters p;
  p.edge_length_rel = l;
  return pipeline::mesh_drawing(pipeline::Source::svg(disk_svg(), "<disk>"), p);
}

TEST(Regions, EvenOddDepthOfASquareWithAHole) {
  const char* text = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">
    <rect x="1" y="1" width="8" height="8" fill="none" stroke="black"/>
    <circle cx="5" cy="5" r="2" fill="none" stroke="black"/></svg>)";
  const MeshedDrawing d = pipeline::mesh_drawing(pipeline::Source::svg(text, "<square>"));
  const regions::Faces r = regions::find_faces(d.mesh);
  std::set<int> depths(r.depth.begin(), r.depth.end());
  EXPECT_EQ(depths, (std::set<int>{0, 1, 2}));
  std::vector<char> ring(d.mesh.triangle_count()), hole(d.mesh.triangle_count());
  for (int t = 0; t < d.mesh.triangle_count(); ++t) {
    ring[t] = r.depth[r.of_triangle[t]] == 1;
    hole[t] = r.depth[r.of_triangle[t]] == 2;
  }
  const io::HighOrderMesh ring_mesh = submesh(d.mesh, ring), hole_mesh = submesh(d.mesh, hole);
  // <circle> is four cubics, 2.7e-4·r from the circle: the curved area follows them.
  EXPECT_NEAR(area(Geometry(hole_mesh)), std::numbers::pi * 4, 4 * 2 * 2.8e-4 * std::numbers::pi);
  EXPECT_NEAR(area(Geometry(ring_mesh)) + area(Geometry(hole_mesh)), 64.0, 1e-9);
  const io::HighOrderMesh straight = straight_mesh(hole_mesh);
  EXPECT_LT(area(Geometry(straight)), area(Geometry(hole_mesh)) - 1e-3);
}

// Cut open along the circle, the disk and its outside are independent: 1 on the inner side of
// the circle and 0 on the outer side give exactly those constants (the box border is free).
TEST(Cut, SidesOfACutAreIndependent) {
  const MeshedDrawing d = disk(0.08);
  std::vector<char> cut(d.mesh.line_count());
  int cuts = 0;
  for (int l = 0; l < d.mesh.line_count(); ++l) cuts += cut[l] = d.mesh.line_physical[l] == io::kPhysicalPrimary;
  ASSERT_GT(cuts, 30);
  const CutMesh c = cut_open(d.mesh, cut);
  EXPECT_EQ(c.mesh.line_count(), d.mesh.line_count() + cuts);
  EXPECT_EQ(c.mesh.nodes.size(), d.mesh.nodes.size() + 3 * cuts);  // one corner and two inner nodes per cut edge
  EXPECT_FALSE(c.mesh.structure_error());
  const regions::Faces r = regions::find_faces(c.mesh);
  const Geometry g(c.mesh);
  const Space s(c.mesh, 2);
  Dirichlet dir(s.size());
  const auto lines = edge_lines(c.mesh);
  for (int t = 0; t < c.mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int l = lines[t][e];
      if (l < 0 || c.mesh.line_physical[l] != io::kPhysicalPrimary) continue;
      const double value = r.depth[r.of_triangle[t]] == 1 ? 1.0 : 0.0;
      for (int i : s.edge_local_dofs(e)) dir.set(s.dofs(t)[i], value);
    }
  const Eigen::VectorXd u = solve(stiffness_matrix(g, s), Eigen::VectorXd::Zero(s.size()), dir, true);
  for (int t = 0; t < c.mesh.triangle_count(); ++t) {
    const double want = r.depth[r.of_triangle[t]] == 1 ? 1.0 : 0.0;
    for (int i : s.dofs(t)) ASSERT_NEAR(u[i], want, 1e-9);
  }
}

// Inflation: the clamped bi-Laplace solution on the unit disk with load f is known,
// u = f (1 − r²)² / 64.
TEST(Inflate, MatchesTheClampedDiskSolution) {
  const MeshedDrawing d = disk(0.04);
  const regions::Faces r = regions::find_faces(d.mesh);
  std::vector<char> keep(d.mesh.triangle_count());
  for (int t = 0; t < d.mesh.triangle_count(); ++t) keep[t] = r.depth[r.of_triangle[t]] == 1;
  const io::HighOrderMesh m = submesh(d.mesh, keep);
  const Geometry g(m);
  const Space s(m, 2);
  const InflateResult res = inflate(g, s, 64.0);
  const double err = l2_error(g, s, res.height, [](const Vec2& p) { return std::pow(1 - p.squaredNorm(), 2); });
  EXPECT_LT(err, 5e-4);  // ‖u‖ = 0.74; measured 2.1e-4
  // The peak: the highest unknown is the exact solution's highest value at the unknowns (1 at the
  // centre only if an unknown sits there), and every unknown is within 1e-3 of it.
  const std::vector<Vec2> at = s.positions(g);
  double highest = 0, worst = 0;
  for (int i = 0; i < s.size(); ++i) {
    const double exact = std::pow(1 - at[i].squaredNorm(), 2);
    highest = std::max(highest, exact);
    worst = std::max(worst, std::abs(res.height[i] - exact));
  }
  EXPECT_NEAR(res.height.maxCoeff(), highest, 1e-3);
  EXPECT_GT(highest, 0.99);
  EXPECT_LT(worst, 1e-3);
}

TEST(Output, SurfaceHasOrderSquaredFacesPerTriangle) {
  const io::HighOrderMesh m = unit_square(2, 3);
  const std::vector<double> z(m.nodes.size(), 0.5);
  const std::string obj = surface_obj(m, z);
  std::size_t faces = 0;
  for (std::size_t i = obj.find("\nf "); i != std::string::npos; i = obj.find("\nf ", i + 1)) ++faces;
  EXPECT_EQ(faces, 8u * 9u);
  const std::string ply = surface_ply(m, z);
  EXPECT_NE(ply.find("element face 72\n"), std::string::npos);
}

}  // namespace
}  // namespace curvemesh::fem
