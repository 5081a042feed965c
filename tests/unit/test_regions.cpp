// Regions: the faces of a finished mesh, which filled element each shows (winding numbers, fill
// rules, paint order), the reader's fills, and `mesh --regions` / `--domain` through the pipeline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <tuple>

#include "curvemesh/parameters.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"
#include "geometry/p3_triangle.hpp"
#include "regions/faces.hpp"
#include "regions/groups.hpp"
#include "regions/paint.hpp"
#include "regions/winding.hpp"
#include "svg/arc.hpp"
#include "svg/reader.hpp"
#include "svg/shapes.hpp"

using namespace curvemesh;
using geometry::CubicBezier;
using geometry::Vec2;

namespace {

std::string doc(const std::string& body, const std::string& root = "viewBox=\"0 0 10 10\"") {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" " + root + ">" +
         body + "</svg>";
}

// The closed polygon through `ps`, as straight cubics.
svg::Subpath polygon(const std::vector<Vec2>& ps) {
  svg::Subpath s;
  s.start = ps[0];
  for (std::size_t i = 0; i < ps.size(); ++i) s.segments.push_back(CubicBezier::line(ps[i], ps[(i + 1) % ps.size()]));
  return s;
}

svg::FillLayer layer_of(const std::vector<svg::Subpath>& subpaths, svg::FillRule rule = svg::FillRule::nonzero) {
  svg::FillLayer l;
  l.fill = svg::Paint::rgb(1, 2, 3);
  l.rule = rule;
  for (const svg::Subpath& s : subpaths) {
    l.subpaths.push_back(s.segments);
    for (const CubicBezier& c : s.segments) l.bounds.add(c.control_bounds());
  }
  return l;
}

// The area a closed loop of cubics encloses (Green's formula, each cubic's integral in closed
// form from its control points): independent of the mesh.
double bezier_loop_area(const std::vector<CubicBezier>& loop) {
  double a = 0;
  for (const CubicBezier& c : loop) {
    const auto& p = c.p;
    // ½ ∫ x dy − y dx over a cubic Bézier = Σ w_ij (p_i × p_j) / 20 with the weights below.
    a += (6 * geometry::cross(p[0], p[1]) + 3 * geometry::cross(p[0], p[2]) + geometry::cross(p[0], p[3]) +
          3 * geometry::cross(p[1], p[2]) + 3 * geometry::cross(p[1], p[3]) + 6 * geometry::cross(p[2], p[3])) /
         20.0;
  }
  return a;
}

pipeline::Result mesh_painted(const std::string& text, regions::Domain domain = regions::Domain::box,
                              bool tag = true, Parameters p = {}) {
  p.regions = tag;
  p.domain = domain;
  return pipeline::run(pipeline::Source::svg(text, "<test>"), p);
}

// The region (name) of the triangle whose sample point is nearest to q.
std::string region_at(const pipeline::Result& r, const Vec2& q) {
  const regions::Painted& p = *r.painted;
  int best = -1;
  double best_d = 1e300;
  for (int t = 0; t < p.mesh.triangle_count(); ++t) {
    const auto tri = p.mesh.triangle(t);
    const Vec2 c = p.mesh.order == 3 ? p.mesh.nodes[tri[9]]
                                     : (p.mesh.nodes[tri[0]] + p.mesh.nodes[tri[1]] + p.mesh.nodes[tri[2]]) / 3.0;
    if ((c - q).norm() < best_d) best_d = (c - q).norm(), best = t;
  }
  return p.regions.at(p.region_of(best)).name;
}

}  // namespace

TEST(Winding, CircleBothWaysAndOnTheCurve) {
  const svg::FillLayer ccw = layer_of(svg::ellipse_subpaths(0, 0, 1, 1));
  const double res = 1e-12, want = 1e-3;
  // SVG's ellipse runs clockwise on screen (y down) = counter-clockwise in these coordinates.
  const regions::Winding in = regions::winding_number(Vec2(0.1, 0.2), ccw, res, want);
  EXPECT_TRUE(in.decided);
  EXPECT_EQ(std::abs(in.number), 1);
  EXPECT_GE(in.clearance, want);
  EXPECT_EQ(regions::winding_number(Vec2(2, 0), ccw, res, want).number, 0);
  EXPECT_EQ(regions::winding_number(Vec2(0.99, 0.0), ccw, res, want).number, in.number);
  EXPECT_EQ(regions::winding_number(Vec2(1.01, 0.0), ccw, res, want).number, 0);
  // Reversed, the number changes sign.
  svg::FillLayer cw = ccw;
  for (auto& loop : cw.subpaths) {
    std::reverse(loop.begin(), loop.end());
    for (CubicBezier& c : loop) c = CubicBezier(c.p[3], c.p[2], c.p[1], c.p[0]);
  }
  EXPECT_EQ(regions::winding_number(Vec2(0.1, 0.2), cw, res, want).number, -in.number);
  // On the curve (its start point): undecided, not guessed.
  EXPECT_FALSE(regions::winding_number(Vec2(1, 0), ccw, res, want).decided);
  // Near it: decided, and the clearance is a lower bound of the true distance (1e-6 here).
  const regions::Winding near = regions::winding_number(Vec2(1 - 1e-6, 0), ccw, res, want);
  EXPECT_TRUE(near.decided);
  EXPECT_EQ(near.number, in.number);
  EXPECT_LE(near.clearance, 1e-6 * 1.0000001);
  EXPECT_GT(near.clearance, 0);
}

TEST(Winding, FillRulesOnTwoNestedLoops) {
  std::vector<svg::Subpath> two = svg::ellipse_subpaths(0, 0, 2, 2);
  for (const svg::Subpath& s : svg::ellipse_subpaths(0, 0, 1, 1)) two.push_back(s);
  const svg::FillLayer l = layer_of(two);
  const regions::Winding centre = regions::winding_number(Vec2(0, 0), l, 1e-12, 1e-3);
  const regions::Winding ring = regions::winding_number(Vec2(1.5, 0), l, 1e-12, 1e-3);
  EXPECT_EQ(std::abs(centre.number), 2);
  EXPECT_EQ(std::abs(ring.number), 1);
  EXPECT_TRUE(regions::inside(centre.number, svg::FillRule::nonzero));
  EXPECT_FALSE(regions::inside(centre.number, svg::FillRule::evenodd));
  EXPECT_TRUE(regions::inside(ring.number, svg::FillRule::evenodd));
}

TEST(Reader, FillLayersInPaintOrderWithRulesAndUse) {
  const svg::FeatureSoup soup = svg::read_svg(doc(R"svg(
      <style>.eo { fill-rule: evenodd }</style>
      <defs><rect id="r" width="2" height="2"/></defs>
      <path id="p" class="eo" fill="#ff0000" d="M 0 0 L 4 0 L 4 4"/>
      <use xlink:href="#r" x="5" fill="blue"/>
      <use xlink:href="#r" x="7" fill="green"/>
      <circle cx="5" cy="5" r="1" fill="none" stroke="black"/>
      <rect x="8" y="8" width="1" height="1" fill="url(#missing)"/>
      <rect x="1" y="8" width="1" height="1" fill="chartreuse-ish"/>
      <rect x="3" y="8" width="1" height="1" mask="url(#c)"/>)svg"));
  ASSERT_EQ(soup.fills.size(), 4u);  // the path, the two uses, the masked rect (black)
  EXPECT_EQ(soup.fills[0].rule, svg::FillRule::evenodd);
  EXPECT_EQ(soup.fills[0].fill.to_string(), "#ff0000");
  EXPECT_EQ(soup.sources[soup.fills[0].source].id, "p");
  // The open path is filled as closed: its loop ends with the line back to its start.
  ASSERT_EQ(soup.fills[0].subpaths.size(), 1u);
  ASSERT_EQ(soup.fills[0].subpaths[0].size(), 3u);
  EXPECT_EQ(soup.fills[0].subpaths[0].back().p[3], Vec2(0, 0));
  EXPECT_EQ(soup.fills[1].fill.to_string(), "#0000ff");
  EXPECT_EQ(soup.fills[2].fill.to_string(), "#008000");
  EXPECT_EQ(soup.fills[1].source, soup.fills[2].source);  // one element, painted twice
  EXPECT_EQ(soup.fills[3].fill.to_string(), "#000000");
  EXPECT_EQ(soup.clipped_elements, 1);
  bool warned = false;
  for (const std::string& w : soup.warnings) warned = warned || w.find("chartreuse-ish") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Reader, ClosingLinesBecomeCurvesOnlyWhenAsked) {
  const std::string text = doc(R"(<path d="M 0 0 L 4 0 L 4 4"/><path fill="none" stroke="red" d="M 5 5 L 9 5 L 9 9"/>)");
  svg::ReadOptions o;
  EXPECT_EQ(svg::read_svg(text, o).curves.size(), 4u);
  o.close_filled_subpaths = true;
  const svg::FeatureSoup closed = svg::read_svg(text, o);
  ASSERT_EQ(closed.curves.size(), 5u);  // the filled path's closing line, not the stroked one's
  EXPECT_EQ(closed.curves[2].bezier.p[0], Vec2(4, 4));
  EXPECT_EQ(closed.curves[2].bezier.p[3], Vec2(0, 0));
}

TEST(Faces, AFaceWhoseSamplesAllLieOnTheOutlineIsNotGuessed) {
  // Two triangles, one face; a filled polygon whose outline runs through every point the
  // classification samples (each triangle's centroid and the points halfway to its corners).
  io::HighOrderMesh m;
  m.nodes = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)};
  m.add_triangle(std::vector<int>{0, 1, 2});
  m.add_triangle(std::vector<int>{0, 2, 3});
  std::vector<Vec2> points;
  for (int t = 0; t < 2; ++t) {
    const Vec2 &a = m.nodes[m.triangle(t)[0]], &b = m.nodes[m.triangle(t)[1]], &c = m.nodes[m.triangle(t)[2]];
    for (const auto& uv : {std::pair{1.0 / 3, 1.0 / 3}, std::pair{1.0 / 6, 1.0 / 6}, std::pair{2.0 / 3, 1.0 / 6},
                           std::pair{1.0 / 6, 2.0 / 3}})
      points.push_back(a + uv.first * (b - a) + uv.second * (c - a));
  }
  regions::ClassifyOptions o;
  o.clearance = 1e-3;
  o.resolution = 1e-12;
  EXPECT_THROW(regions::classify(m, {layer_of({polygon(points)})}, o), regions::Undecided);
  // The pipeline names the element (exit code 3 on the command line): tested in cli_mesh.
  // A polygon through all but one sample decides the face at that one.
  points.pop_back();
  EXPECT_NO_THROW(regions::classify(m, {layer_of({polygon(points)})}, o));
}

TEST(Faces, AFaceAnOutlineCrossesIsDecidedTriangleByTriangle) {
  // One face of two triangles that the line of a filled half-plane crosses, as where the mesh
  // follows an outline only within ε. Each triangle is painted where most of its samples (its
  // centroid and the points halfway to its corners) are: what covers most of its area.
  io::HighOrderMesh m;
  m.nodes = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)};
  m.add_triangle(std::vector<int>{0, 1, 2});  // samples at x = 4/3, 2/3, 5/3, 5/3; x + y = 2, 1, 2, 3
  m.add_triangle(std::vector<int>{0, 2, 3});  // samples at x = 2/3, 1/3, 4/3, 1/3; x + y = 2, 1, 3, 2
  const auto below = [&](double c) {  // x + y < c
    return polygon({Vec2(c + 3, -3), Vec2(-3, c + 3), Vec2(-9, -9)});
  };
  const auto right_of = [&](double c) {  // x > c
    return polygon({Vec2(c, -9), Vec2(9, -9), Vec2(9, 9), Vec2(c, 9)});
  };
  regions::ClassifyOptions o;
  o.clearance = 10;  // more than any sample has: every one is tried
  o.resolution = 1e-12;
  // x + y < 1.5: one sample of each inside; < 2.5: three of each.
  EXPECT_EQ(regions::classify(m, {layer_of({below(1.5)})}, o).visible, (std::vector<int>{-1, -1}));
  EXPECT_EQ(regions::classify(m, {layer_of({below(2.5)})}, o).visible, (std::vector<int>{0, 0}));
  // x > 0.9: three samples of the first triangle, one of the second. The face's sample farthest
  // from the line (x = 5/3) is inside, but the second triangle is mostly outside.
  EXPECT_EQ(regions::classify(m, {layer_of({right_of(0.9)})}, o).visible, (std::vector<int>{0, -1}));
  // x + 2y > 8/3 + 0.05, just beyond the first triangle's centroid (4/3, 2/3) towards its sample
  // (5/3, 4/3): that sample is its farthest from the line (0.72), and the only one inside; the
  // triangle is mostly outside. Three of the second's samples are inside.
  const double k = 8.0 / 3 + 0.05;
  const svg::Subpath beyond = polygon({Vec2(k + 18, -9), Vec2(60, -9), Vec2(60, 9), Vec2(k - 18, 9)});
  EXPECT_EQ(regions::classify(m, {layer_of({beyond})}, o).visible, (std::vector<int>{-1, 0}));
  // x > 1.5: two samples of the first triangle on either side, a tie, which its sample farthest
  // from the line decides (x = 2/3, outside).
  EXPECT_EQ(regions::classify(m, {layer_of({right_of(1.5)})}, o).visible, (std::vector<int>{-1, -1}));
}

TEST(Faces, AFaceAnOutlineCrossesIsNotDecidedAtItsFirstSampleFarFromIt) {
  // One face of two triangles, and a small filled square around its first sample (the centroid
  // of the first triangle): that sample is 0.1 inside it, more than ε, as a triangle of a face
  // can reach into a thin shape drawn over it where a secondary line leaves the shape's outline
  // for a neighbour's envelope. The other samples are outside and farther from it (0.33 to
  // 1.27): the face is not covered.
  io::HighOrderMesh m;
  m.nodes = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 2), Vec2(0, 2)};
  m.add_triangle(std::vector<int>{0, 1, 2});
  m.add_triangle(std::vector<int>{0, 2, 3});
  const Vec2 centroid = (m.nodes[0] + m.nodes[1] + m.nodes[2]) / 3.0;
  const auto square = [&](double h) {
    svg::Subpath s;
    const Vec2 c[4] = {centroid + Vec2(-h, -h), centroid + Vec2(h, -h), centroid + Vec2(h, h), centroid + Vec2(-h, h)};
    s.start = c[0];
    for (int i = 0; i < 4; ++i) s.segments.push_back(CubicBezier::line(c[i], c[(i + 1) % 4]));
    return s;
  };
  regions::ClassifyOptions o;
  o.clearance = 0.05;
  o.resolution = 1e-12;
  EXPECT_EQ(regions::classify(m, {layer_of({square(0.1)})}, o).visible[0], -1);
  // Grown to a half-width of 0.75: the centroid, 0.75 from its sides, is the farthest sample (the
  // others are at most 0.36 from them); the face is covered.
  EXPECT_EQ(regions::classify(m, {layer_of({square(0.75)})}, o).visible[0], 0);
  // Two layers: the square on top of a layer covering the whole face. The face is the lower one's.
  svg::Subpath all;
  const Vec2 c[4] = {Vec2(-1, -1), Vec2(3, -1), Vec2(3, 3), Vec2(-1, 3)};
  all.start = c[0];
  for (int i = 0; i < 4; ++i) all.segments.push_back(CubicBezier::line(c[i], c[(i + 1) % 4]));
  EXPECT_EQ(regions::classify(m, {layer_of({all}), layer_of({square(0.1)})}, o).visible[0], 0);
}

TEST(Regions, LoneCircleAreaIsItsCurvesArea) {
  const pipeline::Result r = mesh_painted(doc(R"(<circle id="c" cx="5" cy="5" r="3" fill="#336699"/>)"));
  ASSERT_TRUE(r.painted);
  const auto& regions = r.painted->regions;
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].name, "background");
  // One drawn element: lines 1..5 fixed, 6 the circle's, then the background and the circle.
  EXPECT_EQ(regions[0].physical, 7);
  EXPECT_EQ(regions[1].name, "c");
  EXPECT_EQ(regions[1].fill.to_string(), "#336699");
  EXPECT_EQ(regions[1].physical, 8);
  // The circle is 36 cubics; the curved triangles follow them exactly, so the region's area is
  // the area those cubics enclose, to rounding. (They run outside the circle, within
  // kArcTolerance·r of it: they enclose π r² to 2·kArcTolerance.)
  double want = 0;
  for (const svg::Subpath& s : svg::ellipse_subpaths(5, 5, 3, 3)) want += std::abs(bezier_loop_area(s.segments));
  EXPECT_NEAR(regions[1].area, want, 1e-12 * want);
  EXPECT_GE(want / (std::numbers::pi * 9) - 1, -1e-15);
  EXPECT_LE(want / (std::numbers::pi * 9) - 1, 2 * svg::kArcTolerance);
  // All regions make the box.
  const geometry::Box2 box = r.box;
  EXPECT_NEAR(regions[0].area + regions[1].area, box.width() * box.height(), 1e-12 * box.width() * box.height());
  // The stats say the same.
  ASSERT_TRUE(r.stats.contains("regions"));
  EXPECT_EQ(r.stats["regions"][1]["name"], "c");
  EXPECT_EQ(r.stats["regions"][1]["fill"], "#336699");
  EXPECT_EQ(r.stats["regions"][1]["triangles"].get<int>(), regions[1].triangles);
  // Straight triangles cannot: the linear mesh's circle region misses area.
  Parameters linear;
  linear.order = 1;
  const pipeline::Result s = mesh_painted(doc(R"(<circle id="c" cx="5" cy="5" r="3" fill="#336699"/>)"),
                                          regions::Domain::box, true, linear);
  EXPECT_GT(std::abs(s.painted->regions[1].area - want), 1e-4 * want);
}

TEST(Regions, PaintOrderFillRuleAndTransforms) {
  // a: a square; b over it, moved by a transform, overlapping a's right half; c: a pentagram
  // with the evenodd rule (its centre is a hole); d: the same nonzero (its centre is filled).
  const std::string text = doc(R"svg(
      <rect id="a" x="0" y="0" width="4" height="4" fill="#ff0000"/>
      <g transform="translate(2 0)"><rect id="b" x="0" y="1" width="4" height="2" fill="#00ff00"/></g>
      <path id="c" fill-rule="evenodd" fill="#0000ff" d="M 5 14 L 7.35 21 L 1.2 16.7 L 8.8 16.7 L 2.65 21 Z"/>
      <path id="d" fill="#000000" d="M 15 14 L 17.35 21 L 11.2 16.7 L 18.8 16.7 L 12.65 21 Z"/>)svg",
                                   "viewBox=\"0 0 20 22\"");
  Parameters p;
  p.edge_length_rel = 0.02;
  const pipeline::Result r = mesh_painted(text, regions::Domain::box, true, p);
  EXPECT_EQ(region_at(r, Vec2(1, 2)), "a");
  EXPECT_EQ(region_at(r, Vec2(3, 2)), "b");      // b is painted over a
  EXPECT_EQ(region_at(r, Vec2(5, 2)), "b");
  EXPECT_EQ(region_at(r, Vec2(3, 0.5)), "a");
  EXPECT_EQ(region_at(r, Vec2(5, 17.7)), "background");  // the pentagram's centre, evenodd
  EXPECT_EQ(region_at(r, Vec2(5, 15.5)), "c");
  EXPECT_EQ(region_at(r, Vec2(15, 17.7)), "d");  // nonzero
  EXPECT_EQ(region_at(r, Vec2(10, 8)), "background");
  // The regions' areas add up to the box's.
  double sum = 0;
  for (const regions::Region& g : r.painted->regions) sum += g.area;
  EXPECT_NEAR(sum, r.box.width() * r.box.height(), 1e-9);
}

TEST(Regions, DomainsKeepTheirTriangles) {
  const std::string text = doc(R"(
      <rect id="a" x="1" y="1" width="4" height="4" fill="#ff0000"/>
      <circle cx="7" cy="7" r="1.5" fill="none" stroke="black"/>)");
  const pipeline::Result box = mesh_painted(text, regions::Domain::box, false);
  const pipeline::Result filled = mesh_painted(text, regions::Domain::filled, false);
  const pipeline::Result evenodd = mesh_painted(text, regions::Domain::evenodd, false);
  const io::HighOrderMesh whole = pipeline::high_order_mesh(box);
  const io::HighOrderMesh f = pipeline::high_order_mesh(filled), e = pipeline::high_order_mesh(evenodd);
  double area_f = 0, area_e = 0;
  for (int t = 0; t < f.triangle_count(); ++t) area_f += regions::triangle_area(f, t);
  for (int t = 0; t < e.triangle_count(); ++t) area_e += regions::triangle_area(e, t);
  EXPECT_NEAR(area_f, 16.0, 1e-9);  // the square alone: the stroked circle is not filled
  double circle = 0;
  for (const svg::Subpath& s : svg::ellipse_subpaths(7, 7, 1.5, 1.5)) circle += std::abs(bezier_loop_area(s.segments));
  EXPECT_NEAR(area_e, 16.0 + circle, 1e-9);  // both curves enclose
  EXPECT_LT(f.triangle_count(), whole.triangle_count());
  // Nodes no triangle uses are gone; the domain's border lines keep their feature tag.
  std::vector<char> used(f.nodes.size(), 0);
  for (int t = 0; t < f.triangle_count(); ++t)
    for (int i : f.triangle(t)) used[i] = 1;
  for (int l = 0; l < f.line_count(); ++l)
    for (int i : f.line(l)) used[i] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
  std::set<int> tags(f.line_physical.begin(), f.line_physical.end());
  EXPECT_EQ(tags, (std::set<int>{io::kPhysicalPrimary}));
  // Triangle physical tags: the domain, untagged by region.
  for (int t = 0; t < f.triangle_count(); ++t) ASSERT_EQ(f.triangle_physical[t], io::kPhysicalDomain);
  // The default run is untouched: no closing lines read, no painted mesh.
  const pipeline::Result plain = pipeline::run(pipeline::Source::svg(text, "<test>"), Parameters{});
  EXPECT_FALSE(plain.painted);
  EXPECT_EQ(pipeline::high_order_mesh(plain).nodes, whole.nodes);
}

TEST(Regions, EmptyDomainAndStrokeOnlyDrawings) {
  const std::string icon = doc(R"(<path fill="none" stroke="black" d="M 1 1 C 3 0 5 4 8 2"/>)");
  const pipeline::Result r = mesh_painted(icon);
  bool said = false;
  for (const std::string& w : r.warnings) said = said || w.find("no element is filled") != std::string::npos;
  EXPECT_TRUE(said);
  ASSERT_EQ(r.painted->regions.size(), 1u);
  EXPECT_EQ(r.painted->regions[0].name, "background");
  try {
    mesh_painted(icon, regions::Domain::filled, false);
    FAIL() << "an empty domain must be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("'filled' is empty"), std::string::npos);
  }
  // Filled, but far smaller than the drawing: no triangle is mostly inside the dot, and the message
  // says so rather than that nothing is filled.
  const std::string dot = doc(R"(<path fill="none" stroke="black" d="M 0 0 L 100 100"/>
                                 <circle cx="50" cy="10" r="0.001" fill="red"/>)");
  try {
    mesh_painted(dot, regions::Domain::filled, false);
    FAIL() << "an empty domain must be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("no triangle is mostly inside what its fills paint"), std::string::npos)
        << e.what();
  }
}

// End to end: a filled element whose outline runs through every sample point of one face (made
// knowing the mesh, which fills do not change) cannot be decided there: the run fails as internal
// (exit code 3) and names the element, rather than guess.
TEST(Regions, AnUndecidableFaceFailsNamingTheElement) {
  svg::FeatureSoup soup;
  soup.sources.push_back({"path", "ring", 0, 7});
  soup.sources.push_back({"path", "trap", 1, 9});
  for (const svg::Subpath& s : svg::ellipse_subpaths(5, 5, 2, 2))
    for (const CubicBezier& c : s.segments) soup.curves.push_back({c, 0, {}, {}, {}, {}});
  Parameters p;
  p.regions = true;
  const pipeline::Result first = pipeline::run(pipeline::Source::curves(soup, "<soup>"), p);
  // The face inside the circle: the one holding the triangle nearest the centre.
  const io::HighOrderMesh whole = pipeline::high_order_mesh(first);
  const regions::Faces faces = regions::find_faces(whole);
  int inner = -1;
  double nearest = 1e300;
  for (int t = 0; t < whole.triangle_count(); ++t) {
    const double d = (whole.nodes[whole.triangle(t)[9]] - Vec2(5, 5)).norm();
    if (d < nearest) nearest = d, inner = faces.of_triangle[t];
  }
  std::vector<Vec2> points;
  for (int t = 0; t < whole.triangle_count(); ++t) {
    if (faces.of_triangle[t] != inner) continue;
    geometry::P3Nodes n;
    for (int i = 0; i < 10; ++i) n[i] = whole.nodes[whole.triangle(t)[i]];
    for (const auto& uv : {std::pair{1.0 / 3, 1.0 / 3}, std::pair{1.0 / 6, 1.0 / 6}, std::pair{2.0 / 3, 1.0 / 6},
                           std::pair{1.0 / 6, 2.0 / 3}})
      points.push_back(geometry::p3_map(n, uv.first, uv.second));
  }
  ASSERT_GT(points.size(), 3u);
  svg::FillLayer trap;
  trap.source = 1;
  trap.fill = svg::Paint::rgb(9, 9, 9);
  trap.subpaths.emplace_back();
  for (std::size_t i = 0; i < points.size(); ++i) {
    trap.subpaths[0].push_back(CubicBezier::line(points[i], points[(i + 1) % points.size()]));
    trap.bounds.add(points[i]);
  }
  soup.fills.push_back(trap);
  try {
    pipeline::run(pipeline::Source::curves(soup, "<soup>"), p);
    FAIL() << "an undecidable face must not be guessed";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::internal);
    EXPECT_NE(std::string(e.what()).find("<path id=\"trap\"> (line 9)"), std::string::npos) << e.what();
  }
}

// The groups a solver selects by (regions/groups.hpp).
namespace {

// Two squares sharing a side, a ring drawn over nothing (stroke only), one id twice and one that is
// a fixed group's name.
const std::string kSharing = R"(<rect id="left" x="1" y="1" width="4" height="4" fill="#ff0000"/>
<rect id="right" x="5" y="1" width="4" height="4" fill="#0000ff"/>
<circle id="border" cx="3" cy="3" r="1" fill="none" stroke="black"/>
<circle id="right" cx="7" cy="3" r="1" fill="#00ff00"/>)";

// {id: (dim, name, count, length or area)} of the stats' groups.
std::map<int, std::tuple<int, std::string, int, double>> groups_of(const pipeline::Result& r) {
  std::map<int, std::tuple<int, std::string, int, double>> out;
  for (const auto& g : r.stats.at("groups")) {
    const bool line = g["dim"] == 1;
    out[g["id"].get<int>()] = {g["dim"].get<int>(), g["name"].get<std::string>(),
                               g[line ? "lines" : "triangles"].get<int>(), g[line ? "length" : "area"].get<double>()};
  }
  return out;
}

TEST(Groups, ElementsBorderAndRegionsAreNumberedByTheDrawing) {
  for (int order : {1, 3}) {
    SCOPED_TRACE("order " + std::to_string(order));
    Parameters p;
    p.order = order;
    const auto box = groups_of(mesh_painted(doc(kSharing), regions::Domain::box, true, p));
    const auto filled = groups_of(mesh_painted(doc(kSharing), regions::Domain::filled, true, p));
    // Four drawn elements: their lines 6..9, the regions from 10 (10 the background).
    EXPECT_EQ(std::get<1>(box.at(5)), "border");
    EXPECT_EQ(std::get<1>(box.at(6)), "left");
    EXPECT_EQ(std::get<1>(box.at(7)), "right");
    EXPECT_EQ(std::get<1>(box.at(8)), "border@2");  // not the border's name
    EXPECT_EQ(std::get<1>(box.at(9)), "right@2");
    EXPECT_EQ(std::get<1>(box.at(10)), "background");
    EXPECT_FALSE(filled.contains(10));  // the filled domain has no background
    for (const auto& [id, g] : filled) {
      // The same ids and names in both domains, lines below regions.
      if (std::get<0>(g) == 2) {
        EXPECT_GE(id, 10);
        EXPECT_EQ(std::get<1>(box.at(id)), std::get<1>(g));
        EXPECT_NEAR(std::get<3>(box.at(id)), std::get<3>(g), 1e-9);
      } else {
        EXPECT_LT(id, 10);
      }
    }
    // Each square's group has its whole outline, the shared side included.
    EXPECT_NEAR(std::get<3>(box.at(6)), 16, 1e-9);
    EXPECT_NEAR(std::get<3>(filled.at(6)), 16, 1e-9);
    // The border: the box's sides, or the outline of the two squares together (the green circle
    // lies inside the right one).
    EXPECT_EQ(std::get<3>(box.at(5)), std::get<3>(box.at(3)));
    EXPECT_NEAR(std::get<3>(filled.at(5)), 24, 1e-9);
  }
}

TEST(Groups, EveryLineOnTheBorderAndNoneInside) {
  const pipeline::Result r = mesh_painted(doc(kSharing), regions::Domain::filled, true);
  const io::HighOrderMesh m = pipeline::high_order_mesh(r);
  const std::vector<char> border = regions::border_lines(m);
  const auto triangles_on = regions::edge_triangles(m);
  int on_border = 0;
  for (const auto& [edge, ts] : triangles_on) on_border += ts.size() == 1;
  int tagged = 0;
  for (int l = 0; l < m.line_count(); ++l) {
    const std::vector<int> g = m.groups_of_line(l);
    const bool in_border = std::find(g.begin(), g.end(), io::kPhysicalBorder) != g.end();
    EXPECT_EQ(in_border, bool(border[l]));
    tagged += in_border;
  }
  EXPECT_EQ(tagged, on_border);  // every edge of the border is a line of the group
}

}  // namespace
