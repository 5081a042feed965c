// `curvemesh mesh`: SVG (or Triangle .poly) in, mesh out, through the pipeline — reading, feature
// processing (§4), exact triangulation and quality optimization (§4.1), curving (§4.2, unless
// --linear) — then .msh, VTU, SVG and statistics.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>
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
#include "io/xdmf_writer.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh::app {

namespace {

struct MeshArgs {
  std::string input, output_msh, output_svg, output_vtu, output_xdmf, output_stats;
  bool verbose = false, quiet = false;
  io::MshOptions msh;
  double memory_limit_gb = 0;
  pipeline::Parameters parameters;
};

// What write_mesh wrote: the files and the mesh in them (with --domain, a part of the whole mesh
// the statistics describe).
struct Written {
  std::vector<std::string> files;
  int order = 0, triangles = 0, lines = 0, nodes = 0;
};

// One line for the user: what was written and how good it is.
void summarize(const Written& w, const pipeline::Result& r, double seconds) {
  std::string files;
  for (const std::string& f : w.files) files += (files.empty() ? "" : ", ") + base::printable(f);
  char line[256];
  std::snprintf(line, sizeof line, "%d triangles of order %d, %d lines, %d nodes", w.triangles, w.order, w.lines,
                w.nodes);
  std::cout << "curvemesh: wrote " << files << ": " << line;
  if (r.stats.contains("regions")) std::cout << ", " << r.stats["regions"].size() << " regions";
  if (r.curved) {
    const auto& c = r.stats["curve"];
    std::snprintf(line, sizeof line, "; max AMIPS %.3g, min scaled Jacobian %.3g", c["max_amips"].get<double>(),
                  c["min_scaled_jacobian"].get<double>());
  } else {
    const auto& mesh = r.stats["mesh"];
    std::snprintf(line, sizeof line, "; max AMIPS %.3g, min angle %.3g°", mesh["max_amips"].get<double>(),
                  mesh["min_angle_deg"].get<double>());
  }
  std::cout << line;
  std::snprintf(line, sizeof line, ", %.2f s\n", seconds);
  std::cout << line;
}

// The HDF5 file beside --xdmf's, or nothing.
std::string xdmf_data(const MeshArgs& args) {
  return args.output_xdmf.empty() ? std::string() : io::xdmf_data_path(args.output_xdmf);
}

// The mesh, its drawing, VTU, XDMF (its data in `hdf5` when made ahead) and statistics, written
// together or not at all.
int write_mesh(const MeshArgs& args, pipeline::Result& r, io::Hdf5FilePtr hdf5, Written& written) {
  return write_together([&](base::OutputFiles& out) {
    const auto t = std::chrono::steady_clock::now();
    // The plain high-order mesh every file is written from (the run made it once).
    const io::HighOrderMesh& mesh = pipeline::high_order_mesh(r);
    written = {{args.output_msh}, mesh.order, mesh.triangle_count(), mesh.line_count(), int(mesh.nodes.size())};
    out.add(args.output_msh, io::msh_string(mesh, args.msh));
    const auto also = [&](const std::string& path, const std::string& text) {
      out.add(path, text);
      written.files.push_back(path);
    };
    if (!args.output_vtu.empty()) also(args.output_vtu, io::vtu_string(mesh, pipeline::cell_data(r)));
    if (!args.output_xdmf.empty()) {
      const std::string data = xdmf_data(args);
      io::XdmfFiles xdmf = io::xdmf_files(mesh, std::filesystem::path(data).filename().string(), std::move(hdf5));
      also(args.output_xdmf, xdmf.xml);
      also(data, xdmf.data);
    }
    if (!args.output_svg.empty()) also(args.output_svg, pipeline::mesh_svg(r));
    r.stats["seconds"]["write"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    if (!args.output_stats.empty()) also(args.output_stats, pipeline::stats_text(r));
  });
}

// XDMF has no cubic triangle: say so before meshing rather than after.
bool xdmf_possible(const MeshArgs& args) {
  if (args.output_xdmf.empty() || io::xdmf_order_supported(args.parameters.order)) return true;
  say("--xdmf: XDMF has no triangle of order " + std::to_string(args.parameters.order) +
      " (dolfinx reads orders 1 and 2 from it): use --order 2 or 1, or read the .msh with the gmsh API "
      "(dolfinx.io.gmshio.model_to_mesh), as docs/guide/fenicsx.md shows");
  return false;
}

int run_mesh(const MeshArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  pipeline::RunOptions run;
  if (!parameters_valid(args.parameters) || !xdmf_possible(args)) return kUsage;
  if (!outputs_distinct({{"input", args.input}}, {{"-o", args.output_msh},
                                                  {"--vtu", args.output_vtu},
                                                  {"--xdmf", args.output_xdmf},
                                                  {"--xdmf's data", xdmf_data(args)},
                                                  {"--svg", args.output_svg},
                                                  {"--stats", args.output_stats}}))
    return kUsage;
  limit_memory(args.memory_limit_gb);
  if (args.verbose) run.log = &std::cerr;
  run.warn = [&](const std::string& w) { warn(args.input, w); };

  // HDF5 and its file made on another thread while the drawing is meshed (their fixed cost was
  // most of what --xdmf added to a small drawing's run); write_mesh uses them only after get().
  std::future<io::Hdf5FilePtr> hdf5;
  if (!args.output_xdmf.empty()) hdf5 = std::async(std::launch::async, io::start_hdf5_file);
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
  Written written;
  if (const int code = write_mesh(args, r, hdf5.valid() ? hdf5.get() : nullptr, written); code != kOk) return code;
  if (!args.quiet)
    summarize(written, r, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
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
      "with --linear, straight 3-node triangles. Prints one line on success (the files written; the "
      "triangles, lines and nodes in them; worst AMIPS energy, smallest scaled Jacobian, seconds). Lengths "
      "are relative to the "
      "diagonal d of the drawing's bounding box.\n"
      "Every output is written whole or not at all, never over the input: when one of them cannot be "
      "written, none is left. Exit codes: 0 success, 1 invalid input, a limit reached (see the --max-* "
      "options) or an unwritable output, 2 usage error (also an output that is the input, or two outputs "
      "naming one file), 3 internal failure (a mesh that could not be certified; nothing is written).");
  cmd->add_option("input", args->input, "SVG file (gzip-compressed too: .svgz) or .poly file to mesh")->required();
  cmd->add_option("-o,--output", args->output_msh, "Gmsh .msh file to write")->required();
  cmd->add_option(
      "--svg", args->output_svg,
      "also draw the mesh into this SVG (primary red, secondary green; curved edges as cubic Béziers)");
  cmd->add_option("--vtu", args->output_vtu,
                  "also write the mesh as VTK XML (.vtu, Lagrange triangles; opens in ParaView); with --regions "
                  "or --domain each triangle's face and region as cell data");
  cmd->add_option("--xdmf", args->output_xdmf,
                  "also write the mesh as XDMF, FEniCSx's format: this .xdmf file and its arrays in an HDF5 "
                  "file beside it (the same name ending in .h5), with grids \"mesh\", \"cell_tags\" (each "
                  "triangle's physical group) and \"facet_tags\" (each feature line's); orders 1 and 2 only");
  add_run_options(*cmd, args->parameters);
  cmd->add_option("--stats", args->output_stats,
                  "write statistics as JSON: counts, min angle, max and mean AMIPS, seconds per stage, and the "
                  "physical groups (dim, id, name, and lines and length or triangles and area)");
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
