// Regions (`curvemesh mesh --regions`): classifying a finished mesh's faces by the drawing's
// fills — faces, winding numbers against each filled element's outline, the tagged mesh and
// its areas — against the number of filled shapes, on a drawing of n overlapping filled
// ellipses (random, sizes shrinking like 1/√n so overlaps per shape stay constant, alternating
// fill rules). The mesh is made once; each iteration classifies it again. Counters: faces,
// fill layers, triangles, and the seconds of meshing the drawing once (mesh_s) to compare with.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "io/curved_mesh.hpp"
#include "pipeline/pipeline.hpp"
#include "regions/paint.hpp"

namespace {

using namespace curvemesh;

std::string ellipses(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 100 100\">\n";
  const double size = 30 / std::sqrt(double(n));
  for (int i = 0; i < n; ++i) {
    const int r = int(255 * unit(rng)), g = int(255 * unit(rng)), b = int(255 * unit(rng));
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", r, g, b);
    s << "<ellipse cx=\"" << 5 + 90 * unit(rng) << "\" cy=\"" << 5 + 90 * unit(rng) << "\" rx=\""
      << size * (0.5 + unit(rng)) << "\" ry=\"" << size * (0.5 + unit(rng)) << "\" fill=\"" << colour
      << "\" fill-rule=\"" << (i % 2 ? "evenodd" : "nonzero") << "\"/>\n";
  }
  s << "</svg>\n";
  return s.str();
}

void BM_Classify(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Parameters p;
  p.regions = true;  // reads the fills and closes what they fill, as `mesh --regions` does
  const auto start = std::chrono::steady_clock::now();
  const pipeline::Result r = pipeline::run(pipeline::Source::svg(ellipses(n, 11), "<ellipses>"), p);
  const double mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const io::HighOrderMesh whole = io::curved_mesh(*r.curved);
  regions::ClassifyOptions c;
  c.clearance = r.resolved.features.epsilon;
  c.resolution = 1e-10 * r.resolved.d;
  regions::Painted painted;
  for (auto _ : state) {
    const regions::Classification classified = regions::classify(whole, r.soup.fills, c);
    painted = regions::paint(whole, classified, r.soup, regions::Domain::box, true);
    benchmark::DoNotOptimize(painted.regions);
  }
  state.counters["faces"] = r.classification.faces.count();
  state.counters["layers"] = static_cast<double>(r.soup.fills.size());
  state.counters["triangles"] = whole.triangle_count();
  state.counters["regions"] = static_cast<double>(painted.regions.size());
  state.counters["mesh_s"] = mesh_seconds;
  state.SetComplexityN(n);
}
BENCHMARK(BM_Classify)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->Complexity();

}  // namespace

BENCHMARK_MAIN();
