#pragma once
// How local operations run side by side: in spatial parts of the mesh, each part's operations in
// its own task, in their usual order, and the operations on the parts' borders afterwards, one
// after another (as the wildmeshing toolkit schedules them). The parts depend on the mesh alone,
// never on the number of threads, so the work done through them gives the same result, byte for
// byte, on any number of threads.
#include <cstddef>
#include <utility>
#include <vector>

#include "base/parallel.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh {

// The vertices with triangles cut into parts of at most `size` by halving at the median, across
// the longer side of each part's box (ties by vertex number): compact parts, whose borders hold
// few of their vertices. `of[v]`: v's part, -1 for a vertex without triangles; `inner[v]`: whether
// v and every corner of its triangles are in v's part. The mesh's journal must be closed (the
// operations run through the parts cannot record into it).
struct Parts {
  std::vector<int> of;
  std::vector<char> inner;
  int count = 0;
};
Parts spatial_parts(const TriMesh& m, int size);
// Sets `inner` again, after operations on the borders (done one after another) changed stars; the
// parts stay as they are while the mesh gains no vertex.
void mark_inner(const TriMesh& m, Parts& parts);

// Runs op(i) for the items 0 … n-1, each an operation on an edge (ends(i): its two ends) that
// reads the stars of its ends and of their neighbours and rewrites triangles of the stars of its
// ends only (a collapse, a swap): the items whose two ends are inner vertices of one part p, in
// their order, in p's own task; the others afterwards, one after another in item order. The parts'
// tasks touch disjoint sets of vertices and triangles: a triangle with a corner outside p is in no
// star an item of p rewrites, so an inner vertex stays inner while the parts run, and whatever the
// task of p reads (the stars of the neighbours of inner vertices: triangles with a corner in p) no
// other task writes. The result is the same for any number of threads, though not the same as
// one sweep in item order.
template <class Ends, class Op>
void for_each_in_parts(const Parts& parts, std::size_t n, const Ends& ends, const Op& op) {
  for_each_in_parts(parts, n, ends, op, [] {}, [] {});
}

// The same, with `before()` called before the parts' tasks start and `after()` when they have all
// ended, before the operations on the borders.
template <class Ends, class Op, class Before, class After>
void for_each_in_parts(const Parts& parts, std::size_t n, const Ends& ends, const Op& op, const Before& before,
                       const After& after) {
  std::vector<std::vector<std::size_t>> items(parts.count);
  std::vector<std::size_t> later;
  for (std::size_t i = 0; i < n; ++i) {
    const auto [a, b] = ends(i);
    const bool inside = parts.inner[a] && parts.inner[b] && parts.of[a] == parts.of[b];
    (inside ? items[parts.of[a]] : later).push_back(i);
  }
  before();
  base::for_each_part(
      static_cast<std::size_t>(parts.count),
      [&](std::size_t p) {
        for (std::size_t i : items[p]) op(i);
      },
      1);
  after();
  for (std::size_t i : later) op(i);
}

// for_each_in_parts for operations tried under the mesh's journal and judged afterwards: while
// the parts run, each has a journal of its own (TriMesh::split_journal), which op(i) opens at an
// end of its edge (TriMesh::open_journal(at)); on the borders afterwards, the mesh's.
template <class Ends, class Op>
void for_each_in_parts_journaled(TriMesh& m, const Parts& parts, std::size_t n, const Ends& ends, const Op& op) {
  for_each_in_parts(
      parts, n, ends, op, [&] { m.split_journal(parts.of, parts.count); }, [&] { m.join_journal(); });
}

// Runs op(v) for `vertices` (ascending), an operation that moves v (and retags its own edges),
// reading its star (its neighbours' positions and tags): for_each_in_parts with v as both ends —
// the inner vertices of each part, in order, in the part's own task, the others afterwards, one
// after another in ascending order.
template <class Op>
void for_each_vertex_in_parts(const Parts& parts, const std::vector<int>& vertices, const Op& op) {
  for_each_in_parts(
      parts, vertices.size(),
      [&](std::size_t i) {
        return std::pair{vertices[i], vertices[i]};
      },
      [&](std::size_t i) { op(vertices[i]); });
}

}  // namespace curvemesh::mesh
