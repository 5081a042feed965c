// `curvemesh diffuse`: diffusion curves (fem/diffuse.hpp) drawn into a PNG picture.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <array>
#include <memory>

#include "app/commands.hpp"
#include "app/mesh_options.hpp"
#include "app/solve_common.hpp"
#include "fem/diffuse.hpp"
#include "pipeline/output.hpp"

namespace curvemesh::app {

namespace {

struct DiffuseArgs {
  SolveOptions solve;  // input, PNG (-o), VTU (--vtu), width, straight, meshing; the domain is the whole box
  std::string background = "white";
};

int run_diffuse(const DiffuseArgs& args) {
  const SolveOptions& o = args.solve;
  fem::DiffuseOptions options;
  const std::array<double, 3> bg = *pipeline::css_colour(args.background);  // checked by the option
  options.background = {bg[0], bg[1], bg[2]};

  int exit_code = kOk;
  const std::optional<fem::MeshedDrawing> meshed = mesh_for_solving(o, "diffused", &exit_code);
  if (!meshed) return exit_code;
  const fem::MeshedDrawing& drawing = *meshed;
  geometry::Box2 view;
  for (const geometry::Vec2& x : drawing.mesh.nodes) view.add(x);

  const fem::DiffusionMesh cut = fem::cut_along_curves(drawing, drawing.colours);
  const io::HighOrderMesh mesh = o.straight ? fem::straight_mesh(cut.cut.mesh) : cut.cut.mesh;
  const fem::Geometry geometry(mesh);
  const fem::Space space(mesh, 2);
  const fem::DiffusionResult r = fem::diffuse(geometry, space, cut.sides, options);

  const auto start = std::chrono::steady_clock::now();
  const fem::Image picture = fem::rasterize(
      geometry, view, o.width, [&](int t, const fem::Vec2& xi) { return r.at(space, t, xi); }, options.background);
  const double raster_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("diffuse: %d triangles (%s map), %d lines cut, %d P2 unknowns per channel (%d held by the curves' "
              "colours), %d part%s with no curve set to the background\n",
              mesh.triangle_count(), o.straight ? "straight" : "cubic", cut.cut_lines, r.unknowns, r.fixed,
              r.background_components, r.background_components == 1 ? "" : "s");
  std::printf("time: meshing %.3f s, assembly %.3f s, solve %.3f s (3 channels), rasterization %.3f s (%dx%d)\n",
              drawing.seconds, r.assembly_seconds, r.solve_seconds, raster_seconds, picture.width, picture.height);

  std::vector<io::VtuPointArray> arrays;
  if (!o.output_vtu.empty()) {
    Eigen::VectorXd interleaved(3 * r.unknowns);
    for (int i = 0; i < r.unknowns; ++i)
      for (int k = 0; k < 3; ++k) interleaved[3 * i + k] = r.channel[k][i];
    arrays.push_back({"colour", 3, fem::values_at_nodes(geometry, space, interleaved, 3)});
  }
  return write_outputs(o, mesh, arrays, &picture);
}

}  // namespace

Runner add_diffuse_command(CLI::App& app) {
  auto args = std::make_shared<DiffuseArgs>();
  SolveOptions& o = args->solve;
  CLI::App* cmd = app.add_subcommand(
      "diffuse",
      "Diffusion curves: each curve's side colours diffused into a PNG\n"
      "Diffusion curves (Orzan et al. 2008; paper §5.1, Fig. 12): mesh the drawing's box, cut the mesh open along "
      "its curves (every primary and secondary line that lies on an input curve), hold each side of every curve at "
      "that side's colour and solve the Laplace equation per colour channel (P2 elements on the cubic map, CHOLMOD; "
      "zero flux on the box's border). A curve's colours: its "
      "element's data-color-left and data-color-right attributes (any CSS colour; inherited from groups), else its "
      "stroke colour on both sides, else its fill colour, else black. Left means on screen (SVG's y points down): "
      "on the left hand when walking along the path the way it is drawn, so a path drawn rightwards has its left "
      "colour above it; a mirroring transform mirrors the colours with the path. Writes a PNG picture and prints "
      "the time of each step.");
  cmd->add_option("input", o.input, "SVG drawing whose curves carry the colours")->required();
  cmd->add_option("-o,--output", o.output_png, "PNG picture to write")->required();
  cmd->add_option("--width", o.width, "width of the picture in pixels (the height follows the drawing's box)")
      ->capture_default_str()
      ->check(CLI::Range(8, 20000));  // and at most fem::kMaxPicturePixels in all
  cmd->add_flag("--straight", o.straight,
                "solve on straight triangles: the same mesh with its straight (P1) map instead of the cubic one "
                "(not `mesh --linear`, which makes another mesh, of order 1)");
  cmd->add_option("--vtu", o.output_vtu,
                  "also write the cut mesh with the colour (3 components in [0, 1]) at its nodes as VTK XML (.vtu)");
  cmd->add_option("--background", args->background,
                  "colour of the parts of the box that no curve borders (any CSS colour), where the colour is "
                  "otherwise undetermined")
      ->capture_default_str()
      ->check([](const std::string& s) { return pipeline::css_colour(s) ? std::string() : "not a CSS colour: " + s; });
  add_feature_options(*cmd, o.parameters);
  add_memory_limit_option(*cmd, o.memory_limit_gb);
  o.vtu_option = "--vtu";
  o.png_option = "-o";
  return [args] { return run_diffuse(*args); };
}

}  // namespace curvemesh::app
