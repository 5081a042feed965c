#pragma once
// The curved element of §4.2 as the curve stage first places it (App. C), written once for the
// two stages that need it: the curve stage places its nodes so, and the optimization foresees
// from it how a triangle beside a curve will be once curved (§4.1's coarsening keeps what the
// curve stage can certify).
#include <array>

#include "geometry/p3_triangle.hpp"
#include "mesh/constraints.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh {

// Whether edge (a, b) lies on a primary curve.
bool is_primary(const TriMesh& m, int a, int b);

// Whether edge (a, b) can follow its curve: it is primary and both ends lie on the curve at their
// recorded parameters (a primary vertex may still sit on the chord, Fig. 8).
bool followable(const TriMesh& m, int a, int b);

// The edge (tri[i], tri[i+1]) that the curve stage bends onto its curve: the triangle's only
// primary edge, if it can follow its curve; −1 otherwise (no primary edge; or more than one, which
// the curve stage splits first; or one with an end off its curve, which it leaves straight).
int followed_edge(const TriMesh& m, const Triangle& tri);

// The inner nodes of an edge from its lower- to its higher-numbered vertex, for `order` 3 (two)
// or 2 (one, the second then unused). On its curve (`curve` over [t_lo, t_hi]): at thirds of the
// parameter interval, where the cubic map reproduces the curve exactly; order 2 at the middle,
// where the quadratic's distance from the curve is smallest along the parameter. Straight, from
// lo to hi: at thirds of the chord (order 2: its middle).
std::array<Vec2, 2> nodes_on_curve(const SectionCurve& curve, double t_lo, double t_hi, int order);
std::array<Vec2, 2> nodes_on_chord(const Vec2& lo, const Vec2& hi, int order);

// Triangle t's cubic element: corners where the mesh has them, the followed edge's inner nodes on
// its curve, the others on their chords, the centre at the corners' centroid (the caller chooses
// among geometry::p3_centre_candidates).
geometry::P3Nodes curved_element(const TriMesh& m, const Constraints& c, int t);
// The same with the followed edge known (followed_edge of the triangle).
geometry::P3Nodes curved_element(const TriMesh& m, const Constraints& c, int t, int followed);

}  // namespace curvemesh::mesh
