// Feature processing cost against the number of curves (paper §4): synthetic soups of random
// cubics whose size shrinks like 1/√n, so the density of crossings per curve stays the same as
// n grows, as in a drawing with more detail. The μ-separation uses box intersection, so the
// whole stage should grow like n log n.
#include <benchmark/benchmark.h>

#include "pipeline/pipeline.hpp"
#include "random_soup.hpp"

namespace {

using curvemesh::bench::random_soup;

void BM_FeatureProcessing(benchmark::State& state) {
  using namespace curvemesh;
  const auto source = random_soup(static_cast<int>(state.range(0)), 7);
  std::size_t sections = 0;
  for (auto _ : state) {
    const auto f = pipeline::run(source, {}, pipeline::Stage::features).features;
    sections = f.sections.size();
    benchmark::DoNotOptimize(sections);
  }
  state.counters["sections"] = static_cast<double>(sections);
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_FeatureProcessing)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oNLogN);

}  // namespace

BENCHMARK_MAIN();
