#include "pipeline/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace curvemesh {

namespace {

// "--epsilon (0.0005) must be ...": the option's name and the value as given.
[[noreturn]] void refuse(const char* option, double value, const std::string& must) {
  std::ostringstream s;
  s << option << " (" << value << ") must be " << must;
  throw Error(Error::Kind::invalid_parameters, s.str());
}

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

}  // namespace

// The range of one option, as its message says it.
void ParameterOption::check(double v) const {
  const ParameterOption& o = *this;
  if (o.kind == ParameterOption::Kind::flag) return;
  if (o.kind == ParameterOption::Kind::choice) {
    if (!(v >= 0 && v < double(o.choices.size()) && v == std::floor(v))) refuse(o.option, v, "one of its names");
    return;
  }
  const bool whole = o.kind != ParameterOption::Kind::integer || v == std::floor(v);
  if (std::isfinite(v) && whole && (o.min_open ? v > o.min : v >= o.min) && v <= o.max) return;
  std::ostringstream must;
  if (o.min == 0 && std::isinf(o.max))
    must << (o.min_open ? "a positive number" : "a non-negative number");
  else if (o.min == 0 && o.kind == ParameterOption::Kind::integer && o.max >= 2147483647.0)
    must << "a non-negative integer";
  else if (o.min == 1 && o.kind == ParameterOption::Kind::integer && o.max > 1e15)
    must << "at least 1";
  else
    must << (o.kind == ParameterOption::Kind::integer ? "an integer in [" : "in [") << o.min << ", " << o.max << "]";
  refuse(o.option, v, must.str());
}

void Parameters::validate() const {
  for (const ParameterOption& o : parameter_options()) o.check(o.get(*this));
  // ε below μ cannot be honoured: resampling already puts secondary chords up to μ from their curves.
  if (epsilon_rel < mu_rel) {
    std::ostringstream mu;
    mu << "at least --mu (" << mu_rel << ")";
    refuse("--epsilon", epsilon_rel, mu.str());
  }
}

namespace pipeline {

bool strokes_as_areas(const Parameters& p) {
  return p.strokes == Strokes::areas || p.domain == Domain::painted;
}

namespace {

// The factor μ and ε are made smaller by so that the narrowest stroke at least `floor` wide keeps
// its sides and its fill's outline primary (kStrokeSides); 1 when every such stroke already does.
double stroke_scale(double mu, const std::vector<double>& widths, double floor) {
  double narrowest = std::numeric_limits<double>::infinity();
  for (const double w : widths)
    if (w >= floor) narrowest = std::min(narrowest, w);
  return std::min(1.0, narrowest / (kStrokeSides * mu));
}

}  // namespace

Resolved resolve(const Parameters& p, double diagonal, const std::vector<double>& stroke_widths) {
  Resolved r;
  r.d = diagonal > 0 ? diagonal : 1.0;
  const bool areas = strokes_as_areas(p);
  const double floor = p.min_stroke_width_rel * r.d;
  const double scale = areas ? stroke_scale(p.mu_rel * r.d, stroke_widths, floor) : 1.0;
  features::Lengths& l = r.features;
  l.d = r.d;
  l.mu = p.mu_rel * r.d * scale;
  l.epsilon = p.epsilon_rel * r.d * scale;
  // Below the floor a stroke still paints when μ resolves it anyway (a small --mu given).
  r.min_stroke_width = areas ? std::min(floor, kStrokeSides * l.mu) : 0.0;
  l.eps_m = p.eps_m_rel * r.d;
  l.edge = p.edge_length_rel * r.d;
  l.min_edge = p.min_edge_length_rel * r.d;
  l.alpha_rad = radians(p.alpha_deg);
  l.junction_angle_rad = radians(p.junction_angle_deg);
  l.features = p.features;
  l.straight_crossings = areas;
  l.max_triangles = p.limits.max_triangles;
  r.triangulate.box_margin = std::max(p.box_margin_rel, 0.0) * r.d;
  r.triangulate.max_triangles = p.limits.max_triangles;
  r.optimize.max_triangles = p.limits.max_triangles;
  r.optimize.edge_length = l.edge;
  r.optimize.min_edge_length = l.min_edge;
  r.optimize.max_iterations = p.max_iterations;
  r.optimize.stop_min_angle_deg = p.alpha_deg;  // the target min angle is α
  r.optimize.stop_max_amips = p.stop_amips;
  r.optimize.curved = p.order != 1;
  r.optimize.curved_stop_amips = p.curved_stop_amips;
  r.curve.order = p.order == 2 ? 2 : 3;
  // An order-2 edge only approximates its curve: within the secondary features' envelope ε unless
  // told otherwise, the distance every other feature of the mesh is kept within.
  r.curve.tolerance = p.curve_tolerance_rel > 0 ? p.curve_tolerance_rel * r.d : l.epsilon;
  r.curve.min_split_length = l.min_edge;
  r.curve.stop_amips = p.curved_stop_amips;
  r.curve.max_smoothing_passes = p.max_curved_passes;
  r.curve.coarsen_edge_length = l.edge;
  r.curve.coarsen_amips = p.stop_amips;
  return r;
}

}  // namespace pipeline
}  // namespace curvemesh
