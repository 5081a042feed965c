#pragma once
// The parameters of the method resolved for one drawing: `resolve` turns the relative set
// (curvemesh::Parameters, validated) into the absolute values each stage takes, once, when the
// diagonal d of the drawing's bounding box is known.
#include <curvemesh/parameters.hpp>

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
};

// `diagonal` is d; a drawing of no size (a single point) is given unit lengths.
Resolved resolve(const Parameters& parameters, double diagonal);

// Whether strokes are read as areas: --strokes areas, or --domain painted, which needs them (the
// one place that implication is made).
bool strokes_as_areas(const Parameters& parameters);

}  // namespace curvemesh::pipeline
