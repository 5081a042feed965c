#pragma once
// Internal to src/geometry (p3_triangle.cpp, p2_triangle.cpp): the sign of a triangular Bernstein
// polynomial of any degree on the whole reference triangle (App. C), exactly on rationals and
// conservatively in doubles. The Jacobian determinant of a Pn element is such a polynomial of
// degree 2(n − 1): 4 for P3, 2 for P2.
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "geometry/p3_triangle.hpp"

namespace curvemesh::geometry::detail {

// ---------------------------------------------------------------------------------------------
// A double with a rigorous bound on its distance to the exact result of the same computation
// (running error analysis; Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., §3.3).
//
// Rounding (IEEE 754 binary64, round to nearest, gradual underflow; Higham §2.1–2.2): with u the
// unit roundoff, an operation's result z rounds to fl(z) with |fl(z) − z| ≤ u |z| + η, where
// η = 2^-1075 (half the smallest subnormal) is only ever needed by a product or a quotient: a sum
// of two doubles is exact when it is subnormal or zero (Hauser, ACM TOPLAS 18(2), 1996). kEps is
// twice u, so u |z| ≤ kEps |fl(z)|. Each operation's bound also holds DBL_MIN = 2^-1022, which
// covers η (a product of two coordinates of 1e-170 rounds to 0, and kEps · 0 would claim no
// error) and keeps every nonzero bound a normal number; only a result known to be exact (exact
// operands, and a zero or subnormal sum, or a zero operand of a product or dividend) keeps the
// bound 0, so an element whose coefficient is computed exactly as 0 is still decided.
//
// Propagation, for exact operands a, b known as â, b̂ with |a − â| ≤ e_a, |b − b̂| ≤ e_b:
// |(a ± b) − (â ± b̂)| ≤ e_a + e_b and |ab − âb̂| ≤ |â| e_b + |b̂| e_a + e_a e_b; a quotient below.
//
// The bounds are themselves computed in doubles. Each operation's bound is at most eight
// operations on non-negative terms, each losing at most a relative u, or, for a product that
// underflows, at most η = u · DBL_MIN, no more than u of a bound that holds DBL_MIN; along a chain
// of k operations the computed bound is therefore at least (1 − 8u)^k of the true one, above half
// of it for any k below 10^14 (a certificate's chains are a few hundred operations long). So the
// sign decisions below compare with twice the bound. Overflow makes a value or a bound infinite
// or NaN, and then no comparison below holds: never a wrong decision, only none. Against node
// coordinates above about 1e-150 in magnitude the DBL_MIN changes no decision.
inline constexpr double kEps = std::numeric_limits<double>::epsilon();

struct ErrorBounded {
  double value = 0, error = 0;
  ErrorBounded() = default;
  explicit ErrorBounded(int k) : value(k) {}  // small integers are exact
  ErrorBounded(double v, double e) : value(v), error(e) {}
  ErrorBounded& operator+=(const ErrorBounded& o);
};

// A result v with the operands' propagated bound `carried`; `exact` when it is known exact.
inline ErrorBounded rounded(double v, double carried, bool exact) {
  return {v, exact ? 0.0 : carried + kEps * std::abs(v) + std::numeric_limits<double>::min()};
}
inline bool exact_operands(const ErrorBounded& a, const ErrorBounded& b) {
  return a.error == 0 && b.error == 0;
}
inline bool zero_or_subnormal(double v) {
  return std::abs(v) < std::numeric_limits<double>::min();
}
inline ErrorBounded operator+(const ErrorBounded& a, const ErrorBounded& b) {
  const double v = a.value + b.value;
  return rounded(v, a.error + b.error, exact_operands(a, b) && zero_or_subnormal(v));
}
inline ErrorBounded operator-(const ErrorBounded& a, const ErrorBounded& b) {
  const double v = a.value - b.value;
  return rounded(v, a.error + b.error, exact_operands(a, b) && zero_or_subnormal(v));
}
inline ErrorBounded operator*(const ErrorBounded& a, const ErrorBounded& b) {
  return rounded(a.value * b.value,
                 std::abs(a.value) * b.error + std::abs(b.value) * a.error + a.error * b.error,
                 exact_operands(a, b) && (a.value == 0 || b.value == 0));
}
// |a/b − â/b̂| ≤ (e_a + |â/b̂| e_b) / (|b̂| − e_b) when |b̂| > e_b; the margin takes twice e_b, as
// the comparisons do. The certificates divide by exact constants only (e_b = 0).
inline ErrorBounded operator/(const ErrorBounded& a, const ErrorBounded& b) {
  const double q = a.value / b.value, margin = std::abs(b.value) - 2 * b.error;
  if (!(margin > 0)) return {q, std::numeric_limits<double>::infinity()};
  return rounded(q, (a.error + std::abs(q) * 2 * b.error) / margin, exact_operands(a, b) && a.value == 0);
}
inline ErrorBounded& ErrorBounded::operator+=(const ErrorBounded& o) {
  return *this = *this + o;
}

// Sign decisions: exact on rationals, outside the error bound on ErrorBounded.
inline bool certainly_positive(const mpq_class& x) {
  return sgn(x) > 0;
}
inline bool certainly_nonpositive(const mpq_class& x) {
  return sgn(x) <= 0;
}
inline double approx(const mpq_class& x) {
  return x.get_d();
}
inline bool certainly_positive(const ErrorBounded& x) {
  return x.value > 2 * x.error;
}
inline bool certainly_nonpositive(const ErrorBounded& x) {
  return x.value + 2 * x.error <= 0;
}
inline double approx(const ErrorBounded& x) {
  return x.value;
}

// ---------------------------------------------------------------------------------------------
// The static filter in front of ErrorBounded: one error bound for every element, known before any
// element is seen, as CGAL's static filters have (Devillers & Pion, "Efficient exact geometric
// predicates for Delaunay triangulations", ALENEX 2003): the coefficients are computed in plain
// doubles and one comparison each decides almost every element; what it leaves goes to
// ErrorBounded, which carries a bound through every operation (several times the work).
//
// The bound. For a computation of +, −, × and ÷ by exact constants, with computed value v̂, exact
// value v and exact magnitude M (the same computation on the operands' absolute values, − taken as
// +, ÷c as ÷|c|), |v̂ − v| ≤ γ_k M, γ_k = ku / (1 − ku), where k counts roundings by the rule of
// Roundings below (induction over the operations, from fl(a ∘ b) = (a ∘ b)(1 + δ), |δ| ≤ u, and
// (1 + γ_i)(1 + γ_j) ≤ 1 + γ_{i+j}; Higham §3.1–3.4). The leaves are the node coordinates relative
// to node 0, one rounding each (|l̂ − l| ≤ u |l|), which keeps the bound relative to the element's
// size. The coefficients are homogeneous of degree 2 in the leaves and M is a polynomial with
// non-negative coefficients, so with m the largest |l̂|, M ≤ m² M₁ / (1 − u)², M₁ being M with every
// leaf 1, computed once at compile time (M̂₁, with M₁ ≤ (1 + γ_k) M̂₁). Altogether
// |v̂ − v| ≤ k·kEps M̂₁ m² while ku ≤ 1/8; a coefficient passes when it exceeds twice that, which
// absorbs the rounding of the bound itself.
//
// Underflow and overflow: the filter is used only when m lies in [2^-400, 2^400]. Then no value
// overflows (all are below 2^820); a + or − that underflows is exact (Hauser, ACM TOPLAS 18(2),
// 1996) and a × or ÷ adds at most 2^-1075 beyond its relative error, which reaches the result
// multiplied by at most 2^10 m (a later product of degree-1 quantities) and 2^10 (constants), over
// fewer than 2^12 operations: at most 2^-1043 max(1, 2^10 m), below the 2^-150 m² added to the bound.
struct Magnitude {
  double value = 0, magnitude = 0;
  constexpr Magnitude() = default;
  constexpr explicit Magnitude(int k) : value(k), magnitude(k < 0 ? -k : k) {}
  constexpr Magnitude(double v, double m) : value(v), magnitude(m) {}
  constexpr Magnitude& operator+=(const Magnitude& o) {
    value += o.value;
    magnitude += o.magnitude;
    return *this;
  }
};
constexpr Magnitude operator+(const Magnitude& a, const Magnitude& b) {
  return {a.value + b.value, a.magnitude + b.magnitude};
}
constexpr Magnitude operator-(const Magnitude& a, const Magnitude& b) {
  return {a.value - b.value, a.magnitude + b.magnitude};
}
constexpr Magnitude operator*(const Magnitude& a, const Magnitude& b) {
  return {a.value * b.value, a.magnitude * b.magnitude};
}
constexpr Magnitude operator/(const Magnitude& a, const Magnitude& b) {  // b an exact constant
  return {a.value / b.value, a.magnitude / (b.value < 0 ? -b.value : b.value)};
}

// The rounding count k of the bound above, evaluated at compile time on the computation itself:
// a sum or difference adds one rounding to the larger count of its operands, a product or
// quotient one to the sum of their counts; a small integer constant is exact (count 0).
struct Roundings {
  int count = 0;
  constexpr Roundings() = default;
  constexpr explicit Roundings(int) {}
  constexpr Roundings& operator+=(const Roundings& o) { return *this = of(std::max(count, o.count) + 1); }
  static constexpr Roundings of(int k) {
    Roundings r;
    r.count = k;
    return r;
  }
};
constexpr Roundings operator+(const Roundings& a, const Roundings& b) {
  return Roundings::of(std::max(a.count, b.count) + 1);
}
constexpr Roundings operator-(const Roundings& a, const Roundings& b) {
  return a + b;
}
constexpr Roundings operator*(const Roundings& a, const Roundings& b) {
  return Roundings::of(a.count + b.count + 1);
}
constexpr Roundings operator/(const Roundings& a, const Roundings& b) {
  return a * b;
}

// The largest rounding count over the coefficients `Bernstein` computes from N nodes, each
// coordinate one rounding (the subtraction of node 0).
template <std::size_t N, class Bernstein>
constexpr int largest_rounding_count() {
  std::array<PointT<Roundings>, N> leaves{};
  for (auto& p : leaves) p = {Roundings::of(1), Roundings::of(1)};
  int k = 0;
  for (const Roundings& r : Bernstein{}(leaves)) k = std::max(k, r.count);
  return k;
}

// Per coefficient, k·kEps M̂₁: the bound on its error is that times m².
template <std::size_t N, class Bernstein>
constexpr auto unit_error_bounds() {
  constexpr int k = largest_rounding_count<N, Bernstein>();
  static_assert(k > 0 && k < 1000, "ku ≤ 1/8 by far");
  std::array<PointT<Magnitude>, N> leaves{};
  for (auto& p : leaves) p = {Magnitude(1.0, 1.0), Magnitude(1.0, 1.0)};
  const auto top = Bernstein{}(leaves);
  std::array<double, std::tuple_size_v<decltype(top)>> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = k * kEps * top[i].magnitude;
  return out;
}

// The coefficients, in doubles, when the static filter proves every one of them positive.
template <std::size_t N, class Bernstein>
auto positive_by_static_bound(const std::array<PointT<double>, N>& local, Bernstein bernstein)
    -> std::optional<decltype(bernstein(local))> {
  static constexpr auto unit = unit_error_bounds<N, Bernstein>();
  double m = 0;
  for (const auto& p : local)
    for (double x : p)
      if (!(std::abs(x) <= m)) m = std::abs(x);  // a NaN makes m NaN, and the filter declines
  if (!(m >= 0x1p-400 && m <= 0x1p400)) return std::nullopt;
  const auto top = bernstein(local);
  const double mm = m * m, floor = 0x1p-150 * mm;
  for (std::size_t i = 0; i < top.size(); ++i)
    if (!(top[i] > 2 * unit[i] * mm + floor)) return std::nullopt;
  return top;
}

// ---------------------------------------------------------------------------------------------
// Subdivision of a degree-D polynomial over the reference triangle.

// The D + 1 choose 2 coefficients of a degree-D polynomial, in bernstein_index order.
template <int D, class T>
using Coefficients = std::array<T, bernstein_count(D)>;

using Corner2 = std::array<int, 3>;  // a point of the parent in barycentrics, times 2

// The four sub-triangles cut by the edge midpoints, as points of the parent (barycentrics × 2).
inline constexpr std::array<std::array<Corner2, 3>, 4> kChildren{{
    {{{2, 0, 0}, {1, 1, 0}, {1, 0, 1}}},  // at corner 0
    {{{1, 1, 0}, {0, 2, 0}, {0, 1, 1}}},  // at corner 1
    {{{1, 0, 1}, {0, 1, 1}, {0, 0, 2}}},  // at corner 2
    {{{0, 1, 1}, {1, 0, 1}, {1, 1, 0}}},  // the middle one
}};

// The coefficients at the corners, which are the polynomial's values there.
template <int D>
constexpr std::array<std::size_t, 3> kCornerIndex{bernstein_index(D, 0, 0), bernstein_index(D, D, 0),
                                                  bernstein_index(D, 0, D)};

// Coefficients of the same polynomial over the sub-triangle q0 q1 q2: the coefficient (i, j, k)
// is the blossom (polar form) at i copies of q0, j of q1 and k of q2, which de Casteljau's
// algorithm evaluates by using one of those points at each of its D steps.
template <int D, class T>
Coefficients<D, T> restrict_to(const Coefficients<D, T>& c, const std::array<Corner2, 3>& q) {
  Coefficients<D, T> out;
  for (int k = 0; k <= D; ++k)
    for (int j = 0; j + k <= D; ++j) {
      Coefficients<D, T> net = c;
      for (int m = D; m > 0; --m) {
        // Steps use q0 (i times), then q1 (j times), then q2 (k times).
        const int step = D - m;
        const auto& w = step < D - j - k ? q[0] : step < D - k ? q[1] : q[2];
        for (int kk = 0; kk < m; ++kk)
          for (int jj = 0; jj + kk < m; ++jj) {
            T acc(0);
            if (w[0]) acc += T(w[0]) * net[bernstein_index(m, jj, kk)];
            if (w[1]) acc += T(w[1]) * net[bernstein_index(m, jj + 1, kk)];
            if (w[2]) acc += T(w[2]) * net[bernstein_index(m, jj, kk + 1)];
            net[bernstein_index(m - 1, jj, kk)] = T(acc / T(2));
          }
      }
      out[bernstein_index(D, j, k)] = net[0];
    }
  return out;
}

struct Search {
  JacobianVerdict verdict = JacobianVerdict::undecided;
  int subtriangles = 0;
  double min_corner = std::numeric_limits<double>::infinity();  // smallest value at a corner seen
};

// Depth-first search for a sub-triangle with a non-positive corner, skipping those whose
// coefficients are all positive (the polynomial is at least its smallest coefficient there, by
// the convex hull property).
//
// On ErrorBounded coefficients, a verdict other than undecided is the verdict the same search on
// the exact rational coefficients gives with the same options (what makes the double search a
// filter for the exact one, as CGAL's filtered predicates are): every ErrorBounded decision is
// the exact one where it is made, so the exact search skips every sub-triangle the double one
// skips (and maybe more) and visits a subset of the same depth-first order, each sub-triangle
// with no more counted before it. Positive: no corner of the exact search can be ≤ 0 on a
// polynomial proved positive, and a depth or work limit it hits the double search hit too. Not
// positive: the exact search cannot skip an ancestor of the sub-triangle whose corner the double
// search found ≤ 0 (it would be positive there), so it reaches that corner unless it finds another
// ≤ 0 first, and never hits the work limit on the way where the double search did not.
template <int D, class T>
Search certify(const Coefficients<D, T>& top, const JacobianCheckOptions& options) {
  Search s;
  auto corners_fail = [&s](const Coefficients<D, T>& c) {
    bool fail = false;
    for (std::size_t i : kCornerIndex<D>) {
      s.min_corner = std::min(s.min_corner, approx(c[i]));
      fail = fail || certainly_nonpositive(c[i]);
    }
    return fail;
  };
  s.verdict = JacobianVerdict::not_positive;  // until the search says otherwise
  if (corners_fail(top)) return s;
  // Most elements are decided by their own coefficients: no search, no stack to allocate.
  if (std::all_of(top.begin(), top.end(), [](const T& x) { return certainly_positive(x); })) {
    s.subtriangles = 1;
    s.verdict = JacobianVerdict::positive;
    return s;
  }
  std::vector<std::pair<Coefficients<D, T>, int>> stack{{top, 0}};
  bool gave_up = false;
  while (!stack.empty()) {
    auto [c, depth] = std::move(stack.back());
    stack.pop_back();
    ++s.subtriangles;
    if (std::all_of(c.begin(), c.end(), [](const T& x) { return certainly_positive(x); })) continue;
    if (depth >= options.max_depth) {
      gave_up = true;  // keep looking: a non-positive corner elsewhere still decides
      continue;
    }
    if (s.subtriangles >= options.max_subtriangles) {
      s.verdict = JacobianVerdict::undecided;
      return s;
    }
    for (const auto& child : kChildren) {
      auto cc = restrict_to<D>(c, child);
      if (corners_fail(cc)) return s;
      stack.emplace_back(std::move(cc), depth + 1);
    }
  }
  s.verdict = gave_up ? JacobianVerdict::undecided : JacobianVerdict::positive;
  return s;
}

// The double-precision certificate of an element of degree-D Jacobian determinant, given by its
// N nodes: `bernstein` gives the determinant's Bernstein coefficients of a node array, `lattice_min`
// its smallest value at the 15 points (j/4, k/4). Relative to node 0: the subtraction's error is relative to the
// difference, i.e. to the element's size, where absolute coordinates would bring errors relative
// to the position. The static filter decides first; ErrorBounded and the search take what it
// leaves. Both give the coefficients the same values (the same operations on the same doubles).
template <int D, std::size_t N, class Bernstein, class LatticeMin>
JacobianCertificate certificate(const std::array<Vec2, N>& nodes, Bernstein bernstein, LatticeMin lattice_min,
                                const JacobianCheckOptions& options) {
  std::array<PointT<double>, N> local_values;
  for (std::size_t i = 0; i < N; ++i)
    for (int c = 0; c < 2; ++c) local_values[i][c] = nodes[i][c] - nodes[0][c];
  JacobianCertificate out;
  Search s;
  std::array<double, bernstein_count(D)> values;
  if (const auto positive = positive_by_static_bound(local_values, bernstein)) {
    values = *positive;
    s.verdict = JacobianVerdict::positive;
    s.subtriangles = 1;
    for (std::size_t i : kCornerIndex<D>) s.min_corner = std::min(s.min_corner, values[i]);
  } else {
    std::array<PointT<ErrorBounded>, N> local;
    for (std::size_t i = 0; i < N; ++i)
      for (int c = 0; c < 2; ++c) local[i][c] = ErrorBounded(nodes[i][c], 0) - ErrorBounded(nodes[0][c], 0);
    const auto top = bernstein(local);
    for (std::size_t i = 0; i < top.size(); ++i) values[i] = top[i].value;
    s = certify<D>(top, options);
  }
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  out.min_coefficient = *lo;
  out.max_coefficient = *hi;
  out.verdict = s.verdict;
  out.subtriangles = s.subtriangles;
  // min det J estimate: the degree-4 lattice and every sub-triangle corner visited.
  out.min_value = std::min(s.min_corner, lattice_min(local_values));
  out.scaled_jacobian = out.max_coefficient > 0 ? out.min_value / out.max_coefficient
                                                : -std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace curvemesh::geometry::detail
