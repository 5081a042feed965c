// Linear meshing cost (paper §4.1) against the number of input curves, through the pipeline:
// up to the exact triangulation, and up to quality optimization, with each stage's seconds as
// counters. Same synthetic soups as the features benchmark (random cubics whose size shrinks
// like 1/√n), so crossings per curve stay constant.
#include <benchmark/benchmark.h>

#include "pipeline/pipeline.hpp"
#include "random_soup.hpp"

namespace {

using namespace curvemesh;

void mesh_soup(benchmark::State& state, pipeline::Stage stop_after) {
  const pipeline::Source source = bench::random_soup(static_cast<int>(state.range(0)), 7);
  pipeline::Result r;
  for (auto _ : state) {
    r = pipeline::run(source, {}, {stop_after});
    benchmark::DoNotOptimize(r.linear);
  }
  state.counters["triangles"] = r.quality.triangles;
  for (const auto& [stage, seconds] : r.stats["seconds"].items())
    state.counters[stage + "_s"] = seconds.get<double>();
  state.SetComplexityN(state.range(0));
}

void BM_Triangulate(benchmark::State& state) {
  mesh_soup(state, pipeline::Stage::triangulate);
}
BENCHMARK(BM_Triangulate)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oNLogN);

void BM_TriangulateAndOptimize(benchmark::State& state) {
  mesh_soup(state, pipeline::Stage::optimize);
}
BENCHMARK(BM_TriangulateAndOptimize)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
