// `curvemesh solve PROBLEM ...`: the partial differential equations of the paper's §5.1 on a
// drawing's curved mesh (or, with --straight, on the same mesh with straight triangles).
#include <CLI/CLI.hpp>
#include <vector>

#include "app/commands.hpp"

namespace curvemesh::app {

Runner add_solve_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Mesh a drawing and solve a PDE on it: inflate, elastic or stokes\n"
      "Mesh a drawing and solve a PDE on it with quadratic (P2) elements on the cubic curved map (paper §5.1); "
      "--straight uses the straight map of the same mesh. Writes the solution as VTU (ParaView) and PNG and "
      "prints the time of each step.");
  cmd->require_subcommand(1);
  std::vector<SubcommandRunner> problems;
  problems.push_back(add_solve_inflate_command(*cmd));
  problems.push_back(add_solve_elastic_command(*cmd));
  problems.push_back(add_solve_stokes_command(*cmd));
  return [problems] {
    for (const auto& [sub, run] : problems)
      if (sub->parsed()) return run();
    return int(kUsage);
  };
}

}  // namespace curvemesh::app
