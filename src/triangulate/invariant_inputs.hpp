#pragma once
// What the invariants of the local operations (mesh/constraints.hpp) take from the features:
// the primary section curves, the ε-envelope of the secondary segments, the box and α.
#include "features/features.hpp"
#include "mesh/constraints.hpp"

namespace curvemesh::triangulate {

// `box` is the outer box the triangulation was built in.
mesh::Constraints invariant_inputs(const features::Features& features, const geometry::Box2& box);

}  // namespace curvemesh::triangulate
