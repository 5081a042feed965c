#pragma once
// Triangle's .poly files (points and segments) as features, so that users of Triangle can mesh
// their own inputs: every segment is secondary (kept within ε, as in the paper's §5.3), vertices
// no segment uses are isolated points. Holes and regional attributes are read and ignored.
#include <curvemesh/parameters.hpp>
#include <string>

#include "features/features.hpp"

namespace curvemesh::features {

// The segments, points and box; `lengths` are left to be resolved for the box's diagonal. Throws
// svg::InputError naming the file and line on anything malformed, and when the file is not a
// regular one, is larger than limits.max_input_mb or has more segments than limits.max_curves.
Features read_poly(const std::string& path, const Limits& limits);

}  // namespace curvemesh::features
