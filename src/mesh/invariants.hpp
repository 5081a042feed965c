#pragma once
// The invariants of §4.1 (listed in mesh/operations.hpp), one check each, for every stage that
// changes the mesh: the linear operations (mesh/operations) and the curved mesh's smoothing
// (curve/).
#include "mesh/constraints.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh {

// Invariant 1: whether v's triangles stay counter-clockwise (exactly, as straight triangles) with
// v at p.
bool star_valid_at(const TriMesh& mesh, int v, const Vec2& p);

// Invariant 2: whether v's secondary edges stay inside the ε-envelope of the secondary input with
// v at p (a free vertex has none).
bool secondary_edges_inside(const TriMesh& mesh, const Constraints& constraints, int v, const Vec2& p);

// Invariant 3: the largest turning a primary edge may cover, α with a floating-point slack (the
// features stage measured the same turning).
double turning_limit(const Constraints& constraints);

// Invariants 2 and 3 for one tagged edge as the mesh stores it.
bool edge_satisfies_invariants(const TriMesh& mesh, const Constraints& constraints, int a, int b);

}  // namespace curvemesh::mesh
