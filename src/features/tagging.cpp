// §4 "Primary and secondary feature tagging": a greedy, discrete μ-separation. Candidate pairs
// come from CGAL's box intersection (boxes grown by μ/2), so the cost is O(n log² n + k), not
// quadratic.
//
// The rule (Definition 3.1 made discrete): two primary pieces are at least μ apart, except
//  - pieces of one input curve (or of one arc, which the reader cut into several cubics) joined
//    by at most π/2·μ of its polyline (consecutive pieces, and the pieces of a bend tighter than
//    μ: one connected component in the μ-ball), unless the curve folds back between them (a
//    cusp sharper than the junction angle, or the two pieces pointing in opposite directions),
//  - pieces that share an endpoint exactly (a path's corners, shapes that touch at a vertex)
//    and meet there at an angle of at least the junction angle (default α = 10°), so that a
//    triangle with minimal angle α fits between them. Both their chords and their curves (the
//    end tangents, along which curved edges leave the point) must meet at that angle, and
//  - with strokes as areas (Lengths::straight_crossings), pieces of two straight sections that
//    cross each other at the junction angle or more: the same X as two pairs of pieces sharing
//    the crossing as an endpoint. A stroke's band has two sides, so the bands of two crossing
//    strokes cross four times, within a width of one another; a piece left secondary there is
//    followed only within ε, about that width, and the painted area loses or gains the band.
//    Not where another such crossing is within μ (three lines through nearly one point), nor
//    within μ of an end of either piece (a straight curve's even cuts into pieces can fall on a
//    crossing): the edges between them would be far shorter than μ.
// Pieces are visited by decreasing length of their curve section (long features first), then
// along the section; a piece in conflict with an already primary piece becomes secondary.
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "base/limits.hpp"
#include "base/parallel.hpp"
#include "features/pieces.hpp"
#include "geometry/vec2.hpp"

namespace curvemesh::features::detail {

namespace {

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int>;

Box box_of(const Vec2& a, const Vec2& b, double grow, int index) {
  double lo[2] = {std::min(a.x(), b.x()) - grow, std::min(a.y(), b.y()) - grow};
  double hi[2] = {std::max(a.x(), b.x()) + grow, std::max(a.y(), b.y()) + grow};
  return Box(lo, hi, index);
}

using geometry::cross;

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

// A tolerance test, not a topological decision: doubles are enough here.
double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({point_segment_distance(a, c, d), point_segment_distance(b, c, d),
                   point_segment_distance(c, a, b), point_segment_distance(d, a, b)});
}

double angle_between(const Vec2& u, const Vec2& v) {
  return std::atan2(std::abs(cross(u, v)), u.dot(v));
}

// Where two straight sections cross, each passing strictly through the other at least μ from its
// ends, at an angle of at least the junction angle; nothing otherwise. Near the crossing their
// pieces come within μ of one another, but what lies in a μ-ball there is one connected
// component, an X whose four wedges are at least that angle (Definition 3.1, as at a shared
// endpoint), and away from it two lines only diverge.
std::optional<Vec2> straight_crossing(const CurveSection& s, const CurveSection& t, const Lengths& len) {
  if (!s.straight || !t.straight) return std::nullopt;
  const Vec2 u = s.line_b - s.line_a, v = t.line_b - t.line_a;
  const double a = cross(u, t.line_a - s.line_a), b = cross(u, t.line_b - s.line_a);
  const double c = cross(v, s.line_a - t.line_a), e = cross(v, s.line_b - t.line_a);
  if (!(((a > 0 && b < 0) || (a < 0 && b > 0)) && ((c > 0 && e < 0) || (c < 0 && e > 0)))) return std::nullopt;
  // At least μ from every end: a line stopping just past another leaves a stub shorter than μ
  // that no edge of the mesh could be.
  const double along_t = a / (a - b) * v.norm(), along_s = c / (c - e) * u.norm();
  if (std::min({along_t, v.norm() - along_t, along_s, u.norm() - along_s}) < len.mu) return std::nullopt;
  const double angle = angle_between(u, v);
  if (std::min(angle, std::numbers::pi - angle) < len.junction_angle_rad) return std::nullopt;
  return Vec2(t.line_a + a / (a - b) * v);
}

enum class Verdict : char { apart, conflict, crossing };
Verdict verdict(bool conflict) { return conflict ? Verdict::conflict : Verdict::apart; }

}  // namespace

// Whether pieces p and q may both be primary: apart, in conflict, or near one another only where
// their straight sections cross (allowed unless another crossing is within μ: see below).
static Verdict in_conflict(const Discretized& d, int i, int j, const Lengths& len) {
  const Piece& p = d.pieces[i];
  const Piece& q = d.pieces[j];
  // One connected component inside the μ-ball (Definition 3.1): pieces of one chain (an input
  // curve, or the pieces of one arc) joined by at most π/2·μ of its polyline, as on a tight bend,
  // may come close; around a closed chain (a circle) the way across its start counts too.
  // Not where the curve folds back on itself, though: consecutive pieces meeting at a cusp at
  // less than the junction angle, or pieces running in opposite directions, would leave a sliver
  // between them that no triangle of minimal angle α fits.
  const int chain = d.sections[p.section].chain;
  if (chain == d.sections[q.section].chain) {
    const Piece* first = i < j ? &p : &q;  // pieces are numbered along their chain
    const Piece* second = i < j ? &q : &p;
    double gap = second->along - (first->along + (first->b - first->a).norm());
    if (d.chains[chain].closed) {
      const double across = d.chains[chain].length - (second->along + (second->b - second->a).norm()) + first->along;
      if (across < gap) gap = across, std::swap(first, second);
    }
    if (gap <= 0.5 * std::numbers::pi * len.mu) {
      if (first->b == second->a)
        return verdict(angle_between(first->a - first->b, second->b - second->a) < len.junction_angle_rad ||
                       angle_between(first->leave_b, second->leave_a) < len.junction_angle_rad);
      return verdict((first->b - first->a).dot(second->b - second->a) <= 0);
    }
  }
  // A shared endpoint: allowed when the pieces leave it at a wide enough angle.
  struct End {
    Vec2 at, other, leaving;
  };
  const std::array<End, 2> p_ends{{{p.a, p.b, p.leave_a}, {p.b, p.a, p.leave_b}}};
  const std::array<End, 2> q_ends{{{q.a, q.b, q.leave_a}, {q.b, q.a, q.leave_b}}};
  End p_end, q_end;
  int shared_count = 0;
  for (const End& pe : p_ends)
    for (const End& qe : q_ends)
      if (pe.at == qe.at) ++shared_count, p_end = pe, q_end = qe;
  if (shared_count == 1) {
    // Pieces are chords: two chords that share an endpoint meet nowhere else. Both the chords
    // and the curves must meet at the junction angle: a curved edge leaves the vertex along its
    // curve's tangent, and two curves leaving at a few degrees while their chords open wider
    // would leave the triangles between them, each with one curved edge, two wedges of half
    // that angle at the vertex.
    const Vec2 u = p_end.other - p_end.at, v = q_end.other - q_end.at;
    if (u.norm() == 0 || v.norm() == 0) return Verdict::conflict;
    if (angle_between(u, v) < len.junction_angle_rad) return Verdict::conflict;
    return verdict(angle_between(p_end.leaving, q_end.leaving) < len.junction_angle_rad);
  }
  if (shared_count > 1) return Verdict::conflict;  // the same chord twice
  if (segment_distance(p.a, p.b, q.a, q.b) >= len.mu) return Verdict::apart;
  if (!len.straight_crossings) return Verdict::conflict;
  const std::optional<Vec2> x = straight_crossing(d.sections[p.section], d.sections[q.section], len);
  // A straight curve is cut into pieces at even steps, and a cut may fall on (or next to) the
  // crossing: the mesh would then have both the cut and the crossing as vertices, an edge far
  // shorter than μ between them. The crossing must be at least μ from both pieces' ends.
  if (!x || std::min({(*x - p.a).norm(), (*x - p.b).norm(), (*x - q.a).norm(), (*x - q.b).norm()}) < len.mu)
    return Verdict::conflict;
  return Verdict::crossing;
}

// The pairs of pieces allowed only by their sections' crossing whose crossing has another within
// μ: three lines through nearly one point, or a line drawn twice across another, would leave the
// mesh edges far shorter than μ between the crossings, which no certified curved triangle may
// need. Those pairs are in conflict after all, as the paper's rule has them.
static std::vector<std::pair<int, int>> crowded_crossings(const Discretized& d,
                                                          const std::vector<std::pair<int, int>>& pairs,
                                                          const Lengths& len) {
  // Each pair of sections once, with its crossing.
  std::map<std::pair<int, int>, Vec2> at;
  for (const auto& [i, j] : pairs) {
    const int s = d.pieces[i].section, t = d.pieces[j].section;
    const std::pair<int, int> key{std::min(s, t), std::max(s, t)};
    if (!at.count(key)) at.emplace(key, *straight_crossing(d.sections[key.first], d.sections[key.second], len));
  }
  std::vector<std::pair<std::pair<int, int>, Vec2>> points(at.begin(), at.end());
  std::vector<Box> boxes;
  for (int k = 0; k < static_cast<int>(points.size()); ++k)
    boxes.push_back(box_of(points[k].second, points[k].second, 0.5 * len.mu, k));
  std::set<std::pair<int, int>> crowded;  // of sections
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const auto& p = points[x.info()];
    const auto& q = points[y.info()];
    if ((p.second - q.second).norm() < len.mu) crowded.insert(p.first), crowded.insert(q.first);
  });
  std::vector<std::pair<int, int>> out;
  for (const auto& [i, j] : pairs) {
    const int s = d.pieces[i].section, t = d.pieces[j].section;
    if (crowded.count({std::min(s, t), std::max(s, t)})) out.emplace_back(i, j);
  }
  return out;
}

// The cuts between pieces of straight curves that fall within μ of a crossing the rule above
// would keep (a curve is cut at even steps, blind to what crosses it): each such cut (between
// pieces c and c + 1, the crossing nearest it first in the pairs' order) with the crossing x.
static std::vector<std::pair<int, Vec2>> cuts_on_crossings(const Discretized& d, const Lengths& len) {
  std::vector<Box> boxes;
  for (int i = 0; i < static_cast<int>(d.pieces.size()); ++i)
    if (!d.pieces[i].unfit && d.sections[d.pieces[i].section].straight)
      boxes.push_back(box_of(d.pieces[i].a, d.pieces[i].b, 0.5 * len.mu, i));
  std::vector<std::pair<int, int>> pairs;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    base::check_pairs(pairs.size() + 1, len.max_triangles, 8, "pieces within mu of each other");
    if (d.pieces[x.info()].section != d.pieces[y.info()].section)
      pairs.emplace_back(std::min(x.info(), y.info()), std::max(x.info(), y.info()));
  });
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::pair<int, Vec2>> cuts;
  for (const auto& [i, j] : pairs) {
    const std::optional<Vec2> x =
        straight_crossing(d.sections[d.pieces[i].section], d.sections[d.pieces[j].section], len);
    if (!x) continue;
    for (const int k : {i, j}) {
      const CurveSection& s = d.sections[d.pieces[k].section];
      if (k > s.first_piece && (d.pieces[k].a - *x).norm() < len.mu) cuts.emplace_back(k - 1, *x);
      if (k + 1 < s.first_piece + s.piece_count && (d.pieces[k].b - *x).norm() < len.mu)
        cuts.emplace_back(k, *x);
    }
  }
  std::stable_sort(cuts.begin(), cuts.end(), [](const auto& u, const auto& v) { return u.first < v.first; });
  cuts.erase(
      std::unique(cuts.begin(), cuts.end(), [](const auto& u, const auto& v) { return u.first == v.first; }),
      cuts.end());
  return cuts;
}

// With strokes as areas, such a cut is moved to the middle of the longer side of the crossing
// between the two pieces' outer ends: the crossing then lies inside a piece, far from its ends,
// and the X stays primary (a crossing within μ of a piece's end is a conflict: the cut and the
// crossing would be two vertices closer than μ). The line is the same; a piece becomes up to
// half as long again as the others, which the optimizer's sizing splits if it must.
static void move_cuts_off_crossings(Discretized& d, const Lengths& len) {
  for (const auto& [c, x] : cuts_on_crossings(d, len)) {
    Piece &before = d.pieces[c], &after = d.pieces[c + 1];
    const CurveSection& s = d.sections[before.section];
    const Vec2 u = s.line_b - s.line_a;
    const Vec2 cut =
        (x - before.a).norm() > (after.b - x).norm() ? 0.5 * (before.a + x) : 0.5 * (x + after.b);
    const double t = std::clamp((cut - s.line_a).dot(u) / u.squaredNorm(), before.t0, after.t1);
    before.t1 = after.t0 = t;
    before.b = after.a = s.line_a + t * u;
    after.along = before.along + (before.b - before.a).norm();
  }
}

// Isolated points within μ of a primary piece or of an earlier point are absorbed by it.
static void absorb_isolated_points(Discretized& d, const Lengths& len) {
  const int n = static_cast<int>(d.pieces.size());
  std::vector<Box> point_boxes, primary_boxes;
  for (int k = 0; k < static_cast<int>(d.points.size()); ++k)
    point_boxes.push_back(box_of(d.points[k].p, d.points[k].p, 0.5 * len.mu, k));
  for (int i = 0; i < n; ++i)
    if (d.pieces[i].kind == Kind::primary) primary_boxes.push_back(box_of(d.pieces[i].a, d.pieces[i].b, 0.5 * len.mu, i));
  std::vector<char> drop(d.points.size(), 0);
  CGAL::box_intersection_d(point_boxes.begin(), point_boxes.end(), primary_boxes.begin(), primary_boxes.end(),
                           [&](const Box& pt, const Box& pc) {
                             const Piece& p = d.pieces[pc.info()];
                             if (point_segment_distance(d.points[pt.info()].p, p.a, p.b) < len.mu) drop[pt.info()] = 1;
                           });
  std::vector<std::vector<int>> near(d.points.size());
  CGAL::box_self_intersection_d(point_boxes.begin(), point_boxes.end(), [&](const Box& x, const Box& y) {
    if ((d.points[x.info()].p - d.points[y.info()].p).norm() < len.mu) {
      near[x.info()].push_back(y.info());
      near[y.info()].push_back(x.info());
    }
  });
  for (std::size_t k = 0; k < d.points.size(); ++k) {
    if (drop[k]) continue;
    for (const int other : near[k])
      if (other < static_cast<int>(k) && !drop[other]) {
        drop[k] = 1;
        break;
      }
  }
  std::vector<IsolatedPoint> kept;
  for (std::size_t k = 0; k < d.points.size(); ++k)
    if (!drop[k]) kept.push_back(d.points[k]);
  d.points = std::move(kept);
}

void tag_primary_secondary(Discretized& d, const Lengths& len) {
  if (len.straight_crossings) move_cuts_off_crossings(d, len);
  const int n = static_cast<int>(d.pieces.size());
  std::vector<Box> boxes;
  boxes.reserve(n);
  // With --no-features nothing is primary, so nothing need be separated.
  for (int i = 0; i < n; ++i)
    if (!d.pieces[i].unfit && len.features) boxes.push_back(box_of(d.pieces[i].a, d.pieces[i].b, 0.5 * len.mu, i));

  // The pairs whose boxes meet, gathered in blocks, and whether each is in conflict decided side
  // by side (the greedy below asks only whether a conflicting piece is primary, so the order of
  // the lists does not matter).
  std::vector<std::vector<int>> conflicts(n);
  std::vector<std::pair<int, int>> block, crossing;
  std::vector<Verdict> verdicts;
  const auto decide = [&] {
    verdicts.assign(block.size(), Verdict::apart);
    base::for_each_part(
        block.size(), [&](std::size_t k) { verdicts[k] = in_conflict(d, block[k].first, block[k].second, len); },
        1024);
    for (std::size_t k = 0; k < block.size(); ++k)
      if (verdicts[k] == Verdict::conflict) {
        conflicts[block[k].first].push_back(block[k].second);
        conflicts[block[k].second].push_back(block[k].first);
      } else if (verdicts[k] == Verdict::crossing) {
        crossing.push_back(block[k]);
      }
    block.clear();
  };
  std::size_t pairs = 0;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    base::check_pairs(++pairs, len.max_triangles, 8, "pieces within mu of each other");
    block.emplace_back(x.info(), y.info());
    if (block.size() == std::size_t{1} << 16) decide();
  });
  decide();
  for (const auto& [i, j] : crowded_crossings(d, crossing, len)) {
    conflicts[i].push_back(j);
    conflicts[j].push_back(i);
  }

  // Greedy: long sections first, pieces in order along each section.
  std::vector<int> order(d.sections.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return d.sections[a].length > d.sections[b].length; });
  std::vector<char> decided(n, 0);
  for (const int s : order) {
    const CurveSection& section = d.sections[s];
    for (int i = section.first_piece; i < section.first_piece + section.piece_count; ++i) {
      Piece& p = d.pieces[i];
      bool primary = !p.unfit && len.features;
      if (primary)
        for (const int j : conflicts[i])
          if (decided[j] && d.pieces[j].kind == Kind::primary) {
            primary = false;
            break;
          }
      p.kind = primary ? Kind::primary : Kind::secondary;
      decided[i] = 1;
    }
  }

  absorb_isolated_points(d, len);
}

}  // namespace curvemesh::features::detail
