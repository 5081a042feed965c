// The synthetic inputs of the features and meshing benchmarks. random_soup: n random cubics whose
// size shrinks like 1/√n inside the unit square, so the number of crossings per curve stays about
// the same as n grows, as in a drawing with more detail. dense_soup: n random cubics across the
// whole square, so that nearly every pair crosses (about n²/4 crossings): the exact
// triangulation's worst case.
#pragma once

#include <cmath>
#include <random>

#include "pipeline/pipeline.hpp"

namespace curvemesh::bench {

// The drawing as the pipeline's input: n cubics, given by their control points.
inline pipeline::Source random_soup(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), v(-1.0, 1.0);
  const double size = 3.0 / std::sqrt(double(n));
  std::vector<std::array<geometry::Vec2, 4>> curves;
  for (int i = 0; i < n; ++i) {
    const geometry::Vec2 c(u(rng), u(rng));
    auto q = [&] { return geometry::Vec2(c.x() + size * v(rng), c.y() + size * v(rng)); };
    curves.push_back({q(), q(), q(), q()});
  }
  return pipeline::Source::beziers(curves, "random soup");
}

inline pipeline::Source dense_soup(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::array<geometry::Vec2, 4>> curves;
  for (int i = 0; i < n; ++i) {
    auto q = [&] { return geometry::Vec2(u(rng), u(rng)); };
    curves.push_back({q(), q(), q(), q()});
  }
  return pipeline::Source::beziers(curves, "dense soup");
}

}  // namespace curvemesh::bench
