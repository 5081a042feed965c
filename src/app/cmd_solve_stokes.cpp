// `curvemesh solve stokes`: viscous flow (fem/stokes.hpp) through a drawing, from the left side
// of the box to the right one, around every curve of the drawing as a thin wall.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/messages.hpp"
#include "app/solve_common.hpp"
#include "fem/domain.hpp"
#include "fem/output.hpp"
#include "fem/stokes.hpp"

namespace curvemesh::app {

namespace {

struct StokesArgs {
  SolveOptions solve;
  fem::StokesOptions stokes;
  double inflow_speed = 1;
  double colour_top = 0;  // the speed at the top of the picture's colour map; 0: the highest speed
};

// The velocity conditions on the box's sides, found by where their ends are (SVG y points down;
// top and bottom are alike here): a parabolic inflow on the left, walls on the top, the bottom
// and every curve; the right side is the natural outflow.
std::pair<fem::VelocityCondition, fem::VelocityCondition> channel_conditions(const io::HighOrderMesh& mesh,
                                                                             const geometry::Box2& box,
                                                                             double speed) {
  const double tol = 1e-9 * (box.max - box.min).norm();
  fem::VelocityCondition inflow, walls;
  walls.velocity = [](const fem::Vec2&) { return fem::Vec2(0, 0); };
  const double y0 = box.min.y(), y1 = box.max.y();
  inflow.velocity = [y0, y1, speed](const fem::Vec2& x) {
    const double s = (x.y() - y0) / (y1 - y0);
    return fem::Vec2(4 * speed * s * (1 - s), 0);
  };
  const auto lines = fem::edge_lines(mesh);
  const auto on = [tol](double u, double v, double side) {
    return std::abs(u - side) <= tol && std::abs(v - side) <= tol;
  };
  for (int t = 0; t < mesh.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int l = lines[t][e];
      if (l < 0) continue;
      if (mesh.line_physical[l] != io::kPhysicalBoundary) {
        walls.edges.emplace_back(t, e);
        continue;
      }
      const fem::Vec2 a = mesh.nodes[mesh.line(l)[0]], b = mesh.nodes[mesh.line(l)[1]];
      if (on(a.x(), b.x(), box.min.x()))
        inflow.edges.emplace_back(t, e);
      else if (!on(a.x(), b.x(), box.max.x()))
        walls.edges.emplace_back(t, e);
    }
  return {std::move(inflow), std::move(walls)};
}

int run_stokes(const StokesArgs& args) {
  int code = kOk;
  std::optional<Problem> p = prepare_problem(args.solve, &code);
  if (!p) return code;
  // Every curve is a wall with fluid on both sides: cut open along it, the two sides have their
  // own velocity and pressure unknowns (a thin plate holds a pressure jump).
  std::vector<char> cut(p->mesh.line_count(), 0);
  for (int l = 0; l < p->mesh.line_count(); ++l)
    cut[l] = p->mesh.line_physical[l] == io::kPhysicalPrimary ||
             p->mesh.line_physical[l] == io::kPhysicalSecondary;
  const io::HighOrderMesh mesh = fem::cut_open(p->mesh, cut).mesh;
  const fem::Geometry geometry(mesh);
  const fem::Space velocity(mesh, 2), pressure(mesh, 1);

  auto [inflow, walls] = channel_conditions(mesh, p->view, args.inflow_speed);
  if (inflow.edges.empty())
    warn(args.solve.input, "the domain does not reach the box's left side; with no inflow the fluid is at rest");

  fem::StokesResult r;
  try {
    r = fem::stokes(geometry, velocity, pressure, {inflow, walls}, args.stokes);
  } catch (const std::runtime_error& e) {
    say(args.solve.input + ": " + e.what());
    return kInternal;
  }
  const std::vector<double> uv = fem::values_at_nodes(geometry, velocity, r.velocity, 2);
  const std::vector<double> pn = fem::values_at_nodes(geometry, pressure, r.pressure);
  std::vector<double> u3(mesh.nodes.size() * 3, 0.0), speed_at(mesh.nodes.size());
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    u3[3 * i] = uv[2 * i], u3[3 * i + 1] = uv[2 * i + 1];
    speed_at[i] = std::hypot(uv[2 * i], uv[2 * i + 1]);
  }
  // The highest speed at the velocity unknowns (corners and edge midpoints), which the straight
  // and the cubic map of a mesh both have, rather than at the nodes, which differ between them.
  double top = 0;
  for (int i = 0; i < velocity.size(); ++i)
    top = std::max(top, std::hypot(r.velocity[2 * i], r.velocity[2 * i + 1]));
  std::printf(
      "stokes: %d velocity unknowns (P2, 2 components; %d given), %d pressure unknowns "
      "(P1; held: %d for closed regions, %d for local modes), %d triangles (%s map); "
      "assembly %.3f s, solve %.3f s; highest speed %.6g\n",
      r.velocity_unknowns, r.fixed_velocities, r.pressure_unknowns, r.closed_parts, r.dependent_pressures,
      mesh.triangle_count(), mesh.order == 1 ? "straight" : "cubic", r.assembly_seconds, r.solve_seconds,
      top);

  std::optional<fem::Image> picture;
  if (!args.solve.output_png.empty()) {
    const double colour_top = args.colour_top > 0 ? args.colour_top : top;
    const double scale = colour_top > 0 ? 1 / colour_top : 0.0;
    picture = fem::rasterize(geometry, p->view, args.solve.width, [&](int t, const fem::Vec2& xi) {
      const double u = fem::value_at(velocity, r.velocity, t, xi, 2, 0);
      const double v = fem::value_at(velocity, r.velocity, t, xi, 2, 1);
      return fem::colour_map(std::hypot(u, v) * scale);
    });
  }
  return write_outputs(args.solve, mesh, {{"velocity", 3, u3}, {"pressure", 1, pn}, {"speed", 1, speed_at}},
                       picture ? &*picture : nullptr);
}

}  // namespace

SubcommandRunner add_solve_stokes_command(CLI::App& solve) {
  auto args = std::make_shared<StokesArgs>();
  CLI::App* cmd = solve.add_subcommand(
      "stokes",
      "Viscous flow through the drawing (Stokes, Taylor-Hood)\n"
      "Viscous (Stokes) flow through the drawing (paper §5.1): -v lap u + grad p = 0, div u = 0 (v: "
      "--viscosity) "
      "with Taylor-Hood elements (P2 velocity, P1 pressure; a saddle-point system solved by UMFPACK). The "
      "fluid "
      "enters at the box's left side with a parabolic profile and leaves at the right side (do-nothing "
      "condition); it sticks to the top and bottom sides and to both sides of every curve of the drawing, "
      "which "
      "the mesh is cut open along. Regions closed off by curves hold fluid at rest. Writes velocity, "
      "pressure and "
      "speed at the nodes; the picture shows the speed.");
  add_solve_options(*cmd, args->solve, Domain::box);
  const CLI::Validator positive_finite(
      [](std::string& text) {
        double value = 0;
        if (CLI::detail::lexical_cast(text, value) && value > 0 && std::isfinite(value)) return std::string();
        return "must be a positive finite number, not " + text;
      },
      "POSITIVE");
  cmd->add_option("--viscosity", args->stokes.viscosity,
                  "the fluid's viscosity v (not the feature option --mu)")
      ->capture_default_str()
      ->check(positive_finite);
  cmd->add_option(
         "--inflow-speed", args->inflow_speed,
         "the inflow's speed at the middle of the box's left side (the top of the parabolic profile)")
      ->capture_default_str()
      ->check(positive_finite);
  cmd->add_option(
         "--colour-top", args->colour_top,
         "the speed drawn with the colour map's top colour in the picture (faster is drawn the same); "
         "default: the highest speed of the solution. Give two pictures the same to compare them")
      ->check(positive_finite);
  return {cmd, [args] { return run_stokes(*args); }};
}

}  // namespace curvemesh::app
