#pragma once
// The curved form of a triangle mesh (§4.2): its higher-order nodes — order 3's two per edge and
// one per triangle, order 2's one per edge — kept as attributes of the mesh, the geogram way:
// per vertex its node, per edge its first inner node and whether it follows its curve or was
// fitted towards it, per triangle its node ids and its certified scaled Jacobian. Every store is
// attached to the mesh's journal, so the level that takes back a local operation, a move or a move
// with its repair takes the nodes back with the mesh, and nothing is ever copied to undo.
//
// The element rule is App. C's, the one the optimization foresees with (mesh/curved_element.hpp):
// an edge that can follow its curve has its inner nodes on it, any other edge on its chord, order
// 3's centre among geometry::p3_centre_candidates. After a local operation of the mesh (split,
// collapse, swap), `adopt` gives the new vertices, edges and triangles their nodes by that rule;
// `forget_edges` drops the nodes of the edges it removed, once it is kept.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/p2_triangle.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/constraints.hpp"
#include "mesh/journal.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh {

class CurvedForm {
 public:
  // Attached to `m` (compacted, at most one primary edge per triangle) for its lifetime: every
  // vertex gets its node, every edge its inner nodes (on its curve where it can follow it), in
  // the order triangles first meet their edges. The triangles get theirs by `push_triangle`.
  CurvedForm(TriMesh& m, const Constraints& c, int order);
  CurvedForm(const CurvedForm&) = delete;
  CurvedForm& operator=(const CurvedForm&) = delete;

  int order() const { return order_; }
  bool quadratic() const { return order_ == 2; }

  // --- reading ---
  const Vec2& at(int v) const { return nodes_[vertex_node_[v]]; }  // the node of vertex v
  const Vec2& node(int id) const { return nodes_[id]; }
  const std::array<int, 10>& triangle_nodes(int t) const { return triangle_nodes_[t]; }
  int triangle_slots() const { return static_cast<int>(triangle_nodes_.size()); }
  // Triangle t's element: order 3's ten nodes, order 2's six.
  geometry::P3Nodes p3(int t) const;
  geometry::P2Nodes p2(int t) const;
  // The curved AMIPS energy of triangle t (geometry::p3_max_amips, p2_max_amips): exact below
  // `bound`, at least `bound` otherwise.
  double energy(int t, double bound = std::numeric_limits<double>::infinity()) const;
  // How far triangle t is from valid, or how good it is: its worst AMIPS energy when det J > 0 at
  // every point of the order-6 lattice, else 1e12 less the smallest det J there over the squared
  // longest side (lower is better either way; only a certificate decides validity).
  double badness(int t) const;
  // The scaled Jacobian of triangle t if it is certified positive, with `depth` subdivisions.
  std::optional<double> certify(int t, int depth) const;
  // The scaled Jacobian recorded for t, −1 if it is not certified.
  double scaled(int t) const { return scaled_[t]; }

  // The two inner nodes of edge (a, b) in the order from a to b; order 2: its middle node twice.
  std::pair<int, int> edge_nodes(int a, int b) const;
  // A triangle's corner and edge node ids in Gmsh's order (order 3's centre, ids[9], left to
  // the caller; order 2: the rest −1).
  std::array<int, 10> corner_and_edge_nodes(const Triangle& tri) const;
  // Whether edge (a, b) follows its curve (nodes on it); false for an edge with no nodes.
  bool follows(int a, int b) const;
  bool fitted(int a, int b) const { return fitted_.contains(edge_key(a, b)); }
  bool any_fitted() const { return !fitted_.empty(); }
  // Index i of the triangle's edge (tri[i], tri[i+1]) that follows its curve, or is fitted; −1.
  int curved_edge_of(const Triangle& tri) const;
  int fitted_edge_of(const Triangle& tri) const;
  bool on_fitted_edge(int v) const;  // an end of a fitted edge

  // --- placing nodes ---
  void set_node(int id, const Vec2& p) { nodes_.set(id, p); }
  void set_scaled(int t, double scaled) { scaled_.set(t, scaled); }
  // Gives the next triangle slot its node ids and order 3's centre, and `scaled`.
  void push_triangle(const Triangle& tri, const Vec2& centre, double scaled);
  // Edge (lo, hi)'s inner nodes on its chord, or on its curve (mesh::nodes_on_curve).
  void place_straight(int lo, int hi);
  void place_on_curve(int lo, int hi);
  // Whether edge (a, b) follows its curve, its nodes left where they are.
  void set_follows(int a, int b, bool follows) { follows_.set(edge_key(a, b), follows); }
  void set_fitted(int a, int b) { fitted_.set(edge_key(a, b), true); }
  // Edge (a, b) back on its chord, if it followed its curve.
  void straighten(int a, int b);
  // Corner v at p, and what depends on it: its edges' inner nodes (on their curve at thirds of
  // the parameter interval where they follow it, else at thirds of the chord; order 2: middles)
  // and its triangles' centres (straight: the centroid; curved: choose_centre). The mesh's own
  // position of v is the caller's.
  void place_corner(int v, const Vec2& p);
  // Order 3: the centre of triangle t (its edge nodes placed) among the candidates, the lowest
  // badness. Returns the triangle's energy when every lattice point's det J is positive there,
  // else NaN (order 2: no centre, the same answer).
  double choose_centre(int t);

  // --- following the mesh's local operations ---
  // After an operation made vertices from `first_new_vertex` on and changed or made `triangles`:
  // the new vertices get nodes, the triangles their edges' nodes (new edges on their curve where
  // they can follow it) and a new centre (choose_centre where an edge follows a curve). Each
  // triangle's energy as its centre was chosen goes to `known` (NaN where none was computed).
  // False if one of them has two primary edges (the curve stage gives each at most one).
  bool adopt(int first_new_vertex, const std::vector<int>& triangles, std::vector<double>& known);
  // Once an operation is kept: the edges among `edges` (edge_key) that no triangle has any more
  // lose their nodes (a later operation may make them again).
  void forget_edges(const std::vector<std::uint64_t>& edges);
  // The nodes of some triangles, to put back when a move is refused without a journal level.
  using Snapshot = std::vector<std::pair<int, Vec2>>;
  Snapshot snapshot(const std::vector<int>& triangles) const;
  void restore(const Snapshot& saved);

  // --- the result ---
  // Compacts the mesh and its curved form together (no journal level open): dead triangles and
  // removed vertices dropped, the nodes renumbered, vertices first in their new order, then every
  // other node still used in its old order.
  void compact();
  const std::vector<Vec2>& nodes() const { return nodes_.values(); }
  const std::vector<std::array<int, 10>>& triangles() const { return triangle_nodes_.values(); }

 private:
  void add_edge(int a, int b);
  void place_inner_nodes(int lo, int hi, const std::array<Vec2, 2>& inner);

  TriMesh& m_;
  const Constraints& c_;
  int order_;
  JournaledVector<Vec2> nodes_;  // vertices first (same indices), then the rest
  // Per triangle slot of the mesh, its nodes (CurvedMesh::triangles' layout).
  JournaledVector<std::array<int, 10>> triangle_nodes_;
  // Where each vertex's node is in nodes_: the vertex's own index until an operation adds
  // vertices (compact puts the vertices first again).
  JournaledVector<int> vertex_node_;
  JournaledMap<std::uint64_t, int> first_node_;  // per edge, its first inner node
  JournaledMap<std::uint64_t, bool> follows_;    // per edge, whether it follows its curve
  JournaledVector<double> scaled_;               // per triangle: its scaled Jacobian, or −1
  JournaledMap<std::uint64_t, bool> fitted_;     // primary edges fitted towards their curve
};

}  // namespace curvemesh::mesh
