// Clip paths (SVG 1.1 §14.3.5): what the reader makes of clip-path="url(#id)", and the regions a
// clipped element covers, against areas known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "curvemesh/parameters.hpp"
#include "pipeline/pipeline.hpp"
#include "regions/paint.hpp"
#include "svg/reader.hpp"
#include "svg/shapes.hpp"

using namespace curvemesh;
using geometry::CubicBezier;
using geometry::Vec2;

namespace {

std::string doc(const std::string& body) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 20 20\">" + body + "</svg>";
}

pipeline::Result mesh_regions(const std::string& body) {
  Parameters p;
  p.regions = true;
  return pipeline::run(pipeline::Source::svg(doc(body), "<test>"), p);
}

double area_of(const pipeline::Result& r, const std::string& name) {
  double a = 0;
  for (const regions::Region& g : r.painted->regions)
    if (g.name == name) a += g.area;
  return a;
}

// The area a closed loop of cubics encloses (Green's formula in closed form per cubic).
double loop_area(const std::vector<CubicBezier>& loop) {
  double a = 0;
  for (const CubicBezier& c : loop) {
    const auto& p = c.p;
    a += (6 * geometry::cross(p[0], p[1]) + 3 * geometry::cross(p[0], p[2]) + geometry::cross(p[0], p[3]) +
          3 * geometry::cross(p[1], p[2]) + 3 * geometry::cross(p[1], p[3]) +
          6 * geometry::cross(p[2], p[3])) /
         20.0;
  }
  return std::abs(a);
}

}  // namespace

TEST(ClipPaths, TheReaderKeepsEachClipOnceWithItsShapes) {
  const svg::FeatureSoup s = svg::read_svg(doc(R"svg(
      <clipPath id="c" transform="translate(1 0)"><rect width="4" height="4"/><circle cx="9" cy="9" r="1"/></clipPath>
      <rect id="a" width="10" height="10" fill="red" clip-path="url(#c)"/>
      <rect id="b" width="10" height="10" fill="blue" style="clip-path: url(#c)"/>
      <g transform="translate(5 5)" clip-path="url(#c)"><rect width="2" height="2"/></g>
      <rect width="1" height="1" clip-path="url(#nothing)"/>
      <rect width="1" height="1" mask="url(#m)"/>)svg"));
  // Two clip paths: the first (used twice in one user space) and the one in the moved group.
  ASSERT_EQ(s.clips.size(), 2u);
  ASSERT_EQ(s.clips[0].shapes.size(), 2u);
  EXPECT_EQ(s.clips[0].shapes[0].bounds.min, Vec2(1, 0));  // the clipPath's own transform
  EXPECT_EQ(s.clips[1].shapes[0].bounds.min, Vec2(6, 5));  // and the group's
  ASSERT_EQ(s.fills.size(), 5u);
  EXPECT_EQ(s.fills[0].clips, std::vector<int>{0});
  EXPECT_EQ(s.fills[1].clips, std::vector<int>{0});
  EXPECT_EQ(s.fills[2].clips, std::vector<int>{1});  // a group's clip is its children's
  EXPECT_TRUE(s.fills[3].clips.empty());             // no such clipPath: drawn unclipped, warned
  EXPECT_TRUE(s.fills[4].clips.empty());
  EXPECT_EQ(s.clipped_elements, 1);  // the mask, not applied
  bool warned = false;
  for (const std::string& w : s.warnings) warned = warned || w.find("url(#nothing)") != std::string::npos;
  EXPECT_TRUE(warned);
  // The clips' outlines are features, once per clip: 4 lines for each of the five rects drawn,
  // and each clip's rect and circle (36 cubics).
  EXPECT_EQ(s.curves.size(), 5 * 4 + 2 * (4 + 36u));
}

TEST(ClipPaths, ACircleClipsARect) {
  // Blue under red; red clipped by a circle inside it: a disc of red, exactly the area of the
  // circle's cubics (the mesh follows curves that cross nothing exactly).
  const pipeline::Result inside = mesh_regions(R"svg(
      <clipPath id="disc"><circle cx="10" cy="10" r="4"/></clipPath>
      <rect id="under" x="2" y="2" width="14" height="14" fill="#0000ff"/>
      <rect id="red" x="3" y="3" width="14" height="14" fill="#ff0000" clip-path="url(#disc)"/>)svg");
  ASSERT_TRUE(inside.painted);
  double disc = 0;
  for (const svg::Subpath& s : svg::ellipse_subpaths(10, 10, 4, 4)) disc += loop_area(s.segments);
  EXPECT_NEAR(area_of(inside, "red"), disc, 1e-9 * disc);
  // Red clipped by a circle centred on its corner: a quarter disc (the 36 cubics are symmetric
  // about the centre's axes). Where the rect's sides cross the circle the mesh follows the curves
  // within ε (§4.1's envelope): the area within ε times the quarter disc's perimeter.
  const pipeline::Result quarter = mesh_regions(R"svg(
      <clipPath id="disc"><circle cx="10" cy="10" r="4"/></clipPath>
      <rect id="under" x="2" y="2" width="14" height="14" fill="#0000ff"/>
      <rect id="red" x="0" y="0" width="10" height="10" fill="#ff0000" clip-path="url(#disc)"/>)svg");
  ASSERT_TRUE(quarter.painted);
  const double bound = quarter.resolved.features.epsilon * (2 * 4 + std::numbers::pi * 4 / 2);
  EXPECT_NEAR(area_of(quarter, "red"), disc / 4, bound);
  EXPECT_NEAR(area_of(quarter, "under"), 14 * 14 - disc / 4, bound);
  EXPECT_NEAR(area_of(quarter, "red") + area_of(quarter, "under") + area_of(quarter, "background"),
              quarter.box.width() * quarter.box.height(), 1e-9 * 14 * 14);
}

TEST(ClipPaths, UnionOfChildrenClipRuleAndTransforms) {
  // Two overlapping squares (their union, 28), moved by the clipPath's transform, through a group.
  const pipeline::Result u = mesh_regions(R"svg(
      <clipPath id="two" transform="translate(3 3)"><rect width="4" height="4"/><rect x="2" y="2" width="4" height="4"/></clipPath>
      <g clip-path="url(#two)"><rect id="big" width="20" height="20" fill="#00ff00"/></g>)svg");
  ASSERT_TRUE(u.painted);
  // The squares' sides cross: within ε times the union's perimeter (24).
  EXPECT_NEAR(area_of(u, "big"), 28, u.resolved.features.epsilon * 24);
  // A square with a square hole under clip-rule evenodd (36 − 4); nonzero would keep the hole
  // (both loops turn the same way): 36. The clipped element's own transform moves its clip too.
  const std::string ring = "M 0 0 H 6 V 6 H 0 Z M 2 2 H 4 V 4 H 2 Z";
  const pipeline::Result eo = mesh_regions(
      "<clipPath id='ring'><path clip-rule='evenodd' d='" + ring +
      "'/></clipPath><rect id='r' transform='translate(7 7)' width='10' height='10' fill='#000000' "
      "clip-path='url(#ring)'/>");
  EXPECT_NEAR(area_of(eo, "r"), 32, 1e-9);  // the rect's sides on the clip's: nothing crosses
  const pipeline::Result nz = mesh_regions(
      "<clipPath id='ring'><path d='" + ring +
      "'/></clipPath><rect id='r' x='1' width='10' height='10' fill='#000000' clip-path='url(#ring)'/>");
  // x from 1 to 6 of the filled 6 × 6; the rect's side crosses the clip's (perimeter 22).
  EXPECT_NEAR(area_of(nz, "r"), 30, nz.resolved.features.epsilon * 22);
}
