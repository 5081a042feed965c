// Order 2: how far an edge is from its curve, and the splits that keep the primary edges within
// Options::tolerance of it. An order-2 edge on its curve only approximates it (an order-3 one
// reproduces a cubic exactly, §4.2): where it is farther than the tolerance it is split, never
// bent further. Its middle node on the curve at the middle of the parameter interval already
// gives the least distance at equal parameters (the difference is odd about the middle; moving
// the node adds an even term), and halving the interval divides that distance by 8.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/parallel.hpp"
#include "curve/steps.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve {

double quadratic_deviation(const mesh::SectionCurve& curve, double ta, double tb) {
  const auto& p = curve.piece.p;
  const double dx = (tb - ta) / (curve.t1 - curve.t0);  // the edge's share of the piece's parameter
  const Vec2 third = p[3] - 3 * p[2] + 3 * p[1] - p[0];
  // max |s (s − ½)(s − 1)| on [0, 1] is √3 / 36, at s = ½ ± √3 / 6.
  return std::abs(dx * dx * dx) * third.norm() * (std::sqrt(3.0) / 36);
}

namespace {

// The polynomial through nodes[0] at s = 0, nodes[1] at s = 1 and the inner nodes at k / order
// (Gmsh's line order), at s.
Vec2 line_point(const std::vector<Vec2>& nodes, double s) {
  const int order = static_cast<int>(nodes.size()) - 1;
  const auto at = [&](int i) { return i == 0 ? 0.0 : i == order ? 1.0 : double(i) / order; };
  const auto node = [&](int i) -> const Vec2& {
    return i == 0 ? nodes[0] : i == order ? nodes[1] : nodes[i + 1];
  };
  Vec2 x = Vec2::Zero();
  for (int i = 0; i <= order; ++i) {
    double w = 1;
    for (int j = 0; j <= order; ++j)
      if (j != i) w *= (s - at(j)) / (at(i) - at(j));
    x += w * node(i);
  }
  return x;
}

// The distance from q to the curve near parameter t: Newton's method on (c(t) − q)·c'(t) = 0,
// within the section, four steps; the smallest distance met.
double distance_near(const mesh::SectionCurve& curve, const Vec2& q, double t) {
  const double lo = std::min(curve.t0, curve.t1), hi = std::max(curve.t0, curve.t1);
  double best = (curve.eval(t) - q).norm();
  for (int step = 0; step < 4; ++step) {
    const Vec2 r = curve.eval(t) - q, d1 = curve.derivative(t), d2 = curve.second_derivative(t);
    const double slope = d1.squaredNorm() + r.dot(d2);
    if (!(slope > 0)) break;
    t = std::clamp(t - r.dot(d1) / slope, lo, hi);
    best = std::min(best, (curve.eval(t) - q).norm());
  }
  return best;
}

}  // namespace

double edge_distance(const std::vector<Vec2>& nodes, const mesh::SectionCurve& curve, double ta, double tb) {
  double worst = 0;
  for (int i = 0; i <= 32; ++i) {
    const double s = i / 32.0;
    worst = std::max(worst, distance_near(curve, line_point(nodes, s), ta + s * (tb - ta)));
  }
  return worst;
}

namespace {

// The largest of distance(i) for i in [0, n): each measured on its own, side by side (the largest
// of a set does not depend on the order it is taken in).
template <class Distance>
double largest(std::size_t n, const Distance& distance) {
  std::vector<double> d(n, 0.0);
  base::for_each_part(n, [&](std::size_t i) { d[i] = distance(i); });
  double worst = 0;
  for (double x : d) worst = std::max(worst, x);
  return worst;
}

}  // namespace

double max_edge_distance(const mesh::TriMesh& m, const mesh::Constraints& c) {
  auto features = m.sorted_features();
  std::erase_if(features, [](const auto& e) { return e.second.kind != mesh::EdgeKind::primary; });
  return largest(features.size(), [&](std::size_t i) {
    const auto& [edge, f] = features[i];
    const bool up = edge[0] < edge[1];
    return edge_distance({m.point(edge[0]), m.point(edge[1])}, c.sections[f.source], up ? f.t_lo : f.t_hi,
                         up ? f.t_hi : f.t_lo);
  });
}

double max_edge_distance(const CurvedMesh& cm, const mesh::Constraints& c) {
  return largest(cm.lines.size(), [&](std::size_t i) {
    const FeatureLine& line = cm.lines[i];
    if (line.kind != mesh::EdgeKind::primary) return 0.0;
    const int a = line.nodes[0], b = line.nodes[1];
    const mesh::EdgeFeature& f = *cm.linear.feature(a, b);
    std::vector<Vec2> nodes;
    for (int k = 0; k <= cm.order; ++k) nodes.push_back(cm.nodes[line.nodes[k]]);
    return edge_distance(nodes, c.sections[f.source], a < b ? f.t_lo : f.t_hi, a < b ? f.t_hi : f.t_lo);
  });
}

namespace detail {

// As step 1 splits (mesh::split_edge at the middle of the parameter interval), on the linear
// mesh before any node is placed: an edge halved is 8 times nearer its curve (quadratic_deviation
// goes with the cube of the interval), so the rounds end quickly; an edge no longer than
// min_split_length stays as it is, and so does one whose middle point on the curve would invert
// a triangle (split_edge would leave the new vertex on the chord, off its curve: two edges that
// cannot follow it instead of one).
int split_beyond_tolerance(TriMesh& m, const mesh::Constraints& c, const Options& o) {
  if (!(o.tolerance > 0)) return 0;
  const double shortest = o.min_split_length * o.min_split_length;
  int splits = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [edge, f] : m.sorted_features()) {
      const int a = edge[0], b = edge[1];
      if (f.kind != EdgeKind::primary || !followable(m, a, b) ||
          (m.point(a) - m.point(b)).squaredNorm() <= shortest)
        continue;
      if (quadratic_deviation(c.sections[f.source], f.t_lo, f.t_hi) <= o.tolerance) continue;
      m.open_journal();
      const int mid = mesh::split_edge(m, c, a, b, std::numeric_limits<double>::infinity());
      if (mid < 0 || !m.tag(mid).on_curve) {
        m.rollback();
        continue;
      }
      m.commit();
      ++splits, changed = true;
    }
  }
  return splits;
}

namespace {

// quadratic_deviation of the edge if it follows its curve (or will: followable), else 0.
double curved_deviation(const Curving& cv, int a, int b) {
  if (!cv.form.quadratic() || !followable(cv.mesh, a, b)) return 0;
  const mesh::EdgeFeature& f = *cv.mesh.feature(a, b);
  return quadratic_deviation(cv.constraints.sections[f.source], f.t_lo, f.t_hi);
}

}  // namespace

bool beyond_tolerance_if_curved(const Curving& cv, int a, int b) {
  return cv.form.quadratic() && cv.options.tolerance > 0 && curved_deviation(cv, a, b) > cv.options.tolerance;
}

double deviation(const Curving& cv, int a, int b) {
  const mesh::EdgeFeature& f = *cv.mesh.feature(a, b);
  if (cv.form.follows(a, b)) return curved_deviation(cv, a, b);
  const auto [first, second] = cv.form.edge_nodes(a, b);
  std::vector<Vec2> nodes{cv.form.at(a), cv.form.at(b), cv.form.node(first)};
  if (!cv.form.quadratic()) nodes.push_back(cv.form.node(second));
  return edge_distance(nodes, cv.constraints.sections[f.source], a < b ? f.t_lo : f.t_hi,
                       a < b ? f.t_hi : f.t_lo);
}

// Rounds over the primary edges with both ends on their curve that are still beyond the
// tolerance (a late projection, a fit, an edge left straight), farthest first: each is split on
// its curve by step 4's split (try_operation), kept when every triangle it changes is certified,
// whatever their energy — the tolerance comes before quality, and step 4 runs again after. Edges
// no longer than min_split_length, and edges with an end off its curve (splitting leaves that end
// where it is), are left; the statistics count them.
int meet_tolerance(Curving& cv) {
  const Options& o = cv.options;
  if (!cv.form.quadratic() || !(o.tolerance > 0)) return 0;
  TriMesh& m = cv.mesh;
  const double shortest = o.min_split_length * o.min_split_length;
  int made = 0;
  for (int round = 0; round < 64; ++round) {
    std::vector<std::pair<double, std::array<int, 2>>> beyond;
    for (const auto& [edge, f] : m.sorted_features())
      if (f.kind == EdgeKind::primary && followable(m, edge[0], edge[1]) &&
          (cv.form.at(edge[0]) - cv.form.at(edge[1])).squaredNorm() > shortest)
        if (const double d = deviation(cv, edge[0], edge[1]); d > o.tolerance) beyond.push_back({-d, edge});
    std::stable_sort(beyond.begin(), beyond.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    int round_made = 0;
    for (const auto& candidate : beyond) {
      const int a = candidate.second[0], b = candidate.second[1];
      if (!is_primary(m, a, b) || deviation(cv, a, b) <= o.tolerance)
        continue;  // changed by an earlier split
      round_made += split_certified(cv, a, b);
    }
    made += round_made;
    if (round_made == 0) break;
  }
  cv.stats.tolerance_splits += made;
  return made;
}

}  // namespace detail
}  // namespace curvemesh::curve
