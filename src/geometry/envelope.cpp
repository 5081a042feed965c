#include "geometry/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace curvemesh::geometry {

namespace {

constexpr double kUnit = std::numeric_limits<double>::epsilon() / 2;  // u = 2⁻⁵³
constexpr std::size_t kMaxCells = std::size_t{1} << 22;
constexpr int kMaxDepth = 24;

// Distance from p to segment ab, evaluated as |p - (a + t (b - a))| for a clamped t. Whatever t
// rounding produced, a + t (b - a) is (in exact arithmetic) a point of the segment, so the true
// distance is at most the exact value of this expression; its floating-point evaluation is off
// by at most a few units of the coordinates' magnitude M (bounded in the constructor).
double distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0 ? (p - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

}  // namespace

SegmentEnvelope::SegmentEnvelope(std::vector<std::array<Vec2, 2>> segments, double epsilon, std::vector<int> groups)
    : segments_(std::move(segments)), groups_(std::move(groups)), epsilon_(epsilon) {
  if (!groups_.empty() && groups_.size() != segments_.size())
    throw std::invalid_argument("SegmentEnvelope: one group per segment");
  if (segments_.empty() || !(epsilon_ > 0)) return;
  Box2 box;
  for (const auto& s : segments_) {
    box.add(s[0]);
    box.add(s[1]);
  }
  // Rounding bound, with M the largest coordinate magnitude: each coordinate of
  // p - (a + t (b - a)) is computed with absolute error at most 4 u M (one product, three sums of
  // numbers at most 2M in size), so the distance is off by at most 8 u M plus a relative 2u.
  // Bisection midpoints are rounded too: each level moves a piece's end by at most u M off the
  // query segment, so after kMaxDepth levels the pieces are within 24 u M of it. Shrinking ε by
  // 64 u M and a relative 1e-9 covers both with room to spare.
  const double m = std::max({std::abs(box.min.x()), std::abs(box.min.y()), std::abs(box.max.x()),
                             std::abs(box.max.y()), epsilon_});
  accept_ = epsilon_ * (1 - 1e-9) - 64 * kUnit * m;
  // A point farther than reject_ from a segment's bounding box in x or in y is farther than
  // accept_ from the segment in `distance` too: the margin, 1e-9 M, is far above the rounding of
  // `distance` (a few u M, as above).
  reject_ = accept_ + 1e-9 * m;
  min_piece_ = epsilon_ / 64;

  // Cells about as many as segments (at least ε wide), capped.
  origin_ = box.min - Vec2(epsilon_, epsilon_);
  const double w = box.width() + 2 * epsilon_, h = box.height() + 2 * epsilon_;
  cell_ = std::max({epsilon_, std::sqrt(w * h / double(2 * segments_.size() + 1)), std::max(w, h) / 4096});
  while (true) {
    nx_ = std::max(1, static_cast<int>(std::ceil(w / cell_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(h / cell_)));
    if (std::size_t(nx_) * std::size_t(ny_) <= kMaxCells) break;
    cell_ *= 1.5;
  }

  // Register each segment in the cells its ε-neighbourhood meets: row by row, the x-range of the
  // segment clipped to the row's y-range grown by ε, then grown by ε.
  const auto for_each_cell = [&](const std::array<Vec2, 2>& s, auto&& visit) {
    const Vec2 &a = s[0], &b = s[1];
    const int j0 = std::clamp(int(std::floor((std::min(a.y(), b.y()) - epsilon_ - origin_.y()) / cell_)), 0, ny_ - 1);
    const int j1 = std::clamp(int(std::floor((std::max(a.y(), b.y()) + epsilon_ - origin_.y()) / cell_)), 0, ny_ - 1);
    for (int j = j0; j <= j1; ++j) {
      const double y0 = origin_.y() + j * cell_ - epsilon_, y1 = origin_.y() + (j + 1) * cell_ + epsilon_;
      double t0 = 0, t1 = 1;
      const double dy = b.y() - a.y();
      if (dy != 0) {
        double ta = (y0 - a.y()) / dy, tb = (y1 - a.y()) / dy;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      if (t0 > t1) {  // rounding at the row's edge: take the whole segment's range, to be safe
        t0 = 0;
        t1 = 1;
      }
      const double xa = a.x() + t0 * (b.x() - a.x()), xb = a.x() + t1 * (b.x() - a.x());
      const int i0 = std::clamp(int(std::floor((std::min(xa, xb) - epsilon_ - origin_.x()) / cell_)) - 1, 0, nx_ - 1);
      const int i1 = std::clamp(int(std::floor((std::max(xa, xb) + epsilon_ - origin_.x()) / cell_)) + 1, 0, nx_ - 1);
      for (int i = i0; i <= i1; ++i) visit(j * nx_ + i);
    }
  };
  start_.assign(std::size_t(nx_) * ny_ + 1, 0);
  for (const auto& s : segments_) for_each_cell(s, [&](int c) { ++start_[c + 1]; });
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  items_.resize(start_.back());
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int k = 0; k < int(segments_.size()); ++k) for_each_cell(segments_[k], [&](int c) { items_[fill[c]++] = k; });
}

int SegmentEnvelope::cell_of(const Vec2& p) const {
  if (nx_ == 0) return -1;
  const double fx = (p.x() - origin_.x()) / cell_, fy = (p.y() - origin_.y()) / cell_;
  if (!(fx >= 0 && fy >= 0 && fx < nx_ && fy < ny_)) return -1;
  return int(fy) * nx_ + int(fx);
}

bool SegmentEnvelope::contains(const Vec2& p, int group) const { return one_capsule(p, p, group); }

bool SegmentEnvelope::one_capsule(const Vec2& p, const Vec2& q, int group) const {
  if (accept_ <= 0) return false;
  const int c = cell_of(p);
  if (c < 0) return false;  // farther than ε from every segment
  // The bounding boxes first: most segments of a cell are not near both points, and a few
  // comparisons spare two divisions and square roots.
  const auto far = [&](const Vec2& x, const std::array<Vec2, 2>& s) {
    for (int i = 0; i < 2; ++i)
      if (std::min(s[0][i], s[1][i]) - x[i] > reject_ || x[i] - std::max(s[0][i], s[1][i]) > reject_) return true;
    return false;
  };
  for (int k = start_[c]; k < start_[c + 1]; ++k) {
    if (group != kAny && (groups_.empty() ? kAny : groups_[items_[k]]) != group) continue;
    const auto& s = segments_[items_[k]];
    if (far(p, s) || far(q, s)) continue;
    if (distance(p, s[0], s[1]) <= accept_ && distance(q, s[0], s[1]) <= accept_) return true;
  }
  return false;
}

bool SegmentEnvelope::covered(const Vec2& p, const Vec2& q, int group, int depth) const {
  return one_capsule(p, q, group) || halves_covered(p, q, group, depth);
}

bool SegmentEnvelope::halves_covered(const Vec2& p, const Vec2& q, int group, int depth) const {
  if (depth >= kMaxDepth || (q - p).norm() < min_piece_) return false;
  const Vec2 m = 0.5 * (p + q);
  if (!contains(m, group)) return false;
  return covered(p, m, group, depth + 1) && covered(m, q, group, depth + 1);
}

bool SegmentEnvelope::contains(const Vec2& p, const Vec2& q, int group) const {
  // One segment near both ends covers pq, ends included: most queries end there, with one scan
  // of a cell instead of three.
  if (one_capsule(p, q, group)) return true;
  if (!contains(p, group) || !contains(q, group)) return false;
  return halves_covered(p, q, group, 0);
}

}  // namespace curvemesh::geometry
