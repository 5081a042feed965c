// Diffusion curves: which side of a curve gets which colour, and the Laplace solve on the mesh
// cut open along the curves.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "fem/diffuse.hpp"
#include "pipeline/output.hpp"

using namespace curvemesh;
using fem::Rgb;
using fem::Vec2;

namespace {

std::string document(const std::string& body) { return "<svg xmlns=\"http://www.w3.org/2000/svg\">" + body + "</svg>"; }

svg::FeatureSoup soup_of(const std::string& body) {
  return pipeline::run(pipeline::Source::svg(document(body), "test.svg"), {}, pipeline::Stage::read).soup;
}

fem::MeshedDrawing mesh_of(const std::string& body, const pipeline::Parameters& parameters = {}) {
  return pipeline::mesh_drawing(pipeline::Source::svg(document(body), "test.svg"), parameters);
}

// A drawing meshed and diffused, cubic or straight.
struct Diffused {
  fem::MeshedDrawing drawing;
  fem::DiffusionMesh cut;
  io::HighOrderMesh mesh;
  std::unique_ptr<fem::Geometry> geometry;
  std::unique_ptr<fem::Space> space;
  fem::DiffusionResult result;

  Diffused(const std::string& body, bool linear, const pipeline::Parameters& parameters = {}) {
    drawing = mesh_of(body, parameters);
    cut = fem::cut_along_curves(drawing, drawing.colours);
    mesh = linear ? fem::straight_mesh(cut.cut.mesh) : cut.cut.mesh;
    geometry = std::make_unique<fem::Geometry>(mesh);
    space = std::make_unique<fem::Space>(mesh, 2);
    result = fem::diffuse(*geometry, *space, cut.sides);
  }

  // The colour at x (the first triangle that holds it).
  Rgb at(const Vec2& x) const {
    for (int t = 0; t < geometry->triangle_count(); ++t) {
      Vec2 xi;
      if (geometry->inverse(t, x, xi) && xi.x() >= -1e-12 && xi.y() >= -1e-12 && xi.x() + xi.y() <= 1 + 1e-12)
        return result.at(*space, t, xi);
    }
    ADD_FAILURE() << "no triangle holds " << x.transpose();
    return {-1, -1, -1};
  }
};

void expect_colour(const Rgb& got, const Rgb& want, double tol, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << what << ", channel " << k;
}

// Two isolated points that make the box square around the curves (the box is the drawing's
// bounding box grown by 5% of its diagonal).
const std::string kPoints = "<path d='M50 0 L50 0'/><path d='M50 100 L50 100'/>";

}  // namespace

TEST(CurveColours, GivenSidesElseStrokeElseFillElseBlack) {
  const svg::FeatureSoup soup = soup_of(
      "<path d='M0 0 L1 0' stroke='#ff0000' fill='#00ff00' data-color-left='#0000ff'/>"
      "<path d='M0 1 L1 1' stroke='none' fill='#00ff00' data-color-right='white'/>"
      "<path d='M0 2 L1 2' stroke='none' fill='none'/>");
  const auto c = pipeline::curve_colours(soup);
  ASSERT_EQ(c.size(), 3u);
  expect_colour(c[0].left, {0, 0, 1}, 0, "given left");
  expect_colour(c[0].right, {1, 0, 0}, 0, "stroke");
  expect_colour(c[1].left, {0, 1, 0}, 0, "fill");
  expect_colour(c[1].right, {1, 1, 1}, 0, "given right");
  expect_colour(c[2].left, {0, 0, 0}, 0, "black");
  expect_colour(c[2].right, {0, 0, 0}, 0, "black");
}

TEST(Diffuse, LeftIsAboveACurveDrawnRightwards) {
  // On screen (y down) a path drawn from left to right has its left side above it.
  const Rgb red{1, 0, 0}, blue{0, 0, 1};
  for (const bool linear : {false, true}) {
    for (const bool reversed : {false, true}) {
      const std::string d = reversed ? "M90 50 L10 50" : "M10 50 L90 50";
      const Diffused f(kPoints + "<path d='" + d + "' data-color-left='red' data-color-right='blue'/>", linear);
      const std::string what = std::string(linear ? "straight" : "cubic") + (reversed ? ", reversed" : "");
      const Rgb above = f.at({50, 49}), below = f.at({50, 51});
      const Rgb& want_above = reversed ? blue : red;
      const Rgb& want_below = reversed ? red : blue;
      // One unit from the middle of a curve 80 long the colour has barely started to blend.
      expect_colour(above, want_above, 0.01, what + ", above");
      expect_colour(below, want_below, 0.01, what + ", below");
    }
  }
}

TEST(Diffuse, SidesOfACurvedPath) {
  // An arc bulging upwards, drawn rightwards: red above it, blue below (inside the bulge).
  const Diffused f(kPoints + "<path d='M10 60 C 30 20 70 20 90 60' data-color-left='red' data-color-right='blue'/>",
                   false);
  // The arc's top is at y = 30 (x = 50).
  expect_colour(f.at({50, 29}), {1, 0, 0}, 0.01, "above");
  expect_colour(f.at({50, 31}), {0, 0, 1}, 0.01, "below");
}

TEST(Diffuse, ClosedCurveSeparatesConstantColours) {
  // A circle is drawn clockwise on screen (from its rightmost point downwards): its right side
  // is inside. Inside and outside are separate parts of the cut mesh, each held by one colour
  // only, so each is exactly that colour; the secondary lines of a circle made of secondary
  // pieces (a large l_m) are cut the same way.
  pipeline::Parameters secondary;
  secondary.min_edge_length_rel = 0.2;
  for (const bool all_secondary : {false, true}) {
    const Diffused f(kPoints + "<circle cx='50' cy='50' r='30' data-color-left='#ffcc00' data-color-right='#3366ff'/>",
                     false, all_secondary ? secondary : pipeline::Parameters{});
    int primary = 0, secondary_lines = 0;
    for (int p : f.drawing.mesh.line_physical)
      primary += p == io::kPhysicalPrimary, secondary_lines += p == io::kPhysicalSecondary;
    if (all_secondary) {
      EXPECT_EQ(primary, 0);
      EXPECT_GT(secondary_lines, 0);
    } else {
      EXPECT_GT(primary, 0);
    }
    const Rgb outside{1, 0.8, 0}, inside{0.2, 0.4, 1};
    const std::string what = all_secondary ? "secondary" : "primary";
    expect_colour(f.at({50, 50}), inside, 1e-9, what + ", centre");
    expect_colour(f.at({50, 21}), inside, 1e-9, what + ", inside near the top");
    expect_colour(f.at({50, 19}), outside, 1e-9, what + ", outside above");
    expect_colour(f.at({85, 85}), outside, 1e-9, what + ", outside corner");
    EXPECT_EQ(f.result.background_components, 0);
  }
}

TEST(Diffuse, OpenCurveBlendsBetweenItsColours) {
  // Around the ends of an open curve the two sides meet: the colour varies, the two sides of
  // the cut differ, and the solution stays within the boundary colours (the continuous problem's
  // maximum principle; P2 nodal values may overshoot where the solution is singular, at the
  // curve's ends, but not by more than a small fraction of the jump).
  for (const bool linear : {false, true}) {
    const Diffused f(kPoints + "<path d='M20 50 C 40 30 60 70 80 50' data-color-left='#ff0000' "
                               "data-color-right='#0000ff'/>",
                     linear);
    const std::string what = linear ? "straight" : "cubic";
    // Across the curve at its middle (it passes through (50, 50)): red above, blue below.
    const Rgb above = f.at({50, 49.5}), below = f.at({50, 50.5});
    EXPECT_GT(above[0] - below[0], 0.8) << what;
    EXPECT_GT(below[2] - above[2], 0.8) << what;
    // Far above and far below, both colours contribute.
    const Rgb top = f.at({50, 5});
    EXPECT_GT(top[0], top[2]) << what;
    EXPECT_GT(top[2], 0.05) << what;
    const auto& r = f.result.channel;
    // At the nodes, here, no overshoot at all.
    EXPECT_GE(r[0].minCoeff(), -1e-12) << what;
    EXPECT_LE(r[0].maxCoeff(), 1 + 1e-12) << what;
    // Between them P2 overshoots at the curve's ends: a loose end's node, held at the mean 1/2,
    // makes the held quadratic along the last edge 1/2, 1, 1 (corner, middle, corner), which
    // peaks at 1 + 1/16. Sampled on a lattice in every triangle, nothing goes further.
    double lo = 0, hi = 1;
    for (int t = 0; t < f.geometry->triangle_count(); ++t)
      for (int i = 0; i <= 8; ++i)
        for (int j = 0; i + j <= 8; ++j) {
          const double v = f.result.at(*f.space, t, Vec2(i / 8.0, j / 8.0))[0];
          lo = std::min(lo, v), hi = std::max(hi, v);
        }
    EXPECT_GE(lo, -1.0 / 16 - 1e-12) << what;
    EXPECT_LE(hi, 1 + 1.0 / 16 + 1e-12) << what;
    EXPECT_GT(hi, 1 + 1.0 / 16 - 1e-12) << what << ": the loose end's overshoot, sampled at its peak (3/4 of the edge)";
    EXPECT_NEAR(r[1].cwiseAbs().maxCoeff(), 0, 1e-12) << what << ": no green anywhere";
    // Red and blue add up to one everywhere: 1 − red solves the same problem as blue.
    EXPECT_NEAR((r[0] + r[2] - Eigen::VectorXd::Ones(r[0].size())).cwiseAbs().maxCoeff(), 0, 1e-9) << what;
  }
}

TEST(Diffuse, OneColourEverywhereIsExact) {
  // Constants are P2 functions: with every side at the same colour the solution is that colour.
  const Diffused f(kPoints + "<path d='M20 50 C 40 30 60 70 80 50' stroke='#336699'/>"
                             "<path d='M30 20 Q 50 40 70 20' stroke='#336699' fill='none'/>",
                   false);
  const Rgb c{0x33 / 255.0, 0x66 / 255.0, 0x99 / 255.0};
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR((f.result.channel[k].array() - c[k]).abs().maxCoeff(), 0, 1e-10) << "channel " << k;
}

TEST(Diffuse, PartsNoCurveBordersTakeTheBackground) {
  // Two circles cut open, but only the first one's sides coloured: the second one's inside has
  // no held unknown, which would make the system singular. It takes the background.
  const std::string body =
      kPoints + "<circle id='a' cx='30' cy='50' r='15' stroke='red'/><circle id='b' cx='70' cy='50' r='15' stroke='blue'/>";
  const svg::FeatureSoup soup = soup_of(body);
  const fem::MeshedDrawing drawing = mesh_of(body);
  fem::DiffusionMesh cut = fem::cut_along_curves(drawing, drawing.colours);
  const auto lines = fem::edge_lines(drawing.mesh);
  std::vector<fem::ColouredEdge> first_only;
  for (const fem::ColouredEdge& s : cut.sides) {
    const int curve = drawing.line_curve[lines[s.triangle][s.edge]];
    if (soup.sources[soup.curves[curve].source].id == "a") first_only.push_back(s);
  }
  ASSERT_FALSE(first_only.empty());
  ASSERT_LT(first_only.size(), cut.sides.size());
  const fem::Geometry geometry(cut.cut.mesh);
  const fem::Space space(cut.cut.mesh, 2);
  fem::DiffuseOptions options;
  options.background = {0, 1, 0};
  const fem::DiffusionResult r = fem::diffuse(geometry, space, first_only, options);
  EXPECT_EQ(r.background_components, 1);
  // Circle b's inside is green; everything else is red (the only colour held).
  const auto positions = space.positions(geometry);
  int green = 0;
  for (int i = 0; i < space.size(); ++i) {
    const Vec2& x = positions[i];
    const bool in_b = (x - Vec2(70, 50)).norm() < 14;
    const bool off_b = (x - Vec2(70, 50)).norm() > 16;
    if (!in_b && !off_b) continue;  // on or near circle b: its two sides share positions
    const Rgb want = in_b ? Rgb{0, 1, 0} : Rgb{1, 0, 0};
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(r.channel[k][i], want[k], 1e-9) << "unknown " << i << " at " << x.transpose();
    green += in_b;
  }
  EXPECT_GT(green, 0);
  // With nothing held at all, every part is background.
  const fem::DiffusionResult none = fem::diffuse(geometry, space, {}, options);
  EXPECT_EQ(none.background_components, 3);  // outside, inside a, inside b
  EXPECT_NEAR((none.channel[1].array() - 1).abs().maxCoeff(), 0, 0);
}
