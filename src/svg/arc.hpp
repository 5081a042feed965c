#pragma once
// Elliptical arcs (SVG 'A' command) to cubic Béziers.
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::svg {

// Converts the SVG endpoint-parametrised arc from `from` to `to` into cubic pieces, each
// spanning at most 90° of the ellipse's parameter. Out-of-range radii are scaled up as the SVG
// spec (F.6.6) says; zero radii give a straight segment; from == to gives no piece at all.
// Error bound: each piece deviates from the true ellipse by at most 2.8e-4 · max(rx, ry)
// (the classic 4/3·tan(θ/4) construction for θ ≤ 90°).
std::vector<geometry::CubicBezier> arc_to_cubics(const geometry::Vec2& from, double rx, double ry,
                                                 double x_axis_rotation_deg, bool large_arc, bool sweep,
                                                 const geometry::Vec2& to);

}  // namespace curvemesh::svg
