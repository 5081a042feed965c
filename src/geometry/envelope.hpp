#pragma once
// The ε-envelope of the secondary input segments (TriWild §4.1, invariant 1 of TetWild): every
// secondary mesh edge must stay within distance ε of the input it stands for. Each segment may
// carry a group (the curve it approximates); a query for one group is answered by that group's
// segments alone, so that an edge standing for one curve cannot wander onto another curve's
// envelope where the two come within ε, and leave its own input behind.
//
// `contains` is certified conservative: it may reject a segment that is inside, never accept one
// that is not. Each accepted piece of a query segment has both ends within ε of one and the same
// input segment; the ε-neighbourhood of a segment (a capsule) is convex, so the whole piece is
// inside it. Pieces are found by bisection, never by sampling alone. Distances are compared
// against ε shrunk by a bound on their floating-point error (see envelope.cpp).
#include <array>
#include <cstddef>
#include <vector>

#include "geometry/vec2.hpp"

namespace curvemesh::geometry {

class SegmentEnvelope {
 public:
  SegmentEnvelope() = default;  // empty: contains nothing
  // groups: per segment, its group (−1: none); empty: every segment in none.
  SegmentEnvelope(std::vector<std::array<Vec2, 2>> segments, double epsilon, std::vector<int> groups = {});

  // Within ε of the union of the segments of `group`, or of all of them for group −1.
  bool contains(const Vec2& p, int group = kAny) const;                 // p
  bool contains(const Vec2& p, const Vec2& q, int group = kAny) const;  // every point of pq
  static constexpr int kAny = -1;
  double epsilon() const { return epsilon_; }
  std::size_t size() const { return segments_.size(); }

 private:
  // Whether p and q are both within the accepted distance of one segment in p's cell.
  bool one_capsule(const Vec2& p, const Vec2& q, int group) const;
  bool covered(const Vec2& p, const Vec2& q, int group, int depth) const;         // one capsule, or both halves
  bool halves_covered(const Vec2& p, const Vec2& q, int group, int depth) const;  // both halves, bisecting
  int cell_of(const Vec2& p) const;  // -1 outside the grid

  std::vector<std::array<Vec2, 2>> segments_;
  std::vector<int> groups_;  // per segment (empty: all −1)
  double epsilon_ = 0;
  double accept_ = -1;  // ε less the rounding error bound; nothing is accepted when negative
  double reject_ = -1;  // beyond it from a segment's bounding box, beyond accept_ from the segment
  double min_piece_ = 0;
  // A uniform grid over the segments' box grown by ε; each cell lists every segment that comes
  // within ε of it (compressed rows: cell c's segments are items_[start_[c] .. start_[c + 1])).
  Vec2 origin_ = Vec2::Zero();
  double cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> start_, items_;
};

}  // namespace curvemesh::geometry
