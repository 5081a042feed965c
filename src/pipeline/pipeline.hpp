#pragma once
// The one driver of the method: read → features (§4) → triangulate → optimize (§4.1) → curve
// (§4.2), with the parameters resolved once, a stop after any stage, what each stage made, and
// the statistics `curvemesh mesh --stats` writes. The command line, the solvers, the public API,
// the Python module, the benchmarks and the tests all mesh through it.
#include <array>
#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "curve/curve.hpp"
#include "features/features.hpp"
#include "io/high_order_mesh.hpp"
#include "mesh/constraints.hpp"
#include "mesh/tri_mesh.hpp"
#include "optimize/optimize.hpp"
#include "pipeline/parameters.hpp"
#include "regions/paint.hpp"
#include "svg/feature_soup.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::pipeline {

enum class Stage { read, features, triangulate, optimize, curve };

const char* stage_name(Stage stage);
// "read", "features", "triangulate", "optimize", "curve"; nothing for another name.
std::optional<Stage> stage_named(const std::string& name);

// What to mesh: an SVG or Triangle .poly file, SVG text, or a soup of curves made by the caller.
// run() refuses a soup with a coordinate that is not a finite number (invalid_input).
struct Source {
  enum class Kind { file, svg_text, soup } kind = Kind::file;
  std::string path;       // file: its path (a name ending in .poly is read as Triangle's format)
  std::string text;       // svg_text: the document
  svg::FeatureSoup soup;  // soup: the curves and points
  std::string name;       // what messages and statistics call the input

  static Source file(std::string path);
  static Source svg(std::string text, std::string name = "<svg>");
  static Source curves(svg::FeatureSoup soup, std::string name = "<curves>");
  // Cubic Bézier curves by their control points, as the reader's curves would be (no paint):
  // curve i of the soup is curves[i], all from one element.
  static Source beziers(const std::vector<std::array<geometry::Vec2, 4>>& curves,
                        std::string name = "<curves>");
};

// Where a run is: a stage starting (pass 0), or one pass of the optimization (triangles, worst
// AMIPS energy) or of curving's step 4 (the triangles still above its stop energy, the worst).
struct Progress {
  Stage stage = Stage::read;
  int pass = 0;
  int triangles = 0;     // optimize: triangles of the mesh; curve: triangles above the stop energy
  double max_amips = 0;  // the worst energy so far (0 while there is no mesh)
};

struct RunOptions {
  RunOptions() = default;
  RunOptions(Stage stop_after)
      : stop_after(stop_after) {}  // NOLINT: run(source, parameters, Stage::features)
  // The last stage the caller needs (`curvemesh features` stops at read or features); the run
  // also stops at Parameters::stop_after, and at `optimize` for order 1.
  Stage stop_after = Stage::curve;
  std::ostream* log = nullptr;  // one line per optimization pass when set
  // Called with each warning as it arises (they are in Result::warnings too).
  std::function<void(const std::string&)> warn;
  // Called as the run goes (for progress displays); never changes what the run makes.
  std::function<void(const Progress&)> progress;
};

struct Result {
  std::string name;  // Source::name
  Parameters parameters;
  Resolved resolved;                        // the parameters in absolute units (d is the box's diagonal)
  Stage last = Stage::read;                 // the last stage that ran
  std::vector<std::string> warnings;        // for the user: the reader's, and "nothing is drawn"
  svg::FeatureSoup soup;                    // read (empty for a .poly file)
  features::Features features;              // features
  geometry::Box2 box;                       // triangulate: the outer box
  mesh::Constraints constraints;            // triangulate: what the invariants know of the features
  std::vector<triangulate::SharedPiece> shared;  // triangulate: where features of several curves coincide
  mesh::TriMesh linear;                     // triangulate, optimize (moved into `curved` by curve)
  optimize::Quality quality;                // of the linear mesh, after triangulate or optimize
  std::optional<curve::CurvedMesh> curved;  // curve
  triangulate::Stats triangulate_stats;
  optimize::Stats optimize_stats;
  curve::Stats curve_stats;
  nlohmann::ordered_json stats;  // counts, quality and seconds per stage, as --stats writes them
  // With RunOptions::regions or a domain other than the box: the faces of the whole mesh and the
  // element each shows (fills classified only then), and the mesh that is given out.
  regions::Classification classification;
  std::optional<regions::Painted> painted;
  // The mesh as it is given out and written (pipeline/output.hpp high_order_mesh), made once at
  // the end of the run with its physical groups; none when no stage made a mesh.
  std::shared_ptr<const io::HighOrderMesh> output;

  // The linear mesh: the optimized one, or the curved mesh's corners after curve's step 1.
  const mesh::TriMesh& corners() const { return curved ? curved->linear : linear; }
};

// Runs the stages up to options.stop_after (at most `optimize` when parameters.order is 1), then
// classifies the mesh's faces when asked. Throws curvemesh::Error: invalid_parameters,
// invalid_input when the drawing cannot be read, has nothing to mesh or leaves the domain empty,
// internal when the mesh cannot be given out or a face's side of a filled element's outline
// cannot be decided. A mesh it returns is valid: no
// broken structure, every vertex in doubles, every curved triangle certified.
Result run(const Source& source, const Parameters& parameters, const RunOptions& options = {});

}  // namespace curvemesh::pipeline
