#include "geometry/p3_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/amips.hpp"

namespace curvemesh::geometry {

Vec2 p3_reference_node(int i) {
  return Vec2(kP3ReferenceNodesTimes3[i][0], kP3ReferenceNodesTimes3[i][1]) / 3.0;
}

P3Nodes p3_straight_nodes(const Vec2& a, const Vec2& b, const Vec2& c) {
  auto third = [](const Vec2& p, const Vec2& q) -> Vec2 { return (2 * p + q) / 3; };  // 1/3 from p
  return {a,           b,           c,           third(a, b), third(b, a),
          third(b, c), third(c, b), third(c, a), third(a, c), (a + b + c) / 3};
}

std::array<Vec2, 3> p3_centre_candidates(const P3Nodes& p) {
  const Vec2 sum_corners = p[0] + p[1] + p[2];
  Vec2 sum_edges = Vec2::Zero();
  for (int i = 3; i < 9; ++i) sum_edges += p[i];
  return {sum_edges / 4 - sum_corners / 6, (sum_corners + sum_edges) / 9, sum_corners / 3};
}

P3NodesT<mpq_class> to_exact(const P3Nodes& nodes) {
  P3NodesT<mpq_class> out;
  for (int i = 0; i < 10; ++i) out[i] = {mpq_class(nodes[i].x()), mpq_class(nodes[i].y())};
  return out;
}

P3NodesT<double> to_array(const P3Nodes& nodes) {
  P3NodesT<double> out;
  for (int i = 0; i < 10; ++i) out[i] = {nodes[i].x(), nodes[i].y()};
  return out;
}

Vec2 p3_map(const P3Nodes& nodes, double u, double v) {
  const auto x = p3_map(to_array(nodes), u, v);
  return {x[0], x[1]};
}

Eigen::Matrix2d p3_jacobian(const P3Nodes& nodes, double u, double v) {
  const auto d = p3_basis_gradients(u, v);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 10; ++i) J += nodes[i] * Eigen::RowVector2d(d[i][0], d[i][1]);
  return J;
}

double p3_amips(const P3Nodes& nodes, double u, double v) {
  const Eigen::Matrix2d J = p3_jacobian(nodes, u, v);  // [x_u x_v]
  return amips_of_edges(J.col(0), J.col(1));
}

namespace {

// The basis gradients at the 28 points (j/6, k/6), j + k ≤ 6, of the order-6 lattice, in the
// order p3_max_amips visits them: evaluated once, at compile time, with the same arithmetic as at
// run time, so the energies are bit for bit those of p3_amips at the same points.
using LatticeGradients = std::array<std::array<std::array<double, 2>, 10>, 28>;
constexpr LatticeGradients lattice_gradients() {
  LatticeGradients g{};
  int n = 0;
  for (int j = 0; j <= 6; ++j)
    for (int k = 0; j + k <= 6; ++k) g[n++] = p3_basis_gradients(j / 6.0, k / 6.0);
  return g;
}
constexpr LatticeGradients kLatticeGradients = lattice_gradients();

// J = Σ node_i ⊗ ∇ℓ_i at a lattice point, summed in p3_jacobian's order; its columns x_u, x_v.
struct LatticeJacobian {
  Vec2 xu, xv;
};
LatticeJacobian lattice_jacobian(const P3Nodes& nodes, const std::array<std::array<double, 2>, 10>& d) {
  double xu = 0, yu = 0, xv = 0, yv = 0;
  for (int i = 0; i < 10; ++i) {
    xu += nodes[i].x() * d[i][0];
    yu += nodes[i].y() * d[i][0];
    xv += nodes[i].x() * d[i][1];
    yv += nodes[i].y() * d[i][1];
  }
  return {Vec2(xu, yu), Vec2(xv, yv)};
}

}  // namespace

double p3_max_amips(const P3Nodes& nodes, double bound) {
  double e = 0;
  for (const auto& d : kLatticeGradients) {
    const LatticeJacobian J = lattice_jacobian(nodes, d);
    e = std::max(e, amips_of_edges(J.xu, J.xv));
    if (e >= bound) break;
  }
  return e;
}

P3LatticeValues p3_lattice_values(const P3Nodes& nodes) {
  P3LatticeValues out{std::numeric_limits<double>::infinity(), 0};
  for (const auto& d : kLatticeGradients) {
    const LatticeJacobian J = lattice_jacobian(nodes, d);
    out.min_det = std::min(out.min_det, cross(J.xu, J.xv));
    out.max_amips = std::max(out.max_amips, amips_of_edges(J.xu, J.xv));
  }
  return out;
}

namespace {

// ---------------------------------------------------------------------------------------------
// A double with a rigorous bound on its distance to the exact result of the same computation
// (running error analysis). kEps is twice the unit roundoff u, so |fl(x ∘ y) − x ∘ y| ≤ u |x ∘ y|
// ≤ kEps |fl(x ∘ y)|. The bounds are themselves rounded; the comparisons below use twice the
// bound, which covers that (its relative error is a few u, far below a factor 2). Assumes no
// overflow or underflow: node coordinates between about 1e-70 and 1e70 in magnitude.
constexpr double kEps = std::numeric_limits<double>::epsilon();

struct ErrorBounded {
  double value = 0, error = 0;
  ErrorBounded() = default;
  explicit ErrorBounded(int k) : value(k) {}  // small integers are exact
  ErrorBounded(double v, double e) : value(v), error(e) {}
  ErrorBounded& operator+=(const ErrorBounded& o);
};

ErrorBounded rounded(double v, double carried) {
  return {v, carried + kEps * std::abs(v)};
}
ErrorBounded operator+(const ErrorBounded& a, const ErrorBounded& b) {
  return rounded(a.value + b.value, a.error + b.error);
}
ErrorBounded operator-(const ErrorBounded& a, const ErrorBounded& b) {
  return rounded(a.value - b.value, a.error + b.error);
}
ErrorBounded operator*(const ErrorBounded& a, const ErrorBounded& b) {
  return rounded(a.value * b.value,
                 std::abs(a.value) * b.error + std::abs(b.value) * a.error + a.error * b.error);
}
// |a/b − â/b̂| ≤ (e_a + |â/b̂| e_b) / (|b̂| − e_b) when |b̂| > e_b.
ErrorBounded operator/(const ErrorBounded& a, const ErrorBounded& b) {
  const double q = a.value / b.value, margin = std::abs(b.value) - b.error;
  if (!(margin > 0)) return {q, std::numeric_limits<double>::infinity()};
  return rounded(q, (a.error + std::abs(q) * b.error) / margin);
}
ErrorBounded& ErrorBounded::operator+=(const ErrorBounded& o) {
  return *this = *this + o;
}

// Sign decisions: exact on rationals, outside the error bound on ErrorBounded.
bool certainly_positive(const mpq_class& x) {
  return sgn(x) > 0;
}
bool certainly_nonpositive(const mpq_class& x) {
  return sgn(x) <= 0;
}
double approx(const mpq_class& x) {
  return x.get_d();
}
bool certainly_positive(const ErrorBounded& x) {
  return x.value > 2 * x.error;
}
bool certainly_nonpositive(const ErrorBounded& x) {
  return x.value + 2 * x.error <= 0;
}
double approx(const ErrorBounded& x) {
  return x.value;
}

// ---------------------------------------------------------------------------------------------
// Subdivision of the degree-4 polynomial det J over the reference triangle.

using Coefficients4 = std::array<int, 3>;  // a point of the parent in barycentrics, times 2

// The four sub-triangles cut by the edge midpoints, as points of the parent (barycentrics × 2).
constexpr std::array<std::array<Coefficients4, 3>, 4> kChildren{{
    {{{2, 0, 0}, {1, 1, 0}, {1, 0, 1}}},  // at corner 0
    {{{1, 1, 0}, {0, 2, 0}, {0, 1, 1}}},  // at corner 1
    {{{1, 0, 1}, {0, 1, 1}, {0, 0, 2}}},  // at corner 2
    {{{0, 1, 1}, {1, 0, 1}, {1, 1, 0}}},  // the middle one
}};

constexpr std::array<std::size_t, 3> kCornerIndex{bernstein_index(4, 0, 0), bernstein_index(4, 4, 0),
                                                  bernstein_index(4, 0, 4)};

// Coefficients of the same polynomial over the sub-triangle q0 q1 q2: the coefficient (i, j, k)
// is the blossom (polar form) at i copies of q0, j of q1 and k of q2, which de Casteljau's
// algorithm evaluates by using one of those points at each of its four steps.
template <class T>
std::array<T, 15> restrict_to(const std::array<T, 15>& c, const std::array<Coefficients4, 3>& q) {
  std::array<T, 15> out;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j + k <= 4; ++j) {
      std::array<T, 15> net = c;
      for (int m = 4; m > 0; --m) {
        // Steps use q0 (i times), then q1 (j times), then q2 (k times).
        const int step = 4 - m;
        const auto& w = step < 4 - j - k ? q[0] : step < 4 - k ? q[1] : q[2];
        for (int kk = 0; kk < m; ++kk)
          for (int jj = 0; jj + kk < m; ++jj) {
            T acc(0);
            if (w[0]) acc += T(w[0]) * net[bernstein_index(m, jj, kk)];
            if (w[1]) acc += T(w[1]) * net[bernstein_index(m, jj + 1, kk)];
            if (w[2]) acc += T(w[2]) * net[bernstein_index(m, jj, kk + 1)];
            net[bernstein_index(m - 1, jj, kk)] = T(acc / T(2));
          }
      }
      out[bernstein_index(4, j, k)] = net[0];
    }
  return out;
}

struct Search {
  JacobianVerdict verdict = JacobianVerdict::undecided;
  int subtriangles = 0;
  double min_corner = std::numeric_limits<double>::infinity();  // smallest det J at a corner seen
};

// Depth-first search for a sub-triangle with a non-positive corner, skipping those whose
// coefficients are all positive (det J ≥ min coefficient by the convex hull property).
template <class T>
Search certify(const std::array<T, 15>& top, const JacobianCheckOptions& options) {
  Search s;
  auto corners_fail = [&s](const std::array<T, 15>& c) {
    bool fail = false;
    for (std::size_t i : kCornerIndex) {
      s.min_corner = std::min(s.min_corner, approx(c[i]));
      fail = fail || certainly_nonpositive(c[i]);
    }
    return fail;
  };
  s.verdict = JacobianVerdict::not_positive;  // until the search says otherwise
  if (corners_fail(top)) return s;
  std::vector<std::pair<std::array<T, 15>, int>> stack{{top, 0}};
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
      auto cc = restrict_to(c, child);
      if (corners_fail(cc)) return s;
      stack.emplace_back(std::move(cc), depth + 1);
    }
  }
  s.verdict = gave_up ? JacobianVerdict::undecided : JacobianVerdict::positive;
  return s;
}

}  // namespace

JacobianVerdict certify_jacobian_exact(const P3NodesT<mpq_class>& nodes,
                                       const JacobianCheckOptions& options) {
  return certify(p3_jacobian_det_bernstein(nodes), options).verdict;
}

JacobianVerdict certify_jacobian_exact(const P3Nodes& nodes, const JacobianCheckOptions& options) {
  return certify_jacobian_exact(to_exact(nodes), options);
}

JacobianCertificate certify_jacobian(const P3Nodes& nodes, const JacobianCheckOptions& options) {
  // Relative to node 0: the subtraction's error is relative to the difference, i.e. to the
  // element's size, where absolute coordinates would bring errors relative to the position.
  P3NodesT<ErrorBounded> local;
  P3NodesT<double> local_values;
  for (int i = 0; i < 10; ++i)
    for (int c = 0; c < 2; ++c) {
      local[i][c] = ErrorBounded(nodes[i][c], 0) - ErrorBounded(nodes[0][c], 0);
      local_values[i][c] = local[i][c].value;
    }
  const auto top = p3_jacobian_det_bernstein(local);
  JacobianCertificate out;
  const auto [lo, hi] = std::minmax_element(top.begin(), top.end(),
                                            [](const auto& a, const auto& b) { return a.value < b.value; });
  out.min_coefficient = lo->value;
  out.max_coefficient = hi->value;
  const Search s = certify(top, options);
  out.verdict = s.verdict;
  out.subtriangles = s.subtriangles;
  // min det J estimate: the degree-4 lattice and every sub-triangle corner visited.
  out.min_value = s.min_corner;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j + k <= 4; ++j)
      out.min_value = std::min(out.min_value, p3_jacobian_det(local_values, j / 4.0, k / 4.0));
  out.scaled_jacobian = out.max_coefficient > 0 ? out.min_value / out.max_coefficient
                                                : -std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace curvemesh::geometry
