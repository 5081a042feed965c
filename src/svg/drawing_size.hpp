#pragma once
// The sizes of drawing that can be meshed in double precision, checked where a drawing comes in:
// by the SVG reader (before its degenerate-path pass, which compares lengths with a tolerance
// relative to the drawing's size) and by the pipeline for .poly files and curves given through
// the API.
//
// Measured on the examples (meshed curved and linear, each mesh certified by `curvemesh check`)
// and 20 openclipart drawings (their features), scaled by powers of ten: the features are those
// found at scale 1 from drawings about 1e-105 across (below, a curve's derivative cubed
// underflows, its curvature turns infinite and the curve secondary; near 1e-160 the curved mesh
// is no longer certified, and the degenerate-path pass's squared lengths vanish), up to the
// diagonal's overflow near 1e154 (that cube overflows from about 1e102). The range keeps a margin.
#include <string>

#include "geometry/vec2.hpp"

namespace curvemesh::svg {

inline constexpr double kMinDrawingSize = 1e-100;  // the drawing's diagonal, unless it is 0 (a point)
inline constexpr double kMaxDrawingSize = 1e100;   // its diagonal, and the magnitude of every coordinate

// Why a drawing whose bounding box is `box` cannot be meshed for its size (e.g. "the drawing is
// 1.4e-160 across, smaller than 1e-100: too small to mesh in double precision; scale it up"), or
// "" when it can. The diagonal is found without overflow or underflow at any finite size.
std::string drawing_size_problem(const geometry::Box2& box);

}  // namespace curvemesh::svg
