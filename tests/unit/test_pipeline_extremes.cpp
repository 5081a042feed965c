// The whole pipeline on inputs at the extremes: what fuzz/fuzz_pipeline.cpp found, each as it
// was found, and the limits the pipeline states for them.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pipeline/check.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"

namespace {

using curvemesh::Error;
using curvemesh::geometry::Vec2;
namespace pipeline = curvemesh::pipeline;
using Curves = std::vector<std::array<Vec2, 4>>;

Curves moved(Curves curves, const Vec2& by, double scale = 1.0) {
  for (auto& c : curves)
    for (Vec2& p : c) p = scale * p + by;
  return curves;
}

// Two crossing cubics and a segment through both, about 1 wide around the origin.
const Curves kCrossing = {{{{0, 0}, {0.3, 1}, {0.7, -1}, {1, 0}}},
                          {{{0, 0.5}, {0.4, -0.5}, {0.6, 1}, {1, 0.2}}},
                          {{{0.1, -0.4}, {0.4, -0.1}, {0.6, 0.2}, {0.9, 0.6}}}};

// The mesh is certified with exact rationals, element by element, as it is written.
void expect_certified(const pipeline::Result& r) {
  const auto check = pipeline::check_mesh(pipeline::high_order_mesh(r));
  EXPECT_GT(check.triangles, 0u);
  EXPECT_EQ(check.invalid, 0u);
}

TEST(PipelineExtremes, DrawingFarFromTheOriginForItsSizeIsRefused) {
  // Doubles near 1e15 are 0.125 apart: the drawing, 1 wide, would have three bits of its
  // coordinates (the curves' resampling once split such a curve for ever).
  try {
    pipeline::run(pipeline::Source::beziers(moved(kCrossing, {1e15, 1e15}), "far"), {});
    FAIL() << "a drawing 1 wide at 1e15 was meshed";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::invalid_input);
    EXPECT_NE(std::string(e.what()).find("far: the drawing is too small for how far it lies from the origin"),
              std::string::npos)
        << e.what();
  }
}

TEST(PipelineExtremes, DrawingOffsetButResolvedIsMeshed) {
  // 1 wide at 1e5: doubles there are 1.5e-11 apart, 2^-36 of its size: meshed and certified.
  expect_certified(pipeline::run(pipeline::Source::beziers(moved(kCrossing, {1e5, -1e5}), "offset"), {}));
}

TEST(PipelineExtremes, HugeAndTinyScales) {
  for (const double scale : {1e-6, 1e12}) {
    SCOPED_TRACE(scale);
    expect_certified(pipeline::run(pipeline::Source::beziers(moved(kCrossing, {0, 0}, scale), "scaled"), {}));
  }
}

// The sizes of drawing meshed (svg/drawing_size.hpp): at both ends of the range, meshed curved
// and certified; beyond them, refused with the reason instead of meshed wrong or not certified.
TEST(PipelineExtremes, SizesAtTheEndsOfTheRange) {
  // kCrossing is about 1.4 across, its coordinates at most 1 in magnitude.
  for (const double scale : {1.01e-100 / 1.4, 0.6e100}) {
    SCOPED_TRACE(scale);
    const Curves curves = moved(kCrossing, {0, 0}, scale);
    expect_certified(pipeline::run(pipeline::Source::beziers(curves, "scaled"), {}));
    pipeline::Parameters linear;
    linear.order = 1;
    expect_certified(pipeline::run(pipeline::Source::beziers(curves, "scaled"), linear));
  }
  const auto error_of = [](double scale) -> std::string {
    try {
      pipeline::run(pipeline::Source::beziers(moved(kCrossing, {0, 0}, scale), "scaled"), {});
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), Error::Kind::invalid_input);
      return e.what();
    }
    return "meshed";
  };
  EXPECT_EQ(error_of(1e-160).find(
                "scaled: the drawing is 1.4e-160 across, smaller than 1e-100: too small to mesh in "
                "double precision; scale it up"),
            0u)
      << error_of(1e-160);
  EXPECT_NE(error_of(0.9e-100 / 1.4).find("smaller than 1e-100"), std::string::npos);
  EXPECT_NE(error_of(1e200).find("beyond 1e+100: too large to mesh in double precision; scale it down"),
            std::string::npos);
  EXPECT_NE(error_of(0.9e100).find("across, larger than 1e+100"), std::string::npos);
}

// Found by fuzz/fuzz_pipeline.cpp (written out with FUZZ_PIPELINE_SVG): a cubic twice over and a
// flat one, at 1e12. Under UndefinedBehaviorSanitizer (CURVEMESH_SANITIZE=ON) the optimizer's
// stop rule overflowed here: its first iteration compared four times "the previous iteration's
// changes", then LONG_MAX.
TEST(PipelineExtremes, FoundByFuzzingCoincidentCubicsAt1e12) {
  const std::string svg =
    R"(<svg xmlns="http://www.w3.org/2000/svg">)"
    R"(<path fill="none" stroke="black" d="M-899993896484.375 -100006103515.625C-299987792968.75 799987792968.75 299987792968.75 -799987792968.75 899993896484.375 100006103515.625"/>)"
    R"(<path fill="none" stroke="black" d="M-899993896484.375 -100006103515.625C-299987792968.75 799987792968.75 299987792968.75 -799987792968.75 899993896484.375 100006103515.625"/>)"
    R"(<path fill="none" stroke="black" d="M-945312500000 -1000000000000C-1000000000000 -1000000000000 -1000000000000 -1000000000000 -1000000000000 -1000000000000"/>)"
    R"(</svg>)";
  expect_certified(pipeline::run(pipeline::Source::svg(svg, "fuzz-1"), {}));
}

// A crossing of a curve and a secondary segment within round-off of the curve's end, at l = 1/10:
// its exact position neither rounds (its nearest double is the curve's end) nor collapses (a free
// vertex lies on the segment through it to round-off, and the collapse would invert a triangle).
// The free vertex is collapsed into it first; the segment left flat through two more vertices is
// released onto the path through them and swapped away.
TEST(PipelineExtremes, FoundByFuzzingACrossingWithinRoundOffOfACurveEnd) {
  const std::string svg =
    R"(<svg xmlns="http://www.w3.org/2000/svg">)"
    R"(<path fill="none" stroke="black" d="M-9.7653198242187499e-07 -7.6406860351562501e-07C-5.9414672851562501e-07 -9.9218749999999998e-07 -9.0469360351562493e-07 -9.3743896484374996e-07 -5.2499389648437499e-07 2.3193359374999997e-09"/>)"
    R"(<path fill="none" stroke="black" d="M-2.9998779296875001e-07 8.99993896484375e-07C2.9998779296875001e-07 2.6406860351562498e-07 -8.99993896484375e-07 -1.9570922851562498e-07 -6.0131835937499998e-07 -9.6508789062499998e-07"/>)"
    R"(<path fill="none" stroke="black" d="M-9.2700759916889806e-07 -7.9433161527174381e-07C-4.1740285257093201e-07 -8.4834103127491245e-07 9.2201894027033937e-08 -9.023504472780813e-07 6.0180664062499994e-07 -9.5635986328124993e-07"/>)"
    R"(<path fill="none" stroke="black" d="M-2.9998779296874e-07 8.9999389648436504e-07C2.9998779296876001e-07 2.6406860351561497e-07 -8.9999389648436504e-07 -1.9570922851563499e-07 -6.0131835937499003e-07 -9.6508789062500993e-07"/>)"
    R"(<path fill="none" stroke="black" d="M1.5215539362679472e-07 -9.0870449621963044e-07C2.3476822791265482e-07 -9.0580096297454536e-07 3.1738106219851486e-07 -9.0289742972946018e-07 3.9999389648437497e-07 -8.99993896484375e-07"/>)"
    R"(<path fill="none" stroke="black" d="M3.3201589242607674e-07 -9.2776664304427828e-07C4.2134596278925949e-07 -3.1903192869618556e-07 5.1067603315244213e-07 2.8970278565190721e-07 6.0000610351562494e-07 8.9843749999999992e-07"/>)"
    R"(<path fill="none" stroke="black" d="M-6.0119628906249996e-07 6.0177612304687501e-07C9.0072631835937499e-07 0 -9.9963378906250001e-07 -9.4299316406249991e-07 9.0393066406249991e-07 9.3594360351562495e-07"/>)"
    R"(<path fill="none" stroke="black" d="M-9.2700759916889806e-07 -7.9433161527174381e-07C-4.1740285257093201e-07 -8.4834103127491245e-07 9.2201894027033937e-08 -9.023504472780813e-07 6.0180664062499994e-07 -9.5635986328124993e-07"/>)"
    R"(<path fill="none" stroke="black" d="M3.2002519250612465e-07 -9.2649583325596845e-07C4.1335216284262476e-07 -3.1766592334252063e-07 5.0667913317912488e-07 2.9116398657092718e-07 6.0000610351562494e-07 8.99993896484375e-07"/>)"
    R"(</svg>)";
  pipeline::Parameters parameters;
  parameters.edge_length_rel = 1.0 / 10;
  expect_certified(pipeline::run(pipeline::Source::svg(svg, "fuzz-2"), parameters));
}

// ε_m is one of the lengths pipeline::resolve makes absolute, against the diagonal d every other
// length is: the tight box of the curves. An S-shaped cubic whose control points reach far beyond
// it (control box 2,000 high, curve 577) makes the two boxes differ by 3.5×. The segment from
// (5, −h) to (5, h) has its points (the start, then four control points) centred at (5, −h/5),
// the farthest 1.2 h from it: it becomes a point when 1.2 h ≤ ε_m, and stays a curve at 1.1 ε_m,
// which the control box's diagonal would have made a point.
TEST(PipelineExtremes, TinyPathsAreMeasuredAgainstTheMeshDiagonal) {
  curvemesh::pipeline::Parameters p;
  p.stop_after = curvemesh::StopAfter::triangulate;
  p.eps_m_rel = 1e-6;  // large enough for paths far above round-off
  const double d = std::hypot(10.0, 1000 / std::sqrt(3.0));  // the S-curve's tight box
  for (const double half : {0.9, 1.1}) {
    SCOPED_TRACE(half);
    const double h = half * p.eps_m_rel * d / 1.2;
    std::ostringstream text;
    text.precision(17);
    text << "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M 0 0 C 0 -1000 10 1000 10 0\" fill=\"none\" "
         << "stroke=\"black\"/><path d=\"M 5 " << -h << " L 5 " << h << "\" fill=\"none\" stroke=\"black\"/></svg>";
    const pipeline::Result r = pipeline::run(pipeline::Source::svg(text.str(), "tiny"), p);
    EXPECT_NEAR(r.resolved.d, d, 1e-9 * d);
    EXPECT_DOUBLE_EQ(r.resolved.features.eps_m, p.eps_m_rel * r.resolved.d);
    EXPECT_EQ(r.soup.points.size(), half < 1 ? 1u : 0u);
    EXPECT_EQ(r.soup.curves.size(), half < 1 ? 1u : 2u);
  }
}

// With strokes as areas μ and ε shrink together, only as far as the narrowest stroke at least
// --min-stroke-width wide needs (three μ: its two sides and its fill's outline between them stay
// μ apart); a narrower stroke moves nothing and paints nothing. Lines leave μ as given.
TEST(PipelineExtremes, StrokesAsAreasShrinkMuToTheirNarrowestWidth) {
  const auto svg = [](double a, double b) {
    std::ostringstream text;
    text << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 100 100\">"
         << "<path d=\"M 0 0 L 100 100\" fill=\"none\" stroke=\"black\" stroke-width=\"" << a << "\"/>"
         << "<path d=\"M 0 100 L 100 0\" fill=\"none\" stroke=\"black\" stroke-width=\"" << b << "\"/></svg>";
    return text.str();
  };
  curvemesh::pipeline::Parameters p;
  p.stop_after = curvemesh::StopAfter::triangulate;
  p.strokes = curvemesh::Strokes::areas;
  const auto resolved = [&](double a, double b) {
    return pipeline::run(pipeline::Source::svg(svg(a, b), "strokes"), p).resolved;
  };
  const pipeline::Resolved wide = resolved(2, 3);  // both at least 3 μ = 0.003 d (about 0.42) wide
  EXPECT_DOUBLE_EQ(wide.features.mu, p.mu_rel * wide.d);
  EXPECT_DOUBLE_EQ(wide.features.epsilon, p.epsilon_rel * wide.d);
  const pipeline::Resolved thin = resolved(0.12, 3);
  EXPECT_NEAR(thin.features.mu, 0.04, 1e-12);
  EXPECT_NEAR(thin.features.epsilon, 0.04 * p.epsilon_rel / p.mu_rel, 1e-12);
  EXPECT_NEAR(thin.curve.tolerance, thin.features.epsilon, 1e-15);
  EXPECT_NEAR(thin.min_stroke_width, p.min_stroke_width_rel * thin.d, 1e-15);
  const double below = 0.5 * p.min_stroke_width_rel * wide.d;  // under the floor: left out
  const pipeline::Resolved hair = resolved(below, 0.12);
  EXPECT_NEAR(hair.features.mu, 0.04, 1e-12);
  p.strokes = curvemesh::Strokes::lines;
  const pipeline::Resolved lines = resolved(0.12, 3);
  EXPECT_DOUBLE_EQ(lines.features.mu, p.mu_rel * lines.d);
  // A --mu small enough for a stroke below the floor lets it paint.
  p.strokes = curvemesh::Strokes::areas;
  p.mu_rel = p.epsilon_rel = 1e-6;
  EXPECT_NEAR(resolved(below, 3).min_stroke_width, 3e-6 * wide.d, 1e-15);
}

}  // namespace
