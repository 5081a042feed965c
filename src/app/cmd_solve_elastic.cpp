// `curvemesh solve elastic`: a drawing's enclosed regions as a Neo-Hookean body hung at its top
// and pulled down by gravity (fem/elastic.hpp; paper §5.1, Figure 14).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/messages.hpp"
#include "app/solve_common.hpp"
#include "fem/elastic.hpp"
#include "fem/output.hpp"

namespace curvemesh::app {

namespace {

struct ElasticArgs {
  SolveOptions solve;
  std::string output_deformed;
  double youngs = 100, poisson = 0.3, density = 1, gravity = 9.81;
  int load_steps = 1, max_iterations = 50, quadrature_degree = 0;
  double tolerance = 1e-10;
  double hang_band_rel = 1e-3;
  std::vector<double> probe;  // x, y in the drawing's coordinates
  bool json = false;
};

// The picture: the undeformed body in light grey behind the deformed one coloured by |u|, in a
// view that holds both.
fem::Image draw(const fem::Geometry& geometry, const fem::Space& space, const Eigen::VectorXd& u,
                const fem::DeformedMesh& deformed, geometry::Box2 view, int width) {
  for (const geometry::Vec2& x : deformed.mesh.nodes) view.add(x);
  double largest = 0;
  for (std::size_t i = 0; i < deformed.mesh.nodes.size(); ++i)
    largest = std::max(largest, std::hypot(deformed.displacement[3 * i], deformed.displacement[3 * i + 1]));
  const fem::Rgb white = {1, 1, 1}, grey = {0.85, 0.85, 0.85}, unset = {1, 0, 1};
  fem::Image image = fem::rasterize(geometry, view, width, [&](int, const fem::Vec2&) { return grey; }, white);
  const fem::Geometry moved(deformed.mesh);
  const fem::Image front = fem::rasterize(
      moved, view, width,
      [&](int t, const fem::Vec2& xi) {
        const double ux = fem::value_at(space, u, t, xi, 2, 0), uy = fem::value_at(space, u, t, xi, 2, 1);
        return fem::colour_map(largest > 0 ? std::hypot(ux, uy) / largest : 0.0);
      },
      unset);
  for (std::size_t p = 0; p < front.rgb.size(); p += 3)
    if (!(front.rgb[p] == 255 && front.rgb[p + 1] == 0 && front.rgb[p + 2] == 255))
      for (int k = 0; k < 3; ++k) image.rgb[p + k] = front.rgb[p + k];
  return image;
}

// What the solve found, beside the result itself, for the reports.
struct ElasticSummary {
  double largest = 0, l2 = 0;  // the largest displacement at a node, its L2 norm
  bool probe_found = false;
  fem::Vec2 probe_value{0, 0};
  int hung = 0;  // nodes clamped at the top
};

void print_elastic_json(const ElasticArgs& args, const Problem& problem, const fem::ElasticResult& r,
                        const ElasticSummary& summary) {
  const double d = problem.drawing.diagonal;
  const double largest = summary.largest, l2 = summary.l2;
  const bool probe_found = summary.probe_found;
  const fem::Vec2& probe_value = summary.probe_value;
  nlohmann::ordered_json j;
  j["converged"] = r.converged;
  if (!r.converged) j["failure"] = r.failure;
  j["map"] = args.solve.straight ? "straight" : "cubic";
  j["triangles"] = problem.mesh.triangle_count();
  j["unknowns"] = r.unknowns;
  j["free_unknowns"] = r.free_unknowns;
  j["diagonal"] = d;
  j["mesh_seconds"] = problem.drawing.seconds;
  j["seconds"] = r.seconds;
  j["assembly_seconds"] = r.assembly_seconds;
  j["factor_seconds"] = r.factor_seconds;
  j["energy"] = r.energy;
  j["l2_norm"] = l2;
  j["max_displacement"] = largest;
  if (probe_found) j["probe"] = {probe_value.x(), probe_value.y()};
  j["newton"] = nlohmann::json::array();
  for (const auto& it : r.iterations)
    j["newton"].push_back({{"load_step", it.load_step},
                           {"iteration", it.iteration},
                           {"residual", it.residual},
                           {"energy", it.energy},
                           {"step_length", it.step_length},
                           {"backtracks", it.backtracks},
                           {"shift", it.shift}});
  std::cout << j.dump(1) << "\n";
}

void print_elastic_text(const ElasticArgs& args, const fem::ElasticOptions& options, const fem::ElasticResult& r,
                        const ElasticSummary& summary, double d) {
  const double largest = summary.largest, l2 = summary.l2;
  const bool probe_found = summary.probe_found;
  const fem::Vec2& probe_value = summary.probe_value;
  const int hung = summary.hung;
  std::printf("elastic: %d unknowns (P2 displacement, x and y), %d clamped at the top; mu = %.6g, lambda = %.6g, "
              "gravity %.6g per unit area along +y (down)\n",
              r.unknowns, 2 * hung, options.material.mu, options.material.lambda, args.density * args.gravity);
  std::printf("%4s %4s %12s %15s %8s %4s %8s\n", "step", "iter", "residual", "energy", "alpha", "bt", "shift");
  for (const auto& it : r.iterations)
    std::printf("%4d %4d %12.4e %15.8e %8.4g %4d %8.2g\n", it.load_step, it.iteration,
                r.initial_residual > 0 ? it.residual / r.initial_residual : it.residual, it.energy, it.step_length,
                it.backtracks, it.shift);
  const int newton = static_cast<int>(r.iterations.size()) - std::max(1, args.load_steps);
  std::printf("%s after %d Newton iterations in %.4f s (assembly %.4f s, CHOLMOD %.4f s); residual relative to "
              "the load\n",
              r.converged ? "converged" : "NOT converged", std::max(newton, 0), r.seconds, r.assembly_seconds,
              r.factor_seconds);
  std::printf("energy %.10g, |u| max %.6g (%.4g d), ||u||_L2 %.6g\n", r.energy, largest, largest / d, l2);
  if (probe_found) std::printf("u at (%g, %g): (%.10g, %.10g)\n", args.probe[0], args.probe[1], probe_value.x(),
                               probe_value.y());
}

int run_elastic(const ElasticArgs& args) {
  if (!args.probe.empty() && args.probe.size() != 2) {
    std::cerr << "curvemesh: --probe takes two numbers, x and y\n";
    return kUsage;
  }
  int code = kOk;
  SolveOptions solve = args.solve;
  solve.other_outputs = {{"--deformed", args.output_deformed}};
  std::optional<Problem> p = prepare_problem(solve, &code);
  if (!p) return code;
  const double d = p->drawing.diagonal;
  const fem::Geometry geometry(p->mesh);
  const fem::Space space(p->mesh, 2);
  fem::ElasticOptions options;
  options.material = fem::lame_parameters(args.youngs, args.poisson);
  // The body is taken to be d = 1 long: with x = d X, −div_x P = f / d, and u = d U.
  options.body_force = fem::Vec2(0, args.density * args.gravity / d);
  options.load_steps = args.load_steps;
  options.tolerance = args.tolerance;
  options.max_iterations = args.max_iterations;
  options.quadrature_degree = args.quadrature_degree;
  const std::vector<char> clamped = fem::hang_from_top(geometry, space, args.hang_band_rel * d);
  const int hung = static_cast<int>(std::count(clamped.begin(), clamped.end(), 1));
  const fem::NeoHookean problem(geometry, space, clamped, options);
  const fem::ElasticResult r = problem.solve();

  const std::vector<double> at_nodes = fem::values_at_nodes(geometry, space, r.displacement, 2);
  std::vector<double> displacement(p->mesh.nodes.size() * 3, 0.0);
  double largest = 0;
  for (std::size_t i = 0; i < p->mesh.nodes.size(); ++i) {
    displacement[3 * i] = at_nodes[2 * i], displacement[3 * i + 1] = at_nodes[2 * i + 1];
    largest = std::max(largest, std::hypot(at_nodes[2 * i], at_nodes[2 * i + 1]));
  }
  const double l2 = fem::displacement_l2_norm(geometry, space, r.displacement);
  fem::Vec2 probe_value(0, 0);
  bool probe_found = false;
  if (!args.probe.empty())
    probe_found =
        fem::displacement_at(geometry, space, r.displacement, fem::Vec2(args.probe[0], args.probe[1]), probe_value);

  ElasticSummary summary{largest, l2, probe_found, probe_value, hung};
  if (args.json) print_elastic_json(args, *p, r, summary);
  else print_elastic_text(args, options, r, summary, d);
  if (!args.probe.empty() && !probe_found)
    std::cerr << "curvemesh: --probe (" << args.probe[0] << ", " << args.probe[1] << ") is not in the body\n";
  if (!r.converged) {
    say(args.solve.input + ": Newton's method failed: " + r.failure + "; try more --load-steps or a smaller --gravity");
    return kInvalidInput;
  }

  std::optional<fem::DeformedMesh> deformed;
  if (!args.solve.output_png.empty() || !args.output_deformed.empty())
    deformed = fem::deformed_mesh(geometry, space, r.displacement);
  std::optional<fem::Image> picture;
  if (!args.solve.output_png.empty())
    picture = draw(geometry, space, r.displacement, *deformed, p->view, args.solve.width);
  std::vector<OtherFile> others;
  if (!args.output_deformed.empty())
    others.push_back({args.output_deformed,
                      io::vtu_string(deformed->mesh, {}, {{"displacement", 3, deformed->displacement}})});
  return write_outputs(args.solve, p->mesh, {{"displacement", 3, displacement}}, picture ? &*picture : nullptr,
                       others);
}

}  // namespace

SubcommandRunner add_solve_elastic_command(CLI::App& solve) {
  auto args = std::make_shared<ElasticArgs>();
  CLI::App* cmd = solve.add_subcommand(
      "elastic",
      "Hang the enclosed regions under gravity (Neo-Hookean elasticity)\n"
      "Hang the drawing's enclosed regions at their top and let gravity pull them down (paper §5.1, Figure 14): "
      "compressible Neo-Hookean elasticity in plane strain, sigma = mu (F - F^-T) + lambda ln(det F) F^-T, P2 "
      "displacement, Newton's method with the exact tangent (CHOLMOD) and a line search on the potential energy. "
      "Each piece of the body (triangles connected through edges) is clamped (zero displacement) at its border points "
      "within --hang-band of its topmost point; where these hold no whole border edge (a rounded or pointed top) the "
      "border edges through the topmost point are clamped too, so that no piece can swing. Gravity points along +y, "
      "which is down in the drawing (SVG's y axis points down). The drawing is taken to be d = 1 long (d: its "
      "bounding-box diagonal) whatever its units, so the same parameters deform every drawing alike; the deformation "
      "grows with density * gravity / youngs. Prints the Newton iterations (residual relative to the load, total "
      "potential energy) and their time. The VTU holds the displacement (3 components, z = 0) at the nodes, in the "
      "drawing's units; the PNG shows |displacement| on the deformed body, over the undeformed one in grey. The "
      "paper's set-up: `curvemesh solve elastic examples/square-with-hole.svg -o out.vtu --png out.png`.");
  add_solve_options(*cmd, args->solve, Domain::evenodd);
  cmd->add_option("--youngs", args->youngs, "Young's modulus E")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--poisson", args->poisson, "Poisson's ratio nu, in (-1, 0.5)")
      ->capture_default_str()
      ->check(CLI::Range(-0.999999, 0.499999));
  cmd->add_option("--density", args->density, "mass per unit area rho")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--gravity", args->gravity, "gravitational acceleration g (along +y, down in the drawing)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--load-steps", args->load_steps,
                  "apply gravity in this many equal steps, each solved by Newton from the previous solution "
                  "(for large deformations)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--tolerance", args->tolerance,
                  "stop Newton when the residual is below this fraction of the load (the residual at zero "
                  "displacement)")
      ->capture_default_str()
      ->check(CLI::Range(1e-15, 1.0));
  cmd->add_option("--max-iterations", args->max_iterations, "Newton iterations per load step before giving up")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--quadrature", args->quadrature_degree,
                  "quadrature degree (exact for polynomials of this total degree on the reference triangle); 0: the "
                  "default of every solve command, 10 on the cubic map and 4 on the straight one")
      ->capture_default_str()
      ->check(CLI::Range(0, 40));
  cmd->add_option("--hang-band", args->hang_band_rel,
                  "clamp the border points of each piece at most this far below its topmost point, relative to d")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--deformed", args->output_deformed,
                  "also write the deformed body as VTU (nodes moved by the displacement; order 3, or 2 with --straight, "
                  "so that the moved map is exact)");
  cmd->add_option("--probe", args->probe, "print the displacement at this point X Y of the body (drawing coordinates)")
      ->expected(2);
  cmd->add_flag("--json", args->json, "print the result (iterations, times, energy, norms, probe) as one JSON object");
  return {cmd, [args] { return run_elastic(*args); }};
}

}  // namespace curvemesh::app
