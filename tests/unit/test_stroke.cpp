// Strokes as areas: offset curves against the exact offset c(t) + d·n(t), densely sampled, both
// ways (every point of the exact offset near a piece, every point of every piece near the exact
// offset); joins, caps and dashes by their geometry and areas; the reader's stroke layers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/bezier_analysis.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/offset.hpp"
#include "svg/arc.hpp"
#include "svg/path_data.hpp"
#include "svg/reader.hpp"
#include "svg/stroke.hpp"

using namespace curvemesh;
using geometry::CubicBezier;
using geometry::OffsetRun;
using geometry::Vec2;

namespace {

constexpr double kPi = std::numbers::pi;

// The exact offset of one run sampled at n + 1 parameters.
struct DenseOffset {
  std::vector<double> t;
  std::vector<Vec2> p;
};

DenseOffset dense_offset(const CubicBezier& c, double d, double lo, double hi, int n) {
  DenseOffset out;
  for (int i = 0; i <= n; ++i) {
    out.t.push_back(lo + (hi - lo) * i / n);
    out.p.push_back(geometry::offset_point(c, out.t.back(), d, lo, hi));
  }
  return out;
}

// The distance from q to the exact offset. The foot of the perpendicular lies between two dense
// samples, each within (distance + gap) of q, gap the largest distance between neighbouring
// samples: every sample that close is refined by golden-section search on the parameters on each
// side of it (several, where the offset crosses itself near q).
double distance_to_offset(const CubicBezier& c, double d, double lo, double hi, const DenseOffset& dense,
                          const Vec2& q) {
  const auto at = [&](double t) { return (geometry::offset_point(c, t, d, lo, hi) - q).norm(); };
  double nearest = INFINITY, gap = 0;
  for (std::size_t i = 0; i < dense.p.size(); ++i) {
    nearest = std::min(nearest, (dense.p[i] - q).norm());
    if (i > 0) gap = std::max(gap, (dense.p[i] - dense.p[i - 1]).norm());
  }
  double best = nearest;
  for (std::size_t i = 0; i < dense.p.size(); ++i) {
    if ((dense.p[i] - q).norm() > nearest + gap) continue;
    for (const int side : {-1, 1}) {
      const long j = static_cast<long>(i) + side;
      if (j < 0 || j >= static_cast<long>(dense.t.size())) continue;
      double a = std::min(dense.t[i], dense.t[j]), b = std::max(dense.t[i], dense.t[j]);
      const double g = (std::sqrt(5.0) - 1) / 2;
      for (int k = 0; k < 60; ++k) {
        const double x = b - g * (b - a), y = a + g * (b - a);
        if (at(x) < at(y))
          b = y;
        else
          a = x;
      }
      best = std::min(best, at((a + b) / 2));
    }
  }
  return best;
}

struct Hausdorff {
  double exact_to_pieces = 0;  // the farthest exact offset point from every piece
  double pieces_to_exact = 0;  // the farthest point of a piece from the exact offset
};

// Both one-sided distances, the exact offset sampled at 4000 parameters per run (the cusps of c
// excluded: there the exact offset jumps, and each run has its own limit), each piece at 400.
Hausdorff hausdorff(const CubicBezier& c, double d, const std::vector<OffsetRun>& runs) {
  Hausdorff h;
  for (const OffsetRun& run : runs) {
    const DenseOffset dense = dense_offset(c, d, run.t0, run.t1, 4000);
    for (const Vec2& q : dense.p) {
      double nearest = INFINITY;
      for (const CubicBezier& piece : run.pieces)
        if (piece.control_bounds().squared_distance(q) < nearest * nearest)  // the curve is inside that box
          nearest = std::min(nearest, geometry::closest_point(piece, q).distance);
      h.exact_to_pieces = std::max(h.exact_to_pieces, nearest);
    }
    for (const CubicBezier& piece : run.pieces)
      for (int k = 0; k <= 400; ++k)
        h.pieces_to_exact = std::max(h.pieces_to_exact,
                                     distance_to_offset(c, d, run.t0, run.t1, dense, piece.eval(k / 400.0)));
  }
  return h;
}

// Checks a curve's offsets on both sides: within the tolerance both ways, each run's pieces
// joined end to start exactly, the runs covering [0, 1].
void expect_offsets_within(const CubicBezier& c, double d, double tolerance) {
  for (const double side : {d, -d}) {
    SCOPED_TRACE("offset " + std::to_string(side));
    const std::vector<OffsetRun> runs = geometry::offset_cubic(c, side, tolerance);
    ASSERT_FALSE(runs.empty());
    EXPECT_EQ(runs.front().t0, 0.0);
    EXPECT_EQ(runs.back().t1, 1.0);
    for (const OffsetRun& run : runs) {
      ASSERT_FALSE(run.pieces.empty());
      EXPECT_LT(run.pieces.size(), 2000u);
      for (std::size_t k = 1; k < run.pieces.size(); ++k)
        EXPECT_EQ(run.pieces[k].p[0], run.pieces[k - 1].p[3]);
    }
    const Hausdorff h = hausdorff(c, side, runs);
    EXPECT_LE(h.exact_to_pieces, tolerance);
    EXPECT_LE(h.pieces_to_exact, tolerance);
  }
}

// The smallest radius of curvature of c over 10001 parameters.
double smallest_radius(const CubicBezier& c) {
  double r = INFINITY;
  for (int i = 0; i <= 10000; ++i) {
    const Vec2 v = c.derivative(i / 10000.0), a = c.second_derivative(i / 10000.0);
    r = std::min(r, std::pow(v.norm(), 3) / std::abs(geometry::cross(v, a)));
  }
  return r;
}

TEST(Offset, OrdinaryCubicsWithinTolerance) {
  expect_offsets_within(CubicBezier({0, 0}, {1, 2}, {3, 2}, {4, 0}), 0.3, 1e-6);
  expect_offsets_within(CubicBezier({0, 0}, {2, -1}, {1, 3}, {5, 2}), 0.25, 1e-7);  // an inflection
}

TEST(Offset, StraightSegmentIsOnePieceOnTheLine) {
  const CubicBezier line = CubicBezier::line({0, 0}, {5, 1});
  const std::vector<OffsetRun> runs = geometry::offset_cubic(line, 0.5, 1e-9);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].pieces.size(), 1u);
  expect_offsets_within(line, 0.5, 1e-9);
}

TEST(Offset, CuspOfTheCurveStartsANewRun) {
  // c'(1/2) = 0: the legs A + 2B + C of the control polygon sum to zero.
  const CubicBezier cusp({0, 0}, {2, 2}, {1, 2}, {1, 0});
  const std::vector<double> cusps = geometry::cusp_parameters(cusp);
  ASSERT_EQ(cusps.size(), 1u);
  EXPECT_NEAR(cusps[0], 0.5, 1e-9);
  EXPECT_EQ(geometry::offset_cubic(cusp, 0.2, 1e-6).size(), 2u);
  expect_offsets_within(cusp, 0.2, 1e-6);
}

TEST(Offset, CurveRunningOutAndBackAlongALine) {
  // p1 = p2, p3 = p0 (drawn as "c a, a, 0 0"): a straight spike out and back with a cusp at its tip,
  // at coordinates far from the origin and a half width far below them. The cross product c' × c''
  // is round-off alone there: no cusp of the offset may be read from its sign, and the normal's
  // round-off beside the tip may not be taken for an error a fit could still reduce.
  const Vec2 p0(12.756, 53.842), a(-0.144, -0.899);
  const CubicBezier spike(p0, p0 + a, p0 + a, p0);
  const double d = 0.018, tolerance = 1e-8 * 2 * d;
  for (const double side : {d, -d}) {
    SCOPED_TRACE("offset " + std::to_string(side));
    EXPECT_TRUE(geometry::offset_cusp_parameters(spike, side, 0, 0.5).empty());
    EXPECT_TRUE(geometry::offset_cusp_parameters(spike, side, 0.5, 1).empty());
    const std::vector<OffsetRun> runs = geometry::offset_cubic(spike, side, tolerance);
    ASSERT_EQ(runs.size(), 2u);
    for (const OffsetRun& run : runs) EXPECT_LE(run.pieces.size(), 4u);
  }
  expect_offsets_within(spike, d, 1e-9);
}

TEST(Offset, CurveWhoseEndControlPointIsItsEnd) {
  // p2 = p3: c' vanishes at the end, where c' and c'' turn parallel and |c'|³ − d·(c' × c'')
  // vanishes faster than its rounding. The curvature grows without bound towards the end, so the
  // offset on its inner side has a cusp just before it, to be found from a sample whose sign holds.
  const CubicBezier c({511.72576, 32.575392}, {511.28301, 34.789162}, {513.49678, 36.560172},
                      {513.49678, 36.560172});
  const std::vector<double> cusps = geometry::offset_cusp_parameters(c, -0.625);
  ASSERT_EQ(cusps.size(), 1u);
  EXPECT_NEAR(cusps[0], 0.98657, 1e-5);
  const std::vector<OffsetRun> runs = geometry::offset_cubic(c, -0.625, 1.25e-8);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_LE(runs[0].pieces.size(), 64u);
  expect_offsets_within(c, 0.625, 1e-7);
}

TEST(Offset, SwallowtailBetweenTwoSamples) {
  // A hairline (half width 0.018) along a curve that turns back within a few hundredths of its
  // parameter: both cusps of the inner offset lie between two of the 64 samples, where the
  // function has one sign; found from the dip between them, the pieces are as few as the shape
  // needs.
  const CubicBezier c({90.782, 276.395}, {90.522, 278.085}, {88.053, 258.716}, {87.403, 246.019});
  const std::vector<double> cusps = geometry::offset_cusp_parameters(c, 0.018);
  ASSERT_EQ(cusps.size(), 2u);
  EXPECT_EQ(std::floor(cusps[0] * 64), std::floor(cusps[1] * 64));  // in one sample interval
  const std::vector<OffsetRun> runs = geometry::offset_cubic(c, 0.018, 0.036e-8);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_LE(runs[0].pieces.size(), 100u);
  expect_offsets_within(c, 0.018, 1e-7);
}

TEST(Offset, PiecesKeepTheirSpeedAtTheirEnds) {
  // Where c' vanishes (p1 = p0: a nearly straight side of a wide stroke) and at the offset's cusps
  // the offset's speed vanishes; a piece following it there would have an arm of no length, and
  // an element edge on it a Jacobian vanishing at its vertex. Every arm is at least 1/64 of its
  // piece's chord, and the pieces stay within the tolerance.
  const CubicBezier nearly_straight({393.56, 293.93}, {393.56, 293.93}, {394.19, 392.18}, {394.19, 392.18});
  const CubicBezier bend({0, 0}, {3, 0}, {3, 1}, {2, 1.2});
  for (const auto& [c, d] : {std::pair(nearly_straight, 6.25), std::pair(bend, 0.5)}) {
    for (const double side : {d, -d}) {
      for (const OffsetRun& run : geometry::offset_cubic(c, side, 1e-8 * 2 * d))
        for (const CubicBezier& piece : run.pieces) {
          const double chord = (piece.p[3] - piece.p[0]).norm();
          EXPECT_GE((piece.p[1] - piece.p[0]).norm(), chord / 64 * (1 - 1e-12));
          EXPECT_GE((piece.p[3] - piece.p[2]).norm(), chord / 64 * (1 - 1e-12));
        }
    }
  }
  expect_offsets_within(nearly_straight, 6.25, 1e-7);
}

TEST(Offset, ToleranceBelowTheCoordinatesRoundOff) {
  // A thin stroke far from the origin: a tolerance of 1e-8 of the width is below the spacing of
  // doubles at these coordinates; the pieces are as few as the shape needs, not as many as the
  // work bound allows.
  const CubicBezier far({1e7, 1e7}, {1e7 + 1, 1e7 + 2}, {1e7 + 3, 1e7 + 2}, {1e7 + 4, 1e7});
  for (const double side : {1e-4, -1e-4}) {
    const std::vector<OffsetRun> runs = geometry::offset_cubic(far, side, 1e-8 * 2e-4);
    ASSERT_EQ(runs.size(), 1u);
    EXPECT_LE(runs[0].pieces.size(), 64u);
  }
}

TEST(Offset, TightLoop) {
  // A loop whose apex bends tighter than the offset distance on its inner side.
  const CubicBezier loop({0, 0}, {3, 2}, {-1, 2}, {2, 0});
  ASSERT_LT(smallest_radius(loop), 0.4);
  EXPECT_FALSE(geometry::offset_cusp_parameters(loop, 0.4).empty() &&
               geometry::offset_cusp_parameters(loop, -0.4).empty());
  expect_offsets_within(loop, 0.4, 1e-6);
}

TEST(Offset, RadiusBelowTheDistance) {
  // A bend whose radius goes below d on one side only: the offset there has two cusps and runs
  // backwards between them (its swallowtail).
  const CubicBezier bend({0, 0}, {3, 0}, {3, 1}, {2, 1.2});
  const double r = smallest_radius(bend);
  const double d = 2 * r;
  ASSERT_LT(d, 1.0);
  const std::size_t cusps_left = geometry::offset_cusp_parameters(bend, d).size();
  const std::size_t cusps_right = geometry::offset_cusp_parameters(bend, -d).size();
  EXPECT_EQ(cusps_left + cusps_right, 2u);
  expect_offsets_within(bend, d, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// Outlines

// The signed area a closed chain of cubics encloses: ½∮(x dy − y dx), 64-point Gauss–Legendre
// would do; composite Simpson over 2000 steps per cubic is within 1e-12 of it here.
double signed_area(const svg::Subpath& loop) {
  double area = 0;
  for (const CubicBezier& c : loop.segments) {
    const int n = 2000;
    for (int i = 0; i <= n; ++i) {
      const double t = double(i) / n, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
      area += w * geometry::cross(c.eval(t), c.derivative(t)) / 2 / (3.0 * n);
    }
  }
  return area;
}

double total_area(const std::vector<svg::Subpath>& loops) {
  double a = 0;
  for (const svg::Subpath& l : loops) a += signed_area(l);
  return std::abs(a);
}

std::vector<svg::Subpath> path(const char* d) {
  return svg::parse_path_data(d);
}

svg::StrokeStyle style(double width, svg::LineJoin join, svg::LineCap cap, double miter_limit = 4) {
  svg::StrokeStyle s;
  s.width = width, s.join = join, s.cap = cap, s.miter_limit = miter_limit;
  return s;
}

// How far an outline reaches beyond p along the unit vector u (over 200 points of each curve).
double reach(const std::vector<svg::Subpath>& loops, const Vec2& p, const Vec2& u) {
  double far = -INFINITY;
  for (const svg::Subpath& l : loops)
    for (const CubicBezier& c : l.segments)
      for (int k = 0; k <= 200; ++k) far = std::max(far, (c.eval(k / 200.0) - p).dot(u));
  return far;
}

TEST(StrokeOutline, LoopsAreClosedAndCapsHaveTheirArea) {
  const double w = 2, length = 10;
  const auto line = path("M 0 0 L 10 0");
  for (const auto& [cap, area] :
       {std::pair{svg::LineCap::butt, w * length}, std::pair{svg::LineCap::square, w * (length + w)},
        std::pair{svg::LineCap::round, w * length + kPi * w * w / 4}}) {
    const auto loops = svg::stroke_outline(line, style(w, svg::LineJoin::miter, cap));
    ASSERT_EQ(loops.size(), 1u);
    EXPECT_EQ(loops[0].segments.back().p[3], loops[0].segments.front().p[0]);
    for (std::size_t k = 1; k < loops[0].segments.size(); ++k)
      EXPECT_EQ(loops[0].segments[k].p[0], loops[0].segments[k - 1].p[3]);
    EXPECT_NEAR(total_area(loops), area, 1e-6 * area);
  }
}

TEST(StrokeOutline, RoundCapIsACircleOfHalfTheWidth) {
  const auto loops =
      svg::stroke_outline(path("M 0 0 L 10 0"), style(3, svg::LineJoin::round, svg::LineCap::round));
  double worst = 0, reach = 0;
  for (const CubicBezier& c : loops[0].segments)
    for (int k = 0; k <= 200; ++k) {
      const Vec2 q = c.eval(k / 200.0);
      if (q.x() > 10 + 1e-12)
        worst = std::max(worst, std::abs((q - Vec2(10, 0)).norm() - 1.5)), reach = std::max(reach, q.x());
    }
  EXPECT_LE(worst, svg::kArcTolerance * 1.5);
  EXPECT_NEAR(reach, 11.5, 1e-9);
}

TEST(StrokeOutline, MiterLengthAndItsLimit) {
  const double w = 2, d = w / 2;
  // A right angle: the miter's tip d/cos(45°) beyond the corner along the outer bisector (the
  // miter's length, tip to inner corner, twice that: w·√2, as SVG's w/sin(θ/2)).
  const auto right =
      svg::stroke_outline(path("M 0 0 L 10 0 L 10 10"), style(w, svg::LineJoin::miter, svg::LineCap::butt));
  const Vec2 bisector = Vec2(1, -1).normalized();
  EXPECT_NEAR(reach(right, {10, 0}, bisector), d * std::sqrt(2.0), 1e-12);
  // A sharp corner of θ between the segments: 1/sin(θ/2) ≈ 20 is beyond a limit of 4 (a bevel,
  // reaching d·sin(θ/2) beyond the corner) and within one of 30 (the whole miter, d/sin(θ/2)).
  const double theta = std::atan2(10.0, 100.0);
  const double ratio = 1 / std::sin(theta / 2);
  ASSERT_GT(ratio, 4);
  ASSERT_LT(ratio, 30);
  const auto sharp = path("M 0 0 L 100 0 L 0 10");
  const Vec2 in(1, 0), out = Vec2(-100, 10).normalized(), u = (in - out).normalized();
  const auto outline = [&](svg::LineJoin join, double limit) {
    return svg::stroke_outline(sharp, style(w, join, svg::LineCap::butt, limit));
  };
  EXPECT_NEAR(reach(outline(svg::LineJoin::miter, 4), {100, 0}, u), d * std::sin(theta / 2), 1e-9);
  EXPECT_NEAR(reach(outline(svg::LineJoin::miter, 30), {100, 0}, u), d * ratio, 1e-9);
  EXPECT_NEAR(reach(outline(svg::LineJoin::bevel, 4), {100, 0}, u), d * std::sin(theta / 2), 1e-9);
  EXPECT_NEAR(reach(outline(svg::LineJoin::round, 4), {100, 0}, u), d, d * svg::kArcTolerance + 1e-12);
}

TEST(StrokeOutline, JoinsAddTheirWedgesToTheArea) {
  // An L of two legs of 10: bands of 10·w each, sharing the square [10 − d, 10]×[0, d] inside the
  // corner, and the outer wedge: a triangle (bevel), a square (miter: a right angle is within the
  // limit), a quarter disc. The inner sides meet at the shared square's corner, so the loop is the
  // painted area's boundary and its signed area counts the square once.
  const double w = 2, d = 1;
  const auto l = path("M 0 0 L 10 0 L 10 10");
  const double bands = 2 * 10 * w - d * d;
  const auto area = [&](svg::LineJoin join) {
    return total_area(svg::stroke_outline(l, style(w, join, svg::LineCap::butt)));
  };
  EXPECT_NEAR(area(svg::LineJoin::bevel), bands + d * d / 2, 1e-9);
  EXPECT_NEAR(area(svg::LineJoin::miter), bands + d * d, 1e-9);
  EXPECT_NEAR(area(svg::LineJoin::round), bands + kPi * d * d / 4, 1e-8);
  // The inner side has no point of the corner's notch: it turns at (10 − d, d).
  for (const svg::Subpath& loop : svg::stroke_outline(l, style(w, svg::LineJoin::miter, svg::LineCap::butt)))
    for (const CubicBezier& c : loop.segments) EXPECT_NE(c.p[3], Vec2(10, 0));
}

// A miter join of two straight segments: the outer side's offsets are extended to the miter's
// point and meet there, so the outline has no short lines from their ends to the point (which
// feature processing would leave unfit, the two sides nearly touching), and the same area: the
// polygon of the two sides, worked out here from the offset lines.
TEST(StrokeOutline, MiterOfStraightSegmentsIsACornerOfTheOutline) {
  const double w = 2, d = w / 2;
  const Vec2 p0(0, 0), p1(10, 0), p2(20, 3);
  const Vec2 out = (p2 - p1).normalized(), left(-out.y(), out.x());
  const auto meet = [](const Vec2& a, const Vec2& u, const Vec2& b, const Vec2& v) {
    return Vec2(a + geometry::cross(b - a, v) / geometry::cross(u, v) * u);
  };
  const Vec2 miter = meet({0, -d}, {1, 0}, p1 - d * left, out);  // the outer (right) side
  const Vec2 inner = meet({0, d}, {1, 0}, p1 + d * left, out);
  const std::vector<Vec2> polygon = {{0, -d}, miter, p2 - d * left, p2 + d * left, inner, {0, d}};
  double area = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k)
    area += geometry::cross(polygon[k], polygon[(k + 1) % polygon.size()]) / 2;
  const auto loops = svg::stroke_outline(path("M 0 0 L 10 0 L 20 3"), style(w, svg::LineJoin::miter, svg::LineCap::butt));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_NEAR(total_area(loops), std::abs(area), 1e-9);
  int at_miter = 0;
  for (const CubicBezier& c : loops[0].segments) {
    EXPECT_GT((c.p[3] - c.p[0]).norm(), d) << "a short line in the outline";  // the caps are w long
    at_miter += (c.p[3] - miter).norm() < 1e-12;
  }
  EXPECT_EQ(at_miter, 1);
}

TEST(StrokeOutline, ClosedSubpathHasTwoLoopsAndNoCaps) {
  const auto loops = svg::stroke_outline(path("M 0 0 L 10 0 L 10 10 L 0 10 Z"),
                                         style(2, svg::LineJoin::miter, svg::LineCap::round));
  ASSERT_EQ(loops.size(), 2u);
  // The square ring from [−1, 11]² (mitred corners) to [1, 9]²: the inner sides meet at the inner
  // square's corners, so the loops bound the painted ring and count it once.
  EXPECT_NEAR(std::abs(signed_area(loops[0]) + signed_area(loops[1])), 12 * 12 - 8 * 8, 1e-9);
}

TEST(StrokeOutline, CircleRingAreaAndDotOfAZeroLengthSubpath) {
  const double r = 5, w = 1.5;
  const auto ring = svg::stroke_outline(svg::parse_path_data("M 5 0 A 5 5 0 1 1 -5 0 A 5 5 0 1 1 5 0 Z"),
                                        style(w, svg::LineJoin::miter, svg::LineCap::butt));
  EXPECT_NEAR(total_area(ring), kPi * ((r + w / 2) * (r + w / 2) - (r - w / 2) * (r - w / 2)), 1e-6);
  // A circle of radius below half the width: its inside is all within the stroke, a disc.
  const auto disc = svg::stroke_outline(svg::parse_path_data("M 2 0 A 2 2 0 1 1 -2 0 A 2 2 0 1 1 2 0 Z"),
                                        style(8, svg::LineJoin::miter, svg::LineCap::butt));
  EXPECT_EQ(disc.size(), 1u);
  EXPECT_NEAR(total_area(disc), kPi * 6 * 6, 1e-6);
  const auto dot = svg::stroke_outline(path("M 3 3"), style(w, svg::LineJoin::miter, svg::LineCap::round));
  EXPECT_NEAR(total_area(dot), kPi * w * w / 4, 1e-8);
  EXPECT_TRUE(svg::stroke_outline(path("M 3 3"), style(w, svg::LineJoin::miter, svg::LineCap::butt)).empty());
}

// ---------------------------------------------------------------------------------------------
// Dashes

double dashed_length(const std::vector<svg::Subpath>& dashes) {
  double total = 0;
  for (const svg::Subpath& sp : dashes)
    for (const CubicBezier& c : sp.segments) total += c.length();
  return total;
}

// The length of the "on" intervals of a pattern along a path of length L, counted interval by
// interval from the definition.
double expected_on_length(std::vector<double> pattern, double offset, double L) {
  if (pattern.size() % 2) pattern.insert(pattern.end(), pattern.begin(), pattern.end());
  double period = 0;
  for (double x : pattern) period += x;
  double on = 0, s = -std::fmod(std::fmod(offset, period) + period, period);
  for (std::size_t k = 0; s < L; k = (k + 1) % pattern.size()) {
    if (k % 2 == 0) on += std::max(0.0, std::min(s + pattern[k], L) - std::max(s, 0.0));
    s += pattern[k];
  }
  return on;
}

TEST(Dashes, TotalLengthFollowsThePattern) {
  const auto line = path("M 0 0 L 100 0");
  EXPECT_NEAR(dashed_length(svg::dash_subpaths(line, {5, 3}, 0)), expected_on_length({5, 3}, 0, 100), 1e-9);
  EXPECT_NEAR(dashed_length(svg::dash_subpaths(line, {5, 3}, 2)), expected_on_length({5, 3}, 2, 100), 1e-9);
  EXPECT_NEAR(dashed_length(svg::dash_subpaths(line, {5, 3}, -7)), expected_on_length({5, 3}, -7, 100), 1e-9);
  // A curve, and an odd pattern (repeated twice: 4 on, 1 off, 2 on, 4 off, 1 on, 2 off).
  const auto curve = path("M 0 0 C 20 30 40 -30 60 0 S 100 10 90 40");
  double length = 0;
  for (const CubicBezier& c : curve[0].segments) length += c.length();
  EXPECT_NEAR(dashed_length(svg::dash_subpaths(curve, {4, 1, 2}, 1.5)),
              expected_on_length({4, 1, 2}, 1.5, length), 1e-8);
  // Invalid patterns draw solid.
  EXPECT_EQ(svg::dash_subpaths(line, {5, -1}, 0).size(), 1u);
  EXPECT_EQ(svg::dash_subpaths(line, {0, 0}, 0).size(), 1u);
}

TEST(Dashes, ClosedPathJoinsItsLastDashToItsFirst) {
  // A square of perimeter 40 in dashes of 6 on, 4 off, shifted by 3: [0, 3], [7, 13], [17, 23],
  // [27, 33], [37, 40] — the last running into the first as one dash of 6 through the corner.
  const auto dashes = svg::dash_subpaths(path("M 0 0 L 10 0 L 10 10 L 0 10 Z"), {6, 4}, 3);
  ASSERT_EQ(dashes.size(), 4u);
  EXPECT_NEAR(dashed_length({dashes.back()}), 6, 1e-9);
  EXPECT_NEAR((dashes.back().segments.back().p[3] - Vec2(3, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR(dashed_length(dashes), 24, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// The reader

TEST(StrokeReader, StrokeIsALayerOverTheFillAndReplacesTheCentreLine) {
  const char* svg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 40">
      <rect id="r" x="5" y="5" width="20" height="10" fill="#ff0000" stroke="#0000ff" stroke-width="2"/>
      <path id="p" d="M 5 30 L 35 30" fill="none" stroke="#000" stroke-width="4" stroke-linecap="square"/>
    </svg>)";
  const svg::FeatureSoup lines = svg::read_svg(svg);
  EXPECT_EQ(lines.fills.size(), 1u);
  svg::ReadOptions o;
  o.strokes_as_areas = true;
  const svg::FeatureSoup areas = svg::read_svg(svg, o);
  ASSERT_EQ(areas.fills.size(), 3u);
  EXPECT_FALSE(areas.fills[0].stroke);
  EXPECT_TRUE(areas.fills[1].stroke);
  EXPECT_EQ(areas.fills[1].fill, svg::Paint::rgb(0, 0, 255));
  EXPECT_EQ(areas.fills[0].source, areas.fills[1].source);
  EXPECT_TRUE(areas.fills[2].stroke);
  // The line's band: 30 long and 2 beyond each end (square caps), 4 wide.
  const geometry::Box2 band = areas.fills[2].bounds;
  EXPECT_NEAR(band.min.x(), 3, 1e-12);
  EXPECT_NEAR(band.max.x(), 37, 1e-12);
  EXPECT_NEAR(band.max.y() - band.min.y(), 4, 1e-12);
  // No curve of the soup is stroked any more; the line's centre (y = 30) is no curve at all.
  for (const svg::SoupCurve& c : areas.curves) {
    EXPECT_EQ(c.stroke.kind, svg::Paint::Kind::none);
    if (c.source == areas.fills[2].source) {
      EXPECT_FALSE(c.bezier.p[0].y() == 30 && c.bezier.p[3].y() == 30);
    }
  }
}

TEST(StrokeReader, NonScalingStrokeKeepsItsWidthUnderATransform) {
  const auto band_height = [](const char* effect) {
    const std::string svg = std::string(R"svg(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
        <path d="M 1 1 L 9 1" transform="scale(10 3)" fill="none" stroke="#000" stroke-width="2" )svg") +
                            effect + "/></svg>";
    svg::ReadOptions o;
    o.strokes_as_areas = true;
    const svg::FeatureSoup soup = svg::read_svg(svg, o);
    return soup.fills.at(0).bounds.height();
  };
  // Offset in user space then scaled by 3 vertically: 6; non-scaling: 2 in the root's units.
  EXPECT_NEAR(band_height(""), 6, 1e-12);
  EXPECT_NEAR(band_height(R"(vector-effect="non-scaling-stroke")"), 2, 1e-12);
}

// A stroke layer's width is where the transform draws it narrowest: its smaller singular value
// times stroke-width (scale(10 3): 3; a rotation changes nothing; a shear x' = x + y, whose
// singular values are the golden ratio and its inverse: 1/φ); non-scaling, stroke-width itself.
TEST(StrokeReader, AStrokeLayerKnowsItsNarrowestWidth) {
  const auto width = [](const std::string& attributes) {
    const std::string svg = R"svg(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
        <path d="M 1 1 L 9 1" fill="none" stroke="#000" stroke-width="2" )svg" + attributes + "/></svg>";
    svg::ReadOptions o;
    o.strokes_as_areas = true;
    return svg::read_svg(svg, o).fills.at(0).width;
  };
  EXPECT_NEAR(width(""), 2, 1e-12);
  EXPECT_NEAR(width(R"x(transform="scale(10 3)")x"), 6, 1e-12);
  EXPECT_NEAR(width(R"x(transform="rotate(30) scale(3)")x"), 6, 1e-12);
  EXPECT_NEAR(width(R"x(transform="matrix(1 0 1 1 0 0)")x"), 2 * (std::sqrt(5.0) - 1) / 2, 1e-12);
  EXPECT_NEAR(width(R"x(transform="scale(10 3)" vector-effect="non-scaling-stroke")x"), 2, 1e-12);
}

TEST(StrokeReader, StrokePropertiesParse) {
  svg::StrokeStyle s;
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-width", "3px", 100, s));
  EXPECT_EQ(s.width, 3);
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-width", "10%", 50, s));
  EXPECT_EQ(s.width, 5);
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-width", "-1", 50, s));
  EXPECT_EQ(s.width, 5);  // invalid: dropped
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-dasharray", "4, 2 1", 100, s));
  EXPECT_EQ(s.dashes, (std::vector<double>{4, 2, 1}));
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-dasharray", "none", 100, s));
  EXPECT_TRUE(s.dashes.empty());
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-linejoin", "round", 100, s));
  EXPECT_EQ(s.join, svg::LineJoin::round);
  EXPECT_TRUE(svg::apply_stroke_declaration("stroke-miterlimit", "0.5", 100, s));
  EXPECT_EQ(s.miter_limit, 4);  // below 1: invalid
  EXPECT_FALSE(svg::apply_stroke_declaration("fill", "red", 100, s));
}

}  // namespace
