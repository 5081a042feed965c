// Feature processing (paper §4) on small drawings whose answers are known, checked with dense
// sampling and brute force rather than with the stage's own bookkeeping.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "features/features.hpp"
#include "geometry/closest_point.hpp"
#include "pipeline/pipeline.hpp"
#include "round_off_path.hpp"
#include "tangent_junction.hpp"

using namespace curvemesh;
using features::Kind;
using geometry::CubicBezier;
using geometry::Vec2;

namespace {

constexpr double kPi = std::numbers::pi;

svg::FeatureSoup soup_of(const std::vector<CubicBezier>& curves) {
  svg::FeatureSoup s;
  for (const CubicBezier& c : curves) s.curves.push_back({c, 0, {}, {}, {}, {}});
  s.sources.push_back({"path", "", 0, 1});
  return s;
}

// The features stage through the pipeline: read (with the paper's ε_m) and processed with the
// paper's parameters, or `p`.
features::Features process(const svg::FeatureSoup& soup, const pipeline::Parameters& p = {}) {
  return pipeline::run(pipeline::Source::curves(soup), p, pipeline::Stage::features).features;
}

svg::FeatureSoup read_text(const std::string& text) {
  return pipeline::run(pipeline::Source::svg(text), {}, pipeline::Stage::read).soup;
}

svg::FeatureSoup read_file(const std::string& path) {
  return pipeline::run(pipeline::Source::file(path), {}, pipeline::Stage::read).soup;
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - a - s * ab).norm();
}

int count(const features::Features& f, Kind kind) {
  int n = 0;
  for (const auto& s : f.sections) n += s.kind == kind;
  return n;
}

std::string drawing(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' viewBox='0 0 100 100'>" + body + "</svg>";
}

}  // namespace

TEST(Features, ResamplingConditionsHoldByDenseSampling) {
  const auto soup = read_file(std::string(CURVEMESH_EXAMPLES) + "/open-curves.svg");
  const auto f = process(soup);
  const auto& L = f.lengths;
  int edges = 0;
  for (const auto& s : f.sections) {
    if (s.kind != Kind::primary) continue;
    const CubicBezier whole = s.straight ? s.piece : soup.curves[s.curve].bezier;
    for (std::size_t k = 0; k + 1 < s.ts.size(); ++k) {
      ++edges;
      const double t0 = s.straight ? (s.ts[k] - s.t0) / (s.t1 - s.t0) : s.ts[k];
      const double t1 = s.straight ? (s.ts[k + 1] - s.t0) / (s.t1 - s.t0) : s.ts[k + 1];
      const Vec2 a = s.polyline[k], b = s.polyline[k + 1];
      EXPECT_LE((b - a).norm(), L.edge * (1 + 1e-12));  // (1) at most l long
      double deviation = 0, turning = 0, prev = 0;
      for (int i = 0; i <= 400; ++i) {
        const double t = t0 + (t1 - t0) * i / 400;
        deviation = std::max(deviation, point_segment_distance(whole.eval(t), a, b));
        const Vec2 d = whole.derivative(t);
        const double angle = std::atan2(d.y(), d.x());
        if (i > 0) turning += std::abs(std::remainder(angle - prev, 2 * kPi));
        prev = angle;
      }
      EXPECT_LE(deviation, L.mu);                   // (2) within μ of its chord
      EXPECT_LE(turning, L.alpha_rad + 1e-9);       // (3) turns at most α
    }
  }
  EXPECT_GT(edges, 50);
}

TEST(Features, ParallelLinesCloserThanMuKeepOnePrimary) {
  // d ≈ 100√2; μ = 1e-3 d ≈ 0.141. Lines 0.05 apart: one must go; 1.0 apart: both stay.
  const auto close = process(soup_of({CubicBezier::line({0, 0}, {100, 0}),
                                                CubicBezier::line({0, 0.05}, {100, 0.05}),
                                                CubicBezier::line({0, 100}, {1, 100})}));
  EXPECT_EQ(count(close, Kind::primary), 2);  // one long line and the far short one
  const auto far = process(soup_of({CubicBezier::line({0, 0}, {100, 0}),
                                              CubicBezier::line({0, 1}, {100, 1}),
                                              CubicBezier::line({0, 100}, {1, 100})}));
  EXPECT_EQ(count(far, Kind::primary), 3);
  EXPECT_EQ(count(far, Kind::secondary), 0);
}

TEST(Features, JunctionRule) {
  // A right-angle corner shared exactly: both primary. A 5° wedge: the pieces at the tip clash.
  const auto corner = process(
      soup_of({CubicBezier::line({0, 0}, {100, 0}), CubicBezier::line({0, 0}, {0, 100})}));
  EXPECT_EQ(count(corner, Kind::secondary), 0);
  const double a = 5 * kPi / 180;
  const auto wedge = process(soup_of(
      {CubicBezier::line({0, 0}, {100, 0}), CubicBezier::line({0, 0}, {100 * std::cos(a), 100 * std::sin(a)})}));
  EXPECT_GE(count(wedge, Kind::secondary), 1);
  // Only near the tip: far from it the wedge's sides are more than μ apart.
  for (const auto& s : wedge.sections) {
    if (s.kind != Kind::secondary) continue;
    for (const Vec2& v : s.polyline) EXPECT_LT(v.norm(), 20.0);
  }
}

// With strokes as areas, two straight sections crossing at the junction angle or more both stay
// primary all along (a band's sides cross wherever two strokes do); as lines, the paper's rule
// leaves the piece at the crossing secondary. Below the angle, where a line stops short of
// another without crossing it, and where it stops just past it, a piece is still secondary.
TEST(Features, StraightSectionsCrossingStayPrimaryWithStrokesAsAreas) {
  pipeline::Parameters areas;
  areas.strokes = Strokes::areas;
  const auto crossing = [](double degrees, double reach) {
    const double a = degrees * kPi / 180;
    const Vec2 c(50, 50), u(std::cos(a), std::sin(a));
    return soup_of({CubicBezier::line({0, 50}, {100, 50}), CubicBezier::line(c - 40 * u, c + reach * u)});
  };
  const auto primary_length = [](const features::Features& f) {
    double length = 0;
    for (const auto& s : f.sections)
      if (s.kind == Kind::primary)
        for (std::size_t k = 0; k + 1 < s.polyline.size(); ++k) length += (s.polyline[k + 1] - s.polyline[k]).norm();
    return length;
  };
  const auto x30 = crossing(30, 40);
  EXPECT_EQ(count(process(x30, areas), Kind::secondary), 0);
  EXPECT_NEAR(primary_length(process(x30, areas)), 180.0, 1e-9);
  EXPECT_GE(count(process(x30), Kind::secondary), 1);
  EXPECT_GE(count(process(crossing(5, 40), areas), Kind::secondary), 1);
  // Ending μ/2 before the horizontal line (μ ≈ 0.141): no crossing, a sliver if both stayed.
  const double short_of = 0.07 / std::sin(30 * kPi / 180);
  EXPECT_GE(count(process(crossing(30, -short_of), areas), Kind::secondary), 1);
  // Crossing it and stopping μ/3 past it: a stub no edge could be.
  EXPECT_GE(count(process(crossing(30, 0.05), areas), Kind::secondary), 1);
  // A third line through the same point: the crossings coincide, and a piece must go.
  svg::FeatureSoup three = crossing(30, 45);
  three.curves.push_back(three.curves[1]);
  three.curves.back().bezier = CubicBezier::line({50, 0}, {50, 100});
  EXPECT_GE(count(process(three, areas), Kind::secondary), 1);
  // Further apart than μ, three crossings are each an X of their own (each well away from the
  // even cuts of the three lines into pieces: 15 of 6.67, 15 of 6.67 and 13 of 6.54).
  three.curves.back().bezier = CubicBezier::line({63, 0}, {63, 100});
  EXPECT_EQ(count(process(three, areas), Kind::secondary), 0);
}

// A straight curve is cut into pieces at even steps, blind to what crosses it. Here the vertical
// line is cut into 10 pieces of 5.6, the middle cut 0.01 past the horizontal line (μ ≈ 0.11): the
// cut is moved to the middle of the longer side, and the X stays primary. Where the moved cut
// lands within μ of another crossing, that one is a conflict (the cut and the crossing would be
// two vertices 0.01 apart), and a piece goes secondary, as the paper's rule has it.
TEST(Features, ACutOfAStraightCurveOnACrossingIsMovedOffIt) {
  pipeline::Parameters areas;
  areas.strokes = Strokes::areas;
  const auto cross_at = [](double cut_past) {
    return soup_of({CubicBezier::line({0, 50}, {100, 50}),
                    CubicBezier::line({60, 22 + cut_past}, {60, 78 + cut_past})});
  };
  const features::Features moved = process(cross_at(0.01), areas);
  EXPECT_EQ(count(moved, Kind::secondary), 0);
  double vertical = 0;  // the vertical line's primary sections still cover it, cut where they meet
  for (const auto& s : moved.sections)
    if (s.kind == Kind::primary && s.polyline.front().x() == 60)
      for (std::size_t k = 0; k + 1 < s.polyline.size(); ++k) {
        vertical += (s.polyline[k + 1] - s.polyline[k]).norm();
        if (k > 0) {
          EXPECT_GT(std::abs(s.polyline[k].y() - 50), 1.0);
        }
      }
  EXPECT_NEAR(vertical, 56, 1e-9);
  EXPECT_EQ(count(process(cross_at(2.8), areas), Kind::secondary), 0);
  // The cut moves to 52.805 (between 50 and the piece's end, 55.61); a line crossing there.
  svg::FeatureSoup two = cross_at(0.01);
  two.curves.push_back(two.curves[0]);
  two.curves.back().bezier = CubicBezier::line({0, 52.815}, {100, 52.815});
  EXPECT_GE(count(process(two, areas), Kind::secondary), 1);
}

namespace {

// The drawing of tangent_junction.hpp as a soup of cubics.
svg::FeatureSoup tangent_junction(double degrees) {
  std::vector<CubicBezier> curves;
  for (const auto& c : testing_support::tangent_junction(degrees)) curves.emplace_back(c[0], c[1], c[2], c[3]);
  return soup_of(curves);
}

}  // namespace

TEST(Features, JunctionRuleAppliesToTheCurvesTangents) {
  const auto f = process(tangent_junction(4));
  // The polyline edges at (0, 0), whatever their kind, and whether they are primary.
  std::vector<Vec2> chords;
  int primary = 0;
  for (const auto& s : f.sections) {
    if (s.curve > 1) continue;
    if (s.polyline.front() == Vec2(0, 0)) chords.push_back(s.polyline[1]), primary += s.kind == Kind::primary;
    if (s.polyline.back() == Vec2(0, 0)) chords.push_back(s.polyline[s.polyline.size() - 2]), primary += s.kind == Kind::primary;
  }
  ASSERT_EQ(chords.size(), 2u);
  // The chords alone would pass the rule: they meet at more than the junction angle...
  const Vec2 u = chords[0].normalized(), v = chords[1].normalized();
  EXPECT_GT(std::acos(std::clamp(u.dot(v), -1.0, 1.0)), f.lengths.junction_angle_rad);
  // ...but curved edges would leave (0, 0) at 4°: one of the two is secondary there.
  EXPECT_EQ(primary, 1);
  // Where the arcs' tangents open wider than the junction angle, both stay primary.
  const auto wide = process(tangent_junction(12));
  EXPECT_EQ(count(wide, Kind::secondary), 0);
}

TEST(Features, CrossingCurvesLoseOnlyTheCrossing) {
  // Two crossing lines: near the crossing one of them is secondary, the rest is primary.
  const auto f = process(
      soup_of({CubicBezier::line({0, 50}, {100, 50}), CubicBezier::line({50, 0}, {50, 100})}));
  double secondary_length = 0, primary_length = 0;
  for (const auto& s : f.sections)
    for (std::size_t k = 0; k + 1 < s.polyline.size(); ++k)
      (s.kind == Kind::primary ? primary_length : secondary_length) += (s.polyline[k + 1] - s.polyline[k]).norm();
  EXPECT_GT(secondary_length, 0);
  EXPECT_LE(secondary_length, 2 * f.lengths.edge + 1e-9);
  EXPECT_NEAR(primary_length + secondary_length, 200, 1e-9);
}

TEST(Features, SecondaryStaysWithinEpsilon) {
  // A dense bundle of nearly overlapping wiggles: most of it is secondary and simplified.
  std::vector<CubicBezier> curves;
  for (int i = 0; i < 20; ++i) {
    const double y = 50 + 0.01 * i;
    curves.push_back({{0, y}, {30, y + 20}, {70, y - 20}, {100, y}});
  }
  curves.push_back(CubicBezier::line({0, 0}, {100, 100}));
  const auto soup = soup_of(curves);
  const auto f = process(soup);
  ASSERT_FALSE(f.segments.empty());
  for (const auto& seg : f.segments) {
    const CubicBezier& c = soup.curves[seg.curve].bezier;
    for (int i = 0; i <= 10; ++i) {
      const Vec2 p = seg.a + (seg.b - seg.a) * (i / 10.0);
      EXPECT_LE(geometry::closest_point(c, p).distance, f.lengths.epsilon);
    }
  }
}

TEST(Features, WithoutFeaturesEveryCurveIsSecondaryAndKeptWithinEpsilon) {
  // Crossing curves that would be primary almost everywhere: with --no-features none is, and
  // every point of every curve is within ε of a segment standing for that curve, and back.
  const auto soup = soup_of({{{0, 0}, {30, 80}, {70, -40}, {100, 50}},
                             CubicBezier::line({0, 50}, {100, 50}),
                             {{50, 0}, {0, 40}, {100, 60}, {50, 100}}});
  pipeline::Parameters p;
  p.features = false;
  const auto f = process(soup, p);
  EXPECT_GT(count(process(soup), Kind::primary), 0);
  EXPECT_EQ(count(f, Kind::primary), 0);
  ASSERT_FALSE(f.segments.empty());
  for (int c = 0; c < static_cast<int>(soup.curves.size()); ++c) {
    const CubicBezier& curve = soup.curves[c].bezier;
    for (int i = 0; i <= 200; ++i) {
      const Vec2 q = curve.eval(i / 200.0);
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& seg : f.segments)
        if (seg.curve == c) nearest = std::min(nearest, point_segment_distance(q, seg.a, seg.b));
      EXPECT_LE(nearest, f.lengths.epsilon) << "curve " << c << " at t = " << i / 200.0;
    }
  }
  for (const auto& seg : f.segments)
    for (int i = 0; i <= 10; ++i)
      EXPECT_LE(geometry::closest_point(soup.curves[seg.curve].bezier, seg.a + (seg.b - seg.a) * (i / 10.0)).distance,
                f.lengths.epsilon);
}

// With ε = μ no secondary end may move (ε − μ is how far one may): thousands of short curves in a
// drawing a few units wide are kept where they are, and their ends are not paired with one another
// (in cells of no size, every end would meet every other, beyond the limit on such pairs).
TEST(Features, NoEndMovesWhenEpsilonIsMu) {
  std::vector<CubicBezier> dashes;
  for (int i = 0; i < 80; ++i)
    for (int j = 0; j < 80; ++j) dashes.push_back(CubicBezier::line({0.025 * i, 0.025 * j}, {0.025 * i + 0.01, 0.025 * j}));
  const svg::FeatureSoup soup = soup_of(dashes);
  pipeline::Parameters p;
  p.features = false;
  p.epsilon_rel = p.mu_rel;
  p.limits.max_triangles = 1000;  // 8,000 pairs of ends allowed: all 12,800 ends in a few cells are 10^8
  const auto f = process(soup, p);
  ASSERT_GE(f.segments.size(), dashes.size());
  for (const auto& seg : f.segments)
    for (const Vec2& end : {seg.a, seg.b})
      EXPECT_EQ(geometry::closest_point(soup.curves[seg.curve].bezier, end).distance, 0.0) << end.transpose();
}

TEST(Features, DegenerateAndStraightCurves) {
  const auto f = process(soup_of({CubicBezier::line({0, 0}, {100, 100}),
                                            CubicBezier({50, 10}, {50 + 1e-12, 10}, {50, 10}, {50, 10}),
                                            CubicBezier({0, 90}, {30, 90 + 1e-12}, {60, 90}, {90, 90}),
                                            CubicBezier({0, 0}, {0, 50}, {50, 100}, {100, 100})}));
  EXPECT_EQ(f.degenerate_curves, 1);
  EXPECT_EQ(f.straight_curves, 2);
  ASSERT_EQ(f.points.size(), 1u);
  EXPECT_NEAR((f.points[0].p - Vec2(50, 10)).norm(), 0, 1e-9);
}

TEST(Features, IsolatedPointsNearPrimaryFeaturesAreAbsorbed) {
  auto soup = soup_of({CubicBezier::line({0, 0}, {100, 0})});
  soup.points.push_back({Vec2(50, 0.01), 0});  // within μ of the line
  soup.points.push_back({Vec2(50, 50), 0});    // far from everything
  soup.points.push_back({Vec2(50, 50.01), 0});  // within μ of the previous point
  const auto f = process(soup);
  ASSERT_EQ(f.points.size(), 1u);
  EXPECT_EQ(f.points[0].p, Vec2(50, 50));
}

TEST(Features, DeterministicAndScaleInvariant) {
  const std::string text = drawing(
      "<path d='M10 10 C 40 90 60 -20 90 50 S 20 80 10 10'/><circle cx='50' cy='50' r='30'/>"
      "<path d='M0 50 L 100 50 M 50 0 L 50 100'/>");
  const auto a = process(read_text(text));
  const auto b = process(read_text(text));
  ASSERT_EQ(a.sections.size(), b.sections.size());
  for (std::size_t i = 0; i < a.sections.size(); ++i) EXPECT_EQ(a.sections[i].polyline, b.sections[i].polyline);
  // The same drawing scaled by 1e-6 and 1e6 gives the same kinds and counts.
  for (const char* scale : {"1e-6", "1e6"}) {
    const auto s = process(
        read_text("<svg><g transform='scale(" + std::string(scale) + ")'>" + text + "</g></svg>"));
    ASSERT_EQ(s.sections.size(), a.sections.size()) << scale;
    for (std::size_t i = 0; i < a.sections.size(); ++i) {
      EXPECT_EQ(s.sections[i].kind, a.sections[i].kind);
      EXPECT_EQ(s.sections[i].polyline.size(), a.sections[i].polyline.size());
    }
  }
}

TEST(Features, CurvesTooTightForAPrimaryEdgeOfLengthLmAreSecondary) {
  // A primary edge turns at most α and is at least l_m long, so curvature above α / l_m cannot be
  // primary. d ≈ 100√2, l_m = 1e-4 d ≈ 0.0141, α / l_m ≈ 12.3; μ = 1e-5 d is small enough for
  // the circles to be μ-separated and large enough not to force pieces shorter than l_m. A circle
  // of radius 0.05 (curvature 20) is secondary; one of radius 0.2 (curvature 5) is primary.
  pipeline::Parameters options;
  options.mu_rel = 1e-5;
  options.epsilon_rel = 2e-5;
  const auto circle = [](Vec2 c, double r) {
    const double k = 0.5522847498 * r;
    return std::vector<CubicBezier>{{c + Vec2(r, 0), c + Vec2(r, k), c + Vec2(k, r), c + Vec2(0, r)},
                                    {c + Vec2(0, r), c + Vec2(-k, r), c + Vec2(-r, k), c + Vec2(-r, 0)},
                                    {c + Vec2(-r, 0), c + Vec2(-r, -k), c + Vec2(-k, -r), c + Vec2(0, -r)},
                                    {c + Vec2(0, -r), c + Vec2(k, -r), c + Vec2(r, -k), c + Vec2(r, 0)}};
  };
  std::vector<CubicBezier> curves{CubicBezier::line({0, 0}, {100, 100})};
  for (const auto& c : circle({20, 80}, 0.05)) curves.push_back(c);
  for (const auto& c : circle({80, 20}, 0.2)) curves.push_back(c);
  const auto f = process(soup_of(curves), options);
  ASSERT_NEAR(f.lengths.alpha_rad / f.lengths.min_edge, 12.3, 0.1);
  for (const auto& s : f.sections) {
    if (s.curve == 0) continue;
    EXPECT_EQ(s.kind, s.curve <= 4 ? Kind::secondary : Kind::primary) << "curve " << s.curve;
  }
}

TEST(Features, CurvesThatFoldBackKeepNoSliverBetweenPrimaryPieces) {
  // Closed cubics that go out and come back along nearly the same line (as drawn in the wild:
  // P0 = P3, inner control points nearly collinear with it), and a cubic with a true cusp. The
  // pieces on the way out and on the way back are close along the curve, but fold back: no two
  // primary pieces of such a curve that touch may meet at less than the junction angle, and two
  // that point opposite ways must be at least μ apart, however close they are along the curve.
  const std::vector<std::array<Vec2, 4>> shapes{{Vec2(0, 0), Vec2(-1.606, -1.235), Vec2(-1.916, -1.473), Vec2(0, 0)},
                                                {Vec2(0, 0), Vec2(-1.606, -1.235), Vec2(-1.916, -1.373), Vec2(0, 0)},
                                                {Vec2(0, 0), Vec2(1, 1), Vec2(0, 1), Vec2(1, 0)}};
  for (const auto& shape : shapes) for (const double s : {5.0, 10.0, 20.0, 37.0}) {
    const CubicBezier curve(s * shape[0], s * shape[1], s * shape[2], s * shape[3]);
    const auto soup = soup_of({curve, CubicBezier::line({-100, -100}, {100, 100})});
    const auto f = process(soup);
    std::vector<std::pair<Vec2, Vec2>> edges;
    for (const auto& sec : f.sections)
      if (sec.kind == Kind::primary && sec.curve == 0)
        for (std::size_t k = 0; k + 1 < sec.polyline.size(); ++k) edges.push_back({sec.polyline[k], sec.polyline[k + 1]});
    ASSERT_FALSE(edges.empty());
    int touching = 0;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      for (std::size_t j = i + 1; j < edges.size(); ++j) {
        for (const auto& [p, p_far] : {edges[i], std::pair{edges[i].second, edges[i].first}}) {
          for (const auto& [q, q_far] : {edges[j], std::pair{edges[j].second, edges[j].first}}) {
            if (p != q) continue;
            ++touching;
            const Vec2 u = (p_far - p).normalized(), v = (q_far - q).normalized();
            EXPECT_GE(std::acos(std::clamp(u.dot(v), -1.0, 1.0)), f.lengths.junction_angle_rad - 1e-9)
                << "scale " << s << " at " << p.transpose();
          }
        }
      }
    }
    EXPECT_GT(touching, 0);
    for (const auto& [a, b] : edges) {
      for (const auto& [c, e] : edges) {
        if (a == c || a == e || b == c || b == e || (b - a).dot(e - c) > 0) continue;
        const double gap = std::min({point_segment_distance(a, c, e), point_segment_distance(b, c, e),
                                     point_segment_distance(c, a, b), point_segment_distance(e, a, b)});
        EXPECT_GE(gap, f.lengths.mu * (1 - 1e-9)) << "scale " << s << " at " << a.transpose();
      }
    }
  }
}

TEST(Features, PiecesShorterThanTheMinimalEdgeLengthAreSecondary) {
  // d ≈ 100√2, l_m = 1e-4 d ≈ 0.0141: a segment of length 0.01 (straight or a gentle cubic)
  // cannot be a primary edge; one of length 0.02 can. μ is made small so that only the length
  // decides.
  pipeline::Parameters options;
  options.mu_rel = 1e-6;
  options.epsilon_rel = 2e-6;
  for (const double length : {0.01, 0.02}) {
    const auto f = process(
        soup_of({CubicBezier::line({0, 0}, {100, 100}), CubicBezier::line({50, 20}, {50 + length, 20}),
                 CubicBezier({20, 50}, {20 + length / 3, 50 + length / 1000},
                             {20 + 2 * length / 3, 50 + length / 1000}, {20 + length, 50})}),
        options);
    ASSERT_LT(f.lengths.min_edge, 0.02);
    ASSERT_GT(f.lengths.min_edge, 0.01);
    for (const auto& s : f.sections) {
      if (s.curve == 0) continue;
      EXPECT_EQ(s.kind, length < f.lengths.min_edge ? Kind::secondary : Kind::primary) << length;
    }
  }
}

TEST(Features, TheCubicsOfOneArcAreOneCurve) {
  // A circle is 36 cubics (9 a quarter, to stay within 1e-9 of it). Where they are shorter than μ
  // (d = 100√2, μ ≈ 0.14: a 10° piece of radius 0.5 is 0.087 long), the pieces of two of them
  // one apart come within μ of each other; they are one curve, whose pieces within π/2·μ of one
  // another along it may come that close — around its start too — and every piece stays primary.
  for (const double r : {5.0, 1.0, 0.5, 0.3, 0.2}) {
    const auto f = process(read_text(drawing("<rect width='100' height='100'/><circle cx='50' cy='50' r='" +
                                             std::to_string(r) + "'/>")));
    EXPECT_EQ(count(f, Kind::secondary), 0) << r;
    EXPECT_TRUE(f.segments.empty()) << r;
    EXPECT_EQ(count(f, Kind::primary), 4 + 36) << r;
  }
}

TEST(Features, AClosedPathComingBackToItsStartWithinRoundOffIsOnePrimaryOutline) {
  // Its relative coordinates sum back to the start only to 7e-15: the reader closes it exactly
  // (no degenerate closing line, no curve ending beside the first), and the curves that meet
  // there keep their primary pieces.
  const std::string d = std::string(testing_support::kClosingWithinRoundOff) + "z";
  const auto f = process(read_text("<svg xmlns='http://www.w3.org/2000/svg'><path d='" + d + "'/></svg>"));
  EXPECT_EQ(f.degenerate_curves, 0);
  EXPECT_EQ(count(f, Kind::secondary), 0);
  EXPECT_TRUE(f.segments.empty());
  EXPECT_TRUE(f.points.empty());
}
