#pragma once
// What every `curvemesh solve ...` command (and `diffuse`) shares: the input drawing and its
// meshing options, the choice of straight geometry, which part of the box is the domain, the
// outputs (VTU, PNG), and the steps from a file name to the mesh a problem is solved on.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/files.hpp"
#include "fem/domain.hpp"
#include "fem/drawing.hpp"
#include "fem/output.hpp"
#include "fem/space.hpp"
#include "io/vtu_writer.hpp"
#include "pipeline/parameters.hpp"

namespace CLI {
class App;
}

namespace curvemesh::app {

struct SolveOptions {
  std::string input;
  std::string output_vtu, output_png;
  const char* vtu_option = "-o";  // the options that name them, for messages
  const char* png_option = "--png";
  int width = 800;       // PNG width in pixels
  bool straight = false;  // P2 on the straight map of the same mesh instead of the cubic one
  Domain domain = Domain::box;  // as `mesh --domain`: the part of the meshed box the problem lives on
  double memory_limit_gb = 0;       // --memory-limit
  pipeline::Parameters parameters;  // of the mesh (always curved: --straight only drops the cubic map)
  // A command's own outputs besides -o and --png (elastic's --deformed, inflate's --surface), with
  // their options: checked against the input and the others before anything is read.
  std::vector<base::NamedPath> other_outputs;
};

// Registers input, -o/--output (VTU), --png, --width, --straight, --domain (default as given),
// --memory-limit and the feature options.
void add_solve_options(CLI::App& cmd, SolveOptions& options, Domain default_domain);

// Checks the outputs (none is the input, none named twice), reads and meshes the drawing through
// the pipeline, and checks that the picture asked for (--png, --width) is within
// fem::kMaxPicturePixels. On failure says why on stderr (ending in "; nothing `done`") and returns
// nothing, with the exit code in *exit_code.
std::optional<fem::MeshedDrawing> mesh_for_solving(const SolveOptions& options, const char* done, int* exit_code);

// The domain of a problem: the chosen regions of the meshed drawing, with the straight map when
// asked.
struct Problem {
  fem::MeshedDrawing drawing;                // the whole box, cubic
  io::HighOrderMesh mesh;                    // the domain (cubic, or straight with --straight)
  std::vector<int> line_origin;              // per line of `mesh`: the line of drawing.mesh
  geometry::Box2 view;                       // the box, for pictures
};

// Reads and meshes the drawing and keeps the domain's triangles. On failure says why on stderr
// and returns nothing, with the exit code in *exit_code.
std::optional<Problem> prepare_problem(const SolveOptions& options, int* exit_code);

// A command's other output: its path and its content.
using OtherFile = std::pair<std::string, std::string>;

// Writes the VTU (the triangles, the nodes they use and the point arrays there), the PNG (when
// asked) and the command's other files, all or none. Returns an exit code.
int write_outputs(const SolveOptions& options, const io::HighOrderMesh& mesh,
                  const std::vector<io::VtuPointArray>& arrays, const fem::Image* picture,
                  const std::vector<OtherFile>& others = {});

}  // namespace curvemesh::app
