// `curvemesh mesh`: SVG (or Triangle .poly) in, linear mesh out — reading, feature processing
// (§4), exact triangulation and quality optimization (§4.1), then .msh, SVG and statistics.
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/feature_options.hpp"
#include "features/features.hpp"
#include "features/poly_input.hpp"
#include "io/mesh_svg.hpp"
#include "io/msh_writer.hpp"
#include "io/output_file.hpp"
#include "optimize/optimize.hpp"
#include "svg/error.hpp"
#include "svg/reader.hpp"
#include "triangulate/constraints.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::app {

namespace {

struct MeshArgs {
  std::string input, output_msh, output_svg, output_stats, stop_after = "optimize";
  bool linear = false, verbose = false;
  int msh_version = 41;
  svg::ReadOptions read;
  features::Options features;
  triangulate::Options triangulate;
  optimize::Options optimize;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

nlohmann::ordered_json quality_json(const optimize::Quality& q) {
  return {{"vertices", q.vertices},           {"triangles", q.triangles},   {"min_angle_deg", q.min_angle_deg},
          {"max_amips", q.max_amips},         {"mean_amips", q.mean_amips}, {"mean_edge_length", q.mean_edge_length}};
}

int run_mesh(MeshArgs args) {
  if (!args.linear) {
    std::cerr << "curvemesh: only linear meshes can be made so far; pass --linear\n";
    return kUsage;
  }
  if (!feature_options_valid(args.features)) return kUsage;
  // One target length for the whole pipeline: the features resample with it, the optimizer aims at it.
  args.optimize.edge_length_rel = args.features.edge_length_rel;
  args.optimize.min_edge_length_rel = args.features.min_edge_length_rel;
  args.optimize.stop_min_angle_deg = args.features.alpha_deg;
  if (args.verbose) args.optimize.log = &std::cerr;

  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  nlohmann::ordered_json stats;
  stats["input"] = args.input;
  auto t = Clock::now();

  features::Features f;
  try {
    if (ends_with(args.input, ".poly")) {
      f = features::read_poly(args.input, args.features);
      stats["seconds"]["read"] = seconds_since(t);
      stats["seconds"]["features"] = 0.0;
    } else {
      const svg::FeatureSoup soup = svg::read_svg_file(args.input, args.read);
      for (const std::string& w : soup.warnings) std::cerr << "curvemesh: " << args.input << ": warning: " << w << "\n";
      stats["seconds"]["read"] = seconds_since(t);
      t = Clock::now();
      f = features::process(soup, args.features);
      stats["seconds"]["features"] = seconds_since(t);
    }
  } catch (const svg::InputError& e) {
    std::cerr << "curvemesh: " << e.what() << "\n";
    return kInvalidInput;
  }
  if (f.box.empty()) {
    std::cerr << "curvemesh: " << args.input << ": nothing to mesh (no curves, segments or points)\n";
    return kInvalidInput;
  }
  if (f.sections.empty() && f.segments.empty() && f.points.empty())
    std::cerr << "curvemesh: " << args.input << ": warning: nothing is drawn; meshing the canvas alone\n";
  int primary = 0;
  for (const auto& s : f.sections) primary += s.kind == features::Kind::primary;
  stats["features"] = {{"primary_sections", primary},
                       {"secondary_segments", f.segments.size()},
                       {"points", f.points.size()}};

  t = Clock::now();
  triangulate::Result tri = triangulate::triangulate(f, args.triangulate);
  stats["seconds"]["triangulate"] = seconds_since(t);
  stats["triangulate"] = {{"vertices", tri.stats.vertices},
                          {"triangles", tri.stats.triangles},
                          {"exact_vertices", tri.stats.exact_vertices}};
  mesh::TriMesh& m = tri.mesh;

  if (args.stop_after == "optimize") {
    const mesh::Constraints constraints = triangulate::constraints_of(f, tri.box);
    t = Clock::now();
    const optimize::Stats s = optimize::optimize(m, constraints, f.lengths.d, args.optimize);
    stats["seconds"]["optimize"] = seconds_since(t);
    stats["optimize"] = {{"iterations", s.iterations},   {"stop_reason", s.stop_reason},
                         {"splits", s.splits},           {"collapses", s.collapses},
                         {"swaps", s.swaps},             {"smooths", s.smooths},
                         {"projections", s.projections}, {"released_secondary_edges", s.released}, {"unprojected_vertices", s.unprojected},
                         {"exact_vertices_left", s.exact_left}};
  }
  const optimize::Quality q = optimize::measure(m);
  stats["mesh"] = quality_json(q);
  stats["mesh"]["target_edge_length"] = args.features.edge_length_rel * f.lengths.d;

  if (const auto error = m.structure_error()) {
    // Every operation checks its result exactly, so this is a bug; refuse rather than write it.
    std::cerr << "curvemesh: internal error: " << args.input << ": the mesh is broken (" << *error
              << "); no mesh written\n";
    return kInternal;
  }
  try {
    if (m.exact_vertex_count() > 0) {
      // Writing rounded coordinates could write an inverted triangle: refuse instead.
      std::cerr << "curvemesh: " << args.input << ": " << m.exact_vertex_count()
                << " vertices still have exact coordinates that do not round to doubles without inverting a "
                   "triangle; no mesh written\n";
      return kInternal;
    }
    t = Clock::now();
    io::write_msh(m, args.output_msh, io::MshOptions{args.msh_version});
    if (!args.output_svg.empty()) io::write_file_atomically(args.output_svg, io::mesh_svg(m));
    stats["seconds"]["write"] = seconds_since(t);
    if (!args.output_stats.empty()) io::write_file_atomically(args.output_stats, stats.dump(1) + "\n");
  } catch (const io::OutputError& e) {
    std::cerr << "curvemesh: " << e.what() << "\n";
    return kInvalidInput;
  }
  return kOk;
}

}  // namespace

Runner add_mesh_command(CLI::App& app) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd = app.add_subcommand(
      "mesh",
      "Mesh an SVG drawing (or a Triangle .poly file: points and segments, all secondary): feature "
      "processing (paper §4), an exact constrained triangulation of the bounding box and every feature, "
      "then quality optimization (§4.1). Writes a Gmsh .msh file with triangles and the feature edges "
      "as line elements in physical groups primary, secondary and boundary.");
  cmd->add_option("input", args->input, "SVG or .poly file to mesh")->required();
  cmd->add_option("-o,--output", args->output_msh, "Gmsh .msh file to write")->required();
  cmd->add_flag("--linear", args->linear, "make a linear mesh (straight-sided triangles)");
  cmd->add_option("--msh-version", args->msh_version, "Gmsh file format: 41 (4.1) or 22 (2.2)")
      ->capture_default_str()
      ->transform(CLI::CheckedTransformer(std::map<std::string, int>{{"4.1", 41}, {"41", 41}, {"2.2", 22}, {"22", 22}}));
  cmd->add_option("--svg", args->output_svg, "also draw the mesh into this SVG (primary red, secondary green)");
  cmd->add_option("--stats", args->output_stats,
                  "write statistics as JSON: counts, min angle, max and mean AMIPS, seconds per stage");
  cmd->add_option("--stop-after", args->stop_after,
                  "last stage to run: triangulate (the exact triangulation, unoptimized) or optimize")
      ->capture_default_str()
      ->check(CLI::IsMember({"triangulate", "optimize"}));
  add_feature_options(*cmd, args->features);
  cmd->add_flag("-v,--verbose", args->verbose, "report each optimization pass on stderr (triangles, min angle, max AMIPS)");
  cmd->add_option("--max-iterations", args->optimize.max_iterations, "optimization passes at most")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--stop-amips", args->optimize.stop_max_amips,
                  "optimization stops once every triangle's AMIPS energy is at most this (2 = equilateral)")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 1e9));
  cmd->add_option("--box-margin", args->triangulate.box_margin_rel,
                  "the meshed box extends the drawing's bounding box by this, relative to d, on every side")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 10.0));
  return [args] { return run_mesh(*args); };
}

}  // namespace curvemesh::app
