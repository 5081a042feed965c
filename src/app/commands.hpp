#pragma once
// The `curvemesh` subcommands. Each registers its options on the CLI11 app and returns the
// function that runs it; exit codes follow the design: 0 ok, 1 invalid input, 2 usage, 3 bug.
#include <curvemesh/parameters.hpp>
#include <functional>
#include <utility>

namespace CLI {
class App;
}

namespace curvemesh::app {

enum ExitCode : int { kOk = 0, kInvalidInput = 1, kUsage = 2, kInternal = 3 };

// The exit code of a failure: 2 for parameters, 3 for an internal one, 1 for the rest.
inline int exit_code(const Error& e) {
  switch (e.kind()) {
    case Error::Kind::invalid_parameters: return kUsage;
    case Error::Kind::internal: return kInternal;
    default: return kInvalidInput;
  }
}

using Runner = std::function<int()>;

Runner add_features_command(CLI::App& app);
Runner add_mesh_command(CLI::App& app);
Runner add_check_command(CLI::App& app);
Runner add_batch_command(CLI::App& app);
Runner add_report_command(CLI::App& app);
Runner add_verify_command(CLI::App& app);
Runner add_solve_command(CLI::App& app);
Runner add_diffuse_command(CLI::App& app);

// The problems under `curvemesh solve`: each registers itself on the `solve` command.
using SubcommandRunner = std::pair<CLI::App*, Runner>;
SubcommandRunner add_solve_inflate_command(CLI::App& solve);
SubcommandRunner add_solve_elastic_command(CLI::App& solve);
SubcommandRunner add_solve_stokes_command(CLI::App& solve);

}  // namespace curvemesh::app
