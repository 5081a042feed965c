// The cubic triangle map against Gmsh's node order and its own definition, the Bernstein form of
// det J against the analytic derivative (exactly, on rationals), and the positive-Jacobian
// certificate on elements whose validity is known by construction or by dense sampling.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/amips.hpp"
#include "geometry/p3_triangle.hpp"
#include "static_filter_cases.hpp"

namespace curvemesh::geometry {
namespace {

// Smallest det J on a dense grid of the reference triangle, from the Lagrange derivative
// (independent of the Bernstein form).
double sampled_min_det(const P3Nodes& n, int steps = 300) {
  double m = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; i + j <= steps; ++j)
      m = std::min(m, p3_jacobian(n, double(i) / steps, double(j) / steps).determinant());
  return m;
}

// The unit right triangle with edge 0→1 replaced by a circular arc of sagitta h (h > 0 bows into
// the element). The centre node stays at the centroid.
P3Nodes arc_element(double h) {
  P3Nodes n = p3_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  const double r = (0.25 + h * h) / (2 * std::abs(h));
  const Vec2 centre(0.5, h > 0 ? h - r : r + h);  // the arc's apex is at (0.5, h)
  const double a0 = std::atan2(-centre.y(), -centre.x()), a1 = std::atan2(-centre.y(), 1 - centre.x());
  double sweep = a1 - a0;
  if (sweep > M_PI) sweep -= 2 * M_PI;
  if (sweep < -M_PI) sweep += 2 * M_PI;
  for (int t = 1; t <= 2; ++t)
    n[2 + t] = centre + r * Vec2(std::cos(a0 + sweep * t / 3), std::sin(a0 + sweep * t / 3));
  return n;
}

// A canonical rational (GMP's arithmetic needs canonical operands).
mpq_class rational(int num, int den) {
  mpq_class q(num, den);
  q.canonicalize();
  return q;
}

P3Nodes transformed(const P3Nodes& n, double scale, const Vec2& shift) {
  P3Nodes out;
  for (int i = 0; i < 10; ++i) out[i] = n[i] * scale + shift;
  return out;
}

TEST(P3NodeOrder, MatchesGmshTriangle10) {
  FILE* pipe = popen(
      "/usr/bin/python3 -c \"import gmsh; gmsh.initialize(); "
      "print(*gmsh.model.mesh.getElementProperties(21)[4]); gmsh.finalize()\" 2>/dev/null",
      "r");
  ASSERT_NE(pipe, nullptr);
  std::vector<double> coords;
  double x;
  while (std::fscanf(pipe, "%lf", &x) == 1) coords.push_back(x);
  pclose(pipe);
  if (coords.size() != 20) GTEST_SKIP() << "python3-gmsh not available";
  for (int i = 0; i < 10; ++i) {
    EXPECT_NEAR(p3_reference_node(i).x(), coords[2 * i], 1e-12) << "node " << i;
    EXPECT_NEAR(p3_reference_node(i).y(), coords[2 * i + 1], 1e-12) << "node " << i;
  }
}

TEST(P3Map, InterpolatesItsNodesExactly) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> num(-50, 50);
  for (int trial = 0; trial < 20; ++trial) {
    P3NodesT<mpq_class> n;
    for (auto& p : n) p = {rational(num(rng), 7), rational(num(rng), 11)};
    for (int i = 0; i < 10; ++i) {
      const mpq_class u = rational(kP3ReferenceNodesTimes3[i][0], 3),
                      v = rational(kP3ReferenceNodesTimes3[i][1], 3);
      const auto x = p3_map(n, u, v);
      EXPECT_EQ(x[0], n[i][0]) << "node " << i;
      EXPECT_EQ(x[1], n[i][1]) << "node " << i;
    }
  }
  const P3Nodes d = arc_element(0.1);
  for (int i = 0; i < 10; ++i)
    EXPECT_LT((p3_map(d, p3_reference_node(i).x(), p3_reference_node(i).y()) - d[i]).norm(), 1e-14);
}

TEST(P3Map, JacobianMatchesFiniteDifferences) {
  const P3Nodes n = arc_element(-0.2);
  const double h = 1e-6;
  for (const Vec2& p : {Vec2(0.2, 0.3), Vec2(0.7, 0.1), Vec2(0.05, 0.9)}) {
    const Eigen::Matrix2d J = p3_jacobian(n, p.x(), p.y());
    const Vec2 du = (p3_map(n, p.x() + h, p.y()) - p3_map(n, p.x() - h, p.y())) / (2 * h);
    const Vec2 dv = (p3_map(n, p.x(), p.y() + h) - p3_map(n, p.x(), p.y() - h)) / (2 * h);
    EXPECT_LT((J.col(0) - du).norm(), 1e-8);
    EXPECT_LT((J.col(1) - dv).norm(), 1e-8);
  }
}

TEST(P3Straight, ConstantJacobianIsTwiceTheArea) {
  const Vec2 a(0.5, -1), b(3, 0.25), c(1, 2);
  const mpq_class twice_area = (mpq_class(b.x()) - a.x()) * (mpq_class(c.y()) - a.y()) -
                               (mpq_class(b.y()) - a.y()) * (mpq_class(c.x()) - a.x());
  ASSERT_GT(twice_area, 0);
  // The straight nodes at thirds are not exact in double; build them exactly.
  P3NodesT<mpq_class> exact;
  const std::array<std::array<int, 3>, 10> weights{{{3, 0, 0},
                                                    {0, 3, 0},
                                                    {0, 0, 3},
                                                    {2, 1, 0},
                                                    {1, 2, 0},
                                                    {0, 2, 1},
                                                    {0, 1, 2},
                                                    {1, 0, 2},
                                                    {2, 0, 1},
                                                    {1, 1, 1}}};
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 2; ++k)
      exact[i][k] = (weights[i][0] * mpq_class(a[k]) + weights[i][1] * mpq_class(b[k]) +
                     weights[i][2] * mpq_class(c[k])) /
                    3;
  for (const mpq_class& coefficient : p3_jacobian_det_bernstein(exact)) EXPECT_EQ(coefficient, twice_area);
  EXPECT_EQ(certify_jacobian_exact(exact), JacobianVerdict::positive);

  const P3Nodes n = p3_straight_nodes(a, b, c);
  for (double coefficient : p3_jacobian_det_bernstein(to_array(n)))
    EXPECT_NEAR(coefficient, twice_area.get_d(), 1e-13 * twice_area.get_d());
  const auto cert = certify_jacobian(n);
  EXPECT_EQ(cert.verdict, JacobianVerdict::positive);
  EXPECT_EQ(cert.subtriangles, 1);
  EXPECT_NEAR(cert.scaled_jacobian, 1.0, 1e-12);

  const P3Nodes cw = p3_straight_nodes(a, c, b);
  EXPECT_EQ(certify_jacobian_exact(cw), JacobianVerdict::not_positive);
  EXPECT_EQ(certify_jacobian(cw).verdict, JacobianVerdict::not_positive);
  EXPECT_LT(certify_jacobian(cw).scaled_jacobian, 0);
}

TEST(P3Bernstein, AgreesWithTheDerivativeAtRandomPoints) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> coord(-1, 1), unit(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    P3NodesT<double> n;
    double scale = 0;
    for (auto& p : n) {
      p = {coord(rng), coord(rng)};
      scale = std::max({scale, std::abs(p[0]), std::abs(p[1])});
    }
    const auto coefficients = p3_jacobian_det_bernstein(n);
    for (int k = 0; k < 20; ++k) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      EXPECT_NEAR(bernstein_eval(coefficients, 4, u, v), p3_jacobian_det(n, u, v), 1e-11 * scale * scale);
    }
  }
}

TEST(P3Bernstein, AgreesExactlyAtRationalPoints) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> num(-100, 100), den(1, 30);
  for (int trial = 0; trial < 50; ++trial) {
    P3NodesT<mpq_class> n;
    for (auto& p : n) p = {rational(num(rng), den(rng)), rational(num(rng), den(rng))};
    const auto coefficients = p3_jacobian_det_bernstein(n);
    const auto net = p3_control_net(n);
    std::array<mpq_class, 10> net_x, net_y;
    for (int i = 0; i < 10; ++i) net_x[i] = net[i][0], net_y[i] = net[i][1];
    for (int k = 0; k < 10; ++k) {
      const int d = den(rng);
      std::uniform_int_distribution<int> a(0, d);
      const int iu = a(rng);
      const mpq_class u = rational(iu, d),
                      v = rational(std::uniform_int_distribution<int>(0, d - iu)(rng), d);
      EXPECT_EQ(bernstein_eval(coefficients, 4, u, v), p3_jacobian_det(n, u, v));
      // The control net is the same cubic map as the Lagrange nodes.
      const auto x = p3_map(n, u, v);
      EXPECT_EQ(bernstein_eval(net_x, 3, u, v), x[0]);
      EXPECT_EQ(bernstein_eval(net_y, 3, u, v), x[1]);
    }
  }
}

TEST(P3Certify, ModeratelyCurvedEdgesArePositive) {
  for (double h : {-0.2, -0.1, 0.05, 0.1}) {
    const P3Nodes n = arc_element(h);
    ASSERT_GT(sampled_min_det(n), 0);
    EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::positive) << h;
    const auto cert = certify_jacobian(n);
    EXPECT_EQ(cert.verdict, JacobianVerdict::positive) << h;
    EXPECT_GT(cert.min_coefficient, 0);
    EXPECT_GT(cert.scaled_jacobian, 0);
    EXPECT_LE(cert.scaled_jacobian, 1);
  }
}

TEST(P3Certify, EdgeNodeAcrossTheOppositeSideFolds) {
  P3Nodes n = p3_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  n[3] = Vec2(1.0 / 3, 1.2);  // beyond the edge 1→2 (x + y = 1)
  ASSERT_LT(sampled_min_det(n), 0);
  EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::not_positive);
  const auto cert = certify_jacobian(n);
  EXPECT_EQ(cert.verdict, JacobianVerdict::not_positive);
  EXPECT_LT(cert.min_value, 0);
}

TEST(P3Certify, FoldInsideIsFoundBySubdivision) {
  // The corner values depend on the edge nodes only: moving the centre far out keeps them
  // positive and folds the inside.
  P3Nodes n = p3_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1));
  n[9] = Vec2(1.2, 1.2);
  ASSERT_LT(sampled_min_det(n), 0);
  const auto coefficients = p3_jacobian_det_bernstein(to_exact(n));
  for (int corner : {0, 1, 2})
    EXPECT_GT(coefficients[bernstein_index(4, corner == 1 ? 4 : 0, corner == 2 ? 4 : 0)], 0);
  EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::not_positive);
  const auto cert = certify_jacobian(n);
  EXPECT_EQ(cert.verdict, JacobianVerdict::not_positive);
  EXPECT_GT(cert.subtriangles, 0);  // decided below the element itself
}

TEST(P3Certify, BorderlineElementNeedsSubdivision) {
  for (double h : {0.16, 0.175, 0.185}) {
    const P3Nodes n = arc_element(h);
    const auto coefficients = p3_jacobian_det_bernstein(to_exact(n));
    EXPECT_TRUE(std::any_of(coefficients.begin(), coefficients.end(), [](const mpq_class& c) {
      return c < 0;
    })) << h;
    EXPECT_GT(sampled_min_det(n, 600), 0) << h;
    EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::positive) << h;
    const auto cert = certify_jacobian(n);
    EXPECT_EQ(cert.verdict, JacobianVerdict::positive) << h;
    EXPECT_GT(cert.subtriangles, 1);
    EXPECT_LT(cert.min_coefficient, 0);
    EXPECT_GT(cert.scaled_jacobian, 0);
    // Without subdivision nothing can be decided.
    EXPECT_EQ(certify_jacobian_exact(n, {.max_depth = 0}), JacobianVerdict::undecided);
    EXPECT_EQ(certify_jacobian(n, {.max_depth = 0}).verdict, JacobianVerdict::undecided);
  }
}

TEST(P3Certify, ZeroAtACornerIsNotPositive) {
  // Edge 0→1 from (0,0) to (4.5,0) with its nodes placed so that the Bézier control next to
  // corner 0 is (18·(0.5,0.5) − 9·(2,0) + 2·(4.5,0)) / 6 = (0, 1.5): the tangent there is
  // parallel to edge 2→0, so det J = 0 exactly at corner 0.
  P3Nodes n = p3_straight_nodes(Vec2(0, 0), Vec2(4.5, 0), Vec2(0, 4.5));
  n[3] = Vec2(0.5, 0.5);
  n[4] = Vec2(2, 0);
  const auto coefficients = p3_jacobian_det_bernstein(to_exact(n));
  EXPECT_EQ(coefficients[bernstein_index(4, 0, 0)], 0);
  EXPECT_EQ(certify_jacobian_exact(n), JacobianVerdict::not_positive);
  // In double the zero is within the rounding bound: never positive, at best undecided.
  EXPECT_NE(certify_jacobian(n).verdict, JacobianVerdict::positive);
}

// Random perturbations of a curved element: the double certificate must reach the exact verdict,
// whatever the element's size or position.
TEST(P3Certify, DoubleAgreesWithExactAtAnyScale) {
  const P3Nodes reference = arc_element(0.1);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  int counts[3] = {0, 0, 0}, subdivided = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    P3Nodes n = reference;
    for (auto& p : n) p += Vec2(noise(rng), noise(rng));
    const JacobianVerdict exact = certify_jacobian_exact(n);
    ++counts[static_cast<int>(exact)];
    if (exact == JacobianVerdict::undecided) continue;
    const auto cert = certify_jacobian(n);
    const JacobianVerdict verdict = cert.verdict;
    subdivided += cert.subtriangles > 1;
    ASSERT_EQ(verdict, exact) << "trial " << trial;
    for (double scale : {1e-6, 1e6})
      EXPECT_EQ(certify_jacobian(transformed(n, scale, Vec2::Zero())).verdict, verdict);
    EXPECT_EQ(certify_jacobian(transformed(n, 1.0, Vec2(1e6, -1e6))).verdict, verdict) << "trial " << trial;
    EXPECT_EQ(certify_jacobian(transformed(n, 1e-6, Vec2(1, 1))).verdict, verdict) << "trial " << trial;
  }
  // Both verdicts are well represented; undecided is rare.
  EXPECT_GT(counts[static_cast<int>(JacobianVerdict::positive)], 300);
  EXPECT_GT(counts[static_cast<int>(JacobianVerdict::not_positive)], 300);
  EXPECT_LT(counts[static_cast<int>(JacobianVerdict::undecided)], 5);
  EXPECT_GT(subdivided, 100);  // many were decided only below the element's own coefficients
}

// The double certificate is a filter for the exact one (bernstein_certificate.hpp): a verdict it
// reaches is the exact search's with the same limits, even limits small enough that both searches
// often stop undecided.
TEST(P3Certify, DecidedVerdictIsTheExactOneUnderTheSameLimits) {
  const P3Nodes reference = arc_element(0.17);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> noise(-0.03, 0.03);
  int decided = 0, undecided = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    P3Nodes n = reference;
    for (auto& p : n) p += Vec2(noise(rng), noise(rng));
    const JacobianCheckOptions limits{.max_depth = 1 + trial % 3, .max_subtriangles = 3 + trial % 7};
    const JacobianVerdict verdict = certify_jacobian(n, limits).verdict;
    if (verdict == JacobianVerdict::undecided) {
      ++undecided;
      continue;
    }
    ++decided;
    ASSERT_EQ(certify_jacobian_exact(n, limits), verdict) << "trial " << trial;
  }
  EXPECT_GT(decided, 300);
  EXPECT_GT(undecided, 100);  // the limits bite
}

// Products of coordinates of 1e-170 underflow: the bound must then leave the element undecided,
// never call a valid element not positive (its coefficients round to 0). Coordinates of 1e200
// overflow: undecided too.
TEST(P3Certify, UnderflowAndOverflowLeaveTheElementUndecided) {
  const P3Nodes n = arc_element(0.1);
  ASSERT_EQ(certify_jacobian_exact(n), JacobianVerdict::positive);
  for (double scale : {1e-170, 1e-300, 1e200, 1e300}) {
    const P3Nodes m = transformed(n, scale, Vec2::Zero());
    EXPECT_EQ(certify_jacobian(m).verdict, JacobianVerdict::undecided) << scale;
    EXPECT_EQ(certify_jacobian_exact(m), JacobianVerdict::positive) << scale;
  }
  for (double scale : {1e-100, 1e100})
    EXPECT_EQ(certify_jacobian(transformed(n, scale, Vec2::Zero())).verdict, JacobianVerdict::positive)
        << scale;
}

// The static filter on P3 elements near a sign change (static_filter_cases.hpp), at several
// scales and positions. A filter with no bound, or one 10⁵ times too small, accepts some of them.
TEST(P3Certify, StaticFilterAcceptsOnlyProvenCoefficients) {
  const auto bernstein = [](const auto& nodes) { return p3_jacobian_det_bernstein(nodes); };
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> noise(-0.05, 0.05);
  testing_support::FilterTally tally;
  for (int trial = 0; trial < 120; ++trial) {
    const double scale = std::ldexp(1.0, 3 * (trial % 12) - 18);
    const Vec2 shift = trial % 3 == 0 ? Vec2::Zero() : Vec2(1e5 * noise(rng), -1e5 * noise(rng));
    P3Nodes n = arc_element(0.1);
    for (auto& p : n) p += Vec2(noise(rng), noise(rng));
    n = transformed(n, scale, shift);
    testing_support::tally_around_sign_change(n, bernstein, tally);
    ASSERT_FALSE(HasFatalFailure()) << "trial " << trial;
  }
  EXPECT_GT(tally.nonpositive, 300);                // the cases that matter are there,
  EXPECT_GT(tally.computed_positive_but_not, 30);   // many of them computed all positive,
  EXPECT_GT(tally.accepted, 100);                   // and the filter does not simply decline everything
}

// The certificate's estimate of min det J, for an element its own coefficients decide: the smallest
// of p3_jacobian_det at the 15 points (j/4, k/4) and of the coefficients at the corners, on the
// nodes relative to node 0 — bit for bit, however the certificate lays out the sums.
TEST(P3Certify, MinValueIsTheLatticesAndCornersSmallestBitForBit) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> noise(-0.02, 0.02);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    P3Nodes n = transformed(arc_element(0.1), std::ldexp(1.0, trial % 30 - 15), Vec2(trial % 7 * 1e3, -5.5));
    for (auto& p : n) p += std::ldexp(1.0, trial % 30 - 15) * Vec2(noise(rng), noise(rng));
    const JacobianCertificate c = certify_jacobian(n);
    if (c.subtriangles != 1 || c.verdict != JacobianVerdict::positive) continue;
    P3NodesT<double> local;
    for (int i = 0; i < 10; ++i)
      for (int d = 0; d < 2; ++d) local[i][d] = n[i][d] - n[0][d];
    const auto coefficients = p3_jacobian_det_bernstein(local);
    double expected = std::numeric_limits<double>::infinity();
    for (std::size_t corner : {bernstein_index(4, 0, 0), bernstein_index(4, 4, 0), bernstein_index(4, 0, 4)})
      expected = std::min(expected, coefficients[corner]);
    for (int k = 0; k <= 4; ++k)
      for (int j = 0; j + k <= 4; ++j) expected = std::min(expected, p3_jacobian_det(local, j / 4.0, k / 4.0));
    ASSERT_EQ(std::bit_cast<std::uint64_t>(c.min_value), std::bit_cast<std::uint64_t>(expected)) << "trial " << trial;
    ++compared;
  }
  EXPECT_GT(compared, 1500);
}

// A straight triangle's sign: the exact certificate of its P3 map where the doubles decide, and
// undecided where they cannot (collinear corners, or within rounding of it; underflow).
TEST(P3Linear, DecidesAsTheExactCertificateOrNotAtAll) {
  const auto exact_verdict = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    P3NodesT<mpq_class> n;
    const std::array<PointT<mpq_class>, 3> x{{{a.x(), a.y()}, {b.x(), b.y()}, {c.x(), c.y()}}};
    for (int i = 0; i < 10; ++i) {
      const mpq_class u(kP3ReferenceNodesTimes3[i][0], 3), v(kP3ReferenceNodesTimes3[i][1], 3);
      for (int k = 0; k < 2; ++k) n[i][k] = (1 - u - v) * x[0][k] + u * x[1][k] + v * x[2][k];
    }
    return certify_jacobian_exact(n);
  };
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  int undecided = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec2 a(unit(rng), unit(rng)), b(unit(rng), unit(rng));
    // Every fourth triangle nearly collinear: c on the line ab, moved by a few units in the last place.
    Vec2 c(unit(rng), unit(rng));
    if (trial % 4 == 0) c = a + 3 * (b - a) + Vec2(0, (trial % 3 - 1) * 1e-16);
    const JacobianVerdict verdict = certify_jacobian_linear(a, b, c);
    undecided += verdict == JacobianVerdict::undecided;
    if (verdict != JacobianVerdict::undecided) {
      ASSERT_EQ(exact_verdict(a, b, c), verdict) << "trial " << trial;
    }
  }
  EXPECT_GT(undecided, 100);
  EXPECT_EQ(certify_jacobian_linear(Vec2(0, 0), Vec2(1, 1), Vec2(3, 3)), JacobianVerdict::undecided);
  EXPECT_EQ(exact_verdict(Vec2(0, 0), Vec2(1, 1), Vec2(3, 3)), JacobianVerdict::not_positive);
  EXPECT_EQ(certify_jacobian_linear(Vec2(0, 0), Vec2(1e-170, 0), Vec2(0, 1e-170)),
            JacobianVerdict::undecided);
  EXPECT_EQ(certify_jacobian_linear(Vec2(0, 0), Vec2(0, 1), Vec2(1, 0)), JacobianVerdict::not_positive);
  EXPECT_EQ(certify_jacobian_linear(Vec2(1e8, 1e8), Vec2(1e8 + 1, 1e8), Vec2(1e8, 1e8 + 1)),
            JacobianVerdict::positive);
}

// The straight triangle's P3 nodes rounded toward zero are those of its exact map rounded by
// mpq_get_d, bit for bit: coordinates of any sign, of exponents far apart, zero, subnormal, and
// results in the subnormal range.
TEST(P3Straight, TruncatedNodesAreTheRationalNodesAsGmpRoundsThem) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> mantissa(0.5, 1);
  std::uniform_int_distribution<int> exponent(-1074, 1015), near(-5, 5), pick(0, 9);
  const auto coordinate = [&](int around) {
    switch (pick(rng)) {
      case 0:
        return pick(rng) % 2 ? 0.0 : -0.0;
      case 1:
        return std::ldexp(mantissa(rng), -1060);  // subnormal results
      case 2:
        return std::ldexp(mantissa(rng), exponent(rng));
      default:
        return (pick(rng) % 2 ? -1 : 1) * std::ldexp(mantissa(rng), around + near(rng));
    }
  };
  for (int trial = 0; trial < 20000; ++trial) {
    const int around = trial % 2 ? exponent(rng) : near(rng);
    const Vec2 a(coordinate(around), coordinate(around)), b(coordinate(around), coordinate(around)),
        c(coordinate(around), coordinate(around));
    const P3Nodes ours = p3_straight_nodes_truncated(a, b, c);
    for (int i = 0; i < 10; ++i) {
      const mpq_class u(kP3ReferenceNodesTimes3[i][0], 3), v(kP3ReferenceNodesTimes3[i][1], 3);
      for (int k = 0; k < 2; ++k) {
        const mpq_class exact = (1 - u - v) * mpq_class(a[k]) + u * mpq_class(b[k]) + v * mpq_class(c[k]);
        const double expected = exact.get_d();
        ASSERT_EQ(std::bit_cast<std::uint64_t>(ours[i][k]), std::bit_cast<std::uint64_t>(expected))
            << "trial " << trial << " node " << i << ": " << ours[i][k] << " against " << expected;
      }
    }
  }
}

}  // namespace
}  // namespace curvemesh::geometry

namespace curvemesh::geometry {
namespace {

TEST(P3Amips, StraightNodesGiveTheLinearEnergyEverywhere) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), w(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Vec2 a(u(rng), u(rng)), b(u(rng), u(rng)), c(u(rng), u(rng));
    if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() < 0) std::swap(b, c);
    const P3Nodes n = p3_straight_nodes(a, b, c);
    const double expected = amips(a, b, c);
    const double s = w(rng), t = (1 - s) * w(rng);
    EXPECT_NEAR(p3_amips(n, s, t), expected, 1e-9 * expected) << "trial " << trial;
    EXPECT_NEAR(p3_max_amips(n), expected, 1e-9 * expected) << "trial " << trial;
  }
  const P3Nodes equilateral = p3_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0.5, std::sqrt(3.0) / 2));
  EXPECT_NEAR(p3_max_amips(equilateral), 2.0, 1e-12);
}

TEST(P3Amips, BendingAnEdgeRaisesTheEnergyAndFoldingMakesItInfinite) {
  P3Nodes n = p3_straight_nodes(Vec2(0, 0), Vec2(1, 0), Vec2(0.5, std::sqrt(3.0) / 2));
  double previous = p3_max_amips(n);
  for (double bulge : {0.05, 0.1, 0.2}) {  // the edge from node 0 to node 1 bends outwards
    P3Nodes b = n;
    b[3] += Vec2(0, -bulge);
    b[4] += Vec2(0, -bulge);
    const double e = p3_max_amips(b);
    EXPECT_GT(e, previous);
    previous = e;
  }
  P3Nodes folded = n;
  folded[3] += Vec2(0, 1.5);  // across the opposite corner: det J < 0 somewhere
  folded[4] += Vec2(0, 1.5);
  EXPECT_EQ(p3_max_amips(folded), std::numeric_limits<double>::infinity());
}

// The lattice sums are the ones p3_amips and p3_jacobian make point by point, so the values must
// be the same bits, not merely close; and a bound may only cut the work, never a value below it.
TEST(P3Amips, LatticeValuesAndBoundsAgreeBitForBitWithThePointwiseMaps) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1, 1), jitter(-0.2, 0.2);
  int folded = 0, cut = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Vec2 a(u(rng), u(rng)), b(u(rng), u(rng)), c(u(rng), u(rng));
    if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() < 0) std::swap(b, c);
    P3Nodes n = p3_straight_nodes(a, b, c);
    for (int i = 3; i < 10; ++i) n[i] += Vec2(jitter(rng), jitter(rng));
    double max_amips = 0, min_det = std::numeric_limits<double>::infinity();
    for (int j = 0; j <= 6; ++j)
      for (int k = 0; j + k <= 6; ++k) {
        max_amips = std::max(max_amips, p3_amips(n, j / 6.0, k / 6.0));
        min_det = std::min(min_det, p3_jacobian(n, j / 6.0, k / 6.0).determinant());
      }
    folded += !(min_det > 0);
    EXPECT_EQ(p3_max_amips(n), max_amips) << "trial " << trial;
    const P3LatticeValues values = p3_lattice_values(n);
    EXPECT_EQ(values.max_amips, max_amips) << "trial " << trial;
    EXPECT_EQ(values.min_det, min_det) << "trial " << trial;
    for (double bound : {2.5, 5.0, 20.0, 1e3}) {
      const double e = p3_max_amips(n, bound);
      if (max_amips < bound) {
        EXPECT_EQ(e, max_amips) << "trial " << trial << " bound " << bound;
      } else {
        EXPECT_GE(e, bound) << "trial " << trial << " bound " << bound;
        EXPECT_LE(e, max_amips) << "trial " << trial << " bound " << bound;
        cut += e < max_amips;
      }
    }
  }
  EXPECT_GT(folded, 20);  // both valid and folded maps were tried
  EXPECT_LT(folded, 480);
  EXPECT_GT(cut, 20);  // and the bound did stop early
}

}  // namespace
}  // namespace curvemesh::geometry
