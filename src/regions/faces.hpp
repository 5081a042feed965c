#pragma once
// The faces of a finished mesh and the part of it a user asks for.
//
// The mesh of a drawing covers its whole box; its feature lines on input curves (primary and
// secondary; the box's sides do not cut) divide it into faces: triangles connected across edges
// that are no such line. A face's depth is the number of feature lines crossed from the box's
// border: the faces touching the border have depth 0, a face next to one of depth k has at most
// k + 1. Odd depth is the drawing's inside under the even–odd rule over all its curves (a square
// with a round hole: the ring has depth 1, the hole 2).
#include <curvemesh/parameters.hpp>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/high_order_mesh.hpp"

namespace curvemesh::regions {

// For every triangle, the line on each of its edges (-1 for none): lines are matched to edges
// by their end nodes.
std::vector<std::array<int, 3>> edge_lines(const io::HighOrderMesh& mesh);

// For every edge (its corner nodes, smaller first), the triangles on it and the edge's index in
// each: (triangle, edge).
std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edge_triangles(const io::HighOrderMesh& mesh);

struct Faces {
  std::vector<int> of_triangle;  // face index per triangle
  std::vector<int> depth;        // per face
  int count() const { return static_cast<int>(depth.size()); }
};

// Faces separated by primary and secondary lines, numbered in order of their first triangle.
Faces find_faces(const io::HighOrderMesh& mesh);

// The faces, and for each triangle the filled shape painted on top of it (regions/paint.hpp): its
// face's, unless an outline crosses the face.
struct Classification {
  Faces faces;
  std::vector<int> visible;  // per triangle: index of the topmost fill layer covering it, -1 none;
                             // empty when the fills were not classified
  std::vector<int> filled;   // per triangle: the topmost layer covering it that is not a stroke's
                             // (svg::FillLayer::stroke), -1 none; as `visible` when none is
};

// Which triangles a mesh keeps: the whole box, the triangles some filled shape covers (the shape
// as it is seen, the background gone), the even–odd inside of all curves (odd depth), the
// triangles some fill or stroke paints, or the even–odd outside (even depth): the public curvemesh::Domain
// of Parameters.
using Domain = curvemesh::Domain;
inline constexpr Domain kDomains[] = {Domain::box, Domain::filled, Domain::evenodd, Domain::painted,
                                      Domain::outside};
// "box", "filled", "evenodd", "painted", "outside".
const char* domain_name(Domain domain);

// Per triangle, whether it is in the domain. `filled` and `painted` need a classification of the
// fills.
std::vector<char> domain_triangles(const Classification& classification, Domain domain);

// The triangles with keep[t] set, their nodes (renumbered, in order of first use) and the lines
// on their edges; line_origin (if given) gets the input line of each line kept, node_origin the
// input node of each node.
io::HighOrderMesh submesh(const io::HighOrderMesh& mesh, const std::vector<char>& keep,
                          std::vector<int>* line_origin = nullptr, std::vector<int>* node_origin = nullptr);

// The length of line l: exact for a straight line, to quadrature accuracy (Gauss–Legendre, five
// points) for a curved one.
double line_length(const io::HighOrderMesh& mesh, int l);

// The area of triangle t, exact up to rounding for every order: Green's formula over its three
// edges, each a polynomial curve of the triangle's order (Gauss–Legendre, exact for them).
double triangle_area(const io::HighOrderMesh& mesh, int t);

}  // namespace curvemesh::regions
