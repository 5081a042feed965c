// Feature processing cost against the number of curves (paper §4): synthetic soups of random
// cubics whose size shrinks like 1/√n, so the density of crossings per curve stays the same as
// n grows, as in a drawing with more detail. The μ-separation uses box intersection, so the
// whole stage should grow like n log n.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "features/features.hpp"

namespace {

curvemesh::svg::FeatureSoup random_soup(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), v(-1.0, 1.0);
  const double size = 3.0 / std::sqrt(double(n));
  curvemesh::svg::FeatureSoup soup;
  soup.sources.push_back({"path", "", 0, 1});
  for (int i = 0; i < n; ++i) {
    const curvemesh::geometry::Vec2 c(u(rng), u(rng));
    auto q = [&] { return curvemesh::geometry::Vec2(c.x() + size * v(rng), c.y() + size * v(rng)); };
    soup.curves.push_back({{q(), q(), q(), q()}, 0, {}, {}, {}, {}});
  }
  return soup;
}

void BM_FeatureProcessing(benchmark::State& state) {
  const auto soup = random_soup(static_cast<int>(state.range(0)), 7);
  std::size_t sections = 0;
  for (auto _ : state) {
    const auto f = curvemesh::features::process(soup);
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
