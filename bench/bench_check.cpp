// `curvemesh check` on real meshes: the peer set's drawings (scripts/bench-peer-set's list,
// ../shared/corpus/peer-set.txt, drawings under /usr/share/openclipart/svg) meshed once per order
// with the default parameters, their .msh text made once; each iteration then certifies every mesh
// (pipeline::check_mesh: the double certificate first, rationals where it cannot decide), or
// certifies them all in rationals (--exact), or parses their text (what `check` does before
// certifying). One core. Counters: triangles per second (items_per_second), triangles, the
// elements decided in rationals (exact_fallbacks), and MB of .msh text per second for the parse.
// The meshes of an order are made the first time a benchmark of that order runs (about 20 s an
// order on a 2-core machine); pick with --benchmark_filter, e.g. 'BM_Check/3'.
#include <benchmark/benchmark.h>

#include <array>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "io/msh_reader.hpp"
#include "io/msh_writer.hpp"
#include "pipeline/check.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"

namespace {

using namespace curvemesh;

struct MeshSet {
  std::vector<std::string> texts;         // the .msh files' text, as `curvemesh mesh` writes them
  std::vector<io::HighOrderMesh> meshes;  // the same, parsed
  std::size_t triangles = 0, bytes = 0;
};

std::vector<std::string> peer_set_drawings() {
  std::ifstream list(CURVEMESH_PEER_SET);
  std::vector<std::string> out;
  for (std::string line; std::getline(list, line);)
    if (!line.empty() && line[0] != '#') out.push_back(std::string(CURVEMESH_OPENCLIPART) + "/" + line);
  return out;
}

MeshSet mesh_peer_set(int order) {
  MeshSet set;
  Parameters p;
  p.order = order;
  for (const std::string& drawing : peer_set_drawings()) {
    const pipeline::Result r = pipeline::run(pipeline::Source::file(drawing), p);
    set.texts.push_back(io::msh_string(pipeline::high_order_mesh(r)));
    set.meshes.push_back(io::parse_msh(set.texts.back()));
    set.triangles += static_cast<std::size_t>(set.meshes.back().triangle_count());
    set.bytes += set.texts.back().size();
  }
  std::cerr << "peer set, order " << order << ": " << set.meshes.size() << " meshes, " << set.triangles
            << " triangles, " << set.bytes / 1e6 << " MB of .msh\n";
  return set;
}

// The meshes of each order, made when first asked for.
class Meshes {
 public:
  const MeshSet& of_order(int order) {
    auto& slot = sets_[static_cast<std::size_t>(order - 1)];
    if (!slot) slot = mesh_peer_set(order);
    return *slot;
  }

 private:
  std::array<std::optional<MeshSet>, 3> sets_;
};

void check(benchmark::State& state, Meshes& meshes, int order, bool exact) {
  const MeshSet& set = meshes.of_order(order);
  if (set.meshes.empty()) {
    state.SkipWithError("no drawing of the peer set found (" CURVEMESH_PEER_SET ")");
    return;
  }
  std::size_t fallbacks = 0;
  for (auto _ : state) {
    fallbacks = 0;
    for (const io::HighOrderMesh& m : set.meshes) {
      const pipeline::MeshCheck c = pipeline::check_mesh(m, {.exact = exact, .threads = 1});  // per core
      if (c.invalid) state.SkipWithError("a mesh of the peer set is invalid");
      fallbacks += c.exact_fallbacks;
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * set.triangles));
  state.counters["triangles"] = static_cast<double>(set.triangles);
  state.counters["exact_fallbacks"] = static_cast<double>(fallbacks);
}

void parse(benchmark::State& state, Meshes& meshes, int order) {
  const MeshSet& set = meshes.of_order(order);
  for (auto _ : state)
    for (const std::string& text : set.texts) benchmark::DoNotOptimize(io::parse_msh(text));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * set.triangles));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * set.bytes));
  state.counters["triangles"] = static_cast<double>(set.triangles);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  Meshes meshes;
  for (const int order : {3, 2, 1}) {
    const std::string o = std::to_string(order);
    benchmark::RegisterBenchmark(("BM_Check/" + o).c_str(), [&meshes, order](benchmark::State& s) {
      check(s, meshes, order, false);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_CheckExact/" + o).c_str(),
                                 [&meshes, order](benchmark::State& s) { check(s, meshes, order, true); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark(("BM_ParseMsh/" + o).c_str(), [&meshes, order](benchmark::State& s) {
      parse(s, meshes, order);
    })->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
