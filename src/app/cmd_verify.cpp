// `curvemesh verify convergence`: the Poisson convergence study of fem/convergence.hpp, P2 on
// cubic and on straight geometry, as a table or one JSON object.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "fem/convergence.hpp"

namespace curvemesh::app {

namespace {

struct VerifyArgs {
  bool json = false;
  std::vector<double> edge_lengths;
};

nlohmann::ordered_json series_json(const fem::ConvergenceSeries& s) {
  nlohmann::ordered_json j;
  j["h"] = nlohmann::json::array();
  for (const char* key : {"l2", "h1", "edge_length_rel", "triangles", "unknowns", "seconds"}) j[key] = nlohmann::json::array();
  for (const auto& l : s.levels) {
    j["h"].push_back(l.h);
    j["l2"].push_back(l.l2);
    j["h1"].push_back(l.h1);
    j["edge_length_rel"].push_back(l.edge_length_rel);
    j["triangles"].push_back(l.triangles);
    j["unknowns"].push_back(l.unknowns);
    j["seconds"].push_back(l.seconds);
  }
  j["rate_l2"] = s.rate_l2;
  j["rate_h1"] = s.rate_h1;
  return j;
}

int run_verify(const VerifyArgs& args) {
  fem::ConvergenceOptions options;
  if (!args.edge_lengths.empty()) options.edge_lengths_rel = args.edge_lengths;
  if (options.edge_lengths_rel.size() < 2) {
    std::cerr << "curvemesh: verify convergence needs at least two edge lengths\n";
    return kUsage;
  }
  if (!args.json) std::cerr << "curvemesh: meshing the disk at " << options.edge_lengths_rel.size() << " edge lengths...\n";
  const fem::ConvergenceResult r = fem::poisson_convergence(options);
  if (args.json) {
    nlohmann::ordered_json j;
    j["problem"] = "-Δu = f in the unit disk, u = 0 on the circle, u = (1 - x² - y²) exp(x) cos(y); P2 elements";
    j["p3_geometry"] = series_json(r.p3_geometry);
    j["p1_geometry"] = series_json(r.p1_geometry);
    j["mesh_seconds"] = r.mesh_seconds;
    std::cout << j.dump(1) << "\n";
    return kOk;
  }
  std::printf("Poisson on the unit disk, P2 unknowns; h = mean edge length (radius 1)\n");
  std::printf("%9s %9s %9s | %12s %12s | %12s %12s\n", "-l", "h", "triangles", "L2 (P3 map)", "H1 (P3 map)",
              "L2 (P1 map)", "H1 (P1 map)");
  for (std::size_t i = 0; i < r.p3_geometry.levels.size(); ++i) {
    const auto& c = r.p3_geometry.levels[i];
    const auto& s = r.p1_geometry.levels[i];
    std::printf("%9.4g %9.4g %9d | %12.4e %12.4e | %12.4e %12.4e\n", c.edge_length_rel, c.h, c.triangles, c.l2, c.h1,
                s.l2, s.h1);
  }
  std::printf("%29s | %12.2f %12.2f | %12.2f %12.2f   (rates)\n", "", r.p3_geometry.rate_l2, r.p3_geometry.rate_h1,
              r.p1_geometry.rate_l2, r.p1_geometry.rate_h1);
  return kOk;
}

}  // namespace

Runner add_verify_command(CLI::App& app) {
  auto args = std::make_shared<VerifyArgs>();
  CLI::App* cmd = app.add_subcommand("verify", "Numerical checks of the meshes in use (paper §5.1)");
  cmd->require_subcommand(1);
  CLI::App* conv = cmd->add_subcommand(
      "convergence",
      "P2 on the cubic against the straight map: errors and rates on a disk\n"
      "Solve -Δu = f on the unit disk (an SVG circle drawn as 32 arcs) with a known smooth solution, meshed "
      "at shrinking edge lengths, with quadratic (P2) elements on the cubic curved map and on the straight "
      "map of the same meshes; print the L2 and H1 errors and their rates (expected: L2 about 3 curved, "
      "at most 2 straight).");
  conv->add_flag("--json", args->json,
                 "print one JSON object: {\"p3_geometry\": {\"h\", \"l2\", \"h1\", \"rate_l2\", \"rate_h1\", ...}, "
                 "\"p1_geometry\": {...}}");
  conv->add_option("--edge-lengths", args->edge_lengths,
                   "target edge lengths of the levels, relative to the disk's bounding-box diagonal (default "
                   "0.04 0.028 0.02 0.014 0.01)")
      ->check(CLI::Range(1e-3, 0.5));
  return [args] { return run_verify(*args); };
}

}  // namespace curvemesh::app
