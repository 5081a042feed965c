#pragma once
// A finished curved mesh with what the applications need to know of the drawing it came from:
// for each feature line the input curve it lies on and its direction, and each curve's colour on
// either side. The finite-element code takes this and nothing of the stages that made it.
#include <array>
#include <vector>

#include "io/high_order_mesh.hpp"
#include "regions/faces.hpp"

namespace curvemesh::pipeline {

// The colour on each side of a soup curve, each channel in [0, 1].
struct SideColours {
  std::array<double, 3> left{}, right{};
};

struct MeshedDrawing {
  io::HighOrderMesh mesh;       // cubic (10-node) triangles over the whole box
  std::vector<int> line_curve;  // per line: the soup curve it lies on (-1: box side, or none)
  // Per line: whether its node 0 → node 1 runs the way its curve's parameter grows (primary and
  // secondary lines; true for the others).
  std::vector<char> line_forward;
  std::vector<SideColours> colours;  // per soup curve (see curve_colours in pipeline/output.hpp)
  // The faces of `mesh`, and the element painted on each when the run read the paint
  // (RunOptions::regions): what regions::domain_triangles picks a problem's domain from.
  regions::Classification classification;
  double diagonal = 0;               // d, the input's bounding-box diagonal
  bool has_strokes = false;          // some stroke was read as an area (a layer of the paint)
  bool has_fills = false;            // some element is filled (a layer of the paint)
  double seconds = 0;                // time to read and mesh
};

}  // namespace curvemesh::pipeline
