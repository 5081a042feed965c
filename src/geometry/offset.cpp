// Offset curves approximated by cubics. Each piece interpolates the exact offset at its ends with
// the exact tangent direction there (a G1 Hermite fit); of two choices of the arms' lengths —
// the offset's own speed (a C1 Hermite fit, error O(h⁴)), or the lengths that put the cubic's
// midpoint on the offset's (exact for circles, as the standard arc cubic) — the closer is kept, and
// a piece still farther than the tolerance is cut in two. The offset's cusps (where the curve bends
// tighter than |d|, Farouki & Neff 1990, "Analytic properties of plane offset curves") are cut
// at first: there its direction turns over, which no cubic of the kind above follows.
#include "geometry/offset.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/bezier_analysis.hpp"
#include "geometry/closest_point.hpp"

namespace curvemesh::geometry {

namespace {

// The size of the control polygon: the scale of "small" for the curve's derivatives.
double polygon_length(const CubicBezier& c) {
  return (c.p[1] - c.p[0]).norm() + (c.p[2] - c.p[1]).norm() + (c.p[3] - c.p[2]).norm();
}

constexpr double kUnit = std::numeric_limits<double>::epsilon();

// |c'|³ − d·(c' × c''): the sign of 1 − d·κ times |c'|³, without dividing by |c'|.
double cusp_function(const CubicBezier& c, double t, double d) {
  const Vec2 v = c.derivative(t);
  const double s = v.norm();
  return s * s * s - d * cross(v, c.second_derivative(t));
}

// cusp_function's value where its sign is not lost in rounding, else 0. Beside a cusp of the curve
// both terms vanish, and a straight curve (c' ∥ c'') has a cross product that is round-off alone:
// its sign there would cut the offset at cusps it does not have, into pieces no fit can meet. c'
// is a sum of the control polygon's legs with an absolute error of a few units of their size,
// whatever its own size.
double cusp_sign_value(const CubicBezier& c, double t, double d) {
  const Vec2 v = c.derivative(t), w = c.second_derivative(t);
  const double s = v.norm(), f = s * s * s - d * cross(v, w);
  const double error = 16 * kUnit * (s * s * s + std::abs(d) * (s + 3 * polygon_length(c)) * w.norm());
  return std::abs(f) > error ? f : 0.0;
}

// How far offset_point may be off at parameters [a, b] from rounding alone: of the coordinates,
// and of the normal's direction, c' computed with an absolute error of a few units of the control
// polygon's size and divided by |c'| (which vanishes at a cusp of the curve). A fit is asked to be
// no closer to the offset than this: it cannot be told apart from the exact offset any closer.
// The normal's part is at most the whole turn of a unit vector, 2|d| (where c' vanishes at a sample).
double rounding_reach(const CubicBezier& c, double d, double a, double b) {
  double slowest = std::numeric_limits<double>::infinity();
  for (int k = 1; k < 16; ++k) slowest = std::min(slowest, c.derivative(a + (b - a) * k / 16).norm());
  const double size = polygon_length(c);
  const double coordinates = c.eval((a + b) / 2).lpNorm<Eigen::Infinity>() + size + std::abs(d);
  const double normal = slowest > 0 ? std::min(2.0, 16 * kUnit * 3 * size / slowest) : 2.0;
  return 16 * kUnit * coordinates + std::abs(d) * normal;
}

// The exact offset's speed |c'|·|1 − d·κ| at t, its limit from inside [a, b] where c' vanishes.
double offset_speed(const CubicBezier& c, double t, double d, double a, double b) {
  const double small = 1e-9 * polygon_length(c);
  Vec2 v = c.derivative(t);
  if (v.norm() <= small) {
    t += (t <= a ? 1e-7 : -1e-7) * (b - a);
    v = c.derivative(t);
  }
  const double s = v.norm();
  if (s == 0) return 0;
  return std::abs(s - d * cross(v, c.second_derivative(t)) / (s * s));
}

// Where f is least on [a, b] by golden-section search of `steps` steps (a local minimum where f
// has several), and f there.
template <class F>
std::pair<double, double> golden_minimum(const F& f, double a, double b, int steps) {
  constexpr double g = 0.6180339887498949;
  double x = b - g * (b - a), y = a + g * (b - a), fx = f(x), fy = f(y);
  for (int i = 0; i < steps; ++i) {
    if (fx < fy)
      b = y, y = x, fy = fx, x = b - g * (b - a), fx = f(x);
    else
      a = x, x = y, fx = fy, y = a + g * (b - a), fy = f(y);
  }
  return fx < fy ? std::pair(x, fx) : std::pair(y, fy);
}

// One approximating cubic: the exact ends and end directions, arms of lengths a0 and a1.
CubicBezier hermite(const Vec2& p0, const Vec2& t0, double a0, const Vec2& p3, const Vec2& t3, double a1) {
  return {p0, p0 + a0 * t0, p3 - a1 * t3, p3};
}

// The cubics of one interval [a, b] of constant direction of travel (no offset cusp inside),
// `sign` that direction relative to the curve's.
class Fitter {
 public:
  Fitter(const CubicBezier& c, double d, double tolerance, double lo, double hi, OffsetRun& run)
      : c_(c), d_(d), tolerance_(tolerance), lo_(lo), hi_(hi), size_(control_polygon_size(c)), run_(run) {}

  void fit(double a, double b, double sign, bool smooth, int depth) {
    ++fits_;
    const double tolerance = std::max(tolerance_, rounding_reach(c_, d_, a, b));
    const Vec2 p0 = point(a), p3 = point(b);
    // An interval whose offset stays within the tolerance of its start (beside a cusp of the curve,
    // where roots of 1 − d·κ crowd into a few ulps): its chord is close enough.
    if (within_reach(p0, a, b, tolerance)) {
      run_.pieces.push_back(CubicBezier::line(p0, p3));
      run_.smooth.push_back(smooth);
      return;
    }
    const Vec2 t0 = sign * tangent(a), t3 = sign * tangent(b);
    // The midpoint fit first (B(1/2) = (p0 + p3)/2 + 3/8·(a0·t0 − a1·t3) set to the offset's
    // midpoint), then arms of a third of the chord (the fit of a nearly straight piece, where the
    // midpoint's system is singular), then the C1 fit (the arms a third of the offset's speed times
    // the interval): the first within the tolerance is taken, else the closer. An arm shorter than
    // 1/64 of the chord is not taken: the piece's speed would nearly vanish at that end, as the
    // offset's does at its cusps and where c' vanishes, and an element edge following such a
    // piece has a Jacobian that nearly vanishes at its vertex.
    CubicBezier best;
    double error = std::numeric_limits<double>::infinity();
    const double chord = (p3 - p0).norm();
    const auto consider = [&](double a0, double a1) {
      if (!(a0 >= chord / 64 && a1 >= chord / 64 && a0 <= 2 * chord && a1 <= 2 * chord)) return false;
      const CubicBezier candidate = hermite(p0, t0, a0, p3, t3, a1);
      if (const double e = distance(candidate, a, b, tolerance); e < error) best = candidate, error = e;
      return error <= tolerance;
    };
    const Vec2 r = 8.0 / 3.0 * (point((a + b) / 2) - (p0 + p3) / 2);
    const double det = cross(t3, t0);  // of the system [t0, −t3]·(a0, a1) = r
    const double h = (b - a) / 3;
    const bool done = (std::abs(det) > 1e-6 && consider(cross(t3, r) / det, cross(r, t0) / -det)) ||
                      consider(chord / 3, chord / 3) ||
                      consider(h * offset_speed(c_, a, d_, lo_, hi_), h * offset_speed(c_, b, d_, lo_, hi_));
    if (!std::isfinite(error)) best = hermite(p0, t0, chord / 3, p3, t3, chord / 3);  // nothing measured
    if (done || depth >= kMaxDepth || fits_ >= kMaxFits) {
      run_.pieces.push_back(best);
      run_.smooth.push_back(smooth);
      return;
    }
    const double m = (a + b) / 2;
    fit(a, m, sign, smooth, depth + 1);
    fit(m, b, sign, true, depth + 1);
  }

 private:
  // unit_tangent and offset_point of c_ on [lo_, hi_], its control polygon measured once.
  Vec2 tangent(double t) const { return unit_tangent(c_, t, lo_, hi_, size_); }
  Vec2 point(double t) const {
    const Vec2 u = tangent(t);
    return c_.eval(t) + d_ * Vec2(-u.y(), u.x());
  }

  static constexpr int kMaxDepth = 40;
  static constexpr int kMaxFits = 1 << 16;  // a bound on the work for one curve, whatever happens
  static constexpr int kChecks = 16;

  // Whether the offset over [a, b] lies within half the tolerance of p0 (at 16 parameters).
  bool within_reach(const Vec2& p0, double a, double b, double tolerance) const {
    for (int k = 1; k <= kChecks; ++k)
      if ((point(a + (b - a) * k / kChecks) - p0).norm() > tolerance / 2)
        return false;
    return true;
  }

  // The larger of the two one-sided distances between `piece` and the exact offset over [a, b]
  // (or a distance above the tolerance, the first found):
  // from the offset at kChecks − 1 inner parameters to their closest points on the piece, and from
  // the piece, at two points between each two of those closest points, to the offset between the
  // parameters they came from (golden-section search). A piece that runs back on itself (closest
  // points out of order by more than round-off) fails at once.
  double distance(const CubicBezier& piece, double a, double b, double tolerance) const {
    std::array<double, kChecks + 1> t{}, s{};
    t[0] = a, s[0] = 0, t[kChecks] = b, s[kChecks] = 1;
    double worst = 0;
    for (int k = 1; k < kChecks; ++k) {
      t[k] = a + (b - a) * k / kChecks;
      const ClosestPoint c = nearest_on(piece, point(t[k]), s[k - 1]);
      worst = std::max(worst, c.distance);
      if (worst > tolerance) return worst;  // a fit that fails need not be measured further
      s[k] = c.t;
      if (s[k] < s[k - 1] - 1e-6) return std::numeric_limits<double>::infinity();
      s[k] = std::max(s[k], s[k - 1]);
    }
    for (int k = 0; k < kChecks; ++k)
      for (const double f : {1.0 / 3, 2.0 / 3}) {
        const Vec2 q = piece.eval(s[k] + f * (s[k + 1] - s[k]));
        worst = std::max(worst, distance_to_offset(q, t[std::max(k - 1, 0)], t[std::min(k + 2, kChecks)]));
      }
    return worst;
  }

  // The point of `piece` nearest q, by Newton's method on (B(s) − q)·B'(s) from the nearest of
  // 9 parameters from `from` on (a local minimum at worst: a distance too large, never too small
  // for the point found, so a fit is never taken for one it is not); closest_point (App. B) when
  // Newton's method leaves [0, 1] or does not settle.
  static ClosestPoint nearest_on(const CubicBezier& piece, const Vec2& q, double from) {
    double s = from, best = INFINITY;
    for (int i = 0; i <= 8; ++i) {
      const double x = from + (1 - from) * i / 8;
      if (const double e = (piece.eval(x) - q).squaredNorm(); e < best) best = e, s = x;
    }
    for (int i = 0; i < 12; ++i) {
      const Vec2 r = piece.eval(s) - q, v = piece.derivative(s);
      const double slope = v.squaredNorm() + r.dot(piece.second_derivative(s));
      if (!(slope > 0)) break;
      const double step = r.dot(v) / slope, next = std::clamp(s - step, 0.0, 1.0);
      // Settled at a step of 1e-10: Newton's error after it is of the order of its square, and
      // a step of 1e-13 is below the rounding of s for many points, which never settle.
      const bool settled = std::abs(next - s) < 1e-10;
      s = next;
      if (settled) return {s, piece.eval(s), (piece.eval(s) - q).norm()};
    }
    return closest_point(piece, q);
  }

  // The distance from q to the exact offset over [a, b]: golden-section search for the foot of
  // the perpendicular, then the distance to the offset's tangent line there (the offset runs along
  // c's tangent), which leaves an error second-order in how far the search stopped from the foot.
  // An end of [a, b] nearer than any inner point is taken as it is.
  double distance_to_offset(const Vec2& q, double a, double b) const {
    const auto at = [&](double t) { return (point(t) - q).norm(); };
    const auto [t, nearest] = golden_minimum(at, a, b, 26);
    const double ends = std::min(at(a), at(b));
    if (ends <= nearest) return ends;
    const Vec2 foot = point(t);
    return std::abs(cross(q - foot, tangent(t)));
  }

  const CubicBezier& c_;
  double d_, tolerance_, lo_, hi_;
  double size_;  // of c's control polygon, for its unit tangent
  OffsetRun& run_;
  int fits_ = 0;
};

}  // namespace

Vec2 unit_normal(const CubicBezier& c, double t, double lo, double hi) {
  const Vec2 u = unit_tangent(c, t, lo, hi);
  return {-u.y(), u.x()};
}

Vec2 offset_point(const CubicBezier& c, double t, double d, double lo, double hi) {
  return c.eval(t) + d * unit_normal(c, t, lo, hi);
}

std::vector<double> cusp_parameters(const CubicBezier& c) {
  // c'/3 = (A − 2B + C)·t² + 2(B − A)·t + A with the control polygon's legs A, B, C: both
  // coordinates vanish at a cusp; the roots of one are the candidates, checked on the other.
  const Vec2 A = c.p[1] - c.p[0], B = c.p[2] - c.p[1], C = c.p[3] - c.p[2];
  const Vec2 q2 = A - 2 * B + C, q1 = 2 * (B - A);
  const double small = 1e-9 * polygon_length(c);
  std::vector<double> out;
  for (int axis = 0; axis < 2; ++axis) {
    const double a = q2[axis], b = q1[axis], k = A[axis];
    std::vector<double> roots;
    if (std::abs(a) > 1e-14 * polygon_length(c)) {
      const double disc = b * b - 4 * a * k;
      if (disc >= 0) {
        const double s = std::sqrt(disc);
        roots = {(-b - s) / (2 * a), (-b + s) / (2 * a)};
      }
    } else if (b != 0) {
      roots = {-k / b};
    }
    for (double t : roots)
      if (t > 0 && t < 1 && c.derivative(t).norm() <= small) out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end(), [](double x, double y) { return y - x < 1e-9; }), out.end());
  return out;
}

namespace {

// The sample of cusp_sign_value nearest the end `end` of [lo, hi] (towards `inward`) whose sign
// is not lost in rounding: where c' vanishes at the end, c' and c'' turn parallel there and both
// terms vanish faster than their rounding, so the sample steps inwards, 1e-9 of the interval at
// first, ten times farther each time, to a hundredth of it at most.
std::pair<double, double> end_sample(const CubicBezier& c, double d, double end, double inward) {
  double t = end, f = 0;
  for (double margin = 1e-9; margin <= 1e-2 && f == 0; margin *= 10) {
    t = end + margin * inward;
    f = cusp_sign_value(c, t, d);
  }
  return {t, f};
}

// The parameter in (x, y) where cusp_function changes sign, by bisection; fx its value at x.
double sign_change(const CubicBezier& c, double d, double x, double y, double fx) {
  for (int k = 0; k < 60 && y - x > 1e-15; ++k) {
    const double m = (x + y) / 2, fm = cusp_function(c, m, d);
    if ((fm < 0) == (fx < 0))
      x = m, fx = fm;
    else
      y = m;
  }
  return (x + y) / 2;
}

// Where sign·cusp_function is least on [x, y], by golden-section search.
double deepest(const CubicBezier& c, double d, double x, double y, double sign) {
  return golden_minimum([&](double t) { return sign * cusp_function(c, t, d); }, x, y, 40).first;
}

}  // namespace

std::vector<double> offset_cusp_parameters(const CubicBezier& c, double d, double lo, double hi) {
  constexpr int kSamples = 64;
  // The samples whose sign holds, in order.
  std::vector<std::pair<double, double>> samples = {end_sample(c, d, lo, hi - lo)};
  for (int i = 1; i < kSamples; ++i) {
    const double t = lo + (hi - lo) * i / kSamples;
    samples.emplace_back(t, cusp_sign_value(c, t, d));
  }
  samples.push_back(end_sample(c, d, hi, lo - hi));
  std::erase_if(samples, [](const auto& s) { return s.second == 0; });
  std::vector<double> out;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const auto [x, fx] = samples[i - 1];
    const auto [y, fy] = samples[i];
    if ((fx < 0) != (fy < 0)) {
      out.push_back(sign_change(c, d, x, y, fx));
      continue;
    }
    // The same sign at both: a bend tighter than |d| between them shows as a dip of the function
    // through zero, two cusps (a swallowtail) between two samples.
    const double m = deepest(c, d, x, y, fx < 0 ? -1.0 : 1.0);
    const double fm = cusp_sign_value(c, m, d);
    if (fm != 0 && (fm < 0) != (fx < 0)) {
      out.push_back(sign_change(c, d, x, m, fx));
      out.push_back(sign_change(c, d, m, y, fm));
    }
  }
  return out;
}

std::vector<OffsetRun> offset_cubic(const CubicBezier& c, double d, double tolerance) {
  std::vector<OffsetRun> runs;
  if (polygon_length(c) == 0) return runs;
  std::vector<double> ends = cusp_parameters(c);
  ends.insert(ends.begin(), 0.0);
  ends.push_back(1.0);
  for (std::size_t r = 0; r + 1 < ends.size(); ++r) {
    OffsetRun run;
    run.t0 = ends[r], run.t1 = ends[r + 1];
    std::vector<double> cuts = offset_cusp_parameters(c, d, run.t0, run.t1);
    cuts.insert(cuts.begin(), run.t0);
    cuts.push_back(run.t1);
    Fitter fitter(c, d, tolerance, run.t0, run.t1, run);
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double a = cuts[k], b = cuts[k + 1];
      // The direction of travel on (a, b): that of the curve where d·κ < 1, reversed where not.
      const double sign = cusp_function(c, (a + b) / 2, d) < 0 ? -1.0 : 1.0;
      fitter.fit(a, b, sign, false, 0);
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

}  // namespace curvemesh::geometry
