// libFuzzer target for the whole method: its bytes become an adversarial soup of at most 100
// cubic curves (and segments, as flat cubics) — curves that coincide, touch, cross at tiny angles,
// lie 1e-15 apart, are tiny or huge, with coordinates from 1e-6 to 1e12 — meshed through the
// pipeline: features → triangulate → optimize → curve, with default parameters but for the target
// edge length (the default or coarser, picked by the input). A finding is a
// crash, a sanitizer report, an exception other than the documented refusal of the input
// (curvemesh::Error, invalid_input), an output the exact check does not certify, or a run over
// libFuzzer's -timeout (FUZZ_PIPELINE_SVG, below, writes an input's soup as a drawing instead).
// fuzz/pipeline.dict has the operation bytes and telling numbers;
// fuzz/pipeline-seeds/ a seed corpus (see docs/testing.md, "Fuzzing").
//
// Layout of the input, read from its last byte backwards (FuzzedDataProvider's order; each
// number's bytes most significant first): one byte picks the scale (10^-6 … 10^12) of the whole
// soup, one the edge length l (1/20, 1/10, 1/5, 1/2), then one record per curve: an operation byte, then what it reads (a coordinate is a
// 16-bit fraction of the scale, an exponent or a parameter one byte; fuzz/pipeline-seeds.py
// writes inputs in this layout). Operations (byte % 10):
//   0 a cubic with four free control points     5 a segment crossing an earlier curve at a tiny angle
//   1 a segment                                  6 a tiny cubic (1e-9 … 1e-15 of the scale)
//   2 an earlier curve again                     7 an earlier curve reversed
//   3 an earlier curve moved by 1e-15 … 1e-9     8 a segment from a point inside an earlier curve
//   4 a cubic starting where an earlier one ends 9 a huge cubic (10^3 … 10^6 times the scale)
#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "geometry/bezier.hpp"
#include "pipeline/check.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"

namespace {

using curvemesh::geometry::Vec2;
using Curve = std::array<Vec2, 4>;

constexpr int kMaxCurves = 100;

struct Soup {
  FuzzedDataProvider& in;
  double scale;
  std::vector<Curve> curves;

  // A coordinate: a 16-bit fraction of the scale, signed.
  double coordinate() { return scale * (in.ConsumeIntegral<std::uint16_t>() / 32768.0 - 1.0); }
  Vec2 point() {
    const double x = coordinate();
    return {x, coordinate()};
  }
  // 10^-e for e read from one byte in [lo, hi].
  double power(int lo, int hi) { return std::pow(10.0, -in.ConsumeIntegralInRange<int>(lo, hi)); }
  const Curve& earlier() { return curves[in.ConsumeIntegralInRange<std::size_t>(0, curves.size() - 1)]; }
  static Curve segment(const Vec2& a, const Vec2& b) { return {a, (2 * a + b) / 3, (a + 2 * b) / 3, b}; }

  void add() {
    const int op = in.ConsumeIntegral<std::uint8_t>() % 10;
    if (curves.empty() && (op == 2 || op == 3 || op == 4 || op == 5 || op == 7 || op == 8)) {
      curves.push_back({point(), point(), point(), point()});
      return;
    }
    switch (op) {
      case 0: {
        const Vec2 a = point(), b = point(), c = point();
        curves.push_back({a, b, c, point()});
        break;
      }
      case 1: {
        const Vec2 a = point();
        curves.push_back(segment(a, point()));
        break;
      }
      case 2: curves.push_back(earlier()); break;
      case 3: {
        Curve c = earlier();
        const double offset = scale * power(9, 15);
        const Vec2 shift(offset, in.ConsumeBool() ? offset : -offset);
        for (Vec2& p : c) p += shift;
        curves.push_back(c);
        break;
      }
      case 4: {
        const Vec2 start = earlier()[3], b = point(), c = point();
        curves.push_back({start, b, c, point()});
        break;
      }
      case 5: {
        const Curve& c = earlier();
        const double t = in.ConsumeIntegral<std::uint8_t>() / 255.0;
        const curvemesh::geometry::CubicBezier b(c[0], c[1], c[2], c[3]);
        const Vec2 p = b.eval(t);
        Vec2 d = b.derivative(t);
        if (!(d.norm() > 0)) d = Vec2(1, 0);
        const double angle = power(1, 12), cs = std::cos(angle), sn = std::sin(angle);
        d = Vec2(cs * d.x() - sn * d.y(), sn * d.x() + cs * d.y()).normalized() * (scale * power(0, 3));
        curves.push_back(segment(p - d, p + d));
        break;
      }
      case 6: {
        const Vec2 a = point();
        const double size = scale * power(9, 15);
        const Vec2 b = a + size * Vec2(1, 0.5), c = a + size * Vec2(0.3, -1);
        curves.push_back({a, b, c, a + size * Vec2(in.ConsumeIntegral<std::int8_t>(), 1)});
        break;
      }
      case 7: {
        const Curve& c = earlier();
        curves.push_back({c[3], c[2], c[1], c[0]});
        break;
      }
      case 8: {
        const Curve& c = earlier();
        const double t = in.ConsumeIntegral<std::uint8_t>() / 255.0;
        const Vec2 p = curvemesh::geometry::CubicBezier(c[0], c[1], c[2], c[3]).eval(t);
        curves.push_back(segment(p, point()));
        break;
      }
      default: {
        const double grow = std::pow(10.0, in.ConsumeIntegralInRange<int>(3, 6));
        const Vec2 a = point() * grow, b = point() * grow, c = point() * grow;
        curves.push_back({a, b, c, point() * grow});
        break;
      }
    }
  }
};

// With FUZZ_PIPELINE_SVG=FILE in the environment an input is not meshed: its soup is written
// there as an SVG drawing (no viewBox, every coordinate to 17 digits: the same doubles), with the
// edge length the input picked in a first-line comment (`curvemesh-options: -l 0.1`), so that a
// finding can be run with `curvemesh mesh FILE -l L` and become a test, and a corpus can be timed
// without sanitizers (fuzz/pipeline-replay reads the comment).
bool dump(const std::vector<Curve>& curves, double edge_length) {
  const char* path = std::getenv("FUZZ_PIPELINE_SVG");
  if (!path) return false;
  std::FILE* f = std::fopen(path, "w");
  if (!f) {
    std::perror(path);
    std::abort();
  }
  std::fprintf(f, "<!-- curvemesh-options: -l %.17g -->\n<svg xmlns=\"http://www.w3.org/2000/svg\">\n", edge_length);
  for (const Curve& c : curves)
    std::fprintf(f, "<path fill=\"none\" stroke=\"black\" d=\"M%.17g %.17gC%.17g %.17g %.17g %.17g %.17g %.17g\"/>\n",
                 c[0].x(), c[0].y(), c[1].x(), c[1].y(), c[2].x(), c[2].y(), c[3].x(), c[3].y());
  std::fprintf(f, "</svg>\n");
  std::fclose(f);
  return true;
}

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_pipeline: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  Soup soup{in, std::pow(10.0, in.ConsumeIntegralInRange<int>(-6, 12)), {}};
  // The target edge length l: the default 1/20 or coarser (1/10, 1/5, 1/2). The sanitizers slow
  // curving some fiftyfold, and coarse meshes take every path of the method at a fraction of the
  // cost.
  curvemesh::pipeline::Parameters parameters;
  parameters.edge_length_rel = std::array{1.0 / 20, 1.0 / 10, 1.0 / 5, 1.0 / 2}[in.ConsumeIntegralInRange<int>(0, 3)];
  while (in.remaining_bytes() > 0 && soup.curves.size() < kMaxCurves) soup.add();
  if (soup.curves.empty()) return 0;
  if (dump(soup.curves, parameters.edge_length_rel)) return 0;
  curvemesh::pipeline::Result result;
  try {
    result = curvemesh::pipeline::run(curvemesh::pipeline::Source::beziers(soup.curves, "fuzz"), parameters);
  } catch (const curvemesh::Error& e) {
    if (e.kind() == curvemesh::Error::Kind::invalid_input) return 0;
    std::fprintf(stderr, "fuzz_pipeline: %s\n", e.what());
    finding("the pipeline failed with an error other than invalid_input");
  }
  // Every element certified positive with exact rationals, as written.
  const auto check = curvemesh::pipeline::check_mesh(curvemesh::pipeline::high_order_mesh(result));
  if (check.triangles == 0) finding("a mesh without triangles");
  if (check.invalid != 0) finding("an element of the output is not certified");
  return 0;
}
