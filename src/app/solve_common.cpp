#include "app/solve_common.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdint>
#include <iostream>

#include "app/commands.hpp"
#include "app/mesh_options.hpp"
#include "app/messages.hpp"
#include "app/outputs.hpp"
#include "app/progress.hpp"
#include "base/text.hpp"
#include "pipeline/domain.hpp"
#include "pipeline/output.hpp"

namespace curvemesh::app {

void add_solve_options(CLI::App& cmd, SolveOptions& o, Domain default_domain) {
  o.domain = default_domain;
  cmd.add_option("input", o.input, "SVG drawing to mesh and solve on")->required();
  cmd.add_option("-o,--output", o.output_vtu,
                 "VTK XML file (.vtu) to write: the domain's mesh with the solution at its nodes (opens in ParaView)");
  cmd.add_option("--png", o.output_png, "also draw the solution into this PNG picture");
  cmd.add_option("--width", o.width, "width of the PNG picture in pixels")->capture_default_str()->check(CLI::Range(8, 20000));
  cmd.add_flag("--straight", o.straight,
               "solve on straight triangles: the same mesh with its straight (P1) map instead of the cubic one "
               "(not `mesh --linear`, which makes another mesh, of order 1)");
  // The names and meanings of `mesh --domain` (Parameters' domain), one vocabulary for every command.
  std::map<std::string, Domain> names;
  const std::vector<std::string> listed = pipeline::domain_names();
  // domain_names() lists them in Domain's order.
  for (std::size_t i = 0; i < listed.size(); ++i) names.emplace(listed[i], static_cast<Domain>(i));
  cmd.add_option("--domain", o.domain,
                 "where the problem lives, as `mesh --domain` keeps it: box (the whole meshed box), filled (what the "
                 "drawing's filled elements cover), evenodd (the regions enclosed by an odd number of curves), "
                 "painted (what some fill or stroke paints, strokes read as areas) or outside (the box without "
                 "evenodd)")
      ->transform(CLI::CheckedTransformer(names))
      ->default_str(pipeline::domain_name(default_domain));
  add_feature_options(cmd, o.parameters);
  add_memory_limit_option(cmd, o.memory_limit_gb);
}

namespace {

// Whether the picture asked for fits fem::kMaxPicturePixels; if not, says so.
bool picture_fits(const SolveOptions& o, const io::HighOrderMesh& mesh, const char* done) {
  if (o.output_png.empty()) return true;
  geometry::Box2 view;
  for (const geometry::Vec2& x : mesh.nodes) view.add(x);
  const auto [width, height] = fem::picture_size(view, o.width);
  if (std::int64_t(width) * height <= fem::kMaxPicturePixels) return true;
  say(o.input + ": a picture " + std::to_string(width) + " pixels wide would be " + std::to_string(height) +
      " high, more than the limit of " + std::to_string(fem::kMaxPicturePixels) + " pixels (--width lowers it); nothing " +
      done);
  return false;
}

}  // namespace

std::optional<fem::MeshedDrawing> mesh_for_solving(const SolveOptions& o, const char* done, int* exit_code) {
  *exit_code = kUsage;
  if (!parameters_valid(o.parameters)) return std::nullopt;
  std::vector<base::NamedPath> outputs = {{o.vtu_option, o.output_vtu}, {o.png_option, o.output_png}};
  outputs.insert(outputs.end(), o.other_outputs.begin(), o.other_outputs.end());
  if (!outputs_distinct({{"input", o.input}}, outputs)) return std::nullopt;
  *exit_code = kOk;
  limit_memory(o.memory_limit_gb);
  pipeline::Parameters curved = o.parameters;
  curved.order = 3;  // --straight solves on the straight map of the curved mesh
  pipeline::RunOptions run;
  run.warn = [&](const std::string& w) { warn(o.input, w); };
  // The paint classified where the domain asks for it: meshed_drawing keeps it.
  curved.regions = o.domain == Domain::filled || o.domain == Domain::painted;
  if (o.domain == Domain::painted) curved.strokes = Strokes::areas;
  try {
    ProgressDisplay display(o.input);
    run.progress = [&](const pipeline::Progress& p) { display(p); };
    fem::MeshedDrawing drawing = pipeline::meshed_drawing(pipeline::run(pipeline::Source::file(o.input), curved, run));
    if (picture_fits(o, drawing.mesh, done)) return drawing;
    *exit_code = kInvalidInput;
    return std::nullopt;
  } catch (const Error& e) {
    say(std::string(e.what()) + "; nothing " + done);
    *exit_code = app::exit_code(e);
    return std::nullopt;
  }
}

std::optional<Problem> prepare_problem(const SolveOptions& o, int* exit_code) {
  Problem p;
  std::optional<fem::MeshedDrawing> drawing = mesh_for_solving(o, "solved", exit_code);
  if (!drawing) return std::nullopt;
  p.drawing = std::move(*drawing);
  const io::HighOrderMesh& whole = p.drawing.mesh;
  p.view = geometry::Box2();
  for (const geometry::Vec2& x : whole.nodes) p.view.add(x);
  std::optional<pipeline::DomainMesh> domain = pipeline::cut_domain(p.drawing, o.domain);
  if (!domain) {
    say(o.input + ": the domain '" + pipeline::domain_name(o.domain) + "' is empty (" +
        pipeline::empty_domain_reason(o.domain, p.drawing.has_fills, p.drawing.has_strokes) + "); try --domain box");
    *exit_code = kInvalidInput;
    return std::nullopt;
  }
  p.mesh = std::move(domain->mesh);
  p.line_origin = std::move(domain->line_origin);
  if (o.straight) p.mesh = fem::straight_mesh(p.mesh);
  std::cerr << "curvemesh: meshed " << base::printable(o.input) << " in " << p.drawing.seconds << " s: " << p.mesh.triangle_count()
            << " triangles in the domain (" << (o.straight ? "straight" : "cubic") << " map)\n";
  return p;
}

int write_outputs(const SolveOptions& o, const io::HighOrderMesh& mesh, const std::vector<io::VtuPointArray>& arrays,
                  const fem::Image* picture, const std::vector<OtherFile>& others) {
  return write_together([&](base::OutputFiles& out) {
    if (!o.output_vtu.empty()) {
      // Only the nodes some triangle uses (a straight map leaves the cubic nodes unused).
      std::vector<int> node_origin;
      const io::HighOrderMesh used = pipeline::used_nodes(mesh, node_origin);
      std::vector<io::VtuPointArray> kept = arrays;
      for (io::VtuPointArray& a : kept) {
        std::vector<double> values;
        values.reserve(node_origin.size() * a.components);
        for (int i : node_origin)
          for (int c = 0; c < a.components; ++c) values.push_back(a.values[std::size_t(i) * a.components + c]);
        a.values = std::move(values);
      }
      out.add(o.output_vtu, io::vtu_string(used, {}, kept));
    }
    if (picture && !o.output_png.empty()) out.add(o.output_png, fem::png_bytes(*picture));
    for (const auto& [path, content] : others) out.add(path, content);
  });
}

}  // namespace curvemesh::app
