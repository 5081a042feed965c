#pragma once
// Internal to the features stage: the discrete curve sections of §4 and their pieces.
#include <vector>

#include "features/features.hpp"

namespace curvemesh::features::detail {

// One polyline edge of a discrete curve section: the curve over [t0, t1] and its chord a -> b.
struct Piece {
  int section = -1;      // index of its CurveSection
  double t0 = 0, t1 = 1;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  // The directions in which the curve leaves a (into the piece) and leaves b (back into it): its
  // end tangents, which a curved edge follows; the chord's directions for a straight curve.
  Vec2 leave_a = Vec2::Zero(), leave_b = Vec2::Zero();
  bool unfit = false;  // shorter than l_m, curvature above α / l_m, or not resolvable: secondary whatever happens
  double along = 0;         // polyline length of its chain before it
  Kind kind = Kind::primary;
};

// One smooth curve of the drawing: an input curve, or the consecutive input curves one arc was cut
// into (svg::SoupCurve::arc), which only round-off parts. Closed when it ends where it starts (a
// circle, an ellipse).
struct Chain {
  double length = 0;  // of its polyline
  bool closed = false;
};

// A piece of an input curve between inflection / turning split points (or a straight curve).
struct CurveSection {
  int curve = -1;
  int chain = -1;  // index into Discretized::chains
  double t0 = 0, t1 = 1;
  bool straight = false;  // a straight input curve, sampled along the chord p0 -> p3
  Vec2 line_a = Vec2::Zero(), line_b = Vec2::Zero();  // the chord of a straight curve
  int first_piece = 0, piece_count = 0;
  double length = 0;      // polyline length, for the greedy order
};

struct Discretized {
  std::vector<Chain> chains;
  std::vector<CurveSection> sections;
  std::vector<Piece> pieces;
  std::vector<IsolatedPoint> points;
  int degenerate_curves = 0, straight_curves = 0;
};

// §4: degenerate and straight curves, inflection and total-curvature splits, resampling.
Discretized discretize(const svg::FeatureSoup& soup, const Lengths& lengths);

// §4: greedy μ-separation: marks each piece primary or secondary; drops isolated points that
// fall within μ of a primary piece or of an earlier point.
void tag_primary_secondary(Discretized& d, const Lengths& lengths);

// §4: secondary endpoints close to each other collapse (primary vertices stay where they are),
// moving no endpoint more than ε − μ.
std::vector<Segment> simplify_secondary(const Discretized& d, const Lengths& lengths);

}  // namespace curvemesh::features::detail
