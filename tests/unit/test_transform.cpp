#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "svg/error.hpp"
#include "svg/transform.hpp"

using namespace curvemesh::svg;
using curvemesh::geometry::Vec2;

namespace {
void expect_maps(const Affine& t, Vec2 from, Vec2 to, double tol = 1e-12) {
  const Vec2 got = t.apply(from);
  EXPECT_NEAR(got.x(), to.x(), tol) << "x of (" << from.x() << "," << from.y() << ")";
  EXPECT_NEAR(got.y(), to.y(), tol) << "y of (" << from.x() << "," << from.y() << ")";
}
}  // namespace

TEST(Transform, EachFunction) {
  expect_maps(parse_transform("translate(10)"), {1, 2}, {11, 2});
  expect_maps(parse_transform("translate(10 -5)"), {1, 2}, {11, -3});
  expect_maps(parse_transform("scale(2)"), {1, 2}, {2, 4});
  expect_maps(parse_transform("scale(2,3)"), {1, 2}, {2, 6});
  expect_maps(parse_transform("rotate(90)"), {1, 0}, {0, 1});
  expect_maps(parse_transform("rotate(90 10 10)"), {11, 10}, {10, 11});
  expect_maps(parse_transform("rotate(45)"), {1, 0}, {std::sqrt(0.5), std::sqrt(0.5)});
  expect_maps(parse_transform("skewX(45)"), {0, 1}, {1, 1});
  expect_maps(parse_transform("skewY(45)"), {1, 0}, {1, 1});
  expect_maps(parse_transform("matrix(1 2 3 4 5 6)"), {1, 1}, {1 + 3 + 5, 2 + 4 + 6});
}

TEST(Transform, RightAnglesAreExact) {
  const Affine t = parse_transform("rotate(-90)");
  EXPECT_EQ(t.apply({3, 0}), Vec2(0, -3));
  EXPECT_EQ(parse_transform("rotate(180)").apply({3, 4}), Vec2(-3, -4));
}

TEST(Transform, ListsApplyRightToLeft) {
  // translate(10,0) scale(2): the point is scaled first, then translated.
  expect_maps(parse_transform("translate(10,0) scale(2)"), {1, 1}, {12, 2});
  expect_maps(parse_transform("scale(2) translate(10,0)"), {1, 1}, {22, 2});
  expect_maps(parse_transform("translate(10,0),scale(2)"), {1, 1}, {12, 2});
  expect_maps(parse_transform("  translate( 10 , 0 )scale(2)  "), {1, 1}, {12, 2});
  expect_maps(parse_transform(""), {1, 1}, {1, 1});
}

TEST(Transform, NumberFormsInArguments) {
  expect_maps(parse_transform("translate(.5.5)"), {0, 0}, {0.5, 0.5});
  expect_maps(parse_transform("translate(-1-2)"), {0, 0}, {-1, -2});
  expect_maps(parse_transform("translate(1e1,2E-1)"), {0, 0}, {10, 0.2});
}

TEST(Transform, Errors) {
  EXPECT_THROW(parse_transform("translate(1"), SyntaxError);
  EXPECT_THROW(parse_transform("spin(30)"), SyntaxError);
  EXPECT_THROW(parse_transform("matrix(1 2 3)"), SyntaxError);
  EXPECT_THROW(parse_transform("rotate(1 2)"), SyntaxError);
  EXPECT_THROW(parse_transform("scale(NaN)"), SyntaxError);
  EXPECT_THROW(parse_transform("scale(1e999)"), SyntaxError);
  EXPECT_THROW(parse_transform("scale(1e300) scale(1e300)"), SyntaxError);  // overflows when composed
  EXPECT_THROW(parse_transform("translate(1 2 3 4 5 6 7)"), SyntaxError);
}

TEST(ViewBox, MeetSliceAndNone) {
  const ViewBox vb{0, 0, 10, 20};
  // meet: uniform scale min(100/10, 100/20) = 5, centred horizontally: 10*5 = 50 wide in 100.
  expect_maps(viewbox_transform(vb, "", 0, 0, 100, 100), {0, 0}, {25, 0});
  expect_maps(viewbox_transform(vb, "xMinYMin meet", 0, 0, 100, 100), {10, 20}, {50, 100});
  expect_maps(viewbox_transform(vb, "xMaxYMax", 0, 0, 100, 100), {0, 0}, {50, 0});
  // slice: scale max = 10, centred vertically: 200 tall in 100 -> offset -50.
  expect_maps(viewbox_transform(vb, "xMidYMid slice", 0, 0, 100, 100), {0, 0}, {0, -50});
  // none: non-uniform.
  expect_maps(viewbox_transform(vb, "none", 0, 0, 100, 100), {10, 20}, {100, 100});
  expect_maps(viewbox_transform({5, 5, 10, 10}, "", 1, 2, 20, 20), {5, 5}, {1, 2});
}
