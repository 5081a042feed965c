// The SVG reader on documents made to break it. Each is read, or refused with an InputError that
// names the limit, and what is read is well-formed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/text.hpp"
#include "svg/drawing_size.hpp"
#include "svg/error.hpp"
#include "svg/paint.hpp"
#include "svg/reader.hpp"
#include "svg/style.hpp"

using namespace curvemesh::svg;
using curvemesh::base::valid_utf8;
using testing::HasSubstr;

namespace {

const std::string kOpen =
    "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\">";

std::string doc(const std::string& body) {
  return kOpen + body + "</svg>";
}

ReadOptions options() {
  ReadOptions o;
  o.degenerate_tolerance = [](const Box2& bounds, const Box2&, const std::vector<FillLayer>&) { return 1e-8 * bounds.diagonal(); };
  return o;
}

// The message read_svg throws for `text`, or "" when it reads it.
std::string error_of(const std::string& text, const ReadOptions& o = options()) {
  try {
    read_svg(text, o, "bad.svg");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Every string the reader put into the soup.
std::vector<std::string> strings_of(const FeatureSoup& s) {
  std::vector<std::string> out = s.warnings;
  for (const SourceElement& e : s.sources) out.insert(out.end(), {e.tag, e.id});
  for (const SoupCurve& c : s.curves)
    for (const Paint* p : {&c.fill, &c.stroke, &c.left, &c.right}) out.push_back(p->to_string());
  for (const FillLayer& f : s.fills) out.push_back(f.fill.to_string());
  return out;
}

bool has_warning(const FeatureSoup& s, const std::string& fragment) {
  for (const std::string& w : s.warnings)
    if (w.find(fragment) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(HostileSvg, InvalidUtf8IsRepairedWherever) {
  const std::vector<std::string> documents = {
      // The command line's example: a class and a fill.
      doc("<path class=\"\xff\" d=\"M0 0 L10 0 L5 8 Z\" fill=\"r\xff"
          "ed\"/>"),
      // An id, a paint's reference and an element name of another namespace.
      doc("<path id=\"p\xfe\" d=\"M0 0 L1 1\" stroke=\"url(#g\xc3)\"/><x:q\xff xmlns:x=\"urn:x\"/>"),
      // An attribute's name, a style sheet, text.
      doc("<style>.a\xff{fill:#f00\xff}</style><path class=\"a\xff\" d=\"M0 0 L1 1\" "
          "da\xfft=\"1\"/><text>\xc0</text>"),
      // An entity's value, expanded into an id; a truncated sequence at the end of a value.
      "<!DOCTYPE svg [<!ENTITY e \"q\xed\xa0\x80\">]>" +
          doc("<path id=\"&e;\" d=\"M0 0 L1 1\" fill=\"#00f\xe2\x82\"/>"),
  };
  for (const std::string& text : documents) {
    SCOPED_TRACE(curvemesh::base::printable(text));
    ASSERT_FALSE(valid_utf8(text));
    const FeatureSoup s = read_svg(text, options(), "x.svg");
    ASSERT_FALSE(s.curves.empty());
    for (const std::string& str : strings_of(s))
      EXPECT_TRUE(valid_utf8(str)) << curvemesh::base::printable(str);
    EXPECT_TRUE(has_warning(s, "invalid UTF-8 replaced by U+FFFD (")) << testing::PrintToString(s.warnings);
    nlohmann::json ids = nlohmann::json::array();
    for (const SourceElement& e : s.sources) ids.push_back(e.id);
    for (const std::string& w : s.warnings) ids.push_back(w);
    EXPECT_NO_THROW((void)ids.dump());
  }
  // The count and the line of the first: the bytes of the class and of the fill, on line 2.
  const FeatureSoup s = read_svg(kOpen +
                                     "\n<path class=\"\xff\" d=\"M0 0 L10 0 L5 8 Z\" fill=\"r\xff"
                                     "ed\"/></svg>",
                                 options(), "x.svg");
  EXPECT_TRUE(has_warning(s, "invalid UTF-8 replaced by U+FFFD (2 bytes, the first at line 2)"))
      << testing::PrintToString(s.warnings);
  // The repaired id is the one <use> finds.
  const FeatureSoup used =
      read_svg(doc("<defs><path id=\"a\xff\" d=\"M0 0 L1 1\"/></defs><use href=\"#a\xff\"/>"));
  EXPECT_EQ(used.curves.size(), 1u);
}

TEST(HostileSvg, MessagesAreWellFormed) {
  // A malformed path in an element with a malformed id: the message quotes the replacement
  // character whole, not one byte of it.
  const std::string e = error_of(doc("\n<path id=\"\xff\" d=\"M0 0 L1 1 \xff\"/>"));
  EXPECT_TRUE(valid_utf8(e)) << curvemesh::base::printable(e);
  EXPECT_THAT(e, HasSubstr("line 2, <path id=\"\xef\xbf\xbd\">: bad path data: unexpected '\xef\xbf\xbd'"));
  const std::string points = error_of(doc("<polygon points=\"0 0 1 1 \xe9\"/>"));
  EXPECT_THAT(points, HasSubstr("bad points: unexpected '\xef\xbf\xbd' in points"));
  // A malformed transform is ignored with a warning that quotes it.
  const FeatureSoup s = read_svg(doc("<line x2=\"1\" transform=\"scale(\xe9)\"/>"), options());
  EXPECT_TRUE(has_warning(s, "ignored a malformed transform (expected a number, found '\xef\xbf\xbd')"))
      << testing::PrintToString(s.warnings);
  // An entity's name, from the document type declaration, which pugixml does not read.
  const std::string cycle = error_of("<!DOCTYPE svg [<!ENTITY a\xff \"&a\xff;\">]>" + doc(""));
  EXPECT_THAT(cycle, HasSubstr("DOCTYPE: entity 'a\xef\xbf\xbd' refers to itself"));
  // A file's name is shown escaped.
  try {
    read_svg("<svg", options(), "a\xff.svg");
    ADD_FAILURE() << "read";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), testing::StartsWith("a\\xff.svg: line 1: not well-formed XML"));
  }
}

TEST(HostileSvg, EntityExpansionIsABudgetForTheWholeDocument) {
  // e4 expands to 100,000 characters: 200 references to it, each well below 16 Mi characters,
  // are 20 million in all.
  std::string dtd = "<!DOCTYPE svg [<!ENTITY e0 \"fill:red;x\">";
  for (int k = 1; k <= 4; ++k) {
    dtd += "<!ENTITY e" + std::to_string(k) + " \"";
    for (int i = 0; i < 10; ++i) dtd += "&e" + std::to_string(k - 1) + ";";
    dtd += "\">";
  }
  dtd += "]>";
  std::string many, few;
  for (int i = 0; i < 200; ++i) many += "<path style=\"&e4;\" d=\"M0 0 L1 1\"/>";
  for (int i = 0; i < 100; ++i) few += "<path style=\"&e4;\" d=\"M0 0 L1 1\"/>";
  EXPECT_THAT(
      error_of(dtd + doc(many)),
      HasSubstr("entity references expand to more than 16777216 characters in all (a limit of the reader)"));
  EXPECT_EQ(read_svg(dtd + doc(few), options()).curves.size(), 100u);
  // The declarations alone count towards it.
  std::string bomb = "<!DOCTYPE svg [<!ENTITY a0 \"aaaaaaaaaa\">";
  for (int k = 1; k <= 8; ++k) {
    bomb += "<!ENTITY a" + std::to_string(k) + " \"";
    for (int i = 0; i < 10; ++i) bomb += "&a" + std::to_string(k - 1) + ";";
    bomb += "\">";
  }
  EXPECT_THAT(error_of(bomb + "]>" + doc("")),
              HasSubstr("DOCTYPE: entity references expand to more than 16777216"));
  // Ampersands without a reference are copied, not searched past.
  const FeatureSoup s = read_svg("<!DOCTYPE svg [<!ENTITY e \"1\">]>" +
                                 doc("<path id=\"" + std::string(1 << 20, '&') + "\" d=\"M0 0 L&e; 1\"/>"));
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.curves[0].bezier.p[3].x(), 1.0);
}

TEST(HostileSvg, StyleSheetsAreBounded) {
  std::string selectors;
  for (std::size_t i = 0; i <= kMaxStyleSelectors; ++i) selectors += ".a,";
  EXPECT_THAT(error_of(doc("<style>" + selectors + ".a{fill:red}</style>")),
              HasSubstr("<style>: the style sheets have more selectors than 100000 (a limit of the reader)"));
  std::string block;
  for (std::size_t i = 0; i <= kMaxStyleDeclarations; ++i) block += "x:y;";
  EXPECT_THAT(error_of(doc("<style>.a{" + block + "}</style>")),
              HasSubstr("the style sheets have more declarations than 1000000 (a limit of the reader)"));
  // Within those, matching: a list of selectors before a long block, for each element (what
  // once took 4 GB: every selector kept its own copy of the block) ...
  std::string list, decls, elements;
  for (int i = 0; i < 10000; ++i) list += ".a,";
  for (int i = 0; i < 10000; ++i) decls += "fill:red;";
  for (int i = 0; i < 100; ++i) elements += "<path class=\"a\" d=\"M0 0 L1 1\"/>";
  const std::string limit =
      "matching the style sheets takes more steps (rules tried, declarations taken) than 20000000";
  EXPECT_THAT(error_of(doc("<style>" + list + ".a{" + decls + "}</style>" + elements)), HasSubstr(limit));
  // ... rules that every element matches ...
  std::string rules;
  for (int i = 0; i < 20000; ++i) rules += "*{fill:red}";
  for (int i = 0; i < 1000; ++i) elements += "<path d=\"M0 0 L1 1\"/>";
  EXPECT_THAT(error_of(doc("<style>" + rules + "</style>" + elements)), HasSubstr(limit));
  // ... and a long value taken by every element.
  EXPECT_THAT(error_of(doc("<style>*{fill:" + std::string(1 << 20, 'x') + "}</style>" + elements)),
              HasSubstr(limit));
  // A sheet of drawings' size is read as before: the last selector of a list and the class
  // named twice match.
  const FeatureSoup s = read_svg(
      doc("<style>.b, .a { fill: #00f; font-family: x }</style><path class=\"a a\" d=\"M0 0 L1 1\"/>"));
  ASSERT_EQ(s.curves.size(), 1u);
  EXPECT_EQ(s.curves[0].fill.to_string(), "#0000ff");
}

TEST(HostileSvg, LimitsNameTheirOptions) {
  ReadOptions o = options();
  o.max_curves = 1000;
  std::string path = "M0 0";
  for (int i = 0; i < 2000; ++i) path += " l1 1";
  EXPECT_THAT(error_of(doc("<path d=\"" + path + "\"/>"), o),
              HasSubstr("the document has more than 1000 curves (--max-curves raises the limit)"));
  std::string points;
  for (int i = 0; i < 2000; ++i) points += "1 1 ";
  EXPECT_THAT(error_of(doc("<polyline points=\"" + points + "\"/>"), o), HasSubstr("more than 1000 curves"));
  // A moveto alone becomes an isolated point, and counts as a curve.
  std::string moves;
  for (int i = 0; i < 2000; ++i) moves += "M1 1 ";
  EXPECT_THAT(error_of(doc("<path d=\"" + moves + "\"/>"), o), HasSubstr("more than 1000 curves"));
  // Exactly at the limit: read.
  EXPECT_EQ(read_svg(doc("<path d=\"" + path.substr(0, 4 + 5 * 1000) + "\"/>"), o).curves.size(), 1000u);
  o = options();
  o.max_elements = 100;
  std::string body = "<defs><path id=\"p\" d=\"M0 0 L1 1\"/></defs>";
  for (int i = 0; i < 60; ++i) body += "<use href=\"#p\"/>";
  EXPECT_THAT(
      error_of(doc(body), o),
      HasSubstr("the document has more than 100 elements, each <use> instance counted (--max-elements "
                "raises the limit)"));
}

TEST(HostileSvg, PaintReferencesAreBounded) {
  // Each curve keeps its element's paints: 100,000 segments stroked with a reference to an id of
  // 10,000 characters took 1 GB.
  std::string path = "M0 0";
  for (int i = 0; i < 1000; ++i) path += " l1 1";
  const std::string id(kMaxPaintReference, 'a');
  EXPECT_THAT(
      error_of(doc("<path d=\"" + path + "\" stroke=\"url(#" + id + "b)\"/>")),
      HasSubstr("<path>: a paint refers to an id of more than 256 characters (a limit of the reader)"));
  EXPECT_THAT(error_of(doc("<style>path{fill:url(#" + id + "b)}</style><path d=\"M0 0 L1 1\"/>")),
              HasSubstr("a paint refers to an id of more than 256 characters"));
  const FeatureSoup s = read_svg(doc("<path d=\"" + path + "\" stroke=\"url(#" + id + ")\"/>"), options());
  ASSERT_EQ(s.curves.size(), 1000u);
  EXPECT_EQ(s.curves[0].stroke.url, id);
}

TEST(HostileSvg, AttributesReadAreBoundedOverUseInstances) {
  // A transform of 12,000 characters on a group drawn 1,000 times through <use>: 12 million
  // characters read (a 1 MB file so made once took minutes).
  std::string transform;
  for (int i = 0; i < 1000; ++i) transform += "translate(0)";
  std::string body = "<defs><g id=\"g0\" transform=\"" + transform + "\"><path d=\"M0 0 L1 1\"/></g>";
  for (int level = 1; level <= 3; ++level) {
    body += "<g id=\"g" + std::to_string(level) + "\">";
    for (int i = 0; i < 10; ++i) body += "<use href=\"#g" + std::to_string(level - 1) + "\"/>";
    body += "</g>";
  }
  body += "</defs><use href=\"#g3\"/>";
  ReadOptions o = options();
  o.max_attribute_text = 10'000'000;
  EXPECT_THAT(
      error_of(doc(body), o),
      HasSubstr("<g id=\"g0\">: the attributes read amount to more than 10000000 characters, each <use> "
                "instance reading its element's again (a limit of the reader)"));
  EXPECT_EQ(read_svg(doc(body), options()).curves.size(), 1000u);
  EXPECT_EQ(ReadOptions{}.max_attribute_text, std::size_t(1) << 30);
}

// Lines are counted from a sparse index (a file of empty lines would take 8 bytes a line), and
// elements numbered by walking the tree in place (a document of many elements took as many
// entries in a table): both as before.
TEST(HostileSvg, LinesAndDocumentOrderFoundWithoutTablesPerLineOrElement) {
  for (const int blank : {0, 1, 1022, 1023, 1024, 5000}) {
    const std::string text = kOpen + std::string(blank, '\n') + "<path id=\"x\" d=\"M0 0 X\"/></svg>";
    EXPECT_THAT(error_of(text), HasSubstr("line " + std::to_string(blank + 1) + ", <path id=\"x\">")) << blank;
  }
  const FeatureSoup s = read_svg(doc("<g><g><path d=\"M0 0 L1 1\"/></g><title/></g><path d=\"M0 0 L2 2\"/>"));
  ASSERT_EQ(s.sources.size(), 2u);
  EXPECT_EQ(s.sources[0].index, 3);  // svg, g, g, path
  EXPECT_EQ(s.sources[1].index, 5);  // ..., title, path
}

TEST(HostileSvg, DrawingSizesOutsideTheRangeAreRefusedWithTheReason) {
  const auto triangle = [](double s) {
    const auto n = [](double v) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", v);
      return std::string(text);
    };
    return doc("<path d=\"M0 0 L" + n(s) + " 0 L" + n(s / 2) + " " + n(0.8 * s) + " Z\"/>");
  };
  // Once meshed wrong (not certified), or collapsed to a point, or refused as "1" across.
  EXPECT_THAT(error_of(triangle(1e-160)),
              HasSubstr("bad.svg: the drawing is 1.3e-160 across, smaller than 1e-100: "
                        "too small to mesh in double precision; scale it up"));
  EXPECT_THAT(error_of(triangle(1e-162)), HasSubstr("the drawing is 1.3e-162 across, smaller than 1e-100"));
  EXPECT_THAT(error_of(triangle(1e200)),
              HasSubstr("bad.svg: the drawing reaches a coordinate of 1e+200, beyond "
                        "1e+100: too large to mesh in double precision; scale it down"));
  EXPECT_THAT(error_of(triangle(0.9e100)), HasSubstr("the drawing is 1.2e+100 across, larger than 1e+100"));
  // Inside the range: read, the triangle's three curves kept (none collapsed into a point).
  for (const double s : {1e-100, 0.7e100}) {
    const FeatureSoup soup = read_svg(triangle(s), options());
    EXPECT_EQ(soup.curves.size(), 3u) << s;
    EXPECT_TRUE(soup.points.empty()) << s;
  }
  // A point is 0 across, which is no size to be out of range.
  EXPECT_EQ(read_svg(doc("<path d=\"M1e-200 0\"/>"), options()).points.size(), 1u);
}

TEST(HostileSvg, DrawingSizeProblem) {
  curvemesh::geometry::Box2 box;
  EXPECT_EQ(drawing_size_problem(box), "");  // empty
  box.add({0, 0});
  EXPECT_EQ(drawing_size_problem(box), "");  // a point
  box.add({3e-101, 4e-101});
  EXPECT_EQ(drawing_size_problem(box),
            "the drawing is 5e-101 across, smaller than 1e-100: too small to mesh in "
            "double precision; scale it up");
  box.add({6e-101, 9e-101});
  EXPECT_EQ(drawing_size_problem(box), "");  // 1.08e-100 across
  // Sides that would overflow a plain diagonal, and coordinates within range but far apart.
  curvemesh::geometry::Box2 wide;
  wide.add({-1e100, 0});
  wide.add({1e100, 0});
  EXPECT_THAT(drawing_size_problem(wide), HasSubstr("the drawing is 2e+100 across, larger than 1e+100"));
  wide.add({0, -1e300});
  EXPECT_THAT(drawing_size_problem(wide), HasSubstr("reaches a coordinate of 1e+300, beyond 1e+100"));
}
