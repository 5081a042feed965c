#pragma once
// The invariants' view of the features: primary section curves and the ε-envelope of the
// secondary segments, for the local operations that follow triangulation.
#include "features/features.hpp"
#include "mesh/constraints.hpp"

namespace curvemesh::triangulate {

// `box` is the outer box the triangulation was built in.
mesh::Constraints constraints_of(const features::Features& features, const geometry::Box2& box);

}  // namespace curvemesh::triangulate
