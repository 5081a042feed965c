#pragma once
// The local operations of §4.1 (TetWild's, in 2D) as proposals: each builds the new local
// configuration, checks every invariant on it, and only then changes the mesh. A rejected
// operation leaves the mesh exactly as it was.
//
// Invariants checked on every proposal:
//  1. no triangle is inverted or degenerate (exact orientation on the coordinates as stored);
//  2. every secondary edge stays inside the ε-envelope of the secondary input (certified test);
//  3. every primary edge covers a curve interval turning at most α;
//  4. primary vertices move only along their curve, boundary vertices only along their side,
//     fixed vertices never move and are never removed.
#include <array>
#include <functional>

#include "mesh/constraints.hpp"
#include "mesh/invariants.hpp"  // the checks of the invariants below, edge_satisfies_invariants
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh {

// Splits edge (a, b) at its middle — for a primary edge at the curve's mid-parameter when that
// inverts nothing and makes no new triangle worse than max(the two old ones, energy_bound), else
// at the chord's middle (then the vertex waits for projection). Returns the new vertex, or -1
// when rejected.
int split_edge(TriMesh& mesh, const Constraints& constraints, int a, int b, double energy_bound);

// Moves vertex `from` onto `to` and removes it. Accepted only if the largest AMIPS energy of the
// new triangles is at most max(largest before, energy_bound). §4.1: curve endpoints never move.
bool collapse_edge(TriMesh& mesh, const Constraints& constraints, int from, int to, double energy_bound);

// Same, with a test of the caller's own, asked with (from, to) after the tests on tags and curves
// (the cheapest, which refuse most collapses) and before the others: a costly test of the caller's
// is then made only where those let the collapse through, and they are made once.
using CollapseTest = std::function<bool(int from, int to)>;
bool collapse_edge(TriMesh& mesh, const Constraints& constraints, int from, int to, double energy_bound,
                   const CollapseTest& also);

// The tests of collapse_edge on tags and curves alone (which vertex may move along which edge, how
// far a curve edge would turn, which tagged edges may merge): the cheapest, and those that refuse
// most collapses. collapse_edge makes them first (and a caller's test right after them).
bool collapse_allowed_by_tags(const TriMesh& mesh, const Constraints& constraints, int from, int to);

// The first of those tests, on the kinds alone: whether `from` may move along the edge to `to` at
// all (a fixed vertex never moves, a curve's only along its curve, a side's along its side, a free
// or secondary one off every curve and side). It reads only the tag of `from` and the edge's,
// which a collapse changes only at its own two ends: a pass that looks again at no edge whose
// ends a collapse changed may ask it for every edge before the pass.
bool collapse_allowed_by_kind(const TriMesh& mesh, int from, int to);

// TetWild's bounds on an edge's length, as multiples of its target length, which the paper's §4.1
// loop takes from TetWild: split above 4/3, collapse below 4/5, and no collapse may make an edge
// longer than 4/3, or the split and collapse passes undo each other forever.
inline constexpr double kSplitAbove = 4.0 / 3.0;
inline constexpr double kCollapseBelow = 0.8;
// The coarsenings (after the §4.1 loop, and the curve stage's along the curves) collapse against
// 1.25 times the target: no new edge longer than 5/3 of it (kSplitAbove × 1.25).
inline constexpr double kCoarseningScale = 1.25;

// TetWild's rule for collapses: no new edge longer than kSplitAbove times the target, or the split
// and collapse passes undo each other forever. target(to, w) is the target of the new edge (to, w);
// a caller passes a larger one to bound the edges at another multiple. For collapse_edge's test.
template <class Target>
bool collapse_keeps_edges_short(const TriMesh& m, int from, int to, const Target& target) {
  for (int t : m.triangles_of(from))  // a neighbour seen twice is checked twice: no harm, no sorting
    for (int w : m.triangle(t))
      if (w != from && w != to && (m.point(w) - m.point(to)).norm() > kSplitAbove * target(to, w)) return false;
  return true;
}

// Replaces the diagonal (a, b) of the quad formed by its two triangles by the other diagonal,
// if the largest AMIPS energy of the two triangles decreases or stays at most energy_bound.
// Tagged edges never swap. `left_hint` may name the triangle with directed edge a -> b, which
// saves a walk round a's star; it is checked, and any other value is ignored. On a swap,
// `rewritten` (when given) receives the two triangle slots that now hold the new diagonal's
// triangles: the same slots that held the old ones.
bool swap_edge(TriMesh& mesh, int a, int b, double energy_bound = 0, int left_hint = -1,
               std::array<int, 2>* rewritten = nullptr);

// One Newton step (with line search) on the summed AMIPS energy of v's triangles: in the plane
// for free and secondary vertices, along the curve for primary ones (App. A), along the side
// for boundary ones; when Newton finds nothing (or a triangle is too flat for doubles), a step
// towards the middle of the star. A move is taken when the sum decreases and the worst of v's
// triangles gets no worse. Returns true if v moved.
bool smooth_vertex(TriMesh& mesh, const Constraints& constraints, int v);

// Fig. 8: moves a primary vertex that is not yet on its curve towards its closest point on the
// curve, as far as the invariants allow without making its worst triangle worse than
// max(now, energy_bound); it never moves away. Returns true if it moved.
bool project_vertex(TriMesh& mesh, const Constraints& constraints, int v, double energy_bound);

// §4.1 (end of "Vertex projection"): drops the tag of secondary edge (a, b) when one of its
// triangles has two other tagged edges a–x and x–b that lie inside the ε-envelope themselves: the
// sliver between the secondary chord and that path could never be improved, and the path stands
// for the secondary input there, within ε as the invariant asks. Secondary vertices left without
// secondary edges become free. Where the path's edges are not tagged yet, but x is on no box
// side (nor a primary vertex still off its curve), lies on a–b to round-off (height below
// 1e-9·|ab|: a flat triangle), a–b is that triangle's longest edge and the path is inside the
// envelope, the tag moves onto the path (x becomes secondary if it was free, fixed if it was
// primary: a crossing). Returns true if anything changed.
bool release_secondary_edge(TriMesh& mesh, const Constraints& constraints, int a, int b);

// Gives a vertex with an exact (rational) position a double position: its nearest double, or,
// if that inverts a triangle, a point slightly towards the centre of its star. Returns success.
bool round_vertex(TriMesh& mesh, const Constraints& constraints, int v);

}  // namespace curvemesh::mesh
