// The ε-envelope test: exact cases at the border, and the property that matters — it never
// accepts a segment with a point farther than ε from the input, checked by brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "geometry/envelope.hpp"

namespace curvemesh::geometry {
namespace {

// Brute-force distance in long double, independent of the code under test.
long double distance_ld(const Vec2& p, const std::array<Vec2, 2>& s) {
  const long double ax = s[0].x(), ay = s[0].y(), bx = s[1].x(), by = s[1].y(), px = p.x(), py = p.y();
  const long double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
  long double t = len2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0;
  t = std::clamp(t, 0.0L, 1.0L);
  const long double ex = px - (ax + t * dx), ey = py - (ay + t * dy);
  return std::sqrt(ex * ex + ey * ey);
}

long double distance_to_union(const Vec2& p, const std::vector<std::array<Vec2, 2>>& segments) {
  long double d = INFINITY;
  for (const auto& s : segments) d = std::min(d, distance_ld(p, s));
  return d;
}

// A point of segment s, moved by up to 1.5ε in each coordinate: the ends of a query near the input.
template <class Rng>
Vec2 jittered_point_of(const std::array<Vec2, 2>& s, double eps, Rng& rng) {
  std::uniform_real_distribution<double> u(0, 1), n(-1, 1);
  return s[0] + u(rng) * (s[1] - s[0]) + 1.5 * eps * Vec2(n(rng), n(rng));
}

// The largest distance from segment ab to `segments`, over 1,001 points of it.
long double farthest_point(const Vec2& a, const Vec2& b, const std::vector<std::array<Vec2, 2>>& segments) {
  long double d = 0;
  for (int i = 0; i <= 1000; ++i) d = std::max(d, distance_to_union(a + (i / 1000.0) * (b - a), segments));
  return d;
}

TEST(Envelope, PointsAtTheBorder) {
  const SegmentEnvelope env({{Vec2(0, 0), Vec2(1, 0)}}, 0.01);
  EXPECT_TRUE(env.contains(Vec2(0.5, 0.009)));
  EXPECT_FALSE(env.contains(Vec2(0.5, 0.011)));
  EXPECT_TRUE(env.contains(Vec2(-0.009, 0)));   // around the end: a disc
  EXPECT_FALSE(env.contains(Vec2(-0.008, 0.008)));
  EXPECT_EQ(env.size(), 1u);
  EXPECT_EQ(env.epsilon(), 0.01);
}

TEST(Envelope, ParallelSegments) {
  const SegmentEnvelope env({{Vec2(0, 0), Vec2(1, 0)}}, 0.01);
  EXPECT_TRUE(env.contains(Vec2(0.1, 0.005), Vec2(0.9, 0.005)));
  EXPECT_FALSE(env.contains(Vec2(0.1, 0.0101), Vec2(0.9, 0.0101)));
  EXPECT_FALSE(env.contains(Vec2(0.1, 0.005), Vec2(0.9, 0.02)));  // ends inside, leaves on the way
  EXPECT_FALSE(env.contains(Vec2(0.5, 0), Vec2(1.2, 0)));
}

TEST(Envelope, ChordAcrossAPolylineCorner) {
  // Two segments meeting at a right angle at (1, 0).
  const SegmentEnvelope env({{Vec2(0, 0), Vec2(1, 0)}, {Vec2(1, 0), Vec2(1, 1)}}, 0.01);
  // Cutting the corner within ε: inside, though no single capsule holds it.
  EXPECT_TRUE(env.contains(Vec2(0.99, 0), Vec2(1, 0.01 - 0.0005)));
  EXPECT_TRUE(env.contains(Vec2(0.5, 0.003), Vec2(1.003, 0.5)) == false);  // the chord is far off at the corner
  EXPECT_TRUE(env.contains(Vec2(0.5, 0), Vec2(1.005, 0.004)));
  // Along both sides through the corner, slightly outside the corner: inside by bisection.
  EXPECT_TRUE(env.contains(Vec2(0.9, 0.002), Vec2(1.002, 0.002)) && env.contains(Vec2(1.002, 0.002), Vec2(1.002, 0.9)));
}

TEST(Envelope, EmptyAndZeroLength) {
  const SegmentEnvelope empty;
  EXPECT_FALSE(empty.contains(Vec2(0, 0)));
  EXPECT_FALSE(empty.contains(Vec2(0, 0), Vec2(0, 0)));
  const SegmentEnvelope none({}, 0.1);
  EXPECT_FALSE(none.contains(Vec2(0, 0)));
  const SegmentEnvelope dot({{Vec2(2, 2), Vec2(2, 2)}}, 0.1);
  EXPECT_TRUE(dot.contains(Vec2(2.05, 2), Vec2(2, 2.05)));
  EXPECT_FALSE(dot.contains(Vec2(2.11, 2)));
}

TEST(Envelope, CopiesAnswerTheSame) {
  const SegmentEnvelope env({{Vec2(0, 0), Vec2(1, 0)}, {Vec2(0, 1), Vec2(1, 1)}}, 0.05);
  const SegmentEnvelope copy = env;
  SegmentEnvelope moved;
  moved = SegmentEnvelope(env);
  for (double y : {0.0, 0.04, 0.06, 0.97, 1.2}) {
    EXPECT_EQ(copy.contains(Vec2(0.5, y)), env.contains(Vec2(0.5, y)));
    EXPECT_EQ(moved.contains(Vec2(0.5, y)), env.contains(Vec2(0.5, y)));
  }
}

// The certificate: whatever is accepted is inside, checked densely in higher precision.
TEST(Envelope, NeverAcceptsASegmentThatLeaves) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1), n(-1, 1);
  int accepted = 0, queries = 0;
  for (int round = 0; round < 200; ++round) {
    const double eps = 0.005 + 0.03 * u(rng);
    std::vector<std::array<Vec2, 2>> segs;
    Vec2 p(u(rng), u(rng));
    const int count = 1 + round % 12;
    for (int k = 0; k < count; ++k) {  // a random polyline, sometimes with jumps
      const Vec2 q = (k % 5 == 4) ? Vec2(u(rng), u(rng)) : Vec2(p + 0.2 * Vec2(n(rng), n(rng)));
      segs.push_back({p, q});
      p = q;
    }
    const SegmentEnvelope env(segs, eps);
    for (int k = 0; k < 50; ++k) {
      // Queries near the input: ends jittered around points of the segments.
      const auto& s1 = segs[rng() % segs.size()];
      const auto& s2 = segs[rng() % segs.size()];
      const Vec2 a = jittered_point_of(s1, eps, rng), b = jittered_point_of(s2, eps, rng);
      ++queries;
      if (!env.contains(a, b)) continue;
      ++accepted;
      ASSERT_LE(farthest_point(a, b, segs), eps) << "accepted a segment that leaves the envelope";
    }
  }
  EXPECT_GT(accepted, queries / 20);  // the test does exercise acceptance
}

// Two curves crossing at 3.8° come within ε of each other over 15ε around the crossing: a query
// along one of them is in the union's envelope, and in its own curve's alone.
TEST(Envelope, AGroupIsAnsweredByItsOwnSegments) {
  const double eps = 0.001, slope = std::tan(3.8 * M_PI / 180);
  const SegmentEnvelope env({{Vec2(-1, 0), Vec2(1, 0)}, {Vec2(-1, -slope), Vec2(1, slope)}}, eps, {0, 1});
  const Vec2 a(0.005, 0.005 * slope), b(0.2, 0.2 * slope);  // along curve 1, from 0.33ε to 13ε off curve 0
  EXPECT_TRUE(env.contains(a, b));
  EXPECT_TRUE(env.contains(a, b, 1));
  EXPECT_FALSE(env.contains(a, b, 0));
  EXPECT_TRUE(env.contains(a, 0));
  EXPECT_FALSE(env.contains(b, 0));
  EXPECT_TRUE(env.contains(Vec2(0.5, 0), Vec2(-0.5, 0), 0));
  EXPECT_THROW(SegmentEnvelope({{Vec2(0, 0), Vec2(1, 0)}}, eps, {0, 1}), std::invalid_argument);
}

// The property of NeverAcceptsASegmentThatLeaves for each group: what a group's query accepts is
// within ε of that group's segments (brute force), whatever the other groups' segments nearby.
TEST(Envelope, AGroupNeverAcceptsASegmentThatLeavesIt) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1), n(-1, 1);
  int accepted = 0, queries = 0;
  for (int round = 0; round < 100; ++round) {
    const double eps = 0.005 + 0.03 * u(rng);
    std::vector<std::array<Vec2, 2>> segs;
    std::vector<int> groups;
    for (int k = 0; k < 12; ++k) {
      const Vec2 p(u(rng), u(rng));
      segs.push_back({p, Vec2(p + 0.3 * Vec2(n(rng), n(rng)))});
      groups.push_back(k % 3);
    }
    const SegmentEnvelope env(segs, eps, groups);
    for (int k = 0; k < 60; ++k) {
      // Half the queries along one segment of the group asked about (most of them accepted), half
      // between any two segments (most not).
      const int group = k % 3;
      const std::size_t own_segment = 3 * (rng() % 4) + group;
      const auto& s1 = k % 2 ? segs[own_segment] : segs[rng() % segs.size()];
      const auto& s2 = k % 2 ? segs[own_segment] : segs[rng() % segs.size()];
      const Vec2 a = jittered_point_of(s1, eps, rng), b = jittered_point_of(s2, eps, rng);
      ++queries;
      if (!env.contains(a, b, group)) continue;
      ++accepted;
      std::vector<std::array<Vec2, 2>> own;
      for (std::size_t i = 0; i < segs.size(); ++i)
        if (groups[i] == group) own.push_back(segs[i]);
      ASSERT_LE(farthest_point(a, b, own), eps) << "accepted a segment that leaves its group";
    }
  }
  EXPECT_GT(accepted, queries / 10);
}

TEST(Envelope, SubSegmentsOfTheInputAreAlwaysAccepted) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<Vec2, 2>> segs;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 a(u(rng), u(rng));
    segs.push_back({a, a + 0.05 * Vec2(u(rng) - 0.5, u(rng) - 0.5)});
  }
  const SegmentEnvelope env(segs, 1e-3);
  for (const auto& s : segs) {
    const double t0 = 0.3 * u(rng), t1 = 1 - 0.3 * u(rng);
    EXPECT_TRUE(env.contains(s[0] + t0 * (s[1] - s[0]), s[0] + t1 * (s[1] - s[0])));
    EXPECT_TRUE(env.contains(s[0], s[1]));
  }
}

TEST(Envelope, ScaledCopiesGiveTheSameAnswers) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<Vec2, 2>> segs;
  for (int k = 0; k < 50; ++k) segs.push_back({Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))});
  std::vector<std::array<Vec2, 2>> queries;
  for (int k = 0; k < 500; ++k) {
    const auto& s = segs[k % segs.size()];
    queries.push_back({s[0] + 0.01 * Vec2(u(rng) - 0.5, u(rng) - 0.5), s[0] + u(rng) * (s[1] - s[0])});
  }
  const SegmentEnvelope base(segs, 0.004);
  for (double scale : {1e-6, 1e6}) {
    std::vector<std::array<Vec2, 2>> scaled;
    for (const auto& s : segs) scaled.push_back({s[0] * scale, s[1] * scale});
    const SegmentEnvelope env(scaled, 0.004 * scale);
    int differ = 0;
    for (const auto& q : queries) differ += env.contains(q[0] * scale, q[1] * scale) != base.contains(q[0], q[1]);
    EXPECT_EQ(differ, 0) << scale;
  }
}

}  // namespace
}  // namespace curvemesh::geometry
