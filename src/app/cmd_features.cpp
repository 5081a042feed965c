// `curvemesh features`: run the SVG reader (and later the feature stage) and dump the result.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
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
  svg::ReadOptions read;
};

int run_features(const FeaturesArgs& args) {
  svg::FeatureSoup soup;
  try {
    soup = svg::read_svg_file(args.input, args.read);
  } catch (const svg::InputError& e) {
    std::cerr << "curvemesh: " << e.what() << "\n";
    return kInvalidInput;
  }
  for (const std::string& w : soup.warnings) std::cerr << "curvemesh: " << args.input << ": warning: " << w << "\n";
  try {
    io::write_file_atomically(args.output_json, io::soup_to_json(soup).dump(1) + "\n");
    if (!args.output_svg.empty()) io::write_file_atomically(args.output_svg, io::soup_to_svg(soup));
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
      "user space (viewBox units, y down), and write it as JSON (and optionally as an SVG drawing).");
  cmd->add_option("input", args->input, "SVG file to read")->required();
  cmd->add_option("-o,--output", args->output_json, "JSON file to write (keys: bbox, curves, points, warnings)")
      ->required();
  cmd->add_option("--svg", args->output_svg, "also draw the soup into this SVG file");
  cmd->add_option("--degenerate-tolerance", args->read.degenerate_tolerance_rel,
                  "paths whose control points all lie within this distance (relative to the bounding-box "
                  "diagonal) become isolated points (paper: epsilon_m)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  return [args] { return run_features(*args); };
}

}  // namespace curvemesh::app
