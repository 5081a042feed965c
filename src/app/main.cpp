// curvemesh: curved triangle meshes from real-world vector drawings.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <map>
#include <memory>
#include <new>
#include <sstream>
#include <string>

#include "app/commands.hpp"
#include "app/messages.hpp"

namespace {

// A command's description is one line, then a paragraph: `curvemesh --help` lists the commands
// with their line, `curvemesh COMMAND --help` shows the whole description.
class CommandListFormatter : public CLI::Formatter {
 public:
  std::string make_subcommand(const CLI::App* sub) const override {
    const std::string& description = sub->get_description();
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true), description.substr(0, description.find('\n')),
                             column_width_);
    return out.str();
  }
};

}  // namespace

int main(int argc, char** argv) {
  using namespace curvemesh::app;
  CLI::App app{"curvemesh: coarse, curved, analysis-ready triangle meshes from SVG drawings"};
  app.formatter(std::make_shared<CommandListFormatter>());
  app.footer("`curvemesh COMMAND --help` explains a command and every one of its options.");
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("curvemesh ") + CURVEMESH_VERSION);

  std::map<const CLI::App*, Runner> runners;
  auto add = [&](Runner r) { runners[app.get_subcommands({}).back()] = std::move(r); };
  add(add_features_command(app));
  add(add_mesh_command(app));
  add(add_check_command(app));
  add(add_batch_command(app));
  add(add_report_command(app));
  add(add_verify_command(app));
  add(add_solve_command(app));
  add(add_diffuse_command(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kOk : kUsage;
  }
  try {
    for (const CLI::App* sub : app.get_subcommands()) return runners.at(sub)();
  } catch (const std::bad_alloc&) {
    say(out_of_memory_message());
    return kInvalidInput;
  } catch (const std::exception& e) {
    say(std::string("internal error (this is a bug): ") + e.what());
    return kInternal;
  }
  return kUsage;
}
