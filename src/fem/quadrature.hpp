#pragma once
// Quadrature on the reference triangle (0,0), (1,0), (0,1) and on the unit interval, exact for
// polynomials up to a given total degree. The triangle rules are collapsed (Duffy) products of
// Gauss–Legendre rules; the Gauss–Legendre nodes and weights come from the eigenvalues of the
// Jacobi matrix (Golub–Welsch).
#include <vector>

#include "geometry/vec2.hpp"

namespace curvemesh::fem {

using geometry::Vec2;

struct Quadrature {
  std::vector<Vec2> points;      // reference coordinates (ξ, η); on the interval, (s, 0)
  std::vector<double> weights;   // sum to the reference measure: 1/2 (triangle), 1 (interval)
  int size() const { return static_cast<int>(weights.size()); }
};

// `degree` >= 0; exact for every polynomial of total degree <= degree.
Quadrature triangle_quadrature(int degree);
Quadrature interval_quadrature(int degree);

}  // namespace curvemesh::fem
