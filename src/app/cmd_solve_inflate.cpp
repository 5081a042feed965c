// `curvemesh solve inflate`: surface inflation (fem/inflate.hpp) of a drawing's enclosed regions.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/solve_common.hpp"
#include "fem/inflate.hpp"
#include "fem/output.hpp"

namespace curvemesh::app {

namespace {

struct InflateArgs {
  SolveOptions solve;
  std::string output_surface;
  double height_rel = 0.1;
};

int run_inflate(const InflateArgs& args) {
  int code = kOk;
  SolveOptions solve = args.solve;
  solve.other_outputs = {{"--surface", args.output_surface}};
  std::optional<Problem> p = prepare_problem(solve, &code);
  if (!p) return code;
  const fem::Geometry geometry(p->mesh);
  const fem::Space space(p->mesh, 2);
  fem::InflateResult r = fem::inflate(geometry, space, 1.0);
  // The problem is linear: scale the constant load so that the highest point is at the asked height.
  const double top = r.height.cwiseAbs().maxCoeff();
  const double scale = top > 0 ? args.height_rel * p->drawing.diagonal / top : 0.0;
  r.height *= scale;
  std::printf("inflate: %d unknowns (P2 height and -Δ height), assembly %.3f s, solve %.3f s; highest point %.6g\n",
              r.unknowns, r.assembly_seconds, r.solve_seconds, r.height.maxCoeff());
  const std::vector<double> z = fem::values_at_nodes(geometry, space, r.height);
  std::optional<fem::Image> picture;
  if (!args.solve.output_png.empty()) {
    const double hi = std::max(r.height.maxCoeff(), 1e-300);
    picture = fem::rasterize(geometry, p->view, args.solve.width, [&](int t, const fem::Vec2& xi) {
      return fem::colour_map(fem::value_at(space, r.height, t, xi) / hi);
    });
  }
  std::vector<OtherFile> others;
  if (!args.output_surface.empty()) {
    const bool ply = args.output_surface.size() >= 4 &&
                     args.output_surface.compare(args.output_surface.size() - 4, 4, ".ply") == 0;
    others.push_back({args.output_surface, ply ? fem::surface_ply(p->mesh, z) : fem::surface_obj(p->mesh, z)});
  }
  return write_outputs(args.solve, p->mesh, {{"height", 1, z}}, picture ? &*picture : nullptr, others);
}

}  // namespace

SubcommandRunner add_solve_inflate_command(CLI::App& solve) {
  auto args = std::make_shared<InflateArgs>();
  CLI::App* cmd = solve.add_subcommand(
      "inflate",
      "Inflate the enclosed regions into a surface (bi-Laplace)\n"
      "Inflate the drawing's enclosed regions into a 3D surface (paper §5.1, Repoussé with a constant load): "
      "the bi-Laplace equation, clamped (zero height and slope) at the curves, in Ciarlet-Raviart mixed form "
      "(P2 height and P2 -Δheight, a saddle-point system solved by UMFPACK).");
  add_solve_options(*cmd, args->solve, Domain::evenodd);
  cmd->add_option("--surface", args->output_surface,
                  "also write the inflated surface as a 3D mesh: Wavefront .obj, or .ply (ASCII)");
  cmd->add_option("--height", args->height_rel, "height of the highest point, relative to d (the load is scaled to it)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 100.0));
  return {cmd, [args] { return run_inflate(*args); }};
}

}  // namespace curvemesh::app
