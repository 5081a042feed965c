// `curvemesh features`: the SVG reader and, with --processed, feature processing (paper §4),
// dumped as JSON and optionally drawn as SVG.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/mesh_options.hpp"
#include "io/features_json.hpp"
#include "app/messages.hpp"
#include "app/outputs.hpp"
#include "io/soup_json.hpp"
#include "io/soup_svg.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh::app {

namespace {
struct FeaturesArgs {
  std::string input;
  std::string output_json;
  std::string output_svg;
  bool processed = false;
  pipeline::Parameters parameters;
};

int run_features(const FeaturesArgs& args) {
  if (!parameters_valid(args.parameters)) return kUsage;
  if (!outputs_distinct({{"input", args.input}}, {{"-o", args.output_json}, {"--svg", args.output_svg}})) return kUsage;
  pipeline::RunOptions run;
  run.stop_after = args.processed ? pipeline::Stage::features : pipeline::Stage::read;
  run.warn = [&](const std::string& w) { warn(args.input, w); };
  pipeline::Result r;
  try {
    r = pipeline::run(pipeline::Source::file(args.input), args.parameters, run);
  } catch (const Error& e) {
    say(e.what());
    return exit_code(e);
  }

  nlohmann::ordered_json json = io::soup_to_json(r.soup);
  std::string drawing;
  if (args.processed) {
    io::add_features_json(r.features, json);
    if (!args.output_svg.empty()) drawing = io::features_to_svg(r.features);
  } else if (!args.output_svg.empty()) {
    drawing = io::soup_to_svg(r.soup);
  }
  return write_together([&](base::OutputFiles& out) {
    out.add(args.output_json, json.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
    if (!args.output_svg.empty()) out.add(args.output_svg, drawing);
  });
}
}  // namespace

Runner add_features_command(CLI::App& app) {
  auto args = std::make_shared<FeaturesArgs>();
  CLI::App* cmd = app.add_subcommand(
      "features",
      "Read an SVG drawing into curves and points (with --processed, its features) as JSON\n"
      "Read an SVG drawing into a soup of cubic Bézier curves and isolated points, in the root element's "
      "user space (viewBox units, y down), and write it as JSON (and optionally as an SVG drawing). "
      "With --processed, also run feature processing (paper §4): primary sections, secondary segments.");
  cmd->add_option("input", args->input, "SVG file to read (gzip-compressed too: .svgz)")->required();
  cmd->add_option("-o,--output", args->output_json, "JSON file to write (keys: bbox, curves, points, warnings)")
      ->required();
  cmd->add_option("--svg", args->output_svg,
                  "also draw into this SVG file: the soup, or with --processed the features (primary red, "
                  "secondary green, points black)");
  cmd->add_flag("--processed", args->processed,
                "run feature processing and add sections, segments and feature_points to the JSON");
  add_feature_options(*cmd, args->parameters);
  return [args] { return run_features(*args); };
}

}  // namespace curvemesh::app
