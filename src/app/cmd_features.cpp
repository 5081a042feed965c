// `curvemesh features`: the SVG reader and, with --processed, feature processing (paper §4),
// dumped as JSON and optionally drawn as SVG.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/feature_options.hpp"
#include "features/features.hpp"
#include "io/features_json.hpp"
#include "io/output_file.hpp"
#include "io/soup_json.hpp"
#include "io/soup_svg.hpp"
#include "svg/error.hpp"
#include "svg/reader.hpp"

namespace curvemesh::app {

namespace {
struct FeaturesArgs {
  std::string input;
  std::string output_json;
  std::string output_svg;
  bool processed = false;
  svg::ReadOptions read;
  features::Options features;
};

int run_features(const FeaturesArgs& args) {
  if (args.processed && !feature_options_valid(args.features)) return kUsage;
  svg::FeatureSoup soup;
  try {
    soup = svg::read_svg_file(args.input, args.read);
  } catch (const svg::InputError& e) {
    std::cerr << "curvemesh: " << e.what() << "\n";
    return kInvalidInput;
  }
  for (const std::string& w : soup.warnings) std::cerr << "curvemesh: " << args.input << ": warning: " << w << "\n";

  nlohmann::ordered_json json = io::soup_to_json(soup);
  std::string drawing;
  if (args.processed) {
    const features::Features f = features::process(soup, args.features);
    io::add_features_json(f, json);
    if (!args.output_svg.empty()) drawing = io::features_to_svg(f);
  } else if (!args.output_svg.empty()) {
    drawing = io::soup_to_svg(soup);
  }
  try {
    io::write_file_atomically(args.output_json, json.dump(1) + "\n");
    if (!args.output_svg.empty()) io::write_file_atomically(args.output_svg, drawing);
  } catch (const io::OutputError& e) {
    std::cerr << "curvemesh: " << e.what() << "\n";
    return kInvalidInput;
  }
  return kOk;
}
}  // namespace

Runner add_features_command(CLI::App& app) {
  auto args = std::make_shared<FeaturesArgs>();
  CLI::App* cmd = app.add_subcommand(
      "features",
      "Read an SVG drawing into a soup of cubic Bézier curves and isolated points, in the root element's "
      "user space (viewBox units, y down), and write it as JSON (and optionally as an SVG drawing). "
      "With --processed, also run feature processing (paper §4): primary sections, secondary segments.");
  cmd->add_option("input", args->input, "SVG file to read")->required();
  cmd->add_option("-o,--output", args->output_json, "JSON file to write (keys: bbox, curves, points, warnings)")
      ->required();
  cmd->add_option("--svg", args->output_svg,
                  "also draw into this SVG file: the soup, or with --processed the features (primary red, "
                  "secondary green, points black)");
  cmd->add_flag("--processed", args->processed,
                "run feature processing and add sections, segments and feature_points to the JSON");
  cmd->add_option("--degenerate-tolerance", args->read.degenerate_tolerance_rel,
                  "reader: paths whose control points all lie within this distance (relative to the "
                  "bounding-box diagonal d) become isolated points")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  add_feature_options(*cmd, args->features);
  return [args] { return run_features(*args); };
}

}  // namespace curvemesh::app
