// The SVG reader end to end: documents in, feature soups out.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pipeline/parameters.hpp"
#include "svg/error.hpp"
#include "round_off_path.hpp"
#include "svg/reader.hpp"

using namespace curvemesh::svg;
using curvemesh::geometry::Vec2;

namespace {

std::string doc(const std::string& body, const std::string& root_attrs = "") {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" " + root_attrs +
         ">" + body + "</svg>";
}

// The reader with the paper's ε_m.
ReadOptions paper_options() {
  ReadOptions o;
  o.degenerate_tolerance = [](const Box2& bounds, const Box2&, const std::vector<FillLayer>&) {
    return curvemesh::pipeline::Parameters{}.eps_m_rel * bounds.diagonal();
  };
  return o;
}

FeatureSoup read(const std::string& text) { return read_svg(text, paper_options(), "test.svg"); }

void expect_point(const Vec2& got, const Vec2& want, double tol = 1e-9) {
  EXPECT_NEAR(got.x(), want.x(), tol);
  EXPECT_NEAR(got.y(), want.y(), tol);
}

// The error message read_svg throws for `text`, or "" when it does not throw.
std::string error_of(const std::string& text, const ReadOptions& options = paper_options()) {
  try {
    read_svg(text, options, "bad.svg");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Reader, PathInRootUserSpace) {
  // The root's width/height/viewBox scale nothing: coordinates stay in viewBox units.
  const FeatureSoup s = read(doc("<path d='M10 20 L 30 40'/>", "width='10cm' height='5cm' viewBox='0 0 50 50'"));
  ASSERT_EQ(s.curves.size(), 1u);
  expect_point(s.curves[0].bezier.p[0], {10, 20});
  expect_point(s.curves[0].bezier.p[3], {30, 40});
  expect_point(s.curves[0].bezier.p[1], {10 + 20.0 / 3, 20 + 20.0 / 3});
  EXPECT_TRUE(s.points.empty());
}

TEST(Reader, WithoutNamespaceReadsTheSame) {
  const FeatureSoup a = read("<svg><rect width='2' height='1'/></svg>");
  const FeatureSoup b = read(doc("<rect width='2' height='1'/>"));
  ASSERT_EQ(a.curves.size(), 4u);
  ASSERT_EQ(b.curves.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(a.curves[i].bezier.p[0], b.curves[i].bezier.p[0]);
}

TEST(Reader, PrefixedSvgNamespace) {
  const FeatureSoup s = read(
      "<svg:svg xmlns:svg='http://www.w3.org/2000/svg' xmlns:foo='urn:foo'><svg:g><svg:line x2='1'/></svg:g>"
      "<foo:line x2='5'/></svg:svg>");
  ASSERT_EQ(s.curves.size(), 1u);
  expect_point(s.curves[0].bezier.p[3], {1, 0});
}

TEST(Reader, BasicShapes) {
  const FeatureSoup s = read(doc(
      "<rect id='r' x='1' y='2' width='10' height='5'/>"
      "<rect x='0' y='0' width='10' height='10' rx='2'/>"
      "<circle cx='5' cy='5' r='2'/>"
      "<ellipse cx='0' cy='0' rx='3' ry='1'/>"
      "<line x1='0' y1='0' x2='3' y2='4'/>"
      "<polyline points='0,0 1,1 2,0'/>"
      "<polygon points='0 0 1 1 2 0'/>"
      "<rect width='0' height='5'/><circle r='0'/>"));  // zero sizes draw nothing
  // rect 4 + rounded rect (4 sides + 4 corners of 9 pieces) 40 + circle 36 + ellipse 36 + line 1
  // + polyline 2 + polygon 3
  EXPECT_EQ(s.curves.size(), 4u + 40u + 36u + 36u + 1u + 2u + 3u);
  ASSERT_GE(s.sources.size(), 1u);
  EXPECT_EQ(s.sources[s.curves[0].source].id, "r");
  EXPECT_EQ(s.sources[s.curves[0].source].tag, "rect");
  // The circle passes through its four extreme points, starting at (cx + r, cy), and closes.
  const int circle = 44;
  EXPECT_EQ(s.sources[s.curves[circle].source].tag, "circle");
  EXPECT_EQ(s.curves[circle].bezier.p[0], Vec2(7, 5));
  EXPECT_EQ(s.curves[circle + 9].bezier.p[0], Vec2(5, 7));
  EXPECT_EQ(s.curves[circle + 18].bezier.p[0], Vec2(3, 5));
  EXPECT_EQ(s.curves[circle + 27].bezier.p[0], Vec2(5, 3));
  EXPECT_EQ(s.curves[circle + 35].bezier.p[3], Vec2(7, 5));
  // Every point of the circle's cubics lies within 1e-9·r of the circle (test_arc proves it).
  for (int k = circle; k < circle + 36; ++k)
    for (int i = 0; i <= 100; ++i)
      EXPECT_NEAR((s.curves[k].bezier.eval(i / 100.0) - Vec2(5, 5)).norm(), 2.0, 1e-9 * 2.0);
}

TEST(Reader, RoundedRectRadiiDefaultAndClamp) {
  // Only rx given: ry takes it; radii larger than half the side are clamped.
  const FeatureSoup s = read(doc("<rect width='10' height='4' rx='3'/>"));
  const auto b = s.bounds();
  expect_point(b.min, {0, 0});
  expect_point(b.max, {10, 4});
  // ry = min(3, 2) = 2: the left side has no straight part, the top has 10 - 6 = 4.
  double top_straight = 0;
  for (const auto& c : s.curves)
    if (c.bezier.p[0].y() == 0 && c.bezier.p[3].y() == 0) top_straight += (c.bezier.p[3] - c.bezier.p[0]).norm();
  EXPECT_NEAR(top_straight, 4.0, 1e-12);
}

TEST(Reader, TransformsNestedGroups) {
  const FeatureSoup s = read(doc(
      "<g transform='translate(100,0)'><g transform='scale(2)'>"
      "<line x1='1' y1='1' x2='2' y2='1' transform='rotate(90)'/></g></g>"));
  ASSERT_EQ(s.curves.size(), 1u);
  // rotate first: (1,1) -> (-1,1); scale: (-2,2); translate: (98,2).
  expect_point(s.curves[0].bezier.p[0], {98, 2});
  expect_point(s.curves[0].bezier.p[3], {98, 4});
}

TEST(Reader, PercentagesReferToTheRootViewBox) {
  const FeatureSoup s = read(doc("<rect x='-50%' y='-50%' width='50%' height='25%'/>", "viewBox='-100 -100 200 400'"));
  const auto b = s.bounds();
  expect_point(b.min, {-100, -200});
  expect_point(b.max, {0, -100});
  // Without a viewBox, the root's width and height (in any unit) are the reference.
  const FeatureSoup t = read(doc("<line x2='100%' y2='10%'/>", "width='1in' height='2in'"));
  expect_point(t.curves.at(0).bezier.p[3], {96, 19.2});
}

TEST(Reader, NestedSvgViewport) {
  const FeatureSoup s =
      read(doc("<svg x='10' y='20' width='100' height='100' viewBox='0 0 10 10'><line x2='10'/></svg>"));
  ASSERT_EQ(s.curves.size(), 1u);
  expect_point(s.curves[0].bezier.p[0], {10, 20});
  expect_point(s.curves[0].bezier.p[3], {110, 20});
}

TEST(Reader, UseWithOffsetsAndHrefForms) {
  const FeatureSoup s = read(doc(
      "<defs><line id='l' x2='1'/></defs>"
      "<use xlink:href='#l' x='5' y='6'/>"
      "<use href='#l' transform='translate(100)' x='1'/>"
      "<use xlink:href='#missing'/>"));
  ASSERT_EQ(s.curves.size(), 2u);
  expect_point(s.curves[0].bezier.p[0], {5, 6});
  expect_point(s.curves[1].bezier.p[0], {101, 0});  // transform, then x offset
  EXPECT_EQ(s.sources[s.curves[0].source].tag, "line");
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings[0].find("#missing"), std::string::npos);
}

TEST(Reader, UseOfSymbolWithViewBox) {
  const FeatureSoup s = read(doc(
      "<symbol id='s' viewBox='0 0 10 10'><line x2='10'/></symbol>"
      "<use xlink:href='#s' x='100' y='0' width='20' height='20'/>"));
  ASSERT_EQ(s.curves.size(), 1u);
  expect_point(s.curves[0].bezier.p[0], {100, 0});
  expect_point(s.curves[0].bezier.p[3], {120, 0});
}

TEST(Reader, UseOfGroupInheritsStyleFromUse) {
  const FeatureSoup s = read(doc("<defs><g id='g'><line x2='1'/></g></defs><use href='#g' stroke='red'/>"));
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.curves[0].stroke.to_string(), "#ff0000");
}

TEST(Reader, NotDrawnUnlessUsed) {
  const FeatureSoup s = read(doc(
      "<defs><line x2='1'/></defs><clipPath><line x2='2'/></clipPath><mask><line x2='3'/></mask>"
      "<pattern><line x2='4'/></pattern><marker><line x2='5'/></marker><symbol><line x2='6'/></symbol>"
      "<linearGradient><stop/></linearGradient><line x2='7'/>"));
  ASSERT_EQ(s.curves.size(), 1u);
  expect_point(s.curves[0].bezier.p[3], {7, 0});
}

TEST(Reader, DisplayAndVisibility) {
  const FeatureSoup s = read(doc(
      "<line x2='1' display='none'/>"
      "<g style='display:none'><line x2='2'/></g>"
      "<line x2='3' style='visibility:hidden'/>"
      "<g visibility='hidden'><line x2='4'/><line x2='5' visibility='visible'/></g>"
      "<line x2='6'/>"));
  ASSERT_EQ(s.curves.size(), 2u);
  expect_point(s.curves[0].bezier.p[3], {5, 0});
  expect_point(s.curves[1].bezier.p[3], {6, 0});
}

TEST(Reader, ColoursFromAttributesStyleAndSheets) {
  const FeatureSoup s = read(doc(
      "<style><![CDATA[ .k { stroke: #00f } #special { fill: lime } ]]></style>"
      "<g fill='red' stroke='green' color='#123456'>"
      "  <line x2='1'/>"                                    // inherits red / green
      "  <line x2='2' class='k' stroke='black'/>"           // sheet beats presentation attribute
      "  <line x2='3' class='k' style='stroke:#fff'/>"      // style attribute beats sheet
      "  <line x2='4' fill='currentColor' stroke='none'/>"  // currentColor
      "  <line x2='5' id='special' fill='url(#grad)'/>"     // id rule beats attribute
      "  <line x2='6' fill='url(#grad) red' stroke='rgb(1,2,3)'/>"
      "  <line x2='7' fill='bogus'/>"                       // unreadable: unfilled, with a warning
      "</g><line x2='8'/>"));                               // defaults: fill black, stroke none
  ASSERT_EQ(s.curves.size(), 8u);
  auto fs = [&](int i) { return s.curves[i].fill.to_string() + " " + s.curves[i].stroke.to_string(); };
  EXPECT_EQ(fs(0), "#ff0000 #008000");
  EXPECT_EQ(fs(1), "#ff0000 #0000ff");
  EXPECT_EQ(fs(2), "#ff0000 #ffffff");
  EXPECT_EQ(fs(3), "#123456 none");
  EXPECT_EQ(fs(4), "#00ff00 #008000");
  EXPECT_EQ(fs(5), "url(#grad) #010203");
  // A browser would ignore the value and inherit red; but a value this reader cannot read may be
  // a colour it does not know (hsl(), color()): not guessed, the element is left unfilled.
  EXPECT_EQ(fs(6), "none #008000");
  EXPECT_EQ(fs(7), "#000000 none");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("fill=\"bogus\""), std::string::npos);
  EXPECT_NE(s.warnings[0].find("left unfilled"), std::string::npos);
}

TEST(Reader, SkippedKindsWarnOncePerKind) {
  const FeatureSoup s = read(doc("<image/><image/><foreignObject/><text><textPath>a</textPath></text><line x2='1'/>"));
  EXPECT_EQ(s.curves.size(), 1u);
  ASSERT_EQ(s.warnings.size(), 3u);
  int image_warnings = 0;
  for (const std::string& w : s.warnings) image_warnings += w.find("2 <image> elements") != std::string::npos;
  EXPECT_EQ(image_warnings, 1);
}

TEST(Reader, SwitchDrawsTheFirstChildThatApplies) {
  // Illustrator's pattern: an extension we do not support, then the fallback group.
  const FeatureSoup s = read(doc(
      "<switch><foreignObject requiredExtensions='http://ns.adobe.com/AdobeIllustrator/10.0/'/>"
      "<g><line x2='1'/></g><g><line x2='2'/></g></switch>"));
  ASSERT_EQ(s.curves.size(), 1u);
  expect_point(s.curves[0].bezier.p[3], {1, 0});
}

TEST(Reader, DegeneratePathsBecomePoints) {
  const FeatureSoup s = read(doc(
      "<path d='M 5 5'/>"                                        // a lone moveto
      "<path d='M 1 1 L 1 1.0000000000001 L 1 1'/>"              // all within eps_m of each other
      "<path d='M 0 0 L 100 100'/>"));
  ASSERT_EQ(s.curves.size(), 1u);
  ASSERT_EQ(s.points.size(), 2u);
  expect_point(s.points[0].p, {5, 5});
  expect_point(s.points[1].p, {1, 1}, 1e-12);
  EXPECT_EQ(s.sources[s.points[0].source].tag, "path");
}

TEST(Reader, ClosedPathsComingBackToTheirStartWithinRoundOffCloseExactly) {
  // Relative path data that does not sum back to its start (50.1 + … = 50.10000000000001): Z
  // would add a closing line of length 7e-15 — a degenerate curve, the last cubic ending beside
  // the first. The last cubic ends exactly at the start instead, its end tangent kept.
  const std::string d = curvemesh::testing_support::kClosingWithinRoundOff;
  const FeatureSoup closed = read(doc("<path d='" + d + "z'/>"));
  ASSERT_EQ(closed.curves.size(), 7u);
  EXPECT_TRUE(closed.points.empty());
  EXPECT_EQ(closed.curves.back().bezier.p[3], Vec2(50.1, 0.3));
  const FeatureSoup open = read(doc("<path d='" + d + "'/>"));
  ASSERT_EQ(open.curves.size(), 7u);
  const auto& moved = closed.curves.back().bezier;
  const auto& as_drawn = open.curves.back().bezier;
  EXPECT_NE(as_drawn.p[3], Vec2(50.1, 0.3));  // without Z nothing is closed
  EXPECT_EQ(moved.p[3] - moved.p[2], as_drawn.p[3] - as_drawn.p[2]);
  EXPECT_EQ(moved.p[1], as_drawn.p[1]);
  // A gap of more than ε_m is the drawing's: Z closes it with a line, as before.
  const FeatureSoup gap = read(doc("<path d='M 0 0 C 10 0 10 10 0 10 C -10 10 -10 0 0 0.001 Z'/>"));
  ASSERT_EQ(gap.curves.size(), 3u);
  EXPECT_EQ(gap.curves[1].bezier.p[3], Vec2(0, 0.001));
}

TEST(Reader, PiecesOfOneArcShareItsNumber) {
  const FeatureSoup s = read(doc(
      "<defs><circle id='c' r='2'/></defs>"
      "<rect width='10' height='4' rx='1'/>"               // four corners, four sides
      "<use href='#c'/><use href='#c' x='10'/>"            // one circle each
      "<path d='M 0 0 L 1 0 A 1 1 0 0 1 3 0 A 1 1 0 0 1 1 0 Q 0 3 0 0'/>"));  // two half circles
  ASSERT_EQ(s.curves.size(), 40u + 72u + 1u + 17u + 17u + 1u);
  std::vector<int> arcs;
  for (const SoupCurve& c : s.curves) arcs.push_back(c.arc);
  std::vector<int> want;
  for (int corner = 0; corner < 4; ++corner) {
    want.push_back(-1);                        // the side before it
    want.insert(want.end(), 9, corner);        // its quarter
  }
  want.insert(want.end(), 36, 4);              // the first circle
  want.insert(want.end(), 36, 5);              // the second
  want.push_back(-1);                          // the line
  want.insert(want.end(), 17, 6);              // each arc command: arc_piece_count(π) = 17 pieces
  want.insert(want.end(), 17, 7);
  want.push_back(-1);                          // the quadratic
  EXPECT_EQ(arcs, want);
  // A rounded rect without sides is one ellipse.
  const FeatureSoup pill = read(doc("<rect width='10' height='4' rx='5' ry='2'/>"));
  ASSERT_EQ(pill.curves.size(), 36u);
  for (const SoupCurve& c : pill.curves) EXPECT_EQ(c.arc, 0);
}

TEST(Reader, IllustratorEntities) {
  const std::string text =
      "<?xml version='1.0'?>\n"
      "<!DOCTYPE svg PUBLIC '-//W3C//DTD SVG 1.0//EN' 'http://www.w3.org/TR/2001/REC-SVG-20010904/DTD/svg10.dtd' [\n"
      "  <!ENTITY ns_svg 'http://www.w3.org/2000/svg'>\n"
      "  <!ENTITY st0 'fill:#FF0000;stroke:none;'>\n"
      "  <!ENTITY both '&st0;'>\n"
      "]>\n"
      "<svg xmlns='&ns_svg;'><path style='&both;' d='M0 0 L 1 1'/></svg>\n";
  const FeatureSoup s = read(text);
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.curves[0].fill.to_string(), "#ff0000");
  EXPECT_EQ(s.curves[0].stroke.to_string(), "none");
}

TEST(Reader, SourcesKnowTheirLine) {
  const FeatureSoup s = read("<svg>\n<g>\n\n<path id='p' d='M0 0 L1 0'/>\n</g></svg>");
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.sources[0].line, 4);
  EXPECT_EQ(s.sources[0].id, "p");
  EXPECT_EQ(s.sources[0].index, 2);  // svg, g, path in document order
}

TEST(Reader, BoundsAreTight) {
  // A circle's bounding box is the circle's, not its control polygon's.
  const FeatureSoup s = read(doc("<circle cx='0' cy='0' r='1'/>"));
  const auto b = s.bounds();
  expect_point(b.min, {-1, -1}, 1e-12);
  expect_point(b.max, {1, 1}, 1e-12);
}

TEST(Reader, UnusualButRenderedByBrowsers) {
  // Path data that ends inside a command is drawn up to there; a malformed transform is ignored.
  // Both with a warning naming the element.
  const FeatureSoup s = read(doc(
      "<path id='p' d='M 0 0 L 10 0 A 5 5 0 1 '/>"
      "<line id='l' x2='1' transform='matrix(1 0 0 1 5 5'/>"));
  ASSERT_EQ(s.curves.size(), 2u);
  expect_point(s.curves[0].bezier.p[3], {10, 0});
  expect_point(s.curves[1].bezier.p[0], {0, 0});
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find("id=\"p\""), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[1].find("id=\"l\""), std::string::npos) << s.warnings[1];
}

// --- bad input: refused with a message naming the file and the place ---

TEST(ReaderErrors, NotXml) {
  const std::string e = error_of("this is not xml");
  EXPECT_NE(e.find("bad.svg"), std::string::npos) << e;
  EXPECT_NE(e.find("XML"), std::string::npos) << e;
}

TEST(ReaderErrors, Truncated) {
  const std::string e = error_of("<svg xmlns='http://www.w3.org/2000/svg'>\n<path d='M0 0 L 1 1'/>\n<g>");
  EXPECT_NE(e.find("bad.svg: line"), std::string::npos) << e;
  EXPECT_NE(error_of("<svg><path d='M0 0 L 1"), "");
  EXPECT_NE(error_of(""), "");
}

TEST(ReaderErrors, NoSvgRoot) {
  const std::string e = error_of("<html><svg/></html>");
  EXPECT_NE(e.find("<html>"), std::string::npos) << e;
}

TEST(ReaderErrors, NonFiniteNumbers) {
  EXPECT_NE(error_of(doc("<path d='M 0 0 L NaN 1'/>")).find("path"), std::string::npos);
  EXPECT_NE(error_of(doc("<path d='M 0 0 L 1e999 1'/>")), "");
  EXPECT_NE(error_of(doc("<path d='M 0 0 L inf 1'/>")), "");
  EXPECT_NE(error_of(doc("<rect x='NaN' width='1' height='1'/>")), "");
  EXPECT_NE(error_of(doc("<rect width='Infinity' height='1'/>")), "");
  EXPECT_NE(error_of(doc("<circle r='1e400'/>")), "");
  EXPECT_NE(error_of(doc("<polygon points='0 0 1e999 1'/>")), "");
  // Finite numbers that overflow only once transformed.
  EXPECT_NE(error_of(doc("<g transform='scale(1e200)'><line x2='1e200'/></g>")).find("overflow"), std::string::npos);
  EXPECT_NE(error_of(doc("<line x2='1' transform='scale(1e999)'/>")), "");
  EXPECT_NE(error_of(doc("<line x2='1' transform='translate(NaN 0)'/>")), "");
}

TEST(ReaderErrors, UnknownPathCommandNamesTheElement) {
  const std::string e = error_of("<svg>\n\n<path id='bad' d='M 0 0 X 1 1'/></svg>");
  EXPECT_NE(e.find("bad.svg: line 3, <path id=\"bad\">"), std::string::npos) << e;
  EXPECT_NE(e.find("X"), std::string::npos) << e;
}

TEST(ReaderErrors, UseCycles) {
  EXPECT_NE(error_of(doc("<g id='a'><use href='#a'/></g>")).find("ancestor"), std::string::npos);
  EXPECT_NE(error_of(doc("<defs><g id='a'><use href='#b'/></g><g id='b'><use href='#a'/></g></defs><use href='#a'/>"))
                .find("cycle"),
            std::string::npos);
  EXPECT_NE(error_of(doc("<use id='u' href='#u'/>")), "");
}

TEST(ReaderErrors, ExponentialUse) {
  // Each level doubles the drawing: 2^40 lines from a few hundred bytes.
  std::string body = "<defs><line id='l0' x2='1'/>";
  for (int i = 1; i <= 40; ++i)
    body += "<g id='l" + std::to_string(i) + "'><use href='#l" + std::to_string(i - 1) + "'/><use href='#l" +
            std::to_string(i - 1) + "'/></g>";
  body += "</defs><use href='#l40'/>";
  EXPECT_NE(error_of(doc(body)).find("more than"), std::string::npos);
}

TEST(ReaderErrors, AbsurdNesting) {
  std::string text = "<svg>";
  for (int i = 0; i < 100000; ++i) text += "<g>";
  for (int i = 0; i < 100000; ++i) text += "</g>";
  text += "</svg>";
  EXPECT_NE(error_of(text).find("nested deeper"), std::string::npos);
  // Deep, but within the limit: read.
  std::string ok = "<svg>";
  for (int i = 0; i < 300; ++i) ok += "<g>";
  ok += "<line x2='1'/>";
  for (int i = 0; i < 300; ++i) ok += "</g>";
  ok += "</svg>";
  EXPECT_EQ(read(ok).curves.size(), 1u);
}

TEST(ReaderErrors, EntityExpansion) {
  std::string bomb = "<?xml version='1.0'?>\n<!DOCTYPE svg [\n<!ENTITY a0 'aaaaaaaaaa'>\n";
  for (int i = 1; i <= 10; ++i) {
    bomb += "<!ENTITY a" + std::to_string(i) + " '";
    for (int k = 0; k < 10; ++k) bomb += "&a" + std::to_string(i - 1) + ";";
    bomb += "'>\n";
  }
  bomb += "]>\n<svg><path d='M0 0 L1 1' class='&a10;'/></svg>";
  EXPECT_NE(error_of(bomb).find("entity"), std::string::npos);
  const std::string cycle = "<!DOCTYPE svg [<!ENTITY a '&b;'><!ENTITY b '&a;'>]><svg/>";
  EXPECT_NE(error_of(cycle).find("itself"), std::string::npos);
}
