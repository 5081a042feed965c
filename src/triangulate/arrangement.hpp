#pragma once
// The two ways to triangulate the input's arrangement, and what both hand back.
//
// The input is a set of points and of constraints between them (primary polyline edges,
// secondary segments, box sides), in priority order. Its arrangement has a vertex at every input
// point and at every crossing of two constraints, computed exactly; each constraint becomes a chain
// of pieces between the vertices on it. Both ways produce that arrangement's vertices, a
// triangulation of the box whose edges include every piece, and for each piece the constraints
// it lies on:
//  - `triangulate_arrangement` finds the crossings itself (exactly, with interval filters),
//    rounds them, triangulates the rounded points with the pieces as constraints (CGAL, exact
//    predicates on doubles) and then checks with the crossings' exact positions that no triangle
//    inverts and no piece was split. Where that cannot be certified it triangulates the same
//    vertices and pieces at the crossings' exact positions. It never guesses: if a piece still
//    does not come out as an edge, it gives up (nullopt).
//  - `triangulate_exact` hands everything to CGAL's constrained triangulation with exact
//    constructions, which always succeeds but is several times slower on dense inputs.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/predicates.hpp"
#include "geometry/vec2.hpp"
#include "mesh/tri_mesh.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::triangulate::detail {

struct InputPoint {
  geometry::Vec2 p;
  bool fixed = false;     // box corner, section end, isolated point
  bool isolated = false;  // an isolated input point
};

struct InputConstraint {
  mesh::EdgeKind kind = mesh::EdgeKind::interior;
  int source = -1;  // section / segment / side
  int edge = -1;    // primary: the polyline edge (between polyline vertices edge, edge + 1)
  int a = -1, b = -1;  // its ends, indices into the input points
};

struct Input {
  std::vector<InputPoint> points;
  std::vector<InputConstraint> constraints;
  // Refuse (base::LimitExceeded) an arrangement whose triangulation would have more triangles,
  // before its crossings are found or its pairs of nearby segments listed beyond that size.
  std::size_t max_triangles = SIZE_MAX;
};

struct ArrangementVertex {
  geometry::Vec2 approx;     // the position in the mesh
  bool exact_needed = false;  // when `approx` is not the exact position, which is then `exact`
  geometry::ExactPoint exact;
  bool fixed = false, isolated = false;
  bool input = false;  // an input point (the others are crossings)

  // At a rational position: the mesh takes its nearest double, and keeps the rational when the
  // double is not it.
  void set_exact(geometry::ExactPoint e) {
    exact = std::move(e);
    approx = geometry::nearest_double(exact);
    const geometry::ExactPoint rounded(approx);
    exact_needed = rounded.x != exact.x || rounded.y != exact.y;
  }
};

// One piece of the arrangement: the constraints `constraints[first, last)` of `piece_constraints`
// all contain the edge (u, w).
struct Piece {
  int u = -1, w = -1;
  int first = 0, last = 0;
};

struct Triangulation {
  Method method = Method::rounded;
  std::vector<ArrangementVertex> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise
  std::vector<Piece> pieces;
  std::vector<int> piece_constraints;  // indices into Input::constraints, in input order per piece
  // Per input constraint: the vertices of its ends (-1 for one of zero length).
  std::vector<std::array<int, 2>> constraint_ends;
};

std::optional<Triangulation> triangulate_arrangement(const Input& input);
Triangulation triangulate_exact(const Input& input);

}  // namespace curvemesh::triangulate::detail
