#pragma once
// The winding number of a point with respect to a filled shape's closed outline of cubic
// Béziers, counted exactly: the net crossings of the ray from the point towards +x. A piece whose
// control box leaves the point outside crosses it, net, as its ends change sides of the ray's
// line when the box is right of the point, and not at all otherwise; other pieces are split until
// their boxes leave the point outside. The same holds for a run of consecutive pieces with one
// box around all their control points, so a tree of such runs over each loop answers with the
// pieces near the point and O(log n) runs for the rest. No angle, no rounding: only comparisons.
#include <vector>

#include "geometry/bezier.hpp"
#include "svg/feature_soup.hpp"

namespace curvemesh::regions {

struct Winding {
  int number = 0;
  // False when the point lies on the outline to within `resolution`: no number is decided.
  bool decided = true;
  // A lower bound on the point's distance to the outline: at least `wanted`, or at least 4/5 of
  // the distance (never larger than the distance).
  double clearance = 0;
};

// Whether a winding number is inside under a fill rule.
bool inside(int winding, svg::FillRule rule);

// A fill layer's outline with its tree of runs; refers to the layer, which must outlive it.
class Outline {
 public:
  explicit Outline(const svg::FillLayer& layer);

  // `resolution`: control boxes smaller than this that still contain the point count as the
  // point lying on the outline. `wanted`: the clearance that is enough to know (pieces are split
  // only far enough to show it, or to bound the distance within a fifth of it).
  Winding winding(const geometry::Vec2& point, double resolution, double wanted) const;

 private:
  struct Node {
    geometry::Box2 box;  // of the control points of its pieces
    int loop = 0, first = 0, last = 0;  // pieces [first, last) of one loop
    int left = -1, right = -1;          // children (-1 for a single piece)
  };
  int build(int loop, int first, int last);

  const svg::FillLayer& layer_;
  std::vector<Node> nodes_;
  std::vector<int> roots_;  // per loop
};

// The same, for one question (builds the tree).
Winding winding_number(const geometry::Vec2& point, const svg::FillLayer& layer, double resolution, double wanted);

}  // namespace curvemesh::regions
