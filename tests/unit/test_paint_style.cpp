#include <gtest/gtest.h>

#include "svg/paint.hpp"
#include "svg/style.hpp"

using namespace curvemesh::svg;

TEST(Color, Forms) {
  EXPECT_EQ(parse_color("#abc")->to_string(), "#aabbcc");
  EXPECT_EQ(parse_color("#A0b1C2")->to_string(), "#a0b1c2");
  EXPECT_EQ(parse_color("rgb(255, 0, 10)")->to_string(), "#ff000a");
  EXPECT_EQ(parse_color("rgb(100%,50%,0%)")->to_string(), "#ff8000");
  EXPECT_EQ(parse_color("RGB(1 2 3)")->to_string(), "#010203");
  EXPECT_EQ(parse_color("rgba(1,2,3,0.5)")->to_string(), "#010203");
  EXPECT_EQ(parse_color("rgb(300,-5,0)")->to_string(), "#ff0000");  // clamped
  EXPECT_EQ(parse_color("  CornflowerBlue ")->to_string(), "#6495ed");
  EXPECT_EQ(parse_color("aliceblue")->to_string(), "#f0f8ff");
  EXPECT_EQ(parse_color("yellowgreen")->to_string(), "#9acd32");
  EXPECT_FALSE(parse_color("#abcd"));
  EXPECT_FALSE(parse_color("#ggg"));
  EXPECT_FALSE(parse_color("blurple"));
  EXPECT_FALSE(parse_color("rgb(1,2)"));
  EXPECT_FALSE(parse_color(""));
}

TEST(Paint, Values) {
  const Paint red = Paint::rgb(255, 0, 0);
  EXPECT_EQ(parse_paint("none", red)->kind, Paint::Kind::none);
  EXPECT_EQ(*parse_paint("currentColor", red), red);
  EXPECT_EQ(parse_paint("url(#grad1)", red)->to_string(), "url(#grad1)");
  EXPECT_EQ(parse_paint("url('#g2') #fff", red)->url, "g2");
  EXPECT_EQ(parse_paint("#00ff00", red)->to_string(), "#00ff00");
  EXPECT_FALSE(parse_paint("inherit", red));
  EXPECT_FALSE(parse_paint("bogus", red));
}

TEST(Style, Declarations) {
  const Declarations d = parse_declarations(" fill : red ; STROKE:#00f;/* c */display:none !important;;junk");
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0], (std::pair<std::string, std::string>{"fill", "red"}));
  EXPECT_EQ(d[1], (std::pair<std::string, std::string>{"stroke", "#00f"}));
  EXPECT_EQ(d[2], (std::pair<std::string, std::string>{"display", "none"}));
}

TEST(Style, SheetSpecificityAndOrder) {
  StyleSheet sheet;
  sheet.add(R"(
    /* comment */ path { fill: red }
    .a { fill: green } .b { fill: blue }
    #x { fill: black }
    path.a.b, circle { stroke: white }
    g path { fill: purple }          /* descendant selectors are not matched */
    @media print { .a { fill: pink } }
    * { color: gray }
  )");
  auto value = [&](std::string_view tag, std::string_view id, std::string_view cls, const std::string& prop) {
    std::vector<const Declarations*> out;
    sheet.match(tag, id, cls, out);
    std::string v;
    for (const Declarations* block : out)
      for (const auto& [n, val] : *block)
        if (n == prop) v = val;  // the last wins
    return v;
  };
  EXPECT_EQ(value("path", "", "", "fill"), "red");
  EXPECT_EQ(value("path", "", "a", "fill"), "green");
  EXPECT_EQ(value("path", "", "b a", "fill"), "blue");  // same specificity: later rule wins
  EXPECT_EQ(value("path", "x", "a b", "fill"), "black");  // id beats classes
  EXPECT_EQ(value("path", "", "a b", "stroke"), "white");
  EXPECT_EQ(value("path", "", "a", "stroke"), "");
  EXPECT_EQ(value("circle", "", "", "stroke"), "white");
  EXPECT_EQ(value("rect", "", "", "color"), "gray");
  EXPECT_EQ(value("rect", "", "", "fill"), "");
}
