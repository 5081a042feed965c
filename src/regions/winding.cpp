#include "regions/winding.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace curvemesh::regions {

namespace {

using geometry::Box2;
using geometry::CubicBezier;
using geometry::Vec2;

double squared_diagonal(const Box2& b) {
  return (b.max - b.min).squaredNorm();
}

// What a path from a to b inside a box that leaves p outside adds to p's winding number: its
// net crossings of the ray from p towards +x. The ray misses a box above, below or left of p;
// it cuts one right of p from side to side, so the path crosses it as often, net, as its ends
// change sides (y below p's, or not: the same rule at every joint, so ends on the ray count once).
int crossings(const Vec2& p, const Box2& box, const Vec2& a, const Vec2& b) {
  if (!(box.min.x() > p.x())) return 0;  // left of p, above or below it: no crossing
  return int(b.y() >= p.y()) - int(a.y() >= p.y());
}

struct Query {
  Vec2 p;
  double resolution2, wanted2;  // squared
  int winding = 0;
  double clearance2 = std::numeric_limits<double>::infinity();  // squared
  bool decided = true;

  // Whether a box (of a run or a piece) can be taken whole: it leaves p outside, and either far
  // enough, or small beside its distance to p (a quarter of it: the box's gap is then at least
  // 4/5 of p's distance to what is in it), or too small to tell more.
  bool whole(const Box2& box, double gap2, int depth) const {
    if (!(gap2 > 0)) return false;
    const double diagonal2 = squared_diagonal(box);
    return gap2 >= wanted2 || 16 * diagonal2 <= gap2 || diagonal2 <= resolution2 || depth >= 60;
  }

  void piece(const CubicBezier& c, int depth) {
    const Box2 box = c.control_bounds();
    const double gap2 = box.squared_distance(p);  // squared: one square root at the end
    if (whole(box, gap2, depth)) {
      winding += crossings(p, box, c.p[0], c.p[3]);
      clearance2 = std::min(clearance2, gap2);
      return;
    }
    if (gap2 == 0 && (squared_diagonal(box) <= resolution2 || depth >= 60)) {
      decided = false;  // p is on the curve, as far as doubles can tell
      return;
    }
    const auto [first, second] = c.split(0.5);
    piece(first, depth + 1);
    piece(second, depth + 1);
  }
};

}  // namespace

bool inside(int winding, svg::FillRule rule) {
  return rule == svg::FillRule::evenodd ? (winding % 2 != 0) : winding != 0;
}

Outline::Outline(const svg::FillLayer& layer) : layer_(layer) {
  for (int l = 0; l < static_cast<int>(layer.subpaths.size()); ++l)
    roots_.push_back(layer.subpaths[l].empty() ? -1 : build(l, 0, static_cast<int>(layer.subpaths[l].size())));
}

int Outline::build(int loop, int first, int last) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Node n;
  n.loop = loop, n.first = first, n.last = last;
  if (last - first > 1) {
    const int middle = first + (last - first) / 2;
    n.left = build(loop, first, middle);
    n.right = build(loop, middle, last);
    n.box = nodes_[n.left].box;
    n.box.add(nodes_[n.right].box);
  } else {
    n.box = layer_.subpaths[loop][first].control_bounds();
  }
  nodes_[index] = n;
  return index;
}

Winding Outline::winding(const Vec2& point, double resolution, double wanted) const {
  Query q{point, resolution * resolution, wanted * wanted};
  // Depth-first over the runs; a run whose box can be taken whole crosses the ray as a path from
  // its first piece's start to its last piece's end (its pieces are joined end to start). The
  // tree of a loop is balanced: its depth is below 64 for any loop that fits in memory.
  std::array<int, 128> stack;
  for (int root : roots_) {
    if (root < 0) continue;
    int top = 0;
    stack[top++] = root;
    while (top > 0 && q.decided) {
      const Node& n = nodes_[stack[--top]];
      const auto& loop = layer_.subpaths[n.loop];
      const double gap2 = n.box.squared_distance(point);
      if (q.whole(n.box, gap2, 0)) {
        q.winding += crossings(point, n.box, loop[n.first].p[0], loop[n.last - 1].p[3]);
        q.clearance2 = std::min(q.clearance2, gap2);
      } else if (n.left < 0) {
        q.piece(loop[n.first], 0);
      } else {
        stack[top++] = n.right;
        stack[top++] = n.left;
      }
    }
    if (!q.decided) break;
  }
  Winding w;
  w.decided = q.decided;
  w.clearance = !q.decided ? 0 : std::isfinite(q.clearance2) ? std::sqrt(q.clearance2) : wanted;
  w.number = q.decided ? q.winding : 0;
  return w;
}

Winding winding_number(const Vec2& point, const svg::FillLayer& layer, double resolution, double wanted) {
  return Outline(layer).winding(point, resolution, wanted);
}

}  // namespace curvemesh::regions
