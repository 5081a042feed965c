#include "pipeline/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

namespace curvemesh {

namespace {

// "--epsilon (0.0005) must be ...": the option's name and the value as given.
[[noreturn]] void refuse(const char* option, double value, const std::string& must) {
  std::ostringstream s;
  s << option << " (" << value << ") must be " << must;
  throw Error(Error::Kind::invalid_parameters, s.str());
}

void positive(const char* option, double value) {
  if (!(std::isfinite(value) && value > 0)) refuse(option, value, "a positive number");
}

void within(const char* option, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream range;
    range << "in [" << lo << ", " << hi << "]";
    refuse(option, value, range.str());
  }
}

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

}  // namespace

void Parameters::validate() const {
  positive("--mu", mu_rel);
  positive("--epsilon", epsilon_rel);
  // ε below μ cannot be honoured: resampling already puts secondary chords up to μ from their curves.
  if (epsilon_rel < mu_rel) {
    std::ostringstream mu;
    mu << "at least --mu (" << mu_rel << ")";
    refuse("--epsilon", epsilon_rel, mu.str());
  }
  if (!(std::isfinite(eps_m_rel) && eps_m_rel >= 0)) refuse("--eps-m", eps_m_rel, "a non-negative number");
  positive("--edge-length", edge_length_rel);
  positive("--min-edge-length", min_edge_length_rel);
  within("--min-angle", alpha_deg, 0.1, 60.0);
  within("--junction-angle", junction_angle_deg, 0.0, 180.0);
  within("--box-margin", box_margin_rel, 1e-3, 10.0);
  if (max_iterations < 0) refuse("--max-iterations", max_iterations, "a non-negative number");
  within("--stop-amips", stop_amips, 2.0, 1e9);
  within("--curved-stop-amips", curved_stop_amips, 2.0, 1e9);
  if (max_curved_passes < 0) refuse("--max-curved-passes", max_curved_passes, "a non-negative number");
  if (order < 1 || order > 3) refuse("--order", order, "1, 2 or 3");
  if (!(std::isfinite(curve_tolerance_rel) && curve_tolerance_rel >= 0))
    refuse("--curve-tolerance", curve_tolerance_rel, "a non-negative number");
  positive("--max-input-mb", limits.max_input_mb);
  for (const auto& [option, value] : {std::pair{"--max-elements", limits.max_elements},
                                      std::pair{"--max-curves", limits.max_curves},
                                      std::pair{"--max-triangles", limits.max_triangles}})
    if (value < 1) refuse(option, double(value), "at least 1");
}

namespace pipeline {

Resolved resolve(const Parameters& p, double diagonal) {
  Resolved r;
  r.d = diagonal > 0 ? diagonal : 1.0;
  features::Lengths& l = r.features;
  l.d = r.d;
  l.mu = p.mu_rel * r.d;
  l.epsilon = p.epsilon_rel * r.d;
  l.eps_m = p.eps_m_rel * r.d;
  l.edge = p.edge_length_rel * r.d;
  l.min_edge = p.min_edge_length_rel * r.d;
  l.alpha_rad = radians(p.alpha_deg);
  l.junction_angle_rad = radians(p.junction_angle_deg);
  l.features = p.features;
  l.max_triangles = p.limits.max_triangles;
  r.triangulate.box_margin = std::max(p.box_margin_rel, 0.0) * r.d;
  r.triangulate.max_triangles = p.limits.max_triangles;
  r.optimize.max_triangles = p.limits.max_triangles;
  r.optimize.edge_length = l.edge;
  r.optimize.min_edge_length = l.min_edge;
  r.optimize.max_iterations = p.max_iterations;
  r.optimize.stop_min_angle_deg = p.alpha_deg;  // the target min angle is α
  r.optimize.stop_max_amips = p.stop_amips;
  r.optimize.curved_stop_amips = p.order == 1 ? 0.0 : p.curved_stop_amips;
  r.curve.order = p.order == 2 ? 2 : 3;
  // An order-2 edge only approximates its curve: within the secondary features' envelope ε unless
  // told otherwise, the distance every other feature of the mesh is kept within.
  r.curve.tolerance = (p.curve_tolerance_rel > 0 ? p.curve_tolerance_rel : p.epsilon_rel) * r.d;
  r.curve.min_split_length = l.min_edge;
  r.curve.stop_amips = p.curved_stop_amips;
  r.curve.max_smoothing_passes = p.max_curved_passes;
  r.curve.coarsen_edge_length = l.edge;
  r.curve.coarsen_amips = p.stop_amips;
  return r;
}

}  // namespace pipeline
}  // namespace curvemesh
