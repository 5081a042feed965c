// The exact orientation of rational points: an interval filter decides the clear cases, the
// rationals the rest. Checked against the determinant's sign in rationals, on points where the
// filter can decide, on exactly collinear points (it cannot), and on points a rational 1e-60
// off a line (it cannot either, and the answer is not 0).
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <random>

#include "geometry/predicates.hpp"

namespace curvemesh::geometry {
namespace {

int reference_sign(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  const mpq_class det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return sgn(det);
}

mpq_class random_rational(std::mt19937_64& rng) {
  std::uniform_int_distribution<long> num(-1000000007L, 1000000007L), den(1, 999999937L);
  mpq_class q(num(rng), den(rng));
  q.canonicalize();
  return q;
}

TEST(ExactOrientation, AgreesWithTheRationalDeterminantNearAndOnLines) {
  std::mt19937_64 rng(5);
  int signs[3] = {0, 0, 0};
  mpz_class ten60 = 1;
  for (int i = 0; i < 60; ++i) ten60 *= 10;
  const mpq_class offset(1, ten60);
  for (int trial = 0; trial < 3000; ++trial) {
    const ExactPoint a(random_rational(rng), random_rational(rng));
    const ExactPoint b(random_rational(rng), random_rational(rng));
    ExactPoint c(random_rational(rng), random_rational(rng));
    if (trial % 3 != 0) {  // on the line through a and b, at a rational parameter
      const mpq_class t = random_rational(rng);
      c = ExactPoint(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
      c.x.canonicalize();
      c.y.canonicalize();
      if (trial % 3 == 2) c.y += (trial % 2 ? offset : -offset);  // then just off it
    }
    const int expected = reference_sign(a, b, c);
    ++signs[expected + 1];
    ASSERT_EQ(orientation(a, b, c), expected) << "trial " << trial;
    ASSERT_EQ(orientation(b, a, c), -expected) << "trial " << trial;
    ASSERT_EQ(orientation(b, c, a), expected) << "trial " << trial;
  }
  EXPECT_GT(signs[1], 900);  // collinear
  EXPECT_GT(signs[0], 600);  // and both sides
  EXPECT_GT(signs[2], 600);
}

TEST(ExactOrientation, DoublesAsRationalsAgreeWithTheDoublePredicate) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec2 a(u(rng), u(rng)), b(u(rng), u(rng));
    // Half the third points on the segment's rounded midpoint: collinear or nearly.
    const Vec2 c = trial % 2 ? Vec2(u(rng), u(rng)) : Vec2(0.5 * (a + b));
    ASSERT_EQ(orientation(ExactPoint(a), ExactPoint(b), ExactPoint(c)), orientation(a, b, c)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace curvemesh::geometry
