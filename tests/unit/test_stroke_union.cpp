// The edge of what a stroke paints (svg/stroke_union.hpp), checked against winding numbers counted
// here by crossings of a ray, segment by segment, on the outline it comes from.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "geometry/bezier.hpp"
#include "svg/path_data.hpp"
#include "svg/stroke.hpp"
#include "svg/stroke_union.hpp"

using namespace curvemesh;
using geometry::CubicBezier;
using geometry::Vec2;

namespace {

svg::Subpath polygon(const std::vector<Vec2>& ps) {
  svg::Subpath s;
  s.start = ps[0];
  s.closed = true;
  for (std::size_t i = 0; i < ps.size(); ++i) s.segments.push_back(CubicBezier::line(ps[i], ps[(i + 1) % ps.size()]));
  return s;
}

// The winding number of p with respect to loops of straight segments (their chords), counted by
// the crossings of the ray from p towards +x.
int winding(const std::vector<svg::Subpath>& loops, const Vec2& p) {
  int w = 0;
  for (const svg::Subpath& l : loops)
    for (const CubicBezier& c : l.segments) {
      const Vec2 &a = c.p[0], &b = c.p[3];
      if ((a.y() <= p.y()) == (b.y() <= p.y())) continue;
      const double x = a.x() + (p.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (x > p.x()) w += b.y() > a.y() ? 1 : -1;
    }
  return w;
}

double distance_to(const std::vector<svg::Subpath>& loops, const Vec2& p) {
  double best = INFINITY;
  for (const svg::Subpath& l : loops)
    for (const CubicBezier& c : l.segments) {
      const Vec2 &a = c.p[0], ab = c.p[3] - c.p[0];
      const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (p - (a + s * ab)).norm());
    }
  return best;
}

// The edge paints what the outline paints (nonzero) at every point of a grid over `box` away from
// both, winds once round it (simple loops, the painted side on the left), and runs nowhere but
// between painted and unpainted: just off the middle of each of its segments, one side is painted
// and the other is not.
void expect_edge_of(const std::vector<svg::Subpath>& outline, const std::vector<svg::Subpath>& edge, Vec2 lo,
                    Vec2 hi) {
  const int n = 150;
  int painted = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const Vec2 p(lo.x() + (hi.x() - lo.x()) * (i + 0.37) / n, lo.y() + (hi.y() - lo.y()) * (j + 0.61) / n);
      if (distance_to(outline, p) < 1e-9 || distance_to(edge, p) < 1e-9) continue;
      const int w = winding(edge, p);
      EXPECT_TRUE(w == 0 || w == 1) << p.transpose();
      EXPECT_EQ(w != 0, winding(outline, p) != 0) << p.transpose();
      painted += w != 0;
    }
  EXPECT_GT(painted, 0);
  for (const svg::Subpath& l : edge)
    for (const CubicBezier& c : l.segments) {
      const Vec2 m = (c.p[0] + c.p[3]) / 2, t = (c.p[3] - c.p[0]).normalized(), left(-t.y(), t.x());
      EXPECT_NE(winding(outline, m + 1e-7 * left), 0) << m.transpose();
      EXPECT_EQ(winding(outline, m - 1e-7 * left), 0) << m.transpose();
    }
}

svg::StrokeStyle style(double width, svg::LineJoin join, svg::LineCap cap) {
  svg::StrokeStyle s;
  s.width = width, s.join = join, s.cap = cap;
  return s;
}

}  // namespace

TEST(PaintedEdge, TwoOverlappingSquaresGiveTheEdgeOfTheirUnion) {
  const std::vector<svg::Subpath> outline = {polygon({Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)}),
                                             polygon({Vec2(1, 1), Vec2(3, 1), Vec2(3, 3), Vec2(1, 3)})};
  const auto edge = svg::painted_edge(outline, 1e-12, 100);
  ASSERT_TRUE(edge);
  ASSERT_EQ(edge->size(), 1u);
  // Eight corners: the two crossings (2, 1) and (1, 2) and six of the squares' (the collinear
  // pieces either side of a crossing are one segment).
  std::set<std::pair<double, double>> corners;
  for (const CubicBezier& c : edge->front().segments) corners.emplace(c.p[0].x(), c.p[0].y());
  const std::set<std::pair<double, double>> want = {{0, 0}, {2, 0}, {2, 1}, {3, 1}, {3, 3}, {1, 3}, {1, 2}, {0, 2}};
  EXPECT_EQ(corners, want);
  expect_edge_of(outline, *edge, Vec2(-1, -1), Vec2(4, 4));
}

TEST(PaintedEdge, AStrokeCrossingItselfLosesTheCurvesInsideItsBand) {
  // A bow tie: its two diagonals cross, and each corner's bands overlap.
  const auto outline =
      svg::stroke_outline(svg::parse_path_data("M 0 0 L 10 10 L 10 0 L 0 10 Z"), style(1, svg::LineJoin::miter, svg::LineCap::butt));
  const auto edge = svg::painted_edge(outline, 1e-12, 1000);
  ASSERT_TRUE(edge);
  expect_edge_of(outline, *edge, Vec2(-2, -2), Vec2(12, 12));
  // A path running back over itself: the bands lie on one another.
  const auto back = svg::stroke_outline(svg::parse_path_data("M 0 0 L 10 0 L 4 0 L 4 6"),
                                        style(2, svg::LineJoin::bevel, svg::LineCap::square));
  const auto back_edge = svg::painted_edge(back, 1e-12, 1000);
  ASSERT_TRUE(back_edge);
  expect_edge_of(back, *back_edge, Vec2(-2, -2), Vec2(12, 8));
}

TEST(PaintedEdge, AnOutlineWithCurvesOrTooManyCrossingsIsKept) {
  const auto path = svg::parse_path_data("M 0 0 L 10 10 L 10 0 L 0 10 Z");
  EXPECT_FALSE(svg::painted_edge(svg::stroke_outline(path, style(1, svg::LineJoin::round, svg::LineCap::butt)), 1e-12, 1000));
  const auto outline = svg::stroke_outline(path, style(1, svg::LineJoin::miter, svg::LineCap::butt));
  EXPECT_FALSE(svg::painted_edge(outline, 1e-12, 3));
}

TEST(PaintedEdge, AnOutlineThatIsItsOwnEdgeIsKeptAsItIs) {
  // A rectangle's band: two loops, the outer and the inner side, neither crossing the other.
  const auto outline = svg::stroke_outline(svg::parse_path_data("M 0 0 H 10 V 6 H 0 Z"),
                                           style(1, svg::LineJoin::miter, svg::LineCap::butt));
  const auto edge = svg::painted_edge(outline, 1e-12, 1000);
  ASSERT_TRUE(edge);
  ASSERT_EQ(edge->size(), outline.size());
  for (std::size_t i = 0; i < outline.size(); ++i) {
    EXPECT_EQ(edge->at(i).start, outline[i].start);
    ASSERT_EQ(edge->at(i).segments.size(), outline[i].segments.size());
    for (std::size_t k = 0; k < outline[i].segments.size(); ++k)
      EXPECT_EQ(edge->at(i).segments[k].p, outline[i].segments[k].p);
  }
}
