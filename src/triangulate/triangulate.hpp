#pragma once
// §4.1, first half: an exact constrained triangulation of the outer box and every feature.
//
// The box, the primary polylines (one constraint per polyline edge), the secondary segments and
// the isolated points form an arrangement whose crossings are computed exactly. It is triangulated
// on the crossings' rounded positions and certified at their exact ones; where that cannot be
// certified, at their exact positions (arrangement.hpp). Each resulting edge is tagged with what it lies on (primary beats secondary
// beats box when inputs overlap), each vertex with how it may move later. Vertices whose exact
// position rounds to doubles without inverting a triangle are rounded; the others keep their
// rational position until the optimizer can round them (TetWild's hybrid kernel).
// Never fails on finite input, but for a triangulation larger than Options::max_triangles.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "features/features.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::triangulate {

// How the arrangement was triangulated: at the crossings' rounded positions, certified (the usual
// case); at their exact positions, where rounding could not be certified; or by CGAL's exact
// constructions.
enum class Method { rounded, exact_crossings, exact_constructions };
const char* method_name(Method m);  // "rounded", "exact crossings", "exact constructions"

struct Options {
  // The outer box is the input's bounding box grown on every side by this length (a fraction of
  // its diagonal d), so that features never touch the box and the domain around them is meshed too.
  double box_margin = 0;
  // Refuse (base::LimitExceeded) a triangulation of more triangles (Limits::max_triangles).
  std::size_t max_triangles = SIZE_MAX;
};

struct Stats {
  int input_constraints = 0;  // constraints inserted (polyline edges, segments, box sides)
  int vertices = 0;
  int triangles = 0;
  int crossing_vertices = 0;  // vertices created by intersecting input constraints
  int exact_vertices = 0;     // of those, the ones that could not be rounded to doubles yet
  Method method = Method::rounded;
  double seconds = 0;
};

// A piece of the arrangement that lies on the curves of more than one input curve (two shapes
// sharing a side): the mesh's edge there takes the tag of one feature (primary beats secondary,
// then the lower section or segment), and this keeps the others. What the output's groups say a
// line lies on (pipeline::line_elements).
struct SharedPiece {
  mesh::EdgeKind kind = mesh::EdgeKind::primary;  // of the feature the edge's tag names
  int source = -1;                                // its section (primary) or segment (secondary)
  // The piece's interval along that feature, from <= to: the curve's parameters (primary), the
  // fraction of the way from the segment's a to its b (secondary).
  double from = 0, to = 0;
  std::vector<int> curves;  // the other input curves on the piece, ascending
};

struct Result {
  mesh::TriMesh mesh;
  geometry::Box2 box;  // the outer box (sides: 0 y = min, 1 x = max, 2 y = max, 3 x = min)
  Stats stats;
  std::vector<SharedPiece> shared;  // in the order of the pieces
};

Result triangulate(const features::Features& features, const Options& options);

}  // namespace curvemesh::triangulate
