// The cost of coarsening (optimize::coarsen, the last step of the linear optimization) against
// the number of input curves: the soups of bench_mesh (random_soup.hpp, crossings per curve
// constant) optimized once without it, then coarsened, a fresh copy each time. Counters: the
// triangles before and after, the collapses, and the rounds.
#include <benchmark/benchmark.h>

#include "optimize/optimize.hpp"
#include "pipeline/pipeline.hpp"
#include "random_soup.hpp"

namespace {

using namespace curvemesh;

void BM_Coarsen(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  pipeline::Result r = pipeline::run(bench::random_soup(n, 7), {}, {pipeline::Stage::triangulate});
  optimize::Options o = r.resolved.optimize;
  o.coarsen = false;
  optimize::optimize(r.linear, r.constraints, o);
  optimize::Stats s;
  mesh::TriMesh m;
  for (auto _ : state) {
    state.PauseTiming();
    m = r.linear;
    s = {};
    state.ResumeTiming();
    optimize::coarsen(m, r.constraints, o, s);
    benchmark::DoNotOptimize(m);
  }
  state.counters["triangles_before"] = s.before_coarsening;
  state.counters["triangles_after"] = m.triangle_count();
  state.counters["collapses"] = static_cast<double>(s.coarsening_collapses);
  state.counters["rounds"] = s.coarsening_rounds;
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_Coarsen)->Arg(100)->Arg(1000)->Arg(4000)->Arg(16000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
