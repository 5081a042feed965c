// The whole pipeline on inputs at the extremes: what fuzz/fuzz_pipeline.cpp found, each as it
// was found, and the limits the pipeline states for them.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
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

}  // namespace
