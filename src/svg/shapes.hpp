#pragma once
// The basic shapes of SVG 1.1 §9 as subpaths of cubic Béziers, in the element's coordinates.
#include <string_view>
#include <vector>

#include "svg/path_data.hpp"

namespace curvemesh::svg {

// Arcs (the corners of a rounded rect, ellipses) are cubics within kArcTolerance (svg/arc.hpp) of
// the conic, nine per quarter, passing exactly through the points where a quarter meets a side or
// the next quarter.
//
// A rectangle with corner radii (already defaulted per §9.2); nothing when width or height ≤ 0.
std::vector<Subpath> rect_subpaths(double x, double y, double width, double height, double rx, double ry);
// An ellipse as four quarters starting at (cx + rx, cy); nothing when a radius ≤ 0.
std::vector<Subpath> ellipse_subpaths(double cx, double cy, double rx, double ry);
// A points list; a trailing odd coordinate is dropped and reported through `odd_count`.
// Throws SyntaxError on a malformed number, and TooManyPieces (path_data.hpp) as soon as the
// points make more than `max_pieces` segments.
std::vector<Subpath> polyline_subpaths(std::string_view points, bool closed, bool* odd_count,
                                       std::size_t max_pieces = std::numeric_limits<std::size_t>::max());

}  // namespace curvemesh::svg
