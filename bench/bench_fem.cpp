// What the cubic map costs a simulation (paper §5.1: "replacing the linear geometric map with a
// cubic one produces systems with exactly the same size and sparsity ... slightly more
// expensive to compute"; Laplace 0.074 s straight, 0.090 s cubic). The same P2 Poisson problem
// on the same meshes with the straight and with the cubic map: assembly alone, and assembly plus
// the CHOLMOD solve. Meshes: the whole box of examples/overlapping-shapes.svg cut open along its
// curves (the diffusion-curve set-up), and the unit disk of fem/convergence.hpp.
#include <benchmark/benchmark.h>

#include "fem/assembly.hpp"
#include "fem/convergence.hpp"
#include "fem/domain.hpp"
#include "fem/drawing.hpp"
#include "pipeline/output.hpp"

namespace {

using namespace curvemesh;

struct Meshes {
  io::HighOrderMesh cubic, straight;
};

Meshes make(int which) {
  pipeline::Parameters p;
  if (which == 1) p.edge_length_rel = 0.01;
  const fem::MeshedDrawing d = pipeline::mesh_drawing(
      which == 0 ? pipeline::Source::file(CURVEMESH_EXAMPLES "/overlapping-shapes.svg")
                 : pipeline::Source::svg(fem::disk_svg(), "<disk>"),
      p);
  std::vector<char> cut(d.mesh.line_count());
  for (int l = 0; l < d.mesh.line_count(); ++l) cut[l] = d.mesh.line_physical[l] != io::kPhysicalBoundary;
  Meshes m;
  m.cubic = fem::cut_open(d.mesh, cut).mesh;
  m.straight = fem::straight_mesh(m.cubic);
  return m;
}

void solve_poisson(const io::HighOrderMesh& mesh, bool with_solve, benchmark::State& state) {
  const fem::Geometry g(mesh);
  const fem::Space s(mesh, 2);
  const fem::SparseMatrix k = fem::stiffness_matrix(g, s);
  const Eigen::VectorXd b = fem::load_vector(g, s, [](const fem::Vec2&) { return 1.0; });
  if (with_solve) {
    fem::Dirichlet d(s.size());
    fem::set_on_edges(g, s, fem::boundary_edges(mesh), [](const fem::Vec2&) { return 0.0; }, d);
    benchmark::DoNotOptimize(fem::solve(k, b, d, true));
  }
  benchmark::DoNotOptimize(b);
  state.counters["unknowns"] = s.size();
  state.counters["triangles"] = mesh.triangle_count();
}

// Arguments: mesh (0 drawing, 1 disk), map (1 straight, 3 cubic).
void BM_PoissonAssembly(benchmark::State& state) {
  const Meshes m = make(static_cast<int>(state.range(0)));  // outside the timed loop
  const io::HighOrderMesh& mesh = state.range(1) == 3 ? m.cubic : m.straight;
  for (auto _ : state) solve_poisson(mesh, false, state);
}
BENCHMARK(BM_PoissonAssembly)->ArgsProduct({{0, 1}, {1, 3}})->Unit(benchmark::kMillisecond);

void BM_PoissonAssemblyAndSolve(benchmark::State& state) {
  const Meshes m = make(static_cast<int>(state.range(0)));  // outside the timed loop
  const io::HighOrderMesh& mesh = state.range(1) == 3 ? m.cubic : m.straight;
  for (auto _ : state) solve_poisson(mesh, true, state);
}
BENCHMARK(BM_PoissonAssemblyAndSolve)->ArgsProduct({{0, 1}, {1, 3}})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
