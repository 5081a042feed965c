// `curvemesh mesh`: SVG (or Triangle .poly) in, mesh out — reading, feature processing (§4),
// exact triangulation and quality optimization (§4.1), curving (§4.2, unless --linear), then
// .msh, VTU, SVG and statistics.
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/feature_options.hpp"
#include "curve/curve.hpp"
#include "features/features.hpp"
#include "features/poly_input.hpp"
#include "io/curved_mesh.hpp"
#include "io/high_order_mesh.hpp"
#include "io/vtu_writer.hpp"
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
  std::string input, output_msh, output_svg, output_vtu, output_stats, stop_after;
  bool linear = false, verbose = false;
  int msh_version = 41;
  svg::ReadOptions read;
  features::Options features;
  triangulate::Options triangulate;
  optimize::Options optimize;
  curve::Options curve;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

nlohmann::ordered_json quality_json(const optimize::Quality& q) {
  return {{"vertices", q.vertices},           {"triangles", q.triangles},   {"min_angle_deg", q.min_angle_deg},
          {"max_amips", q.max_amips},         {"mean_amips", q.mean_amips}, {"mean_edge_length", q.mean_edge_length}};
}

int run_mesh(MeshArgs args) {
  if (args.stop_after.empty()) args.stop_after = args.linear ? "optimize" : "curve";
  if (args.linear && args.stop_after == "curve") {
    std::cerr << "curvemesh: --stop-after curve makes no sense with --linear\n";
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

  const mesh::Constraints constraints = triangulate::constraints_of(f, tri.box);
  if (args.stop_after != "triangulate") {
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
  if (m.exact_vertex_count() > 0) {
    // Writing rounded coordinates could write an inverted triangle: refuse instead.
    std::cerr << "curvemesh: " << args.input << ": " << m.exact_vertex_count()
              << " vertices still have exact coordinates that do not round to doubles without inverting a "
                 "triangle; no mesh written\n";
    return kInternal;
  }
  std::optional<curve::CurvedMesh> curved;
  if (args.stop_after == "curve") {
    t = Clock::now();
    curve::Stats s;
    curved = curve::curve(std::move(m), constraints, args.curve, &s);
    stats["seconds"]["curve"] = seconds_since(t);
    stats["curve"] = {{"split_triangles", s.split_triangles},
                      {"primary_edges", s.primary_edges},
                      {"curved_edges", s.curved_edges},
                      {"fitted_edges", s.fitted_edges},
                      {"straight_primary_edges", s.straight_primary_edges},
                      {"curved_triangles", s.curved_triangles},
                      {"alternative_centres", s.alternative_centres},
                      {"invalid_triangles", s.invalid_triangles},
                      {"min_scaled_jacobian", s.min_scaled_jacobian},
                      {"max_amips_before_smoothing", s.max_amips_before_smoothing},
                      {"smoothing_moves", s.smoothing_moves},
                      {"curved_splits", s.curved_splits},
                      {"curved_collapses", s.curved_collapses},
                      {"curved_swaps", s.curved_swaps},
                      {"late_projections", s.late_projections},
                      {"max_amips", s.max_amips},
                      {"mean_amips", s.mean_amips},
                      {"max_distance", s.max_distance},
                      {"max_distance_rel", s.max_distance / f.lengths.d},
                      {"mean_fit_distance_rel", s.mean_fit_distance / f.lengths.d}};
    stats["mesh"]["triangles"] = curved->triangles.size();
    if (s.invalid_triangles > 0) {
      std::cerr << "curvemesh: internal error: " << args.input << ": " << s.invalid_triangles
                << " curved triangles could not be certified valid; no mesh written\n";
      return kInternal;
    }
  }
  try {
    t = Clock::now();
    if (curved) {
      const io::HighOrderMesh out = io::curved_mesh(*curved);
      io::write_msh(out, args.output_msh, io::MshOptions{args.msh_version});
      if (!args.output_vtu.empty()) io::write_vtu(out, args.output_vtu);
      if (!args.output_svg.empty()) io::write_file_atomically(args.output_svg, io::mesh_svg(*curved));
    } else {
      io::write_msh(m, args.output_msh, io::MshOptions{args.msh_version});
      if (!args.output_vtu.empty()) io::write_vtu(io::linear_mesh(m), args.output_vtu);
      if (!args.output_svg.empty()) io::write_file_atomically(args.output_svg, io::mesh_svg(m));
    }
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
      "quality optimization (§4.1), and curving (§4.2): cubic 10-node triangles whose edges follow the "
      "primary curves, each certified to have a positive Jacobian. Writes a Gmsh .msh file with the "
      "triangles and the feature edges as line elements in physical groups primary, secondary and "
      "boundary; with --linear, straight 3-node triangles.");
  cmd->add_option("input", args->input, "SVG or .poly file to mesh")->required();
  cmd->add_option("-o,--output", args->output_msh, "Gmsh .msh file to write")->required();
  cmd->add_flag("--linear", args->linear, "make a linear mesh (straight-sided 3-node triangles) instead of a curved one");
  cmd->add_option("--msh-version", args->msh_version, "Gmsh file format: 41 (4.1) or 22 (2.2)")
      ->capture_default_str()
      ->transform(CLI::CheckedTransformer(std::map<std::string, int>{{"4.1", 41}, {"41", 41}, {"2.2", 22}, {"22", 22}}));
  cmd->add_option("--svg", args->output_svg,
                  "also draw the mesh into this SVG (primary red, secondary green; curved edges as cubic Béziers)");
  cmd->add_option("--vtu", args->output_vtu, "also write the mesh as VTK XML (.vtu, Lagrange triangles; opens in ParaView)");
  cmd->add_option("--stats", args->output_stats,
                  "write statistics as JSON: counts, min angle, max and mean AMIPS, seconds per stage");
  cmd->add_option("--stop-after", args->stop_after,
                  "last stage to run: triangulate (the exact triangulation, unoptimized), optimize (the linear "
                  "mesh) or curve (default; optimize with --linear)")
      ->check(CLI::IsMember({"triangulate", "optimize", "curve"}));
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
