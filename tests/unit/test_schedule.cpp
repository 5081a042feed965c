// Local operations side by side (mesh/schedule.hpp): the parts cover the mesh, none larger than
// asked, `inner` says exactly which stars lie inside their vertex's part; and collapses, swaps and
// smoothing run through the parts give the same mesh, bit for bit, on 1 and 4 threads, a valid
// one by every invariant (exact orientation included).
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "base/parallel.hpp"
#include "grid_fixture.hpp"
#include "mesh/operations.hpp"
#include "mesh/schedule.hpp"

namespace curvemesh::mesh {
namespace {

using fixture::Fixture;
using fixture::make_grid;

TEST(SpatialParts, CoverTheMeshInPartsOfTheSizeAskedAndKnowTheirInnerVertices) {
  const Fixture f = make_grid(24, 3);
  const TriMesh& m = f.mesh;
  const Parts parts = spatial_parts(m, 64);
  ASSERT_EQ(static_cast<int>(parts.of.size()), m.vertex_count());
  std::map<int, int> sizes;
  for (int v = 0; v < m.vertex_count(); ++v) {
    ASSERT_GE(parts.of[v], 0) << v;
    ASSERT_LT(parts.of[v], parts.count);
    ++sizes[parts.of[v]];
    bool inner = true;
    for (int t : m.triangles_of(v))
      for (int w : m.triangle(t)) inner = inner && parts.of[w] == parts.of[v];
    EXPECT_EQ(bool(parts.inner[v]), inner) << v;
  }
  EXPECT_EQ(static_cast<int>(sizes.size()), parts.count);
  for (const auto& [part, size] : sizes) EXPECT_LE(size, 64) << part;
  EXPECT_GE(parts.count, 25 * 25 / 64);
  // Compact parts: most vertices are inner.
  EXPECT_GT(std::count(parts.inner.begin(), parts.inner.end(), 1), m.vertex_count() / 3);
}

TEST(SpatialParts, RefuseAMeshWhoseJournalIsOpen) {
  Fixture f = make_grid(8, 1);
  f.mesh.open_journal();  // operations side by side cannot record into one journal
  EXPECT_THROW(spatial_parts(f.mesh, 16), std::logic_error);
  f.mesh.commit();
  EXPECT_NO_THROW(spatial_parts(f.mesh, 16));
}

// Collapses of the short edges, swaps and smoothing, as the optimization runs them part by part.
Fixture operated(int threads) {
  Fixture f = make_grid(24, 11);
  TriMesh& m = f.mesh;
  base::with_threads(threads, [&] {
    for (int round = 0; round < 3; ++round) {
      Parts parts = spatial_parts(m, 48);
      std::vector<std::array<int, 2>> edges = fixture::edges_of(m);
      std::vector<char> touched(m.vertex_count(), 0);
      for_each_in_parts(
          parts, edges.size(),
          [&](std::size_t i) {
            return std::pair{edges[i][0], edges[i][1]};
          },
          [&](std::size_t i) {
            const auto [a, b] = edges[i];
            if (touched[a] || touched[b] || (m.point(a) - m.point(b)).norm() > 0.8 / 24) return;
            if (collapse_edge(m, f.constraints, a, b, 1e9) || collapse_edge(m, f.constraints, b, a, 1e9))
              touched[a] = touched[b] = 1;
          });
      mark_inner(m, parts);
      edges = fixture::edges_of(m);
      for_each_in_parts(
          parts, edges.size(),
          [&](std::size_t i) {
            return std::pair{edges[i][0], edges[i][1]};
          },
          [&](std::size_t i) { swap_edge(m, edges[i][0], edges[i][1], 0); });
      mark_inner(m, parts);
      std::vector<int> vertices;
      for (int v = 0; v < m.vertex_count(); ++v)
        if (!m.triangles_of(v).empty()) vertices.push_back(v);
      for_each_vertex_in_parts(parts, vertices, [&](int v) { smooth_vertex(m, f.constraints, v); });
    }
  });
  return f;
}

TEST(ForEachInParts, CollapsesSwapsAndSmoothingGiveOneMeshOnAnyNumberOfThreads) {
  const Fixture one = operated(1), four = operated(4);
  fixture::expect_invariants(one, "operations in parts, 1 thread");
  fixture::expect_invariants(four, "operations in parts, 4 threads");
  ASSERT_EQ(one.mesh.vertex_count(), four.mesh.vertex_count());
  ASSERT_EQ(one.mesh.triangle_slots(), four.mesh.triangle_slots());
  EXPECT_LT(one.mesh.triangle_count(), 2 * 24 * 24);  // some collapses were made
  for (int t = 0; t < one.mesh.triangle_slots(); ++t)
    EXPECT_EQ(one.mesh.triangle(t), four.mesh.triangle(t)) << t;
  for (int v = 0; v < one.mesh.vertex_count(); ++v) {
    EXPECT_EQ(one.mesh.point(v).x(), four.mesh.point(v).x()) << v;
    EXPECT_EQ(one.mesh.point(v).y(), four.mesh.point(v).y()) << v;
    EXPECT_EQ(one.mesh.tag(v), four.mesh.tag(v)) << v;
  }
  EXPECT_EQ(one.mesh.sorted_features(), four.mesh.sorted_features());
}

}  // namespace
}  // namespace curvemesh::mesh
