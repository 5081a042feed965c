// The reader's diffusion-curve colours: data-color-left and data-color-right on drawn elements
// and groups reach every soup curve of what they draw.
#include <gtest/gtest.h>

#include <string>

#include "svg/reader.hpp"

using namespace curvemesh::svg;

namespace {

FeatureSoup read(const std::string& body) {
  return read_svg("<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\">" + body +
                      "</svg>",
                  {}, "test.svg");
}

std::string sides(const SoupCurve& c) { return c.left.to_string() + " " + c.right.to_string(); }

}  // namespace

TEST(SideColors, ReachEveryCurveOfTheElement) {
  const FeatureSoup s = read(
      "<rect width='4' height='2' data-color-left='red' data-color-right='rgb(0, 0, 255)'/>"
      "<path d='M0 5 C 1 6 2 6 3 5 L 4 5' data-color-left='#0f0'/>"
      "<path d='M0 9 L 4 9'/>");
  ASSERT_EQ(s.curves.size(), 7u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(sides(s.curves[i]), "#ff0000 #0000ff") << i;
  // A side not given stays absent: the stroke and fill are not copied into it.
  EXPECT_EQ(sides(s.curves[4]), "#00ff00 none");
  EXPECT_EQ(sides(s.curves[5]), "#00ff00 none");
  EXPECT_EQ(sides(s.curves[6]), "none none");
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SideColors, InheritedFromGroupsAndUse) {
  const FeatureSoup s = read(
      "<g data-color-left='white' data-color-right='black'>"
      "  <line x2='1'/>"
      "  <g data-color-right='orange'><line y1='1' x2='1' y2='1'/></g>"
      "</g>"
      "<defs><path id='p' d='M0 3 L1 3'/><path id='q' d='M0 4 L1 4' data-color-left='navy'/></defs>"
      "<use xlink:href='#p' data-color-left='teal'/>"
      "<use xlink:href='#q' data-color-left='teal'/>");
  ASSERT_EQ(s.curves.size(), 4u);
  EXPECT_EQ(sides(s.curves[0]), "#ffffff #000000");
  EXPECT_EQ(sides(s.curves[1]), "#ffffff #ffa500");
  EXPECT_EQ(sides(s.curves[2]), "#008080 none");  // from the <use>
  EXPECT_EQ(sides(s.curves[3]), "#000080 none");  // the element's own wins
}

TEST(SideColors, FromTheRootAndThroughSymbols) {
  const FeatureSoup s = read_svg(
      "<svg xmlns='http://www.w3.org/2000/svg' data-color-left='silver'>"
      "<symbol id='s' data-color-right='lime'><path d='M0 5 L1 5'/></symbol>"
      "<path d='M0 0 L1 0'/><use href='#s'/></svg>",
      {}, "test.svg");
  ASSERT_EQ(s.curves.size(), 2u);
  EXPECT_EQ(sides(s.curves[0]), "#c0c0c0 none");
  EXPECT_EQ(sides(s.curves[1]), "#c0c0c0 #00ff00");
}

TEST(SideColors, NotCssProperties) {
  // Data attributes: neither the style attribute nor a style sheet sets them.
  const FeatureSoup s = read(
      "<style>path { data-color-left: red }</style>"
      "<path d='M0 0 L1 0' style='data-color-right: blue'/>");
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(sides(s.curves[0]), "none none");
}

TEST(SideColors, MirroringTransformExchangesTheSides) {
  // Left and right are on screen: mirroring the drawing mirrors the colours with it, so the
  // colour given as left ends up on the right of the mirrored path.
  const FeatureSoup s = read(
      "<g data-color-left='red' data-color-right='blue'>"
      "  <path d='M0 0 L1 0'/>"
      "  <path d='M0 0 L1 0' transform='scale(1, -1)'/>"
      "  <path d='M0 0 L1 0' transform='scale(-1, -1)'/>"
      "  <g transform='matrix(0 1 1 0 0 0)'><path d='M0 0 L1 0'/></g>"
      "  <path d='M0 0 L1 0' transform='rotate(90)'/>"
      "</g>");
  ASSERT_EQ(s.curves.size(), 5u);
  EXPECT_EQ(sides(s.curves[0]), "#ff0000 #0000ff");
  EXPECT_EQ(sides(s.curves[1]), "#0000ff #ff0000");
  EXPECT_EQ(sides(s.curves[2]), "#ff0000 #0000ff");  // a half turn mirrors nothing
  EXPECT_EQ(sides(s.curves[3]), "#0000ff #ff0000");
  EXPECT_EQ(sides(s.curves[4]), "#ff0000 #0000ff");
}

TEST(SideColors, BadColourIsIgnoredWithAWarning) {
  // As a malformed transform: the value is dropped (the inherited one stays) and the reader
  // says where.
  const FeatureSoup s = read(
      "<g data-color-left='red'>"
      "  <path id='a' d='M0 0 L1 0' data-color-left='reddish' data-color-right='#12345'/>"
      "</g>");
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(sides(s.curves[0]), "#ff0000 none");
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("data-color-left=\"reddish\""), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("id=\"a\""), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[1].find("data-color-right=\"#12345\""), std::string::npos) << s.warnings[1];
}
