#pragma once
// How local operations run side by side: in spatial parts of the mesh, each part's operations in
// its own task, in their usual order (as the wildmeshing toolkit schedules them). An operation
// whose star crosses a part's border cannot run in the part's task; the mesh is cut twice, the
// second time across the first cut's borders, so that most of those run inside a part of the
// second cut, and only what lies on the borders of both runs afterwards, one after another. The
// cuts depend on the mesh alone, never on the number of threads, so the work done through them
// gives the same result, byte for byte, on any number of threads.
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

#include "base/parallel.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh {

// One cut of the vertices with triangles into parts. `of[v]`: v's part, -1 for a vertex without
// triangles when the cut was made; `inner[v]`: whether v and every corner of its triangles are in
// v's part (mark_inner).
struct Cut {
  std::vector<int> of;
  std::vector<char> inner;
  int count = 0;
};

// The mesh cut twice into parts of at most `size` vertices, each cut by halving at the median
// across the longer side of each part's box (ties by vertex number): compact parts, whose borders
// hold few of their vertices. The second cut halves the coordinates turned by 45°, so its borders
// cross the first's. The mesh's journal must be closed (operations run through the parts cannot
// record into it); the cuts stay good while the mesh gains no vertex.
struct Parts {
  Cut first, second;
};
Parts spatial_parts(const TriMesh& m, int size);
// Sets `inner` from the mesh as it is now.
void mark_inner(const TriMesh& m, Cut& cut);

// Runs op(i) for the items 0 … n-1, each an operation on an edge (ends(i): its two ends) that
// reads the stars of its ends and of their neighbours and rewrites triangles of the stars of its
// ends only (a collapse, a swap). For each cut in turn, the items not yet run whose two ends are
// inner vertices of one part p run in p's own task, in their order; the others wait for the next
// cut, and those left after both run one after another in item order. The parts' tasks touch
// disjoint sets of vertices and triangles: a triangle with a corner outside p is in no star an
// item of p rewrites, so an inner vertex stays inner while the parts run, and whatever the task of
// p reads (the stars of the neighbours of inner vertices: triangles with a corner in p) no other
// task writes. The result is the same for any number of threads, though not the same as one
// sweep in item order. `around(cut, run)` calls run() (the parts' tasks of that cut): a caller
// may prepare the mesh for them and restore it afterwards.
template <class Ends, class Op, class Around>
void for_each_in_parts(const TriMesh& m, Parts& parts, std::size_t n, const Ends& ends, const Op& op,
                       const Around& around) {
  std::vector<std::size_t> left(n);
  std::iota(left.begin(), left.end(), std::size_t{0});
  for (Cut* cut : {&parts.first, &parts.second}) {
    mark_inner(m, *cut);
    std::vector<std::vector<std::size_t>> items(cut->count);
    std::vector<std::size_t> later;
    for (std::size_t i : left) {
      const auto [a, b] = ends(i);
      const bool inside = cut->inner[a] && cut->inner[b] && cut->of[a] == cut->of[b];
      (inside ? items[cut->of[a]] : later).push_back(i);
    }
    around(*cut, [&] {
      base::for_each_part(
          static_cast<std::size_t>(cut->count),
          [&](std::size_t p) {
            for (std::size_t i : items[p]) op(i);
          },
          1);
    });
    left = std::move(later);
  }
  for (std::size_t i : left) op(i);
}

template <class Ends, class Op>
void for_each_in_parts(const TriMesh& m, Parts& parts, std::size_t n, const Ends& ends, const Op& op) {
  for_each_in_parts(m, parts, n, ends, op, [](const Cut&, const auto& run) { run(); });
}

// for_each_in_parts for operations tried under the mesh's journal and judged afterwards: while
// the parts of a cut run, each has a journal of its own (TriMesh::split_journal), which op(i)
// opens at an end of its edge (TriMesh::open_journal(at)); on the borders afterwards, the mesh's.
template <class Ends, class Op>
void for_each_in_parts_journaled(TriMesh& m, Parts& parts, std::size_t n, const Ends& ends, const Op& op) {
  for_each_in_parts(m, parts, n, ends, op, [&](const Cut& cut, const auto& run) {
    m.split_journal(cut.of, cut.count);
    run();
    m.join_journal();
  });
}

// Runs op(v) for `vertices` (ascending), an operation that moves v (and retags its own edges),
// reading its star (its neighbours' positions and tags): for_each_in_parts with v as both ends.
template <class Op>
void for_each_vertex_in_parts(const TriMesh& m, Parts& parts, const std::vector<int>& vertices, const Op& op) {
  for_each_in_parts(
      m, parts, vertices.size(),
      [&](std::size_t i) {
        return std::pair{vertices[i], vertices[i]};
      },
      [&](std::size_t i) { op(vertices[i]); });
}

}  // namespace curvemesh::mesh
