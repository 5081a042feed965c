// `curvemesh check`: certifies any 2D triangle mesh in a Gmsh .msh file (P1, P2 or P3; ours or
// not). Every element's Jacobian determinant is decided positive on the whole element as exact
// rationals on the coordinates as a reader of the file get them decide it (a double certificate
// with a rigorous error bound first, rationals where it cannot decide; all rationals with
// --exact); with the drawing, the largest
// distance from a primary feature edge to the nearest input curve is measured too. The
// certification itself is the pipeline's (pipeline/check.hpp), shared with the public API.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/mesh_options.hpp"
#include "io/high_order_mesh.hpp"
#include "io/msh_reader.hpp"
#include "pipeline/check.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh::app {

namespace {

struct CheckArgs {
  std::string input, svg;
  bool json = false, exact = false, timing = false;
  pipeline::Parameters parameters;  // --threads alone
  double max_input_mb = io::kDefaultMaxMshMb;
};

int run_check(const CheckArgs& args) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const Clock::time_point start = Clock::now();
  io::HighOrderMesh m;
  try {
    m = io::read_msh(args.input, static_cast<std::uint64_t>(args.max_input_mb * 1048576.0), "--max-input-mb");
  } catch (const io::MshError& e) {
    std::cerr << "curvemesh: " << e.what() << "\n";  // it starts with the path
    return kInvalidInput;
  } catch (const std::exception& e) {
    std::cerr << "curvemesh: " << args.input << ": " << e.what() << "\n";
    return kInvalidInput;
  }
  const double reading = seconds_since(start);
  const Clock::time_point certifying = Clock::now();
  const pipeline::MeshCheck c =
      pipeline::check_mesh(m, {.exact = args.exact, .threads = args.parameters.threads});
  const double certified = seconds_since(certifying);
  nlohmann::ordered_json report;
  report["file"] = args.input;
  report["order"] = c.order;
  report["triangles"] = c.triangles;
  report["invalid"] = c.invalid;
  report["undecided"] = c.undecided;
  report["min_scaled_jacobian"] = c.min_scaled_jacobian;
  report["exact_fallbacks"] = c.exact_fallbacks;
  if (args.timing) report["seconds"] = {{"read", reading}, {"certify", certified}};

  if (!args.svg.empty()) {
    pipeline::Result read;
    try {
      read = pipeline::run(pipeline::Source::file(args.svg), {}, pipeline::Stage::read);
    } catch (const Error& e) {
      std::cerr << "curvemesh: " << e.what() << "\n";
      return exit_code(e);
    }
    const pipeline::FeatureDistance d = pipeline::feature_distance(m, read.soup);
    report["primary_lines"] = d.primary_lines;
    report["max_feature_distance"] = d.max;
    report["max_feature_distance_rel"] = d.max_rel;
  }

  if (args.json) {
    std::cout << report.dump() << "\n";
  } else {
    for (const auto& [k, v] : report.items()) std::cout << k << ": " << v << "\n";
    std::cout << (c.invalid ? "INVALID" : "OK") << "\n";
  }
  return c.invalid ? kInvalidInput : kOk;
}

}  // namespace

Runner add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Certify every element of a Gmsh .msh file exactly (a positive Jacobian)\n"
      "Certify a 2D triangle mesh in a Gmsh .msh file (4.1 or 2.2, ASCII; linear, quadratic or cubic "
      "triangles, from any program): the Jacobian determinant of every element is decided positive "
      "on the whole element as exact rational arithmetic on the coordinates as written decides it. A "
      "certificate in doubles with a rigorous bound on its rounding errors decides first, and only "
      "the elements it cannot decide are decided again in rationals (exact_fallbacks counts them); "
      "--exact decides every element in rationals. Prints the number of invalid elements and the "
      "smallest scaled Jacobian; with --svg, also the largest distance from a primary feature edge to "
      "the drawing's curves. Exit 1 if any element is invalid.");
  cmd->add_option("input", args->input, ".msh file to check")->required();
  cmd->add_option("--svg", args->svg,
                  "the SVG drawing the mesh was made from: measure primary edges against its curves");
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->add_flag("--exact", args->exact,
                "decide every element with exact rationals, without the double certificate first "
                "(the same verdicts, slower: the independent check of the filtered one)");
  cmd->add_flag("--timing", args->timing,
                "also report the seconds spent reading the file and certifying its elements (which vary "
                "from run to run; the rest of the report does not)");
  add_threads_option(*cmd, args->parameters);
  cmd->add_option("--max-input-mb", args->max_input_mb,
                  "refuse a .msh file larger than this many MiB (a cubic mesh of two million triangles "
                  "is about 500)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  return [args] { return run_check(*args); };
}

}  // namespace curvemesh::app
