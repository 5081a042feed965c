#pragma once
// The differential geometry of one cubic that feature processing needs (paper §3.2, §4):
// inflections, turning, the half-turning split, degenerate and straight tests.
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::geometry {

// Parameters in (0, 1) where the curvature changes sign: the simple roots of
// det(c'(t), c''(t)) = 0 (paper eq. 1) with c'(t) ≠ 0, sorted. That determinant is a quadratic
// in t; coefficients below `tolerance_rel` times the squared size of the control polygon count
// as zero, so straight and degenerate curves have none, and no result is ever NaN.
std::vector<double> inflection_parameters(const CubicBezier& c, double tolerance_rel = 1e-12);

// Total turning of the tangent over [t0, t1], in radians: the sum of the absolute angles between
// tangents at 33 evenly spaced parameters (plus the inflections inside). Exact for pieces without
// inflections whose tangent turns less than π between neighbouring samples; a cusp counts π.
// Where c' vanishes the tangent is its limit from inside the interval.
double turning_angle(const CubicBezier& c, double t0 = 0.0, double t1 = 1.0);

// The unit tangent c'(t) / |c'(t)|, for t in [lo, hi]. Where c' vanishes (a cusp, coincident
// control points at an end) the direction is its limit from inside [lo, hi]; (1, 0) for a curve
// that is a point.
Vec2 unit_tangent(const CubicBezier& c, double t, double lo = 0.0, double hi = 1.0);
// The same, for a caller asking many times of one curve: `size` is control_polygon_size(c), what
// c' is measured against (unit_tangent measures it at every call).
Vec2 unit_tangent(const CubicBezier& c, double t, double lo, double hi, double size);
double control_polygon_size(const CubicBezier& c);

// The angle between the unit tangents at t0 and t1 (same limits where c' vanishes). Equal to the
// turning over [t0, t1] when the curve has no inflection there and turns by less than π (a
// section of §4), at the cost of two tangents instead of 33.
double end_tangent_angle(const CubicBezier& c, double t0, double t1);

// True when c has no inflection inside (0, 1) and turns by less than π: then end_tangent_angle
// is its turning on every sub-interval. An inflection within 1e-9 of an end (what rounding leaves
// on a piece split off at an inflection) is ignored when the whole turning and the end-tangent
// angle still agree to 1e-10.
bool turns_monotonically(const CubicBezier& c);

// §4 "Total curvature split": the t in (0, 1) where the tangent is parallel to the average of the
// end tangents (minus the average when the ends turn by more than π), which halves the turning of
// a curve without inflections. 0.5 when the equation gives nothing usable.
double half_turning_parameter(const CubicBezier& c);

// Split parameters in (0, 1), sorted, such that each piece of a curve without inflections turns
// less than `max_turning` (repeated half-turning splits). Empty when it already does.
std::vector<double> split_for_turning(const CubicBezier& c, double max_turning);

// All control points within `eps` of their average (paper §4: removal of degenerate curves).
bool is_degenerate(const CubicBezier& c, double eps);

// The sum of the distances of the control points to their least-squares line is below `eps`
// (paper §4: such curves are replaced by segments).
bool is_straight(const CubicBezier& c, double eps);

}  // namespace curvemesh::geometry
