#pragma once
// The parameters of the method resolved for one drawing: `resolve` turns the relative set
// (curvemesh::Parameters, validated) into the absolute values each stage takes, once, when the
// diagonal d of the drawing's bounding box is known.
#include <curvemesh/parameters.hpp>

#include <vector>

#include "curve/curve.hpp"
#include "features/features.hpp"
#include "optimize/optimize.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::pipeline {

// The one parameter set (curvemesh/parameters.hpp, also the public API's): the paper's symbols
// and defaults, relative to d; invalid ones are refused with curvemesh::Error.
using Parameters = curvemesh::Parameters;

// What each stage receives, in absolute units for a drawing of diagonal d.
struct Resolved {
  double d = 1;
  features::Lengths features;
  triangulate::Options triangulate;
  optimize::Options optimize;
  curve::Options curve;
  // With strokes as areas: strokes narrower than this paint nothing (--min-stroke-width, or less
  // when μ resolves narrower strokes anyway); 0 otherwise.
  double min_stroke_width = 0;
};

// `diagonal` is d; a drawing of no size (a single point) is given unit lengths. `stroke_widths`
// are the widths of the drawing's strokes read as areas (svg::FillLayer::width): μ and ε shrink
// together until the narrowest of those at least --min-stroke-width wide is kStrokeSides μ wide.
Resolved resolve(const Parameters& parameters, double diagonal, const std::vector<double>& stroke_widths = {});

// A stroke read as an area is three curves, its two sides and, at half its width from each, the
// outline of its element's fill: all three stay primary (§4's μ-separation) when the stroke is at
// least this many μ wide.
inline constexpr double kStrokeSides = 3;

// Whether strokes are read as areas: --strokes areas, or --domain painted, which needs them (the
// one place that implication is made).
bool strokes_as_areas(const Parameters& parameters);

}  // namespace curvemesh::pipeline
