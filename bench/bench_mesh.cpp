// Meshing cost against the number of input curves, through the pipeline: up to the exact
// triangulation, up to quality optimization (paper §4.1) and the whole curved mesh, with each
// stage's seconds and the triangles as counters. Two kinds of synthetic soups (random_soup.hpp):
// crossings per curve constant (as the features benchmark), and dense (every pair crossing, the
// exact triangulation's worst case). The largest sizes take minutes; pick with
// --benchmark_filter, e.g. 'BM_Dense.*/1000'.
#include <benchmark/benchmark.h>

#include "pipeline/pipeline.hpp"
#include "random_soup.hpp"

namespace {

using namespace curvemesh;

void mesh_soup(benchmark::State& state, pipeline::Stage stop_after, bool dense = false) {
  const int n = static_cast<int>(state.range(0));
  const pipeline::Source source = dense ? bench::dense_soup(n, 7) : bench::random_soup(n, 7);
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

void BM_Mesh(benchmark::State& state) {
  mesh_soup(state, pipeline::Stage::curve);
}
BENCHMARK(BM_Mesh)->Arg(1000)->Arg(4000)->Arg(16000)->Unit(benchmark::kMillisecond);

void BM_DenseTriangulate(benchmark::State& state) {
  mesh_soup(state, pipeline::Stage::triangulate, true);
}
BENCHMARK(BM_DenseTriangulate)->Arg(125)->Arg(250)->Arg(500)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);

void BM_DenseMesh(benchmark::State& state) {
  mesh_soup(state, pipeline::Stage::curve, true);
}
BENCHMARK(BM_DenseMesh)->Arg(250)->Arg(500)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
