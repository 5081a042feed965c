// The path data grammar: each command, each number form, implicit repeats, errors.
#include <gtest/gtest.h>

#include <cmath>

#include "svg/arc.hpp"
#include "svg/error.hpp"
#include "svg/numbers.hpp"
#include "svg/path_data.hpp"

using namespace curvemesh::svg;
using curvemesh::geometry::CubicBezier;
using curvemesh::geometry::Vec2;

namespace {

void expect_cubic(const CubicBezier& c, Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, double tol = 1e-12) {
  const Vec2 want[4] = {p0, p1, p2, p3};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(c.p[i].x(), want[i].x(), tol) << "control point " << i;
    EXPECT_NEAR(c.p[i].y(), want[i].y(), tol) << "control point " << i;
  }
}

void expect_line(const CubicBezier& c, Vec2 a, Vec2 b) {
  expect_cubic(c, a, a + (b - a) / 3.0, a + 2.0 * (b - a) / 3.0, b);
}

std::vector<CubicBezier> segments(const std::string& d) {
  std::vector<CubicBezier> all;
  for (const Subpath& sp : parse_path_data(d)) all.insert(all.end(), sp.segments.begin(), sp.segments.end());
  return all;
}

}  // namespace

TEST(Numbers, Forms) {
  NumberScanner in("1e-5 .5.5-1-2,+3 1.5E3 7. 0.0e+0 10e1 2e 3");
  for (double want : {1e-5, 0.5, 0.5, -1.0, -2.0, 3.0, 1500.0, 7.0, 0.0, 100.0}) {
    in.skip_separator();
    EXPECT_DOUBLE_EQ(in.number(), want);
  }
  // "2e" is the number 2 followed by the letter e (which then is not a number).
  in.skip_separator();
  EXPECT_DOUBLE_EQ(in.number(), 2.0);
  EXPECT_EQ(in.peek(), 'e');
}

TEST(Numbers, Errors) {
  EXPECT_THROW(NumberScanner("nan").number(), SyntaxError);
  EXPECT_THROW(NumberScanner("-Infinity").number(), SyntaxError);
  EXPECT_TRUE([] {
    try {
      NumberScanner("inf").number();
    } catch (const SyntaxError& e) {
      return e.non_finite();
    }
    return false;
  }());
  EXPECT_THROW(NumberScanner("1e999").number(), SyntaxError);
  NumberScanner hex("0x10");  // no hex: the number 0, then an 'x'
  EXPECT_DOUBLE_EQ(hex.number(), 0.0);
  EXPECT_EQ(hex.peek(), 'x');
  EXPECT_THROW(NumberScanner(".").number(), SyntaxError);
  EXPECT_THROW(NumberScanner("-").number(), SyntaxError);
  EXPECT_THROW(NumberScanner("").number(), SyntaxError);
  EXPECT_DOUBLE_EQ(NumberScanner("1e-400").number(), 0.0);  // underflow is zero, as in browsers
}

TEST(Numbers, WithUnits) {
  std::string_view unit;
  EXPECT_DOUBLE_EQ(*parse_number_with_unit(" 10px ", &unit), 10.0);
  EXPECT_EQ(unit, "px");
  EXPECT_DOUBLE_EQ(*parse_number_with_unit("1e2%", &unit), 100.0);
  EXPECT_EQ(unit, "%");
  EXPECT_DOUBLE_EQ(*parse_number_with_unit("3em", &unit), 3.0);
  EXPECT_EQ(unit, "em");
  EXPECT_FALSE(parse_number_with_unit("auto", &unit));
  EXPECT_THROW(parse_number_with_unit("NaN", &unit), SyntaxError);
  EXPECT_THROW(parse_number_with_unit("1e999px", &unit), SyntaxError);
}

TEST(PathData, MoveLineAbsoluteAndRelative) {
  const auto s = segments("M 10 20 L 30 40 l 5 -5 H 0 h 2 V 3 v -1");
  ASSERT_EQ(s.size(), 6u);
  expect_line(s[0], {10, 20}, {30, 40});
  expect_line(s[1], {30, 40}, {35, 35});
  expect_line(s[2], {35, 35}, {0, 35});
  expect_line(s[3], {0, 35}, {2, 35});
  expect_line(s[4], {2, 35}, {2, 3});
  expect_line(s[5], {2, 3}, {2, 2});
}

TEST(PathData, ImplicitRepeats) {
  // After M the extra pairs are L; after m they are l.
  auto s = segments("M0 0 1 0 1 1");
  ASSERT_EQ(s.size(), 2u);
  expect_line(s[1], {1, 0}, {1, 1});
  s = segments("m1 1 1 0 0 1");
  ASSERT_EQ(s.size(), 2u);
  expect_line(s[0], {1, 1}, {2, 1});
  expect_line(s[1], {2, 1}, {2, 2});
  s = segments("M0 0 C 1 0 2 0 3 0 4 1 5 1 6 1");
  ASSERT_EQ(s.size(), 2u);
  expect_cubic(s[1], {3, 0}, {4, 1}, {5, 1}, {6, 1});
  s = segments("M0 0 h1 2 3");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[2].p[3], Vec2(6, 0));
}

TEST(PathData, CubicsAndSmoothReflection) {
  const auto s = segments("M0 0 C 1 2 3 4 5 6 S 9 10 11 12 s 1 1 2 0 c 1 0 1 1 0 1");
  ASSERT_EQ(s.size(), 4u);
  expect_cubic(s[0], {0, 0}, {1, 2}, {3, 4}, {5, 6});
  expect_cubic(s[1], {5, 6}, {7, 8}, {9, 10}, {11, 12});          // reflection of (3,4) about (5,6)
  expect_cubic(s[2], {11, 12}, {13, 14}, {12, 13}, {13, 12});     // reflection of (9,10) about (11,12)
  expect_cubic(s[3], {13, 12}, {14, 12}, {14, 13}, {13, 13});
  // S after a non-cubic command: the first control point is the current point.
  const auto t = segments("M0 0 L 1 0 S 2 1 3 0");
  expect_cubic(t[1], {1, 0}, {1, 0}, {2, 1}, {3, 0});
}

TEST(PathData, QuadraticsAreElevatedExactly) {
  const auto s = segments("M0 0 Q 3 3 6 0 T 12 0 t 6 0 q 0 3 3 3");
  ASSERT_EQ(s.size(), 4u);
  expect_cubic(s[0], {0, 0}, {2, 2}, {4, 2}, {6, 0});
  // T reflects the previous quadratic control (3,3) about (6,0): (9,-3).
  expect_cubic(s[1], {6, 0}, {8, -2}, {10, -2}, {12, 0});
  // t reflects (9,-3) about (12,0): (15,3).
  expect_cubic(s[2], {12, 0}, {14, 2}, {16, 2}, {18, 0});
  expect_cubic(s[3], {18, 0}, {18, 2}, {19, 3}, {21, 3});
  // The elevated cubic is the same curve: compare with the quadratic at many t.
  for (double t = 0; t <= 1; t += 0.125) {
    const Vec2 q = (1 - t) * (1 - t) * Vec2(0, 0) + 2 * t * (1 - t) * Vec2(3, 3) + t * t * Vec2(6, 0);
    EXPECT_NEAR((s[0].eval(t) - q).norm(), 0.0, 1e-14);
  }
  // T after a non-quadratic command: the control point is the current point (a line).
  const auto u = segments("M0 0 T 3 0");
  expect_cubic(u[0], {0, 0}, {0, 0}, {1, 0}, {3, 0});
}

TEST(PathData, CloseAndSubpaths) {
  const auto sps = parse_path_data("M0 0 L 1 0 L 1 1 Z l 2 2 M 5 5 L 6 5 z m 1 1 L 7 7");
  ASSERT_EQ(sps.size(), 4u);
  EXPECT_TRUE(sps[0].closed);
  ASSERT_EQ(sps[0].segments.size(), 3u);  // the closing segment is added
  expect_line(sps[0].segments[2], {1, 1}, {0, 0});
  // A command after Z without M starts a new subpath at the old start.
  EXPECT_EQ(sps[1].start, Vec2(0, 0));
  expect_line(sps[1].segments[0], {0, 0}, {2, 2});
  EXPECT_TRUE(sps[2].closed);
  // m after z is relative to the closed subpath's start (5,5).
  EXPECT_EQ(sps[3].start, Vec2(6, 6));
  // Z at the start point adds nothing.
  EXPECT_EQ(parse_path_data("M0 0 L1 0 L0 0 Z")[0].segments.size(), 2u);
}

TEST(PathData, LoneMovetoAndEmpty) {
  EXPECT_TRUE(parse_path_data("").empty());
  EXPECT_TRUE(parse_path_data("  \n ").empty());
  const auto sps = parse_path_data("M 3 4");
  ASSERT_EQ(sps.size(), 1u);
  EXPECT_TRUE(sps[0].segments.empty());
  EXPECT_EQ(sps[0].start, Vec2(3, 4));
  EXPECT_EQ(parse_path_data("M1 1 M2 2 L 3 3").size(), 2u);
}

TEST(PathData, PackedNumberForms) {
  auto s = segments("M0,0L10,10z");
  ASSERT_EQ(s.size(), 2u);
  expect_line(s[0], {0, 0}, {10, 10});
  s = segments("m0 0l1-2.5.5.5");
  ASSERT_EQ(s.size(), 2u);
  expect_line(s[0], {0, 0}, {1, -2.5});
  expect_line(s[1], {1, -2.5}, {1.5, -2});
  s = segments("M1e1-1E-1L+2 .2e1");
  expect_line(s[0], {10, -0.1}, {2, 2});
}

TEST(PathData, ArcsWithPackedFlags) {
  // "a1 1 0 011 1": rx 1, ry 1, rotation 0, large 0, sweep 1, to (+1, +1).
  const auto s = segments("M0 0 a1 1 0 011 1");
  ASSERT_EQ(s.size(), 9u);  // a quarter circle, in arc_piece_count(π/2) pieces
  EXPECT_EQ(s.back().p[3], Vec2(1, 1));
  // The same arc with separators.
  const auto t = segments("M0 0 a 1 1 0 0 1 1 1");
  ASSERT_EQ(t.size(), s.size());
  for (std::size_t k = 0; k < s.size(); ++k)
    for (int i = 0; i < 4; ++i) EXPECT_EQ(s[k].p[i], t[k].p[i]);
  // sweep=1 (clockwise on screen) from (0,0) to (1,1) with r=1: the centre is (0,1).
  for (const CubicBezier& c : s) EXPECT_NEAR((c.eval(0.5) - Vec2(0, 1)).norm(), 1.0, kArcTolerance);
  // The pieces after the first continue it, as one arc.
  const std::vector<Subpath> sub = parse_path_data("M0 0 L 0 -1 M0 0 a1 1 0 011 1 l 1 0");
  ASSERT_EQ(sub.size(), 2u);
  ASSERT_EQ(sub[1].segments.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k) EXPECT_EQ(sub[1].continues_at(k), k >= 1 && k < 9) << k;
  EXPECT_FALSE(sub[0].continues_at(0));
}

TEST(PathData, Errors) {
  auto offset_of = [](const std::string& d) -> long {
    try {
      parse_path_data(d);
    } catch (const SyntaxError& e) {
      return static_cast<long>(e.offset());
    }
    return -1;
  };
  EXPECT_EQ(offset_of("M 0 0 X 1 1"), 6);    // unknown command
  EXPECT_EQ(offset_of("L 1 1"), 0);          // does not start with a moveto
  EXPECT_EQ(offset_of("M 0 0 L 1 # 2"), 10);  // garbage
  EXPECT_EQ(offset_of("M 0 0 Z 1 1"), 8);     // numbers after Z
  EXPECT_GE(offset_of("M 0 0 a 1 1 0 2 1 3 3"), 0);  // a flag must be 0 or 1
  EXPECT_GE(offset_of("M 0 0 L 1e999 0"), 0);
  EXPECT_GE(offset_of("M 0 0 L NaN 0"), 0);
  EXPECT_GE(offset_of("M 0 0 L 5"), 0);  // truncated: strict mode throws
  EXPECT_EQ(segments("M 0 0 L 1..2")[0].p[3], Vec2(1, 0.2));  // "1." then ".2"
  // Truncated data is drawn up to the incomplete command when the caller allows it.
  bool truncated = false;
  const auto sps = parse_path_data("M 0 0 L 5 5 L 6", &truncated);
  EXPECT_TRUE(truncated);
  ASSERT_EQ(sps.size(), 1u);
  EXPECT_EQ(sps[0].segments.size(), 1u);
  // Malformed data is never "truncated".
  EXPECT_THROW(parse_path_data("M 0 0 L 5 5 K 6", &truncated), SyntaxError);
  EXPECT_THROW(parse_path_data("M 0 0 L 5 5 L 6 NaN", &truncated), SyntaxError);
}
