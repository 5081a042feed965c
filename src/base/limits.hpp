#pragma once
// A drawing that would cost more than a bound of curvemesh::Limits allows. Thrown by the stage
// that finds out (the reader, the triangulation, the optimization) before it allocates the
// excess; the pipeline turns it into curvemesh::Error (invalid input, exit code 1).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace curvemesh::base {

class LimitExceeded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws LimitExceeded when a mesh would have `triangles` > `max_triangles`: "the mesh would have
// more than MAX triangles (WHY; --max-triangles raises the limit)".
inline void check_triangles(std::size_t triangles, std::size_t max_triangles, const std::string& why) {
  if (triangles > max_triangles)
    throw LimitExceeded("the mesh would have more than " + std::to_string(max_triangles) + " triangles (" + why +
                        "; --max-triangles raises the limit)");
}

// The work a stage does on pairs of nearby pieces grows with the square of the curves piled on one
// another (a <use> fan-out whose copies coincide): bounded alongside the mesh, at `per_triangle`
// pairs per triangle allowed. Throws LimitExceeded naming what was being paired.
inline void check_pairs(std::size_t pairs, std::size_t max_triangles, std::size_t per_triangle, const char* what) {
  const std::size_t max_pairs =
      max_triangles > SIZE_MAX / per_triangle ? SIZE_MAX : per_triangle * max_triangles;
  if (pairs > max_pairs)
    throw LimitExceeded("the curves lie too densely on one another: more than " + std::to_string(max_pairs) +
                        " pairs of " + what + " (" + std::to_string(per_triangle) +
                        " per triangle allowed; --max-triangles raises the limit)");
}

}  // namespace curvemesh::base
