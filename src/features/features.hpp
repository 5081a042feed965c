#pragma once
// Feature processing (paper §4, first half): from the reader's Bézier soup to primary and
// secondary features. Primary sections are curve pieces the mesh will reproduce with curved
// edges; secondary segments are straight pieces the mesh keeps within ε of the input.
#include <vector>

#include "features/options.hpp"
#include "svg/feature_soup.hpp"

namespace curvemesh::features {

using geometry::Box2;
using geometry::CubicBezier;
using geometry::Vec2;

enum class Kind { primary, secondary };

// A run of consecutive pieces of one input curve with the same kind. Its polyline has a vertex
// per piece boundary; each polyline edge will be one mesh edge, so for primary sections each
// edge's piece is at most l long, within μ of its chord and turns at most α (Theorem 3.4).
struct Section {
  int curve = -1;              // index into the soup's curves
  double t0 = 0, t1 = 1;       // parameter interval on that curve
  CubicBezier piece;           // the curve restricted to [t0, t1]
  Kind kind = Kind::primary;
  // A straight input curve is replaced by its chord (§4): then `piece` and `ts` refer to that
  // line (p0 -> p3 of the input curve, parametrised by arc length), not to the input cubic.
  bool straight = false;
  std::vector<double> ts;      // parameters of the polyline vertices on the soup curve
  std::vector<Vec2> polyline;  // the curve at those parameters (after simplification for secondary)
};

// A secondary straight piece after simplification: what the mesh must keep within ε.
struct Segment {
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
  int curve = -1;          // the input curve it approximates
  double t0 = 0, t1 = 1;   // the interval of that curve it stands for
  // Other input curves whose pieces became this very segment (coincident curves of two shapes),
  // ascending: the mesh's lines along it lie on them too.
  std::vector<int> other_curves;
};

// How far along segment s (0 at a, 1 at b) the point nearest p lies, unclamped.
double fraction_along(const Segment& s, const Vec2& p);

struct IsolatedPoint {
  Vec2 p = Vec2::Zero();
  int source = -1;  // index into the soup's sources
};

struct Features {
  std::vector<Section> sections;
  std::vector<Segment> segments;     // secondary straight pieces, endpoints collapsed
  std::vector<IsolatedPoint> points;
  Box2 box;                          // the input's bounding box (d is its diagonal)
  Lengths lengths;                   // the options in absolute units
  int degenerate_curves = 0;         // curves turned into points
  int straight_curves = 0;           // curves turned into straight segments
};

// The box the drawing is meshed in (its diagonal is d): the soup's bounds, or its canvas (viewBox
// or width/height) when nothing is drawn.
Box2 drawing_box(const svg::FeatureSoup& soup);
// The same for a soup whose curves and points span `bounds`, drawn in `canvas`.
Box2 drawing_box(const Box2& bounds, const Box2& canvas);

// The whole stage, with `lengths` resolved for drawing_box(soup). Deterministic; never fails on
// finite input.
Features process(const svg::FeatureSoup& soup, const Lengths& lengths);

}  // namespace curvemesh::features
