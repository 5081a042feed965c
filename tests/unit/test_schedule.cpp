// Local operations side by side (mesh/schedule.hpp): each cut's parts cover the mesh, none larger
// than asked, `inner` says exactly which stars lie inside their vertex's part, the second cut
// crosses the first's borders; and collapses, swaps and smoothing run through the parts give the
// same mesh, bit for bit, on 1 and 4 threads, a valid one by every invariant (exact orientation
// included); with the journal split per part, each part
// takes back its own changes alone, and operations tried and taken back side by side give one
// mesh on any number of threads too.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "base/parallel.hpp"
#include "geometry/amips.hpp"
#include "grid_fixture.hpp"
#include "mesh/operations.hpp"
#include "mesh/journal.hpp"
#include "mesh/schedule.hpp"

namespace curvemesh::mesh {
namespace {

using fixture::Fixture;
using fixture::make_grid;

TEST(SpatialParts, CoverTheMeshInPartsOfTheSizeAskedAndKnowTheirInnerVertices) {
  const Fixture f = make_grid(24, 3);
  const TriMesh& m = f.mesh;
  const Parts parts = spatial_parts(m, 64);
  for (const Cut* cut : {&parts.first, &parts.second}) {
    ASSERT_EQ(static_cast<int>(cut->of.size()), m.vertex_count());
    std::map<int, int> sizes;
    for (int v = 0; v < m.vertex_count(); ++v) {
      ASSERT_GE(cut->of[v], 0) << v;
      ASSERT_LT(cut->of[v], cut->count);
      ++sizes[cut->of[v]];
      bool inner = true;
      for (int t : m.triangles_of(v))
        for (int w : m.triangle(t)) inner = inner && cut->of[w] == cut->of[v];
      EXPECT_EQ(bool(cut->inner[v]), inner) << v;
    }
    EXPECT_EQ(static_cast<int>(sizes.size()), cut->count);
    for (const auto& [part, size] : sizes) EXPECT_LE(size, 64) << part;
    EXPECT_GE(cut->count, 25 * 25 / 64);
    // Compact parts: most vertices are inner.
    EXPECT_GT(std::count(cut->inner.begin(), cut->inner.end(), 1), m.vertex_count() / 3);
  }
}

// The second cut crosses the first's borders: few vertices are on the borders of both (on a
// 97 × 97 grid in parts of 1,024, 168 of the first cut's 1,212 border vertices).
TEST(SpatialParts, CutTheSecondTimeAcrossTheFirstCutsBorders) {
  const Fixture f = make_grid(96, 3);
  const TriMesh& m = f.mesh;
  const Parts parts = spatial_parts(m, 1024);
  int first_border = 0, both = 0;
  for (int v = 0; v < m.vertex_count(); ++v) {
    first_border += !parts.first.inner[v];
    both += !parts.first.inner[v] && !parts.second.inner[v];
  }
  EXPECT_GT(first_border, 0);
  EXPECT_LT(both, first_border / 4) << both << " of " << first_border;
}

// The halves are cut side by side, each numbering its parts from where the other's end: the parts
// are the same, numbers included, on any number of threads.
TEST(SpatialParts, TheSamePartsOnAnyNumberOfThreads) {
  const Fixture f = make_grid(96, 5);
  const Parts one = base::with_threads(1, [&] { return spatial_parts(f.mesh, 200); });
  const Parts four = base::with_threads(4, [&] { return spatial_parts(f.mesh, 200); });
  for (const auto& [a, b] : {std::pair{&one.first, &four.first}, std::pair{&one.second, &four.second}}) {
    EXPECT_GE(a->count, 97 * 97 / 200);
    EXPECT_EQ(a->count, b->count);
    EXPECT_EQ(a->of, b->of);
    EXPECT_EQ(a->inner, b->inner);
  }
}

TEST(SpatialParts, RefuseAMeshWhoseJournalIsOpen) {
  Fixture f = make_grid(8, 1);
  f.mesh.open_journal();  // operations side by side cannot record into one journal
  EXPECT_THROW(spatial_parts(f.mesh, 16), std::logic_error);
  f.mesh.commit();
  EXPECT_NO_THROW(spatial_parts(f.mesh, 16));
}

// Two inner vertices of different parts, each with an inner edge to swap.
std::array<int, 2> inner_of_two_parts(const Cut& cut) {
  std::array<int, 2> found{-1, -1};
  for (int v = 0; v < static_cast<int>(cut.of.size()); ++v)
    if (cut.inner[v] && (cut.of[v] == 0 || cut.of[v] == 1) && found[cut.of[v]] < 0) found[cut.of[v]] = v;
  return found;
}

TEST(SplitJournal, EachPartTakesBackItsOwnChangesAlone) {
  Fixture f = make_grid(16, 5);
  TriMesh& m = f.mesh;
  const Cut parts = spatial_parts(m, 40).first;
  const auto [a, b] = inner_of_two_parts(parts);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  const TriMesh before = m;
  m.split_journal(parts.of, parts.count);
  EXPECT_TRUE(m.journal_open());
  EXPECT_THROW(m.open_journal(), std::logic_error);  // a level needs its part
  EXPECT_THROW(m.add_vertex(Vec2(0.5, 0.5)), std::logic_error);
  m.open_journal(a);
  m.open_journal(b);
  m.set_position(a, m.point(a) + Vec2(1e-3, 0));
  const int b_neighbour = m.neighbours(b).front();
  ASSERT_TRUE(swap_edge(m, b, b_neighbour, 0) || collapse_edge(m, f.constraints, b, b_neighbour, 1e9));
  m.set_position(b, m.point(b) + Vec2(0, 1e-3));
  const TriMesh changed = m;
  EXPECT_THROW(m.join_journal(), std::logic_error);  // levels still open
  m.rollback(a);  // a's part only: b's changes stay
  EXPECT_EQ(m.point(a), before.point(a));
  EXPECT_EQ(m.point(b), changed.point(b));
  for (int t = 0; t < m.triangle_slots(); ++t) EXPECT_EQ(m.triangle(t), changed.triangle(t)) << t;
  m.rollback(b);
  m.join_journal();
  EXPECT_FALSE(m.journal_open());
  EXPECT_EQ(m.point(b), before.point(b));
  for (int t = 0; t < m.triangle_slots(); ++t) EXPECT_EQ(m.triangle(t), before.triangle(t)) << t;
  EXPECT_EQ(m.triangle_count(), before.triangle_count());
  EXPECT_EQ(m.sorted_features(), before.sorted_features());
  EXPECT_FALSE(m.structure_error()) << *m.structure_error();
}

TEST(SplitJournal, RefusesAnOpenLevelAndAttachedStores) {
  Fixture f = make_grid(8, 1);
  const Cut parts = spatial_parts(f.mesh, 16).first;
  f.mesh.open_journal();
  EXPECT_THROW(f.mesh.split_journal(parts.of, parts.count), std::logic_error);
  f.mesh.commit();
  {
    JournaledVector<int> store(f.mesh.journal());  // a store the parts could not share
    EXPECT_THROW(f.mesh.split_journal(parts.of, parts.count), std::logic_error);
  }
  EXPECT_NO_THROW(f.mesh.split_journal(parts.of, parts.count));
  f.mesh.join_journal();
}

// Collapses tried under the journal, part by part, and taken back when a triangle they make has
// an energy above `keep_below`: as the coarsening runs them.
Fixture tried(int threads, double keep_below) {
  Fixture f = make_grid(24, 13);
  TriMesh& m = f.mesh;
  base::with_threads(threads, [&] {
    for (int round = 0; round < 2; ++round) {
      Parts parts = spatial_parts(m, 48);
      const std::vector<std::array<int, 2>> edges = fixture::edges_of(m);
      std::vector<char> touched(m.vertex_count(), 0);
      for_each_in_parts_journaled(
          m, parts, edges.size(),
          [&](std::size_t i) {
            return std::pair{edges[i][0], edges[i][1]};
          },
          [&](std::size_t i) {
            const auto [a, b] = edges[i];
            if (touched[a] || touched[b] || (m.point(a) - m.point(b)).norm() > 0.9 / 24) return;
            m.open_journal(a);
            if (!collapse_edge(m, f.constraints, a, b, 1e9)) return m.commit(a);
            double worst = 0;
            for (int t : m.triangles_of(b)) {
              const auto& tri = m.triangle(t);
              worst = std::max(worst, geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])));
            }
            if (worst > keep_below) return m.rollback(a);
            m.commit(a);
            touched[a] = touched[b] = 1;
          });
      EXPECT_FALSE(m.journal_open());
    }
  });
  return f;
}

TEST(ForEachInPartsJournaled, OperationsTakenBackGiveOneMeshOnAnyNumberOfThreads) {
  const Fixture one = tried(1, 3.0), four = tried(4, 3.0), all = tried(1, 1e9);
  fixture::expect_invariants(one, "operations tried in parts, 1 thread");
  fixture::expect_invariants(four, "operations tried in parts, 4 threads");
  // Some collapses were kept, some taken back.
  EXPECT_LT(one.mesh.triangle_count(), 2 * 24 * 24);
  EXPECT_GT(one.mesh.triangle_count(), all.mesh.triangle_count());
  ASSERT_EQ(one.mesh.triangle_slots(), four.mesh.triangle_slots());
  for (int t = 0; t < one.mesh.triangle_slots(); ++t)
    EXPECT_EQ(one.mesh.triangle(t), four.mesh.triangle(t)) << t;
  for (int v = 0; v < one.mesh.vertex_count(); ++v) EXPECT_EQ(one.mesh.point(v), four.mesh.point(v)) << v;
  EXPECT_EQ(one.mesh.sorted_features(), four.mesh.sorted_features());
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
          m, parts, edges.size(),
          [&](std::size_t i) {
            return std::pair{edges[i][0], edges[i][1]};
          },
          [&](std::size_t i) {
            const auto [a, b] = edges[i];
            if (touched[a] || touched[b] || (m.point(a) - m.point(b)).norm() > 0.8 / 24) return;
            if (collapse_edge(m, f.constraints, a, b, 1e9) || collapse_edge(m, f.constraints, b, a, 1e9))
              touched[a] = touched[b] = 1;
          });
      edges = fixture::edges_of(m);
      for_each_in_parts(
          m, parts, edges.size(),
          [&](std::size_t i) {
            return std::pair{edges[i][0], edges[i][1]};
          },
          [&](std::size_t i) { swap_edge(m, edges[i][0], edges[i][1], 0); });
      std::vector<int> vertices;
      for (int v = 0; v < m.vertex_count(); ++v)
        if (!m.triangles_of(v).empty()) vertices.push_back(v);
      for_each_vertex_in_parts(m, parts, vertices, [&](int v) { smooth_vertex(m, f.constraints, v); });
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
