#pragma once
// Offset curves of cubics: the points c(t) + d·n(t) at a signed distance d along the unit normal,
// which is not a cubic (its degree is not even finite: n has a square root in its denominator),
// approximated by cubics within a tolerance of it. What a stroke's outline is made of
// (svg/stroke.hpp).
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::geometry {

// The unit normal of c at t: its unit tangent turned by +90° ((x, y) -> (−y, x)). Where c'
// vanishes it is the limit from inside [lo, hi], as unit_tangent's.
Vec2 unit_normal(const CubicBezier& c, double t, double lo = 0.0, double hi = 1.0);

// The exact offset point c(t) + d·n(t) (the normal's limit from inside [lo, hi] where c' vanishes).
Vec2 offset_point(const CubicBezier& c, double t, double d, double lo = 0.0, double hi = 1.0);

// The parameters in (0, 1) where c' vanishes, sorted: cusps of the curve itself, where its normal
// turns over and the offset jumps from one side of the curve to the other.
std::vector<double> cusp_parameters(const CubicBezier& c);

// The parameters in (lo, hi) where the radius of curvature is |d| on the side of the curve d lies
// on (d·κ(t) = 1, κ signed as n turns), sorted: the offset has a cusp there — its speed
// |c'|·|1 − d·κ| vanishes and its direction turns over — and between two of them it runs backwards
// (the swallowtail of an offset where the curve bends tighter than |d|). Found as the sign changes
// of |c'|³ − d·(c' × c'') on 64 samples, and as its dips through zero between two samples of one
// sign (a bend so tight that both cusps of its swallowtail fall between them: the least value
// there by golden-section search), refined by bisection. A sample whose sign is within that
// function's rounding error has none (beside a cusp of c, or where c is straight); the samples
// at the ends step inwards until theirs holds.
std::vector<double> offset_cusp_parameters(const CubicBezier& c, double d, double lo = 0.0, double hi = 1.0);

// One connected piece of an offset: cubics joined end to start exactly, covering the parameters
// [t0, t1] of the curve.
struct OffsetRun {
  std::vector<CubicBezier> pieces;
  // Per piece, whether it continues the one before it tangent-continuously (cut only to stay
  // within the tolerance); not at the first piece nor across a cusp of the offset.
  std::vector<char> smooth;
  double t0 = 0, t1 = 1;
};

// The offset of c at signed distance d: one run, or one more after each cusp of c itself (where
// the exact offset jumps across the curve). Each piece is within `tolerance` of the exact offset
// over its parameter interval — or, where rounding alone moves the offset's points farther (its
// normal beside a cusp of c, where c' is nearly zero; coordinates far larger than the tolerance),
// within a bound of that rounding —, both ways (checked from 15 points of the offset to their closest
// points on the piece, and from 32 points of the piece between those to the offset; cut in two
// until it is, at most 40 times deep); pieces are cut at the offset's cusps, so
// that each fits a curve of constant direction of travel. A curve that is a point has no run.
std::vector<OffsetRun> offset_cubic(const CubicBezier& c, double d, double tolerance);

}  // namespace curvemesh::geometry
