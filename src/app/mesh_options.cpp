#include "app/mesh_options.hpp"

#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <limits>
#include <map>

#include "app/messages.hpp"

namespace curvemesh::app {

namespace {

// What a drawing may cost (curvemesh::Limits): refused beyond, with exit 1.
void add_limit_options(CLI::App& cmd, Limits& l) {
  const auto count = CLI::Range(std::size_t(1), std::numeric_limits<std::size_t>::max());
  cmd.add_option("--max-input-mb", l.max_input_mb,
                 "refuse an input file larger than this many MiB (and any that is not a regular file)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--max-elements", l.max_elements,
                 "refuse a drawing with more SVG elements than this, each instance of a <use> counted")
      ->capture_default_str()
      ->check(count);
  cmd.add_option("--max-curves", l.max_curves,
                 "refuse a drawing with more cubic curves than this, after <use> and path data")
      ->capture_default_str()
      ->check(count);
  cmd.add_option("--max-triangles", l.max_triangles,
                 "refuse a drawing whose mesh has more triangles than this at any stage (curves crossing "
                 "everywhere, a tiny --edge-length); with the other limits' defaults, a run stays under "
                 "about 2 GB of memory")
      ->capture_default_str()
      ->check(count);
}

}  // namespace

void add_memory_limit_option(CLI::App& cmd, double& gigabytes) {
  cmd.add_option("--memory-limit", gigabytes,
                 "address space of the run in GB (2^30 bytes; setrlimit RLIMIT_AS): reaching it ends the run with "
                 "exit 1, out of memory, and nothing written (default: no limit)")
      ->check(CLI::Range(0.1, 1e6));
}

void limit_memory(double gigabytes) {
  if (!(gigabytes > 0)) return;
  rlimit limit{};
  ::getrlimit(RLIMIT_AS, &limit);
  limit.rlim_cur = std::min<rlim_t>(static_cast<rlim_t>(gigabytes * 1073741824.0), limit.rlim_max);
  ::setrlimit(RLIMIT_AS, &limit);
}

void add_feature_options(CLI::App& cmd, pipeline::Parameters& p) {
  cmd.add_option("--mu", p.mu_rel,
                 "feature envelope mu, relative to d: min distance between primary features")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--epsilon", p.epsilon_rel,
                 "envelope epsilon of secondary features, relative to d; at least mu")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("-l,--edge-length", p.edge_length_rel, "target edge length l, relative to d")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--min-edge-length", p.min_edge_length_rel,
                 "minimal edge length l_m, relative to d: pieces shorter than l_m, or curving more than "
                 "alpha/l_m (a primary edge turning alpha would be shorter than l_m), are secondary")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--min-angle", p.alpha_deg,
                 "alpha in degrees: max turning of the curve along one primary edge (target min angle)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 60.0));
  cmd.add_option(
         "--junction-angle", p.junction_angle_deg,
         "primary pieces sharing an endpoint stay primary when they meet at least at this angle, both their chords and their curves' tangents there (deg)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 180.0));
  cmd.add_flag_callback("--no-features", [&p] { p.features = false; },
               "no feature curves: every curve is secondary, kept within epsilon by straight segments and "
               "followed by no edge, as TriWild meshes a drawing without a feature file (its linear mode, "
               "there with epsilon 0.001); the curved mesh then has straight edges only");
  cmd.add_option(
         "--eps-m,--degenerate-tolerance", p.eps_m_rel,
         "round-off tolerance epsilon_m, relative to d: paths whose control points all lie within it of "
         "each other become isolated points, curves within it of a line become straight")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  add_limit_options(cmd, p.limits);
}

std::vector<const CLI::Option*> add_mesh_options(CLI::App& cmd, pipeline::Parameters& p, int& msh_version) {
  const std::size_t first = cmd.get_options().size();
  cmd.add_option("--order", p.order,
                 "the elements' order: 3 (curved, cubic 10-node triangles whose edges follow the primary curves), "
                 "2 (curved, quadratic 6-node triangles whose edges stay within --curve-tolerance of the primary "
                 "curves) or 1 (straight 3-node triangles)")
      ->capture_default_str()
      ->check(CLI::IsMember({1, 2, 3}));
  cmd.add_option("--curve-tolerance", p.curve_tolerance_rel,
                 "with --order 2: the largest distance from an edge on a primary curve to the curve, relative to "
                 "d; an edge farther is split (0: epsilon)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd.add_flag_callback("--linear", [&p] { p.order = 1; },
                        "make a linear mesh (straight-sided 3-node triangles): --order 1");
  cmd.add_option("--msh-version", msh_version, "Gmsh file format: 41 (4.1) or 22 (2.2)")
      ->capture_default_str()
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, int>{{"4.1", 41}, {"41", 41}, {"2.2", 22}, {"22", 22}}));
  add_feature_options(cmd, p);
  cmd.add_option("--max-iterations", p.max_iterations, "optimization passes at most")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd.add_option("--stop-amips", p.stop_amips,
                 "optimization stops once every triangle's AMIPS energy is at most this (2 = equilateral); "
                 "coarsening, of the linear mesh and along the curves, keeps what it changes at most this or "
                 "its worst before")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 1e9));
  cmd.add_option("--box-margin", p.box_margin_rel,
                 "the meshed box extends the drawing's bounding box by this, relative to d, on every side")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 10.0));
  cmd.add_option("--curved-stop-amips", p.curved_stop_amips,
                 "curving: smoothing and local operations stop once every curved triangle's AMIPS energy is "
                 "at most this")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 1e9));
  cmd.add_option("--max-curved-passes", p.max_curved_passes,
                 "curving: smoothing and operation passes at most")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  const auto all = cmd.get_options();
  return {all.begin() + static_cast<std::ptrdiff_t>(first), all.end()};
}

bool parameters_valid(const pipeline::Parameters& p) {
  try {
    p.validate();
    return true;
  } catch (const Error& e) {
    say(e.what());
    return false;
  }
}

}  // namespace curvemesh::app
