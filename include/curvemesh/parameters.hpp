#pragma once
// curvemesh's parameters and its one error type: plain C++, no dependency. Part of the public
// API (curvemesh/curvemesh.hpp includes it); the library's pipeline resolves these same
// parameters for each drawing.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "curvemesh/export.hpp"

namespace curvemesh {

// What one drawing may cost before it is refused with Error (invalid_input), whose message names
// the limit and its option: a small hostile file can describe an enormous drawing (<use> fanning
// out, a path of millions of segments, curves crossing everywhere). With these defaults a
// `curvemesh mesh` run stays under about 2 GB of memory (README, "Errors and limits").
struct CURVEMESH_API Limits {
  double max_input_mb = 64;              // --max-input-mb: the input file's size, in MiB (2^20 bytes)
  std::size_t max_elements = 1'000'000;  // --max-elements: SVG elements drawn, each <use> instance counted
  std::size_t max_curves = 500'000;      // --max-curves: cubic curves read, after <use> and path data
  std::size_t max_triangles = 2'000'000;  // --max-triangles: triangles of the mesh at any stage
};

// What part of the meshed box a run gives out: all of it, what the drawing's filled elements cover
// (the shape as it is seen), the even-odd inside of its curves, what some fill or stroke paints
// (strokes read as areas), or the even-odd outside of its curves (the box without evenodd). The
// same names serve `mesh --domain`, the solvers' --domain and the Python module.
enum class Domain { box, filled, evenodd, painted, outside };

// What a stroked element contributes: its centre line (a curve of no width), or the outline of the
// area its stroke paints, with the stroke's width, joins, caps and dashes.
enum class Strokes { lines, areas };

// The last stage a run makes: the exact triangulation, the optimized linear mesh, or the curved one.
enum class StopAfter { triangulate, optimize, curve };

// The method's parameters with the paper's symbols and defaults (TriWild, Hu et al. 2019: §4,
// §4.1, §4.2). Lengths are relative to d, the diagonal of the drawing's bounding box; each is
// made absolute once d is known. Each field is the command line's long option of the same name
// (`mu_rel` is --mu, `edge_length_rel` is -l/--edge-length, `alpha_deg` is --min-angle, ...).
struct CURVEMESH_API Parameters {
  // §4: feature processing.
  double mu_rel = 1e-3;               // --mu: μ, feature envelope; min distance between primary features
  double epsilon_rel = 2e-3;          // --epsilon: ε, envelope of secondary features (2μ); at least μ
  double eps_m_rel = 1e-8;            // --eps-m: ε_m, round-off tolerance on control points
  double alpha_deg = 10.0;            // --min-angle: α, max turning per primary edge; target min angle
  double edge_length_rel = 1.0 / 20;  // --edge-length: l, the target edge length
  double min_edge_length_rel = 1e-4;  // --min-edge-length: l_m; curvature above α / l_m is secondary
  double junction_angle_deg = 10.0;   // --junction-angle: primary pieces sharing an end meet at least at this (chords and tangents)
  bool features = true;               // --no-features (false): no piece is primary; every curve is kept within ε by
                                      // straight secondary segments, as TriWild meshes a drawing without a feature file
  // §4.1: the meshed box and the linear optimization's stop.
  double box_margin_rel = 0.05;  // --box-margin: the box grows the drawing's bounds by this on every side
  int max_iterations = 80;       // --max-iterations: optimization passes at most
  double stop_amips = 10.0;      // --stop-amips: ... or once every triangle's AMIPS energy is at most this;
                                 // also the bound of both coarsenings (linear, and along the curves)
  // §4.2: curving.
  int order = 3;  // --order: the elements' order: 3 (cubic 10-node triangles), 2 (quadratic 6-node) or 1
                  // (straight 3-node; --linear)
  double curve_tolerance_rel = 0;  // --curve-tolerance: order 2, the largest distance from an edge on a primary
                                   // curve to the curve (edges farther are split); 0 is ε (epsilon_rel)
  double curved_stop_amips =
      20.0;                    // --curved-stop-amips: step 4 stops once every curved triangle is at most this
  int max_curved_passes = 10;  // --max-curved-passes: ... or after this many passes

  // Not the method's: what the run gives out.
  bool regions = false;                     // --regions: triangles tagged by the element painted on them
  Strokes strokes = Strokes::lines;         // --strokes: a stroke as its centre line or as its area
  double min_stroke_width_rel = 5e-4;       // --min-stroke-width: strokes as areas narrower than this paint
                                            // nothing; μ and ε shrink to keep the sides of every wider one
  Domain domain = Domain::box;              // --domain: the part of the box meshed
  StopAfter stop_after = StopAfter::curve;  // --stop-after: the last stage (optimize when order is 1)

  Limits limits;  // not the method's: bounds on what a drawing may cost
  // Not the method's either: how many threads one run may use (--threads; 0: every hardware
  // thread). The mesh is the same, byte for byte, whatever the number.
  int threads = 0;

  // Throws Error (Error::Kind::invalid_parameters) naming the first inconsistent parameter by
  // its command-line option, e.g. "--epsilon (0.0005) must be at least --mu (0.001)".
  void validate() const;
};

// One field of Parameters as every interface spells it: the command line's option, Python's
// keyword, the paper's symbol, its range and its help. The command line registers its options from
// these, Python takes its keywords from them, validate() checks their ranges and the reference
// documentation is generated from the command line's help: one definition each.
struct CURVEMESH_API ParameterOption {
  // What the option's value is.
  enum class Kind {
    number,   // a real number in [min, max] (min excluded when min_open)
    integer,  // an integer in [min, max]
    flag,     // true or false; on the command line the flag alone sets `flag_value`
    choice,   // one of `choices`, its index the value
  };
  const char* option;       // the long option, as messages name it: "--edge-length"
  const char* names;        // every name on the command line, CLI11's syntax: "-l,--edge-length"
  const char* python;       // Python's keyword: "edge_length"
  const char* symbol;       // the paper's symbol ("l"), or ""
  const char* group;        // "features", "limits", "mesh" or "run": which commands take it
  Kind kind;                // what its value is
  double min;               // the range (number, integer): its lower end ...
  double max;               // ... and its upper end
  bool min_open;            // min itself excluded (number)
  double flag_value;        // what the command line's flag sets (flag)
  std::vector<const char*> choices;  // the names of the values (choice)
  const char* help;         // the command line's help text
  double (*get)(const Parameters&);  // the field as a number (a flag 0 or 1, a choice its index)
  void (*set)(Parameters&, double);  // sets the field from such a number (checked first: check())

  // Throws Error (invalid_parameters) when `value` is outside the option's range, naming the
  // option as validate() does: "--mu (0) must be a positive number".
  void check(double value) const;
};

// Every option of Parameters, in the order --help lists them.
CURVEMESH_API std::vector<ParameterOption> parameter_options();

// Every failure curvemesh reports. what() is the message the command line prints after
// "curvemesh: "; it names the input (file, line and element where it can).
class CURVEMESH_API Error : public std::runtime_error {
 public:
  // What failed; each kind is one of the command line's exit codes.
  enum class Kind {
    invalid_parameters,  // Parameters::validate refused them (the command line's exit code 2)
    invalid_input,       // the drawing cannot be read or has nothing to mesh (exit code 1)
    output,              // a file could not be written (exit code 1)
    internal,            // a mesh that could not be made valid and certified: a bug (exit code 3)
  };
  // An error of this kind with this message (what() returns it).
  Error(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  // What failed.
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

}  // namespace curvemesh
