#pragma once
// The edge of what a stroke paints, when its outline is made of straight segments. A stroke's
// outline (svg/stroke.hpp) is the sum of its segments' bands and its joins' wedges: filled by the
// nonzero rule it paints their union, but as curves it also runs inside that union, wherever two
// bands overlap (a path crossing itself, a closed path's two sides at a tight corner, laps of a
// star). Those inner curves separate nothing the drawing shows; as features they crowd the
// band's own edge within μ, and the edge loses pieces to the separation rule (paper §4). This is
// the union's edge alone: the arrangement of the outline's segments (CGAL, exact), each face's
// winding number from the unbounded face's 0 across the segments between, and the edges with a
// painted face on one side only, chained into loops, collinear edges merged. The loops' corners
// where two segments cross are rounded to the nearest doubles.
#include <optional>
#include <vector>

#include "svg/path_data.hpp"

namespace curvemesh::svg {

// The loops bounding the nonzero fill of `outline` (closed subpaths), each with the painted side
// on its left as x and y go (winding number 1 inside them, 0 outside); `outline` itself when it is
// that edge already (no crossing, nothing inside the painted area: most strokes); nothing when a segment of the outline is not straight within `tolerance` (a curve
// would need its crossings with curves: the outline is kept as it is), or when its segments'
// bounding boxes meet in more than `max_pairs` pairs (its crossings would be too many to be worth
// finding here: the later stages refuse such a drawing by their own limits).
std::optional<std::vector<Subpath>> painted_edge(const std::vector<Subpath>& outline, double tolerance,
                                                 std::size_t max_pairs);

}  // namespace curvemesh::svg
