// <text> read as its glyphs' outlines (svg/text, svg/fonts): fonts chosen by fontconfig among the
// installed ones (Debian's fonts-dejavu-core at least), shaped by HarfBuzz.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "svg/error.hpp"
#include "svg/reader.hpp"

using namespace curvemesh::svg;
using curvemesh::geometry::Vec2;

namespace {

std::string doc(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 400 200\">" + body + "</svg>";
}

FeatureSoup read(const std::string& body) {
  return read_svg(doc(body), ReadOptions{}, "text.svg");
}

bool has_warning(const FeatureSoup& s, const std::string& part) {
  return std::any_of(s.warnings.begin(), s.warnings.end(),
                     [&](const std::string& w) { return w.find(part) != std::string::npos; });
}

// The same curves in the same order, to round-off.
void expect_same_curves(const FeatureSoup& a, const FeatureSoup& b, double tol = 1e-9) {
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t i = 0; i < a.curves.size(); ++i)
    for (int k = 0; k < 4; ++k)
      EXPECT_LT((a.curves[i].bezier.p[k] - b.curves[i].bezier.p[k]).norm(), tol) << i;
}

}  // namespace

TEST(Text, GlyphsAreCurvesAndAFilledShape) {
  const FeatureSoup s = read("<text id='t' x='10' y='50' font-family='DejaVu Sans' font-size='20'>Hi</text>");
  EXPECT_TRUE(s.warnings.empty()) << testing::PrintToString(s.warnings);
  // H is one contour of 12 lines, i a dot and a stem: at least 16 curves, every one the text's.
  EXPECT_GE(s.curves.size(), 16u);
  ASSERT_EQ(s.sources.size(), 1u);
  EXPECT_EQ(s.sources[0].tag, "text");
  EXPECT_EQ(s.sources[0].id, "t");
  for (const SoupCurve& c : s.curves) EXPECT_EQ(c.source, 0);
  // Filled black, as any shape is by default, each glyph contour a closed loop of the fill.
  ASSERT_EQ(s.fills.size(), 1u);
  EXPECT_EQ(s.fills[0].fill, Paint::rgb(0, 0, 0));
  EXPECT_EQ(s.fills[0].subpaths.size(), 3u);
  for (const auto& loop : s.fills[0].subpaths) EXPECT_EQ(loop.front().p[0], loop.back().p[3]);
  // On the baseline at y = 50 (y up in the font, down here), beginning at x = 10; the i's dot,
  // the highest point, about 3/4 em above the baseline.
  const Box2 b = s.bounds();
  EXPECT_NEAR(b.max.y(), 50, 1e-9);
  EXPECT_GT(b.min.y(), 50 - 0.8 * 20);
  EXPECT_LT(b.min.y(), 50 - 0.7 * 20);
  EXPECT_GT(b.min.x(), 10);
  EXPECT_LT(b.min.x(), 10 + 0.2 * 20);
}

TEST(Text, BoundingBoxScalesWithFontSize) {
  const Box2 small = read("<text font-family='DejaVu Serif' font-size='20'>Scale me</text>").bounds();
  const Box2 large = read("<text font-family='DejaVu Serif' font-size='50'>Scale me</text>").bounds();
  ASSERT_FALSE(small.empty());
  // The layout is linear in the size: the baseline origin (0, 0) stays, everything else scales.
  for (int axis = 0; axis < 2; ++axis) {
    EXPECT_NEAR(large.min[axis], 2.5 * small.min[axis], 1e-9);
    EXPECT_NEAR(large.max[axis], 2.5 * small.max[axis], 1e-9);
  }
}

TEST(Text, FontSizeFromCssEmAndShorthandAgree) {
  const Box2 attribute = read("<text font-family='DejaVu Sans' font-size='40'>Em</text>").bounds();
  const Box2 sheet =
      read("<style>text { font-size: 40px; font-family: 'DejaVu Sans' }</style><text>Em</text>").bounds();
  const Box2 em =
      read("<g font-size='20'><text font-family='DejaVu Sans' style='font-size:2em'>Em</text></g>").bounds();
  const Box2 shorthand = read("<text style='font: 30pt \"DejaVu Sans\"'>Em</text>").bounds();
  for (const Box2* b : {&sheet, &em, &shorthand}) {
    EXPECT_NEAR((b->min - attribute.min).norm(), 0, 1e-9);
    EXPECT_NEAR((b->max - attribute.max).norm(), 0, 1e-9);
  }
  // Bold is wider than regular (another face: DejaVu Sans Bold).
  const Box2 bold =
      read("<text font-family='DejaVu Sans' font-size='40' font-weight='bold'>Em</text>").bounds();
  EXPECT_GT(bold.max.x() - bold.min.x(), 1.05 * (attribute.max.x() - attribute.min.x()));
}

TEST(Text, AnchorMiddleCentresAndEndEnds) {
  const std::string text = "font-family='DejaVu Sans' font-size='30' x='200' y='100'>HIH</text>";
  const Box2 start = read("<text " + text).bounds();
  const Box2 middle = read("<text text-anchor='middle' " + text).bounds();
  const Box2 end = read("<text text-anchor='end' " + text).bounds();
  // The chunk moves by half its advance, then by all of it.
  const double half = start.min.x() - middle.min.x();
  EXPECT_GT(half, 0);
  EXPECT_NEAR(start.min.x() - end.min.x(), 2 * half, 1e-9);
  EXPECT_NEAR(middle.max.y(), start.max.y(), 1e-12);
  // H and I have equal side bearings in DejaVu Sans: the ink is centred on x = 200.
  EXPECT_NEAR((middle.min.x() + middle.max.x()) / 2, 200, 0.01 * 30);
  // The advance is wider than the ink by the two outer side bearings.
  EXPECT_GT(2 * half, start.max.x() - start.min.x());
}

TEST(Text, TransformMovesAndScalesIt) {
  const std::string text = "font-family='DejaVu Sans' font-size='20'>Move</text>";
  const Box2 plain = read("<text " + text).bounds();
  const Box2 moved =
      read("<g transform='translate(30 40)'><text transform='scale(2)' " + text + "</g>").bounds();
  EXPECT_NEAR((moved.min - (2 * plain.min + Vec2(30, 40))).norm(), 0, 1e-9);
  EXPECT_NEAR((moved.max - (2 * plain.max + Vec2(30, 40))).norm(), 0, 1e-9);
}

TEST(Text, MissingFamilyWarnsAndFallsBack) {
  const FeatureSoup missing = read("<text font-family='No Such Family 1234' font-size='20'>Fallback</text>");
  EXPECT_TRUE(has_warning(missing, "'No Such Family 1234' is not installed"))
      << testing::PrintToString(missing.warnings);
  // fontconfig's substitute for an unknown family is its default one, sans-serif, as librsvg draws it.
  const FeatureSoup sans = read("<text font-family='sans-serif' font-size='20'>Fallback</text>");
  EXPECT_TRUE(sans.warnings.empty()) << testing::PrintToString(sans.warnings);
  expect_same_curves(missing, sans);
  // A list falls back to the next family that exists, without a warning.
  const FeatureSoup listed =
      read("<text font-family='No Such Family 1234, DejaVu Serif' font-size='20'>Fallback</text>");
  EXPECT_TRUE(listed.warnings.empty()) << testing::PrintToString(listed.warnings);
  expect_same_curves(listed, read("<text font-family='DejaVu Serif' font-size='20'>Fallback</text>"));
}

TEST(Text, PositionListsPlaceEachCharacter) {
  // x='0 100': the second character starts a chunk of its own at 100.
  const FeatureSoup listed = read("<text font-family='DejaVu Sans' x='0 100' y='50'>AB</text>");
  const FeatureSoup apart =
      read("<text font-family='DejaVu Sans' x='0' y='50'>A<tspan x='100'>B</tspan></text>");
  expect_same_curves(listed, apart);
  // dx and dy shift from the current position; a tspan continues where the text left off.
  const Box2 a = read("<text font-family='DejaVu Sans' y='50'>A</text>").bounds();
  const Box2 shifted = read("<text font-family='DejaVu Sans' y='50' dx='7' dy='-3'>A</text>").bounds();
  EXPECT_NEAR((shifted.min - a.min - Vec2(7, -3)).norm(), 0, 1e-9);
}

TEST(Text, WhiteSpaceCollapsesUnlessPreserved) {
  const std::string font = "font-family='DejaVu Sans' x='10' y='50'";
  const FeatureSoup collapsed = read("<text " + font + ">\n   a \t  b\n </text>");
  expect_same_curves(collapsed, read("<text " + font + ">a b</text>"));
  // Between elements a space is kept, even alone (librsvg strips a piece's leading and trailing
  // spaces only where no element is beside it).
  expect_same_curves(read("<text " + font + "><tspan>a</tspan>\n  <tspan>b</tspan>\n</text>"),
                     read("<text " + font + "><tspan>a</tspan> <tspan>b</tspan></text>"));
  const Box2 ab = read("<text " + font + "><tspan>a</tspan><tspan>b</tspan></text>").bounds();
  const Box2 a_b = read("<text " + font + "><tspan>a</tspan> <tspan>b</tspan></text>").bounds();
  EXPECT_GT(a_b.max.x(), ab.max.x() + 2);  // a space of DejaVu Sans at 12 is 3.8 wide
  expect_same_curves(read("<text " + font + ">a<tspan> b</tspan></text>"),
                     read("<text " + font + ">ab</text>"));
  const FeatureSoup preserved = read("<text xml:space='preserve' " + font + ">   a</text>");
  // Three spaces kept before the a: it starts three space advances further right.
  EXPECT_GT(preserved.bounds().min.x(), read("<text " + font + ">a</text>").bounds().min.x() + 10);
}

TEST(Text, TspansKeepTheirPaintInOneSourceElement) {
  const FeatureSoup s = read(
      "<text font-family='DejaVu Sans' font-size='20' y='40'>A<tspan fill='#ff0000'>B</tspan>"
      "<tspan fill='none' stroke='#0000ff'>C</tspan><tspan display='none'>D</tspan></text>");
  ASSERT_EQ(s.sources.size(), 1u);
  ASSERT_EQ(s.fills.size(), 2u);  // C is stroked only, D not drawn
  EXPECT_EQ(s.fills[0].fill, Paint::rgb(0, 0, 0));
  EXPECT_EQ(s.fills[1].fill, Paint::rgb(255, 0, 0));
  EXPECT_TRUE(std::any_of(s.curves.begin(), s.curves.end(),
                          [](const SoupCurve& c) { return c.stroke == Paint::rgb(0, 0, 255); }));
  // Without D, the text ends where C does.
  const Box2 abc = read("<text font-family='DejaVu Sans' font-size='20' y='40'>ABC</text>").bounds();
  EXPECT_NEAR(s.bounds().max.x(), abc.max.x(), 0.05 * 20);
}

TEST(Text, CountsAgainstTheCurveLimit) {
  ReadOptions o;
  o.max_curves = 40;
  const std::string text = doc("<text font-family='DejaVu Sans'>" + std::string(100, 'W') + "</text>");
  try {
    read_svg(text, o, "long.svg");
    FAIL() << "100 W read under a limit of 40 curves";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than 40 curves"), std::string::npos) << e.what();
  }
  // A hidden text draws no curve: 30 W would be about 400 curves.
  EXPECT_TRUE(read_svg(doc("<text visibility='hidden'>" + std::string(30, 'W') + "</text>"), o, "h.svg")
                  .curves.empty());
  // Every character counts as a curve at least, white space too where it is kept: the memory a
  // text takes stays bounded by the limit.
  EXPECT_NO_THROW(
      read_svg(doc("<text xml:space='preserve'>" + std::string(39, ' ') + "</text>"), o, "s.svg"));
  try {
    read_svg(doc("<text xml:space='preserve'>" + std::string(100, ' ') + "</text>"), o, "s.svg");
    FAIL() << "100 characters read under a limit of 40 curves";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than 40 curves"), std::string::npos) << e.what();
  }
}

TEST(Text, DefaultsAreLibrsvgs) {
  // librsvg draws text without a font-size at 12 user units (not CSS's 16) and without a family in
  // its default one; neither is a reason to warn.
  const FeatureSoup plain = read("<text y='50'>Default</text>");
  EXPECT_TRUE(plain.warnings.empty()) << testing::PrintToString(plain.warnings);
  expect_same_curves(plain, read("<text y='50' font-size='12'>Default</text>"));
  const Box2 medium = read("<text y='50' font-size='medium'>Default</text>").bounds();
  EXPECT_NEAR(medium.width(), plain.bounds().width() * 16 / 12, 1e-9);
}

TEST(Text, LetterSpacingBetweenCharacters) {
  const std::string font = "font-family='DejaVu Sans' font-size='20' x='100' y='50'";
  const Box2 plain = read("<text " + font + ">HHH</text>").bounds();
  const Box2 spaced = read("<text " + font + " letter-spacing='10'>HHH</text>").bounds();
  const Box2 em = read("<text " + font + " style='letter-spacing:0.5em'>HHH</text>").bounds();
  // Two gaps between three letters, none before the first.
  EXPECT_NEAR(spaced.min.x(), plain.min.x(), 1e-9);
  EXPECT_NEAR(spaced.max.x(), plain.max.x() + 20, 1e-9);
  EXPECT_NEAR(em.max.x(), spaced.max.x(), 1e-9);
  // None after the last either: an end-anchored chunk ends where it would without spacing.
  const Box2 end = read("<text " + font + " text-anchor='end' letter-spacing='10'>HHH</text>").bounds();
  const Box2 end_plain = read("<text " + font + " text-anchor='end'>HHH</text>").bounds();
  EXPECT_NEAR(end.max.x(), end_plain.max.x(), 1e-9);
  EXPECT_NEAR(end.min.x(), end_plain.min.x() - 20, 1e-9);
}
