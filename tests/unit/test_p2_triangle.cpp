// The quadratic triangle map against Gmsh's node order and its own definition, the Bernstein form
// of its det J against the analytic derivative (exactly, on rationals), and its positive-Jacobian
// certificate: on elements whose validity is known in closed form, against the P3 certificate of
// the very same map (written exactly with ten nodes), and in doubles against the exact verdict.
#include <gtest/gtest.h>

#include <Eigen/LU>  // determinant
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "geometry/amips.hpp"
#include "geometry/p2_triangle.hpp"
#include "geometry/p3_triangle.hpp"
#include "static_filter_cases.hpp"

namespace curvemesh::geometry {
namespace {

mpq_class rational(int num, int den) {
  mpq_class q(num, den);
  q.canonicalize();
  return q;
}

P2NodesT<mpq_class> exact_of(const std::array<std::array<int, 2>, 6>& integer_nodes) {
  P2NodesT<mpq_class> n;
  for (int i = 0; i < 6; ++i) n[i] = {mpq_class(integer_nodes[i][0]), mpq_class(integer_nodes[i][1])};
  return n;
}

P2Nodes doubles_of(const std::array<std::array<int, 2>, 6>& integer_nodes) {
  P2Nodes n;
  for (int i = 0; i < 6; ++i) n[i] = Vec2(integer_nodes[i][0], integer_nodes[i][1]);
  return n;
}

P2Nodes transformed(const P2Nodes& n, double scale, const Vec2& shift) {
  P2Nodes out;
  for (int i = 0; i < 6; ++i) out[i] = n[i] * scale + shift;
  return out;
}

// The exact minimum of det J over the closed triangle, for these tests' known cases: det J is a
// quadratic, so its minimum is at a corner, at a critical point of an edge or of the inside; the
// values there are computed from the Lagrange derivative (p2_jacobian_det), not the Bernstein form.
mpq_class exact_minimum(const P2NodesT<mpq_class>& n) {
  // det J(u, v) = a + b u + c v + d u² + e u v + f v², its coefficients from six values.
  const auto at = [&](const mpq_class& u, const mpq_class& v) { return p2_jacobian_det(n, u, v); };
  const mpq_class a = at(0, 0), half(1, 2);
  const mpq_class d = 2 * (at(1, 0) - 2 * at(half, 0) + a), f = 2 * (at(0, 1) - 2 * at(0, half) + a);
  const mpq_class b = at(1, 0) - a - d, c = at(0, 1) - a - f, e = at(1, 1) - a - b - c - d - f;
  std::vector<mpq_class> values{at(0, 0), at(1, 0), at(0, 1)};
  const auto inside = [](const mpq_class& u, const mpq_class& v) { return u >= 0 && v >= 0 && u + v <= 1; };
  // Inside: b + 2d u + e v = 0, c + e u + 2f v = 0.
  if (const mpq_class det = 4 * d * f - e * e; det != 0) {
    const mpq_class u = (-2 * f * b + e * c) / det, v = (-2 * d * c + e * b) / det;
    if (inside(u, v)) values.push_back(at(u, v));
  }
  // Edges v = 0, u = 0, and u + v = 1 (u = t, v = 1 − t): a quadratic in t each.
  if (d != 0) {
    const mpq_class t = -b / (2 * d);
    if (inside(t, 0)) values.push_back(at(t, 0));
  }
  if (f != 0) {
    const mpq_class t = -c / (2 * f);
    if (inside(0, t)) values.push_back(at(0, t));
  }
  // On u + v = 1: g(t) = a + b t + c (1 − t) + d t² + e t (1 − t) + f (1 − t)².
  if (const mpq_class quad = d - e + f; quad != 0) {
    const mpq_class t = -(b - c + e - 2 * f) / (2 * quad);
    if (inside(t, 1 - t)) values.push_back(at(t, 1 - t));
  }
  return *std::min_element(values.begin(), values.end());
}

// Integer nodes found to exercise each outcome (the coordinates are exact doubles).
// det J ≥ 177/2800 · 1600 > 0, but one Bernstein coefficient is negative: decided by subdivision.
constexpr std::array<std::array<int, 2>, 6> kNeedsSubdivision{{{0, 0}, {40, 0}, {0, 40}, {18, 9}, {15, 22}, {-7, 10}}};
// Positive at the three corners, negative inside: a fold only subdivision finds.
constexpr std::array<std::array<int, 2>, 6> kFoldInside{{{0, 0}, {40, 0}, {0, 40}, {8, -4}, {27, 29}, {10, 13}}};

TEST(P2NodeOrder, MatchesGmshTriangle6) {
  FILE* pipe = popen(
      "/usr/bin/python3 -c \"import gmsh; gmsh.initialize(); "
      "print(*gmsh.model.mesh.getElementProperties(9)[4]); gmsh.finalize()\" 2>/dev/null",
      "r");
  ASSERT_NE(pipe, nullptr);
  std::vector<double> coords;
  double x;
  while (std::fscanf(pipe, "%lf", &x) == 1) coords.push_back(x);
  pclose(pipe);
  if (coords.size() != 12) GTEST_SKIP() << "python3-gmsh not available";
  const P2Nodes reference = p2_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(reference[i].x(), coords[2 * i]) << "node " << i;
    EXPECT_EQ(reference[i].y(), coords[2 * i + 1]) << "node " << i;
  }
}

TEST(P2Map, InterpolatesItsNodesAndMatchesFiniteDifferences) {
  const P2Nodes n = doubles_of(kNeedsSubdivision);
  const P2Nodes reference = p2_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  for (int i = 0; i < 6; ++i) EXPECT_EQ(p2_map(n, reference[i].x(), reference[i].y()), n[i]) << "node " << i;
  const double h = 1e-6;
  for (const Vec2& p : {Vec2(0.2, 0.3), Vec2(0.7, 0.1), Vec2(0.05, 0.9)}) {
    const Eigen::Matrix2d J = p2_jacobian(n, p.x(), p.y());
    const Vec2 du = (p2_map(n, p.x() + h, p.y()) - p2_map(n, p.x() - h, p.y())) / (2 * h);
    const Vec2 dv = (p2_map(n, p.x(), p.y() + h) - p2_map(n, p.x(), p.y() - h)) / (2 * h);
    EXPECT_LT((J.col(0) - du).norm(), 1e-6);
    EXPECT_LT((J.col(1) - dv).norm(), 1e-6);
    EXPECT_DOUBLE_EQ(J.determinant(), p2_jacobian_det(P2NodesT<double>{{{n[0].x(), n[0].y()},
                                                                        {n[1].x(), n[1].y()},
                                                                        {n[2].x(), n[2].y()},
                                                                        {n[3].x(), n[3].y()},
                                                                        {n[4].x(), n[4].y()},
                                                                        {n[5].x(), n[5].y()}}},
                                                      p.x(), p.y()));
  }
}

// The Bernstein form is the polynomial: at rational points de Casteljau on the coefficients gives
// the Lagrange derivative's value exactly; and it is the P3 form of the same map, degree-elevated.
TEST(P2Bernstein, AgreesExactlyWithTheDerivativeAndWithTheP3Form) {
  std::mt19937 rng(2);
  std::uniform_int_distribution<int> num(-40, 40);
  for (int trial = 0; trial < 30; ++trial) {
    P2NodesT<mpq_class> n;
    for (auto& p : n) p = {rational(num(rng), 7), rational(num(rng), 5)};
    const auto c = p2_jacobian_det_bernstein(n);
    for (int j = 0; j <= 5; ++j)
      for (int k = 0; j + k <= 5; ++k) {
        const mpq_class u = rational(j, 5), v = rational(k, 5);
        EXPECT_EQ(bernstein_eval(c, 2, u, v), p2_jacobian_det(n, u, v));
        EXPECT_EQ(p3_jacobian_det(p2_as_p3(n), u, v), p2_jacobian_det(n, u, v));
      }
    // Degree elevation 2 → 4 of the P2 coefficients gives the P3 form's 15 coefficients.
    const auto c4 = p3_jacobian_det_bernstein(p2_as_p3(n));
    for (int k = 0; k <= 4; ++k)
      for (int j = 0; j + k <= 4; ++j) {
        const int i = 4 - j - k;
        mpq_class elevated = 0;
        for (int b = 0; b <= std::min(2, k); ++b)
          for (int a = 0; a + b <= 2 && a <= j; ++a) {
            const int r = 2 - a - b;
            if (r > i) continue;
            elevated += mpq_class(multinomial(r, a, b) * multinomial(i - r, j - a, k - b)) *
                        c[bernstein_index(2, a, b)];
          }
        elevated /= multinomial(i, j, k);
        EXPECT_EQ(elevated, c4[bernstein_index(4, j, k)]) << j << " " << k;
      }
  }
}

TEST(P2Certify, StraightTriangleIsTwiceItsAreaEverywhere) {
  const Vec2 a(0.5, -1), b(3, 0.25), c(1, 2);
  const P2Nodes n = p2_straight_nodes(a, b, c);  // middles exact in doubles
  const mpq_class twice_area = (mpq_class(b.x()) - a.x()) * (mpq_class(c.y()) - a.y()) -
                               (mpq_class(b.y()) - a.y()) * (mpq_class(c.x()) - a.x());
  for (const mpq_class& coefficient : p2_jacobian_det_bernstein(to_exact(n))) EXPECT_EQ(coefficient, twice_area);
  EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::positive);
  const auto cert = certify_jacobian(n);
  EXPECT_EQ(cert.verdict, JacobianVerdict::positive);
  EXPECT_EQ(cert.subtriangles, 1);
  EXPECT_NEAR(cert.scaled_jacobian, 1.0, 1e-12);
  EXPECT_EQ(certify_jacobian_exact(p2_straight_nodes(a, c, b)), JacobianVerdict::not_positive);
  EXPECT_EQ(certify_jacobian(p2_straight_nodes(a, c, b)).verdict, JacobianVerdict::not_positive);
}

// Edge 0→1 of the unit right triangle with its middle pulled towards corner 2 by h: det J =
// 1 − 4hu (by hand from the basis), smallest at u = 0 or u = 1, so its minimum is min(1, 1 − 4h):
// positive on the whole triangle exactly when h < 1/4, and its coefficients 1 − 2hj all positive
// then: decided without subdivision. At h = 1/4 det J is 0 at corner 1: the exact test says not
// positive, the one in doubles may only say it cannot decide (its bound on round-off is not 0).
TEST(P2Certify, BentEdgeIsPositiveBelowTheClosedFormLimit) {
  for (int sixteenths : {-6, -2, 1, 2, 3, 4, 5}) {  // h = sixteenths / 16
    P2Nodes n = p2_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
    n[3] = Vec2(0.5, sixteenths / 16.0);
    const bool valid = sixteenths < 4;
    EXPECT_EQ(exact_minimum(to_exact(n)), std::min(mpq_class(1), mpq_class(1 - rational(sixteenths, 4)))) << sixteenths;
    EXPECT_EQ(certify_jacobian_exact(n), valid ? JacobianVerdict::positive : JacobianVerdict::not_positive)
        << sixteenths;
    const auto cert = certify_jacobian(n);
    if (valid) {
      EXPECT_EQ(cert.verdict, JacobianVerdict::positive) << sixteenths;
      EXPECT_EQ(cert.subtriangles, 1) << sixteenths;
    } else if (sixteenths == 4) {
      EXPECT_NE(cert.verdict, JacobianVerdict::positive);
    } else {
      EXPECT_EQ(cert.verdict, JacobianVerdict::not_positive) << sixteenths;
    }
  }
}

TEST(P2Certify, MiddleNodeAcrossTheOppositeSideIsInverted) {
  // The deliberately inverted element of the command-line tests: the middle of edge 0→1 beyond
  // the opposite corner.
  P2Nodes n = p2_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  n[3] = Vec2(0.5, 1.5);
  EXPECT_LT(exact_minimum(to_exact(n)), 0);
  EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::not_positive);
  const auto cert = certify_jacobian(n);
  EXPECT_EQ(cert.verdict, JacobianVerdict::not_positive);
  EXPECT_LT(cert.min_value, 0);
  EXPECT_EQ(certify_jacobian_exact(p2_as_p3(to_exact(n))), JacobianVerdict::not_positive);
}

TEST(P2Certify, UndecidedCoefficientsArePositiveAfterSubdivision) {
  const P2NodesT<mpq_class> exact = exact_of(kNeedsSubdivision);
  ASSERT_EQ(exact_minimum(exact), mpq_class(177, 2800) * 1600);
  const auto c = p2_jacobian_det_bernstein(exact);
  EXPECT_TRUE(std::any_of(c.begin(), c.end(), [](const mpq_class& x) { return x < 0; }));
  EXPECT_EQ(certify_jacobian_exact(exact), JacobianVerdict::positive);
  EXPECT_EQ(certify_jacobian_exact(exact, {.max_depth = 0}), JacobianVerdict::undecided);
  const auto cert = certify_jacobian(doubles_of(kNeedsSubdivision));
  EXPECT_EQ(cert.verdict, JacobianVerdict::positive);
  EXPECT_GT(cert.subtriangles, 1);
  EXPECT_LT(cert.min_coefficient, 0);
  EXPECT_GT(cert.scaled_jacobian, 0);
  EXPECT_EQ(certify_jacobian(doubles_of(kNeedsSubdivision), {.max_depth = 0}).verdict, JacobianVerdict::undecided);
}

TEST(P2Certify, FoldInsideIsFoundBySubdivision) {
  const P2NodesT<mpq_class> exact = exact_of(kFoldInside);
  ASSERT_LT(exact_minimum(exact), 0);
  const auto c = p2_jacobian_det_bernstein(exact);
  for (const std::size_t corner : {bernstein_index(2, 0, 0), bernstein_index(2, 2, 0), bernstein_index(2, 0, 2)})
    EXPECT_GT(c[corner], 0);
  EXPECT_EQ(certify_jacobian_exact(exact), JacobianVerdict::not_positive);
  const auto cert = certify_jacobian(doubles_of(kFoldInside));
  EXPECT_EQ(cert.verdict, JacobianVerdict::not_positive);
  EXPECT_GT(cert.subtriangles, 0);
}

TEST(P2Certify, ZeroAtACornerIsNotPositive) {
  // The control point of edge 0→1 is 2·(1, 1) − (0 + (4, 0))/2 = (0, 2): the edge leaves corner 0
  // along edge 2→0, so det J = 0 there.
  P2Nodes n = p2_straight_nodes(Vec2(0, 0), Vec2(4, 0), Vec2(0, 4));
  n[3] = Vec2(1, 1);
  EXPECT_EQ(p2_jacobian_det_bernstein(to_exact(n))[bernstein_index(2, 0, 0)], 0);
  EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::not_positive);
  EXPECT_NE(certify_jacobian(n).verdict, JacobianVerdict::positive);
}

// Random elements: the exact P2 verdict is the exact P3 verdict of the same map (an independent
// polynomial, of degree 4), and the double verdict is the exact one at any size or position.
TEST(P2Certify, AgreesWithTheP3CertificateAndInDoublesAtAnyScale) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-0.3, 0.3);
  int counts[3] = {0, 0, 0}, subdivided = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    P2Nodes n = p2_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
    for (int i = 3; i < 6; ++i) n[i] += Vec2(noise(rng), noise(rng));
    const JacobianVerdict exact = certify_jacobian_exact(n);
    ++counts[static_cast<int>(exact)];
    if (exact == JacobianVerdict::undecided) continue;
    ASSERT_EQ(certify_jacobian_exact(p2_as_p3(to_exact(n))), exact) << "trial " << trial;
    ASSERT_EQ(exact_minimum(to_exact(n)) > 0, exact == JacobianVerdict::positive) << "trial " << trial;
    const auto cert = certify_jacobian(n);
    subdivided += cert.subtriangles > 1;
    ASSERT_EQ(cert.verdict, exact) << "trial " << trial;
    for (double scale : {1e-6, 1e6})
      EXPECT_EQ(certify_jacobian(transformed(n, scale, Vec2::Zero())).verdict, exact) << "trial " << trial;
    EXPECT_EQ(certify_jacobian(transformed(n, 1.0, Vec2(1e6, -1e6))).verdict, exact) << "trial " << trial;
  }
  EXPECT_GT(counts[static_cast<int>(JacobianVerdict::positive)], 300);
  EXPECT_GT(counts[static_cast<int>(JacobianVerdict::not_positive)], 300);
  EXPECT_LT(counts[static_cast<int>(JacobianVerdict::undecided)], 5);
  EXPECT_GT(subdivided, 20);
}

// The static filter on P2 elements near a sign change (static_filter_cases.hpp), at several scales
// and positions; it fails without the bound.
TEST(P2Certify, StaticFilterAcceptsOnlyProvenCoefficients) {
  const auto bernstein = [](const auto& nodes) { return p2_jacobian_det_bernstein(nodes); };
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  testing_support::FilterTally tally;
  for (int trial = 0; trial < 120; ++trial) {
    P2Nodes n = p2_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
    for (int i = 3; i < 6; ++i) n[i] += Vec2(noise(rng), noise(rng));
    n = transformed(n, std::ldexp(1.0, 3 * (trial % 12) - 18), trial % 3 ? Vec2(1e5 * noise(rng), 3.5) : Vec2::Zero());
    testing_support::tally_around_sign_change(n, bernstein, tally);
    ASSERT_FALSE(HasFatalFailure()) << "trial " << trial;
  }
  EXPECT_GT(tally.nonpositive, 300);
  EXPECT_GT(tally.accepted, 100);
}

TEST(P2Amips, IsTheEnergyOfTheSameMapWrittenAsP3) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1, 1), jitter(-0.15, 0.15);
  for (int trial = 0; trial < 300; ++trial) {
    Vec2 a(u(rng), u(rng)), b(u(rng), u(rng)), c(u(rng), u(rng));
    if (cross(b - a, c - a) < 0) std::swap(b, c);
    const P2Nodes straight = p2_straight_nodes(a, b, c);
    EXPECT_NEAR(p2_max_amips(straight), amips(a, b, c), 1e-9 * amips(a, b, c)) << trial;
    P2Nodes n = straight;
    for (int i = 3; i < 6; ++i) n[i] += jitter(rng) * (b - a).norm() * Vec2(u(rng), u(rng));
    const auto p3 = p2_as_p3(to_exact(n));
    P3Nodes q;
    for (int i = 0; i < 10; ++i) q[i] = Vec2(p3[i][0].get_d(), p3[i][1].get_d());
    const double e2 = p2_max_amips(n), e3 = p3_max_amips(q);
    if (std::isinf(e3)) {
      EXPECT_TRUE(std::isinf(e2) || e2 > 1e6) << trial;
      continue;
    }
    EXPECT_NEAR(e2, e3, 1e-7 * e3) << trial;
    const P3LatticeValues v = p2_lattice_values(n);
    EXPECT_EQ(v.max_amips, e2) << trial;
    // A bound cuts the work only: the value is at least the bound, or exact.
    EXPECT_GE(p2_max_amips(n, e2 / 2), e2 / 2);
    EXPECT_EQ(p2_max_amips(n, 2 * e2), e2);
  }
}

}  // namespace
}  // namespace curvemesh::geometry
