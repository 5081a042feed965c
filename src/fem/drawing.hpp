#pragma once
// From a drawing to the curved mesh a problem is solved on: the whole pipeline (read, features,
// triangulate, optimize, curve) with the mesh command's defaults, and what the problems need to
// know about each feature line besides its kind: the input curve it lies on and its direction.
#include <stdexcept>
#include <string>
#include <vector>

#include "curve/curve.hpp"
#include "features/options.hpp"
#include "io/high_order_mesh.hpp"
#include "optimize/optimize.hpp"
#include "svg/feature_soup.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::fem {

struct DrawingOptions {
  features::Options features;
  triangulate::Options triangulate;
  optimize::Options optimize;
  curve::Options curve;
};

struct MeshedDrawing {
  io::HighOrderMesh mesh;          // cubic (10-node) triangles over the whole box
  std::vector<int> line_curve;     // per line: the soup curve it lies on (-1: box side, or none)
  // Per line: whether its node 0 → node 1 runs the way its curve's parameter grows (primary and
  // secondary lines; true for the others).
  std::vector<char> line_forward;
  double diagonal = 0;             // d, the input's bounding-box diagonal
  double seconds = 0;              // time to mesh
};

// Thrown when the drawing has nothing to mesh or the mesh cannot be certified (the mesh command
// refuses the same drawings).
struct DrawingError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

MeshedDrawing mesh_drawing(const svg::FeatureSoup& soup, DrawingOptions options = {});

}  // namespace curvemesh::fem
