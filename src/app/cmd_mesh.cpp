// `curvemesh mesh`: SVG (or Triangle .poly) in, mesh out, through the pipeline — reading, feature
// processing (§4), exact triangulation and quality optimization (§4.1), curving (§4.2, unless
// --linear) — then .msh, VTU, SVG and statistics.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/mesh_options.hpp"
#include "app/messages.hpp"
#include "app/outputs.hpp"
#include "app/progress.hpp"
#include "base/text.hpp"
#include "io/msh_writer.hpp"
#include "io/vtu_writer.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh::app {

namespace {

struct MeshArgs {
  std::string input, output_msh, output_svg, output_vtu, output_stats, stop_after, domain = "box";
  bool verbose = false, quiet = false, regions = false;
  io::MshOptions msh;
  double memory_limit_gb = 0;
  pipeline::Parameters parameters;
};

// One line for the user: what was written and how good it is.
void summarize(const MeshArgs& args, const pipeline::Result& r, double seconds) {
  const auto& mesh = r.stats["mesh"];
  char line[256];
  if (r.curved) {
    const auto& c = r.stats["curve"];
    std::snprintf(line, sizeof line,
                  "%d triangles (%d curved), max AMIPS %.3g, min scaled Jacobian %.3g, %.2f s",
                  mesh["triangles"].get<int>(), c["curved_triangles"].get<int>(),
                  c["max_amips"].get<double>(), c["min_scaled_jacobian"].get<double>(), seconds);
  } else {
    std::snprintf(line, sizeof line, "%d triangles (linear), max AMIPS %.3g, min angle %.3g°, %.2f s",
                  mesh["triangles"].get<int>(), mesh["max_amips"].get<double>(),
                  mesh["min_angle_deg"].get<double>(), seconds);
  }
  std::cout << "curvemesh: wrote " << base::printable(args.output_msh) << ": " << line;
  if (r.stats.contains("regions")) std::cout << ", " << r.stats["regions"].size() << " regions";
  std::cout << "\n";
}

// The mesh, its drawing, VTU and statistics, written together or not at all.
int write_mesh(const MeshArgs& args, pipeline::Result& r) {
  return write_together([&](base::OutputFiles& out) {
    const auto t = std::chrono::steady_clock::now();
    // The plain high-order mesh, made once for both files (what pipeline::write_msh and
    // write_vtu write).
    const io::HighOrderMesh mesh = pipeline::high_order_mesh(r);
    out.add(args.output_msh, io::msh_string(mesh, args.msh));
    if (!args.output_vtu.empty()) out.add(args.output_vtu, io::vtu_string(mesh, pipeline::cell_data(r)));
    if (!args.output_svg.empty()) out.add(args.output_svg, pipeline::mesh_svg(r));
    r.stats["seconds"]["write"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    if (!args.output_stats.empty()) out.add(args.output_stats, pipeline::stats_text(r));
  });
}

int run_mesh(const MeshArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  pipeline::RunOptions run;
  if (!args.stop_after.empty()) run.stop_after = *pipeline::stage_named(args.stop_after);
  if (args.parameters.order == 1 && run.stop_after == pipeline::Stage::curve && !args.stop_after.empty()) {
    say("--stop-after curve makes no sense with --linear");
    return kUsage;
  }
  if (!parameters_valid(args.parameters)) return kUsage;
  if (!outputs_distinct({{"input", args.input}}, {{"-o", args.output_msh},
                                                  {"--vtu", args.output_vtu},
                                                  {"--svg", args.output_svg},
                                                  {"--stats", args.output_stats}}))
    return kUsage;
  limit_memory(args.memory_limit_gb);
  if (args.verbose) run.log = &std::cerr;
  run.regions = args.regions;
  run.domain = *regions::domain_named(args.domain);  // CLI checked the name
  run.warn = [&](const std::string& w) { warn(args.input, w); };

  pipeline::Result r;
  try {
    std::optional<ProgressDisplay> display;
    if (!args.quiet) {
      display.emplace(args.input);
      run.progress = [&](const pipeline::Progress& p) { (*display)(p); };
    }
    r = pipeline::run(pipeline::Source::file(args.input), args.parameters, run);
  } catch (const Error& e) {
    say(std::string(e.what()) + (e.kind() == Error::Kind::internal ? "; no mesh written" : ""));
    return exit_code(e);
  }
  if (const int written = write_mesh(args, r); written != kOk) return written;
  if (!args.quiet)
    summarize(args, r, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return kOk;
}

}  // namespace

Runner add_mesh_command(CLI::App& app) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mesh",
      "Mesh an SVG drawing: a curved (or linear) Gmsh .msh file\n"
      "Mesh an SVG drawing (or a Triangle .poly file: points and segments, all secondary): feature "
      "processing (paper §4), an exact constrained triangulation of the bounding box and every feature, "
      "quality optimization (§4.1), and curving (§4.2): cubic 10-node triangles whose edges follow the "
      "primary curves, each certified to have a positive Jacobian. Writes a Gmsh .msh file with the "
      "triangles and the feature edges as line elements in physical groups: primary, secondary and boundary "
      "(ids 1-3, what a line lies on), border (5, the border of the meshed domain) and one per drawn element "
      "(6 on, named by its id, else TAG#INDEX; a side two shapes share is in both); the triangles in domain "
      "(4), or with --regions one group per region, numbered after the lines' so that no id is used twice; "
      "with --linear, straight 3-node triangles. Prints one line on success (what was written, "
      "triangles, worst AMIPS energy, smallest scaled Jacobian, seconds). Lengths are relative to the "
      "diagonal d of the drawing's bounding box.\n"
      "Every output is written whole or not at all, never over the input: when one of them cannot be "
      "written, none is left. Exit codes: 0 success, 1 invalid input, a limit reached (see the --max-* "
      "options) or an unwritable output, 2 usage error (also an output that is the input, or two outputs "
      "naming one file), 3 internal failure (a mesh that could not be certified; nothing is written).");
  cmd->add_option("input", args->input, "SVG or .poly file to mesh")->required();
  cmd->add_option("-o,--output", args->output_msh, "Gmsh .msh file to write")->required();
  cmd->add_option(
      "--svg", args->output_svg,
      "also draw the mesh into this SVG (primary red, secondary green; curved edges as cubic Béziers)");
  cmd->add_option("--vtu", args->output_vtu,
                  "also write the mesh as VTK XML (.vtu, Lagrange triangles; opens in ParaView); with --regions "
                  "or --domain each triangle's face and region as cell data");
  cmd->add_flag(
      "--regions", args->regions,
      "tag the triangles by what the drawing paints on them, as a browser does (fill, fill-rule, transforms, "
      "<use>, CSS; the topmost filled element wins): one physical surface per visible element, named by its id "
      "(else TAG#INDEX, its index in the document), and 'background' where nothing is filled, with the same ids "
      "whatever --domain keeps; --stats lists them with fill, triangles and area; --svg fills each triangle with its element's colour. Opacity, "
      "gradients and patterns do not change what covers what; clip paths and masks are ignored (with a "
      "warning). The line closing an open filled subpath becomes a feature");
  cmd->add_option("--domain", args->domain,
                  "the part of the box to mesh: box (all of it), filled (what some filled element covers: the "
                  "shape as it is seen, without the background) or evenodd (the even-odd inside of all curves); "
                  "nodes no triangle uses are dropped, lines on the domain's border keep their tag")
      ->capture_default_str()
      ->check(CLI::IsMember({"box", "filled", "evenodd"}));
  cmd->add_option("--stats", args->output_stats,
                  "write statistics as JSON: counts, min angle, max and mean AMIPS, seconds per stage, and the "
                  "physical groups (dim, id, name, and lines and length or triangles and area)");
  cmd->add_option(
         "--stop-after", args->stop_after,
         "last stage to run: triangulate (the exact triangulation, unoptimized), optimize (the linear "
         "mesh) or curve (default; optimize with --linear)")
      ->check(CLI::IsMember({"triangulate", "optimize", "curve"}));
  add_mesh_options(*cmd, args->parameters, args->msh);
  add_memory_limit_option(*cmd, args->memory_limit_gb);
  cmd->add_flag("-v,--verbose", args->verbose,
                "report each optimization pass on stderr (triangles, min angle, max AMIPS)");
  cmd->add_flag(
      "-q,--quiet", args->quiet,
      "print nothing on success, and no progress (a run longer than about 2 s otherwise says on stderr "
      "where it is: stage, pass, triangles, worst AMIPS energy)");
  return [args] { return run_mesh(*args); };
}

}  // namespace curvemesh::app
