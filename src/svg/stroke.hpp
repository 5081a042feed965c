#pragma once
// A stroke as the area it paints (SVG 2 §13.5, "Stroke shape"): the outline of the band a line
// of the stroke's width sweeps along each subpath, with its joins, caps and dashes, as closed
// subpaths whose nonzero fill is that area. The band's sides are offset curves of the path's
// cubics (geometry/offset.hpp); round joins and caps are circular arcs made as the reader's
// circles are (svg/arc.hpp).
#include <cstdint>
#include <string_view>
#include <vector>

#include "svg/path_data.hpp"

namespace curvemesh::svg {

// How far (times the stroke's width) each offset cubic of an outline may lie from the exact
// offset of the path: within the features stage's round-off ε_m (1e-8 of the drawing's diagonal)
// for any stroke no wider than the drawing.
inline constexpr double kStrokeTolerance = 1e-8;

enum class LineJoin : std::uint8_t { miter, round, bevel };
enum class LineCap : std::uint8_t { butt, round, square };

// The stroke properties (SVG 2 §13.5.1–13.5.5 and `vector-effect`), with their initial values.
// Lengths in the element's user units.
struct StrokeStyle {
  double width = 1;
  LineJoin join = LineJoin::miter;
  LineCap cap = LineCap::butt;
  double miter_limit = 4;
  std::vector<double> dashes;  // as given (an odd count is repeated when dashing); empty: solid
  double dash_offset = 0;
  bool non_scaling = false;  // vector-effect: non-scaling-stroke (not inherited)
};

// Reads one declaration into `style` when `name` is a property of StrokeStyle (then true; a value
// it cannot read leaves the property as it was, as CSS drops an invalid declaration). A
// percentage is of `percent_base` (SVG: the viewport's diagonal over √2).
bool apply_stroke_declaration(std::string_view name, std::string_view value, double percent_base,
                              StrokeStyle& style);

// The dashes of `subpaths` (SVG 2 §13.5.6): each subpath cut by arc length into the "on" pieces of
// the pattern (repeated twice when of odd count), shifted by `offset`, restarting at each
// subpath; of a closed subpath the last dash and the first make one when they meet at its start.
// A pattern with a negative entry or none positive draws the subpaths solid (returned as they are).
// A dash of no length is a subpath without a segment.
std::vector<Subpath> dash_subpaths(const std::vector<Subpath>& subpaths, const std::vector<double>& dashes,
                                   double offset);

// The outline of the stroke of `subpaths` (dashed first when style.dashes asks) at style.width:
// closed subpaths whose nonzero fill is the stroke. An open subpath gives one loop — the left side
// forward, the end cap, the right side back, the start cap; a closed one two, its two sides, with
// joins all round and no caps. At a corner the outer side gets the join (a miter beyond
// style.miter_limit is bevelled, as SVG says) and the inner side runs to the corner point and back,
// so that the loop is the sum of each segment's band and each join's wedge (or straight across,
// where that adds only a triangle inside both bands); where both inner sides are straight and cross
// inside both, they end where they meet, the painted area's own inner corner. A cusp of a curve
// (where it turns back on itself) is joined as a corner of 180°. A closed path bending tighter than
// the half width towards one side all round keeps only its other side's loop (the inside is all
// painted). A subpath of no length paints a dot
// for round and square caps (an axis-aligned square: it has no direction). Each offset cubic is
// within kStrokeTolerance·width of the exact offset.
std::vector<Subpath> stroke_outline(const std::vector<Subpath>& subpaths, const StrokeStyle& style);

}  // namespace curvemesh::svg
