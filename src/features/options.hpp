#pragma once
// The parameters of feature processing (paper §4) in absolute units, for a drawing of diagonal d.
// They are chosen relative to d and resolved once, above this stage (pipeline/parameters.hpp).
#include <cstddef>
#include <cstdint>

namespace curvemesh::features {

struct Lengths {
  double d = 1, mu = 0, epsilon = 0, eps_m = 0, edge = 0, min_edge = 0;
  double alpha_rad = 0, junction_angle_rad = 0;
  bool features = true;  // false: every piece is secondary (--no-features)
  // Straight sections that cross at the junction angle or more may both stay primary (with strokes
  // as areas, whose bands' sides cross wherever two strokes do; tagging.cpp).
  bool straight_crossings = false;
  // Limits::max_triangles: the pairs of nearby pieces and ends examined are bounded with it
  // (base::check_pairs), so that curves piled on one another are refused, not paired forever.
  std::size_t max_triangles = SIZE_MAX;
};

}  // namespace curvemesh::features
