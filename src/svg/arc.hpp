#pragma once
// Elliptical arcs (SVG 'A' command, and the arcs of <circle>, <ellipse> and rounded <rect>) to
// cubic Béziers within kArcTolerance of the true conic.
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::svg {

// How far (times max(rx, ry)) every cubic the reader makes of an arc may lie from its conic:
// far below any tolerance of the method (ε_m is 1e-8 of the drawing's diagonal), so that a curved
// mesh of a circle is a mesh of the circle, not of its approximation.
inline constexpr double kArcTolerance = 1e-9;

// The largest radial distance between the unit circle and the standard cubic for an arc of angle
// `theta` (radians, |theta| < 2π): ends on the arc, control arms tangent to it of length
// k = 4/3·tan(θ/4). The cubic never runs inside the circle; times max(rx, ry) it bounds the
// distance of the affine image of that cubic from an ellipse.
double arc_cubic_error(double theta);

// The fewest pieces of equal angle into which an arc of `sweep` radians must be cut for each
// piece's cubic to be within kArcTolerance: 9 for a quarter, 33 for a whole turn.
int arc_piece_count(double sweep);

// The arc of the ellipse  centre + R(φ)·(rx·cos a, ry·sin a)  for the parameter a from `start` to
// `end` (either way round), with R(φ) the rotation of cosine `cos_phi` and sine `sin_phi`.
struct EllipticArc {
  geometry::Vec2 centre = geometry::Vec2::Zero();
  double rx = 1, ry = 1;
  double cos_phi = 1, sin_phi = 0;
  double start = 0, end = 0;
};

// Its cubics: arc_piece_count(end − start) pieces of equal parameter angle, from `from` to `to`
// exactly (the points the caller puts the arc's ends at, on the ellipse to round-off), joined
// tangent-continuously without a round-off kink: at every joint the arm into it and the arm out of
// it are the same vector of doubles. At a parameter that is an exact multiple of π/2 (a quarter's
// end, as the shapes make them: q·(π/2) in doubles) the tangent is exactly along an axis of the
// ellipse, so that quarters, and a quarter and a straight side, join parallel as doubles too.
std::vector<geometry::CubicBezier> elliptic_arc_cubics(const EllipticArc& arc, const geometry::Vec2& from,
                                                       const geometry::Vec2& to);

// Converts the SVG endpoint-parametrised arc from `from` to `to` into cubic pieces, as many as
// arc_piece_count asks for its sweep. Out-of-range radii are scaled up as the SVG spec (F.6.6)
// says; zero radii give a straight segment; from == to gives no piece at all. The first piece
// starts exactly at `from`, the last ends exactly at `to`.
std::vector<geometry::CubicBezier> arc_to_cubics(const geometry::Vec2& from, double rx, double ry,
                                                 double x_axis_rotation_deg, bool large_arc, bool sweep,
                                                 const geometry::Vec2& to);

}  // namespace curvemesh::svg
