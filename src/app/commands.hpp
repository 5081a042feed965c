#pragma once
// The `curvemesh` subcommands. Each registers its options on the CLI11 app and returns the
// function that runs it; exit codes follow the design: 0 ok, 1 invalid input, 2 usage, 3 bug.
#include <functional>
#include <utility>

namespace CLI {
class App;
}

namespace curvemesh::app {

enum ExitCode : int { kOk = 0, kInvalidInput = 1, kUsage = 2, kInternal = 3 };

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
