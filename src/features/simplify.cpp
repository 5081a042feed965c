// §4 "Secondary feature simplification": secondary endpoints closer than μ collapse, which
// removes most of the slivers a drawing's near-misses would otherwise force into the mesh.
//
// To keep every secondary segment within ε of its input, where resampling already spent μ (the
// chord's distance to the curve), no endpoint moves farther than ε − μ (= μ by default): an
// endpoint within ε − μ of a primary vertex snaps to that vertex (primary features never move);
// the others are clustered greedily, each cluster holding the endpoints within (ε − μ)/2 of its
// first member, and collapse at the cluster's barycentre.
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

#include "base/limits.hpp"
#include "features/pieces.hpp"

namespace curvemesh::features::detail {

namespace {

// A uniform grid over points, for neighbourhood queries at one radius.
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell > 0 ? cell : 1.0) {}
  void insert(const Vec2& p, int id) { cells_[key(cell_of(p.x()), cell_of(p.y()))].push_back(id); }
  template <class F>
  void near(const Vec2& p, F&& visit) const {
    const long long cx = cell_of(p.x()), cy = cell_of(p.y());
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        if (const auto it = cells_.find(key(cx + dx, cy + dy)); it != cells_.end())
          for (const int id : it->second) visit(id);
  }
  // near() over the ids for which gone(id) is false, dropping the others from the grid for good:
  // a cluster's ends, once placed, are not visited again by each of its later neighbours.
  template <class Gone, class F>
  void near_pruning(const Vec2& p, Gone&& gone, F&& visit) {
    const long long cx = cell_of(p.x()), cy = cell_of(p.y());
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        if (const auto it = cells_.find(key(cx + dx, cy + dy)); it != cells_.end()) {
          std::erase_if(it->second, gone);
          for (const int id : it->second) visit(id);
        }
  }

 private:
  long long cell_of(double v) const { return static_cast<long long>(std::floor(v / cell_)); }
  static long long key(long long x, long long y) { return x * 73856093LL ^ y * 19349663LL; }
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;  // never iterated: order is irrelevant
};

struct Vec2Less {
  bool operator()(const Vec2& a, const Vec2& b) const { return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y(); }
};

struct SegmentLess {
  bool operator()(const std::pair<Vec2, Vec2>& x, const std::pair<Vec2, Vec2>& y) const {
    const Vec2Less less;
    if (x.first != y.first) return less(x.first, y.first);
    return less(x.second, y.second);
  }
};

// Where each secondary end goes (`ends` unique): to the nearest primary vertex within ε − μ, else
// to the barycentre of its greedy cluster of radius (ε − μ)/2 (paper §4: secondary curves only
// need to stay within ε, so their nearly coincident ends are merged).
std::vector<Vec2> end_targets(const std::vector<Vec2>& ends, const Discretized& d, const Lengths& len) {
  const double budget = std::max(0.0, len.epsilon - len.mu);  // how far an endpoint may move
  // None (ε ≤ μ): every end stays, and a grid of cells of no size would hold every end in one.
  if (budget <= 0) return ends;

  // Primary vertices are fixed: snap to them first.
  PointGrid primary_grid(budget);
  std::vector<Vec2> primary_vertices;
  for (const Piece& p : d.pieces)
    if (p.kind == Kind::primary)
      for (const Vec2& v : {p.a, p.b}) {
        primary_grid.insert(v, static_cast<int>(primary_vertices.size()));
        primary_vertices.push_back(v);
      }
  std::vector<Vec2> target(ends.size());
  std::vector<char> placed(ends.size(), 0);
  std::size_t visits = 0;  // ends close together: a pile of coincident curves makes it quadratic
  const auto count = [&] { base::check_pairs(++visits, len.max_triangles, 8, "curve ends within epsilon of each other"); };
  for (std::size_t k = 0; k < ends.size(); ++k) {
    double best = budget;
    int best_id = -1;
    primary_grid.near(ends[k], [&](int id) {
      count();
      const double dist = (primary_vertices[id] - ends[k]).norm();
      if (dist <= best && (best_id < 0 || dist < best || id < best_id)) best = dist, best_id = id;
    });
    if (best_id >= 0) target[k] = primary_vertices[best_id], placed[k] = 1;
  }

  // Greedy clusters of radius budget/2 among the rest, collapsed at their barycentre.
  PointGrid grid(0.5 * budget);
  for (std::size_t k = 0; k < ends.size(); ++k)
    if (!placed[k]) grid.insert(ends[k], static_cast<int>(k));
  for (std::size_t k = 0; k < ends.size(); ++k) {
    if (placed[k]) continue;
    std::vector<int> members;
    grid.near_pruning(
        ends[k], [&](int id) { return placed[id] != 0; },
        [&](int id) {
          count();
          if ((ends[id] - ends[k]).norm() <= 0.5 * budget) members.push_back(id);
        });
    std::sort(members.begin(), members.end());
    Vec2 sum = Vec2::Zero();
    for (const int m : members) sum += ends[m];
    const Vec2 centre = sum / double(members.size());
    for (const int m : members) target[m] = centre, placed[m] = 1;
  }
  return target;
}

}  // namespace

std::vector<Segment> simplify_secondary(const Discretized& d, const Lengths& len) {
  // Unique secondary endpoints, in first-seen order.
  std::map<Vec2, int, Vec2Less> ids;
  std::vector<Vec2> ends;
  auto id_of = [&](const Vec2& p) {
    const auto [it, inserted] = ids.emplace(p, static_cast<int>(ends.size()));
    if (inserted) ends.push_back(p);
    return it->second;
  };
  std::vector<std::pair<int, int>> secondary;  // endpoint ids per secondary piece
  std::vector<int> piece_of;
  for (int i = 0; i < static_cast<int>(d.pieces.size()); ++i) {
    const Piece& p = d.pieces[i];
    if (p.kind != Kind::secondary) continue;
    secondary.emplace_back(id_of(p.a), id_of(p.b));
    piece_of.push_back(i);
  }
  if (secondary.empty()) return {};
  const std::vector<Vec2> target = end_targets(ends, d, len);

  std::vector<Segment> out;
  std::map<std::pair<Vec2, Vec2>, int, SegmentLess> seen;  // -> index in out
  for (std::size_t s = 0; s < secondary.size(); ++s) {
    Vec2 a = target[secondary[s].first], b = target[secondary[s].second];
    if (a == b) continue;  // collapsed away
    const Vec2 lo = Vec2Less()(a, b) ? a : b, hi = Vec2Less()(a, b) ? b : a;
    const Piece& p = d.pieces[piece_of[s]];
    const int curve = d.sections[p.section].curve;
    const auto [it, inserted] = seen.emplace(std::pair{lo, hi}, static_cast<int>(out.size()));
    if (!inserted) {
      // The same segment twice: kept once, standing for both curves.
      Segment& kept = out[it->second];
      auto& others = kept.other_curves;
      if (curve != kept.curve && !std::binary_search(others.begin(), others.end(), curve))
        others.insert(std::upper_bound(others.begin(), others.end(), curve), curve);
      continue;
    }
    out.push_back({a, b, curve, p.t0, p.t1, {}});
  }
  return out;
}

}  // namespace curvemesh::features::detail
