// The static filter of bernstein_certificate.hpp on elements whose smallest coefficient is within
// rounding of 0, for the P3 and P2 certificates alike: an element's node 3 is moved to where the
// computed coefficient changes sign, then a few units in the last place either way, so that the
// exact and computed signs disagree often. The filter must decline every element whose exact
// coefficients are not all positive, and each computed coefficient must lie within the bound the
// filter doubles, k·kEps M̂₁ m², of the exact one (GMP).
#pragma once

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/bernstein_certificate.hpp"
#include "geometry/p2_triangle.hpp"
#include "geometry/p3_triangle.hpp"

namespace curvemesh::testing_support {

struct FilterTally {
  int accepted = 0, nonpositive = 0, computed_positive_but_not = 0;
};

// One element through the filter, with the nodes relative to node 0 as the certificate takes them:
// the bound checked on every coefficient, an accepted element checked positive (fatal failures).
template <std::size_t N, class Bernstein>
void tally_static_filter(const std::array<geometry::Vec2, N>& n, Bernstein bernstein, FilterTally& tally) {
  using geometry::PointT;
  constexpr auto unit = geometry::detail::unit_error_bounds<N, Bernstein>();
  std::array<PointT<double>, N> local;
  std::array<PointT<mpq_class>, N> exact_local;
  double m = 0;
  for (std::size_t i = 0; i < N; ++i)
    for (int d = 0; d < 2; ++d) {
      local[i][d] = n[i][d] - n[0][d];
      m = std::max(m, std::abs(local[i][d]));
      exact_local[i][d] = mpq_class(n[i][d]) - mpq_class(n[0][d]);
    }
  const auto exact = bernstein(exact_local);
  const auto computed = bernstein(local);
  for (std::size_t i = 0; i < exact.size(); ++i)
    ASSERT_LE(abs(mpq_class(computed[i]) - exact[i]), mpq_class(unit[i]) * mpq_class(m) * mpq_class(m));
  const bool positive = std::all_of(exact.begin(), exact.end(), [](const mpq_class& x) { return sgn(x) > 0; });
  tally.nonpositive += !positive;
  tally.computed_positive_but_not +=
      !positive && std::all_of(computed.begin(), computed.end(), [](double x) { return x > 0; });
  if (!geometry::detail::positive_by_static_bound(local, bernstein)) return;
  ++tally.accepted;
  ASSERT_TRUE(positive);
}

// Node 3 of element n (certified positive) moved across the side from node 0 to node 2, which
// folds corner 0, to where the certificate's smallest coefficient changes sign (bisection), then
// each of −ulps … ulps units in the last place from there: every such element goes to `visit`.
template <std::size_t N, class Visit>
void visit_near_sign_change(const std::array<geometry::Vec2, N>& n, int ulps, Visit visit) {
  const geometry::Vec2 side = n[2] - n[0], away(-side.y(), side.x());
  const auto smallest = [&](double t) {
    std::array<geometry::Vec2, N> e = n;
    e[3] += t * away;
    return geometry::certify_jacobian(e).min_coefficient;
  };
  double lo = 0, hi = 1;
  while (smallest(hi) > 0) hi *= 2;
  for (int i = 0; i < 80; ++i) (smallest(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  std::array<geometry::Vec2, N> m = n;
  m[3] += lo * away;
  for (int k = -ulps; k <= ulps; ++k) {
    std::array<geometry::Vec2, N> e = m;
    for (int d = 0; d < 2; ++d) e[3][d] = m[3][d] + k * (std::nextafter(m[3][d], INFINITY) - m[3][d]);
    visit(e);
  }
}

// Element n itself, then, when it is certified positive, the elements near its sign change.
template <std::size_t N, class Bernstein>
void tally_around_sign_change(const std::array<geometry::Vec2, N>& n, Bernstein bernstein, FilterTally& tally) {
  tally_static_filter(n, bernstein, tally);
  if (::testing::Test::HasFatalFailure()) return;
  if (geometry::certify_jacobian(n).verdict != geometry::JacobianVerdict::positive) return;
  visit_near_sign_change(n, 12, [&](const std::array<geometry::Vec2, N>& e) {
    if (!::testing::Test::HasFatalFailure()) tally_static_filter(e, bernstein, tally);
  });
}

}  // namespace curvemesh::testing_support
