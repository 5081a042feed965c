// Linear meshing cost (paper §4.1) against the number of input curves: the exact triangulation
// alone, and triangulation plus quality optimization. Same synthetic soups as the features
// benchmark (random cubics whose size shrinks like 1/√n), so crossings per curve stay constant.
#include <benchmark/benchmark.h>

#include "features/features.hpp"
#include "optimize/optimize.hpp"
#include "random_soup.hpp"
#include "triangulate/constraints.hpp"
#include "triangulate/triangulate.hpp"

namespace {

using curvemesh::bench::random_soup;

void BM_Triangulate(benchmark::State& state) {
  const auto features = curvemesh::features::process(random_soup(static_cast<int>(state.range(0)), 7));
  int triangles = 0;
  for (auto _ : state) {
    const auto r = curvemesh::triangulate::triangulate(features);
    triangles = r.stats.triangles;
    benchmark::DoNotOptimize(triangles);
  }
  state.counters["triangles"] = triangles;
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Triangulate)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNLogN);

void BM_TriangulateAndOptimize(benchmark::State& state) {
  const auto features = curvemesh::features::process(random_soup(static_cast<int>(state.range(0)), 7));
  int triangles = 0;
  for (auto _ : state) {
    auto r = curvemesh::triangulate::triangulate(features);
    const auto constraints = curvemesh::triangulate::constraints_of(features, r.box);
    const auto stats = curvemesh::optimize::optimize(r.mesh, constraints, features.lengths.d);
    triangles = r.mesh.triangle_count();
    benchmark::DoNotOptimize(stats);
  }
  state.counters["triangles"] = triangles;
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_TriangulateAndOptimize)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
