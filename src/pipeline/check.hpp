#pragma once
// The certification of a finished mesh as a file holds it (`curvemesh check`, and the public
// API's check): every element's Jacobian determinant decided on the whole element as exact
// rationals decide it, and the distance from the primary lines to the drawing's curves. It takes
// any 2D triangle mesh of order 1, 2 or 3, ours or another program's.
#include <cstddef>

#include "io/high_order_mesh.hpp"
#include "svg/feature_soup.hpp"

namespace curvemesh::pipeline {

struct MeshCheck {
  int order = 0;
  std::size_t triangles = 0;
  std::size_t invalid = 0;          // elements not certified positive
  std::size_t undecided = 0;        // of those, the ones the exact test could not decide
  double min_scaled_jacobian = 0;   // over the elements (0 for a mesh without any)
  std::size_t exact_fallbacks = 0;  // elements decided with rationals (all of them when exact)
};

struct CheckOptions {
  // Decide every element with rationals, without the double certificate first: the independent
  // check of the filtered one, whose verdicts are the same.
  bool exact = false;
  // Threads the check may use (0: every hardware thread); the verdicts are the same.
  int threads = 0;
};

// Each element's det J decided as certify_jacobian_exact decides it on the rationals of its
// nodes: a P2 element's degree-2 form, a P1 or P3 element's map written exactly as a P3 map (a P1
// map evaluated at the ten P3 reference nodes). The double certificate with its rigorous error
// bound decides first, and rationals only what it leaves undecided (unless options.exact); the
// scaled Jacobian in doubles.
MeshCheck check_mesh(const io::HighOrderMesh& mesh, const CheckOptions& options = {});

struct FeatureDistance {
  std::size_t primary_lines = 0;  // lines in the physical group named "primary"
  double max = 0;                 // the largest distance from one of them to the nearest curve
  double max_rel = 0;             // the same over the diagonal of the curves' control points (0 if none)
};

// Each primary line sampled at 9 points, each measured to the nearest curve of `soup`.
FeatureDistance feature_distance(const io::HighOrderMesh& mesh, const svg::FeatureSoup& soup);

}  // namespace curvemesh::pipeline
