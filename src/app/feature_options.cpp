#include "app/feature_options.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

namespace curvemesh::app {

void add_feature_options(CLI::App& cmd, features::Options& f) {
  cmd.add_option("--mu", f.mu_rel, "feature envelope mu, relative to d: min distance between primary features")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--epsilon", f.epsilon_rel, "envelope epsilon of secondary features, relative to d")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("-l,--edge-length", f.edge_length_rel, "target edge length l, relative to d")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--min-edge-length", f.min_edge_length_rel,
                 "minimal edge length l_m, relative to d: pieces shorter than l_m, or curving more than alpha/l_m (a primary edge turning alpha would be shorter than l_m), are secondary")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd.add_option("--min-angle", f.alpha_deg,
                 "alpha in degrees: max turning of the curve along one primary edge (target min angle)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 60.0));
  cmd.add_option("--junction-angle", f.junction_angle_deg,
                 "primary pieces sharing an endpoint stay primary when they meet at least at this angle (deg)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 180.0));
  cmd.add_option("--eps-m", f.eps_m_rel, "round-off tolerance epsilon_m on control points, relative to d")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

bool feature_options_valid(const features::Options& f) {
  if (f.epsilon_rel >= f.mu_rel) return true;
  std::cerr << "curvemesh: --epsilon (" << f.epsilon_rel << ") must be at least --mu (" << f.mu_rel << ")\n";
  return false;
}

}  // namespace curvemesh::app
