// Property tests of the local operations: random sequences of proposals on meshes with every kind
// of tag; after each committed operation every invariant is re-checked, orientation with GMP
// rationals computed here (not through the mesh's own predicate).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <stdexcept>

#include "grid_fixture.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/curved_element.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::mesh {
namespace {

using namespace fixture;

TEST(MeshOperations, GridFixtureIsValid) {
  const Fixture f = make_grid(12, 1);
  expect_invariants(f, "construction");
  EXPECT_EQ(f.mesh.triangle_count(), 2 * 12 * 12);
}

TEST(MeshOperations, RandomSequencesKeepEveryInvariant) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    Fixture f = make_grid(10, seed);
    std::mt19937 rng(seed * 7919);
    std::map<std::string, int> committed;
    for (int step = 0; step < 1500; ++step) {
      const auto edges = edges_of(f.mesh);
      const auto& e = edges[std::uniform_int_distribution<std::size_t>(0, edges.size() - 1)(rng)];
      const int v = e[rng() % 2];
      const int op = static_cast<int>(rng() % 5);
      bool done = false;
      std::string name;
      switch (op) {
        case 0: name = "split"; done = split_edge(f.mesh, f.constraints, e[0], e[1], 10.0) >= 0; break;
        case 1: name = "collapse"; done = collapse_edge(f.mesh, f.constraints, v, e[0] + e[1] - v, 1e9); break;
        case 2: name = "swap"; done = swap_edge(f.mesh, e[0], e[1]); break;
        case 3: name = "smooth"; done = smooth_vertex(f.mesh, f.constraints, v); break;
        default: {
          // Push a vertex off its curve by a split on the chord, then ask for projection.
          name = "project";
          done = project_vertex(f.mesh, f.constraints, v, 10.0);
        }
      }
      if (!done) continue;
      ++committed[name];
      expect_invariants(f, name + " at step " + std::to_string(step) + " (seed " + std::to_string(seed) + ")");
      if (HasFatalFailure()) return;
      if (step % 300 == 299) {
        // Compaction keeps everything and reclaims the dead slots.
        std::map<int, Vec2> fixed;
        const auto remap = f.mesh.compact();
        for (const auto& [old, p] : f.fixed_positions)
          if (remap[old] >= 0) fixed[remap[old]] = p;
        f.fixed_positions = fixed;
        EXPECT_EQ(f.mesh.triangle_slots(), f.mesh.triangle_count());
        expect_invariants(f, "compaction");
        // Each incidence list in triangle order, its memory at least its size and at most twice
        // it (compaction keeps a list's memory only then); each tagged list by its other end.
        for (int w = 0; w < f.mesh.vertex_count(); ++w) {
          const auto& list = f.mesh.triangles_of(w);
          EXPECT_TRUE(std::is_sorted(list.begin(), list.end())) << "vertex " << w;
          EXPECT_LE(list.capacity(), 2 * list.size()) << "vertex " << w;
          const auto& tagged = f.mesh.tagged_edges(w);
          EXPECT_TRUE(std::is_sorted(tagged.begin(), tagged.end(),
                                     [](const TaggedEdge& x, const TaggedEdge& y) { return x.other < y.other; }));
        }
      }
    }
    // Each kind of operation was exercised, not just proposed.
    for (const char* name : {"split", "collapse", "swap", "smooth"}) EXPECT_GT(committed[name], 10) << name << ", seed " << seed;
  }
}

TEST(MeshOperations, RejectedOperationsLeaveNoTrace) {
  Fixture f = make_grid(6, 3);
  const auto before = f.mesh.sorted_features();
  std::vector<Vec2> points;
  for (int v = 0; v < f.mesh.vertex_count(); ++v) points.push_back(f.mesh.point(v));
  int rejected = 0;
  for (const auto& e : edges_of(f.mesh)) {
    // A fixed corner never collapses; tagged edges never swap.
    for (int from : {e[0], e[1]}) {
      if (f.mesh.tag(from).kind != VertexKind::fixed) continue;
      EXPECT_FALSE(collapse_edge(f.mesh, f.constraints, from, e[0] + e[1] - from, 1e9));
      ++rejected;
    }
    if (f.mesh.feature(e[0], e[1])) {
      EXPECT_FALSE(swap_edge(f.mesh, e[0], e[1]));
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 20);
  EXPECT_EQ(f.mesh.sorted_features(), before);
  for (int v = 0; v < f.mesh.vertex_count(); ++v) EXPECT_EQ(f.mesh.point(v), points[v]);
}

// Everything a TriMesh holds, incidence lists as sets (a rollback may reorder them).
struct MeshState {
  std::vector<Vec2> points;
  std::vector<VertexTag> tags;
  std::vector<bool> exact;
  std::vector<Triangle> triangles;
  std::vector<std::set<int>> incidence;
  std::vector<std::pair<std::array<int, 2>, EdgeFeature>> features;
  int alive = 0;
  bool operator==(const MeshState&) const = default;
};
MeshState state_of(const TriMesh& m) {
  MeshState s;
  for (int v = 0; v < m.vertex_count(); ++v) {
    s.points.push_back(m.point(v));
    s.tags.push_back(m.tag(v));
    s.exact.push_back(m.has_exact(v));
    s.incidence.emplace_back(m.triangles_of(v).begin(), m.triangles_of(v).end());
  }
  for (int t = 0; t < m.triangle_slots(); ++t) s.triangles.push_back(m.triangle(t));
  s.features = m.sorted_features();
  s.alive = m.triangle_count();
  return s;
}

// collapse_allowed_by_tags makes the tests of collapse_edge on tags and curves alone: where it
// refuses, collapse_edge refuses too and changes nothing; every collapse made was allowed. On
// every directed edge of grids whose curve may turn at most 10° and 1.5° per edge (the second
// refuses merging curve edges by turning).
TEST(MeshOperations, CollapseAllowedByTagsAgreesWithCollapseEdge) {
  int refused_by_kind = 0, refused_by_tags = 0, refused_by_turning = 0, refused_later = 0, made = 0;
  for (const double turning_deg : {10.0, 1.5})
    for (unsigned seed : {1u, 2u, 3u}) {
      Fixture f = make_grid(8, seed);
      f.constraints.max_turning = turning_deg * M_PI / 180;
      const MeshState original = state_of(f.mesh);
      for (const auto& e : edges_of(f.mesh))
        for (int from : {e[0], e[1]}) {
          const int to = e[0] + e[1] - from;
          for (const double bound : {10.0, 1e9}) {
            TriMesh copy = f.mesh;
            const bool by_kind = collapse_allowed_by_kind(copy, from, to);
            const bool allowed = collapse_allowed_by_tags(copy, f.constraints, from, to);
            if (!by_kind) {
              EXPECT_FALSE(allowed) << from << " -> " << to;
              ++refused_by_kind;
            }
            const bool done = collapse_edge(copy, f.constraints, from, to, bound);
            if (!allowed) {
              EXPECT_FALSE(done) << from << " -> " << to;
              EXPECT_TRUE(state_of(copy) == original) << from << " -> " << to;
              const EdgeFeature* g = f.mesh.feature(from, to);
              const bool along_curve = f.mesh.tag(from).kind == VertexKind::primary && g &&
                                       g->kind == EdgeKind::primary && g->source == f.mesh.tag(from).section;
              ++(along_curve ? refused_by_turning : refused_by_tags);
            } else if (done) {
              ++made;
            } else {
              ++refused_later;
            }
          }
        }
    }
  EXPECT_GT(refused_by_kind, 100);
  EXPECT_GT(refused_by_tags, refused_by_kind / 2);  // the tests after the kinds refuse too
  EXPECT_GT(refused_by_tags, 100);
  EXPECT_GT(refused_by_turning, 10);  // with α = 1.5°: two curve edges of the grid turn more
  EXPECT_GT(refused_later, 10);       // by energy, orientation, the link condition or the envelope
  EXPECT_GT(made, 100);
}

// A collapse with a test of the caller's: the test is asked only where the tags and curves allow
// the collapse, and only then; when it says yes the collapse is the one without it, when it says
// no nothing changes.
TEST(MeshOperations, TheCallersCollapseTestComesAfterTheTagsAndDecides) {
  int asked = 0, made = 0;
  for (unsigned seed : {1u, 2u}) {
    Fixture f = make_grid(8, seed);
    const MeshState original = state_of(f.mesh);
    for (const auto& e : edges_of(f.mesh))
      for (int from : {e[0], e[1]}) {
        const int to = e[0] + e[1] - from;
        const bool allowed = collapse_allowed_by_tags(f.mesh, f.constraints, from, to);
        TriMesh plain = f.mesh, yes = f.mesh, no = f.mesh;
        int calls = 0;
        const bool done = collapse_edge(plain, f.constraints, from, to, 10.0);
        const bool done_yes = collapse_edge(yes, f.constraints, from, to, 10.0, [&](int x, int y) {
          ++calls;
          EXPECT_EQ(x, from);
          EXPECT_EQ(y, to);
          return true;
        });
        EXPECT_EQ(calls, allowed ? 1 : 0) << from << " -> " << to;
        EXPECT_EQ(done_yes, done) << from << " -> " << to;
        EXPECT_TRUE(state_of(yes) == state_of(plain)) << from << " -> " << to;
        EXPECT_FALSE(collapse_edge(no, f.constraints, from, to, 10.0, [](int, int) { return false; }));
        EXPECT_TRUE(state_of(no) == original) << from << " -> " << to;
        asked += calls;
        made += done;
      }
  }
  EXPECT_GT(asked, 100);
  EXPECT_GT(made, 50);
}

// A swap given the triangle left of a -> b as a hint does what it does without one, and a wrong
// hint (any other triangle at a or b, a dead one, none at all) is ignored.
TEST(MeshOperations, ASwapHintIsCheckedAndChangesNothingElse) {
  int swapped = 0;
  for (unsigned seed : {1u, 2u, 3u}) {
    Fixture f = make_grid(8, seed);
    f.mesh.remove_triangle(0);  // a dead slot to hint at
    for (const auto& e : edges_of(f.mesh))
      for (const auto& [a, b] : {std::pair{e[0], e[1]}, std::pair{e[1], e[0]}}) {
        int left = -1;
        for (int t : f.mesh.triangles_of(a)) {
          const auto& tri = f.mesh.triangle(t);
          for (int i = 0; i < 3; ++i)
            if (tri[i] == a && tri[(i + 1) % 3] == b) left = t;
        }
        for (const double bound : {0.0, 1e9}) {
          TriMesh plain = f.mesh;
          const bool done = swap_edge(plain, a, b, bound);
          swapped += done;
          std::vector<int> hints{left, 0, f.mesh.triangle_slots(), -7};  // 0 is dead
          for (int v : {a, b}) hints.insert(hints.end(), f.mesh.triangles_of(v).begin(), f.mesh.triangles_of(v).end());
          for (const int hint : hints) {
            TriMesh hinted = f.mesh;
            EXPECT_EQ(swap_edge(hinted, a, b, bound, hint), done) << a << " -> " << b << ", hint " << hint;
            EXPECT_TRUE(state_of(hinted) == state_of(plain)) << a << " -> " << b << ", hint " << hint;
          }
        }
      }
  }
  EXPECT_GT(swapped, 100);
}

// The slots a swap names are the two triangles of the new diagonal, and they were the old
// diagonal's: after a rollback they hold the old triangles again. (The coarsening reads the
// energies before and after a swap from them.) A refused swap names nothing.
TEST(MeshOperations, ASwapNamesTheSlotsOfBothDiagonals) {
  const auto sorted = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  int swapped = 0, refused = 0;
  for (unsigned seed : {4u, 5u}) {
    Fixture f = make_grid(8, seed);
    for (const auto& e : edges_of(f.mesh)) {
      const int a = e[0], b = e[1];
      const std::vector<int> old = sorted(f.mesh.edge_triangles(a, b));
      std::array<int, 3> opposite{};  // the corner off (a, b) of each old triangle
      for (std::size_t k = 0; k < old.size(); ++k)
        for (int v : f.mesh.triangle(old[k]))
          if (v != a && v != b) opposite[k] = v;
      TriMesh m = f.mesh;
      std::array<int, 2> slots{-1, -1};
      m.open_journal();
      if (!swap_edge(m, a, b, 1e9, -1, &slots)) {
        m.commit();
        EXPECT_EQ(slots, (std::array<int, 2>{-1, -1}));
        ++refused;
        continue;
      }
      ++swapped;
      ASSERT_EQ(old.size(), 2u);
      EXPECT_EQ(sorted({slots[0], slots[1]}), old) << a << " - " << b;
      EXPECT_EQ(sorted(m.edge_triangles(opposite[0], opposite[1])), old) << a << " - " << b;
      EXPECT_TRUE(m.edge_triangles(a, b).empty());
      const std::array<mesh::Triangle, 2> before{f.mesh.triangle(slots[0]), f.mesh.triangle(slots[1])};
      m.rollback();
      EXPECT_EQ(m.triangle(slots[0]), before[0]);
      EXPECT_EQ(m.triangle(slots[1]), before[1]);
      EXPECT_EQ(sorted(m.edge_triangles(a, b)), old);
    }
  }
  EXPECT_GT(swapped, 50);
  EXPECT_GT(refused, 10);
}

TEST(MeshOperations, RolledBackOperationsLeaveTheMeshAsItWas) {
  // Runs of random committed operations under a journal: rolled back, the mesh is the one before
  // (every array and tag compared); committed, the changes stay.
  Fixture f = make_grid(8, 5);
  std::mt19937 rng(2024);
  int rolled_back = 0, changes = 0;
  for (int run = 0; run < 60; ++run) {
    const MeshState before = state_of(f.mesh);
    f.mesh.open_journal();
    int done = 0;
    for (int step = 0; step < 12; ++step) {
      const auto edges = edges_of(f.mesh);
      const auto& e = edges[std::uniform_int_distribution<std::size_t>(0, edges.size() - 1)(rng)];
      const int v = e[rng() % 2];
      switch (rng() % 4) {
        case 0: done += split_edge(f.mesh, f.constraints, e[0], e[1], 10.0) >= 0; break;
        case 1: done += collapse_edge(f.mesh, f.constraints, v, e[0] + e[1] - v, 1e9); break;
        case 2: done += swap_edge(f.mesh, e[0], e[1], 1e9); break;
        default: done += smooth_vertex(f.mesh, f.constraints, v);
      }
    }
    changes += done;
    if (run % 3 == 2) {
      f.mesh.commit();
      EXPECT_FALSE(f.mesh.journal_open());
      if (done > 0) {
        EXPECT_NE(state_of(f.mesh), before);
      }
      expect_invariants(f, "commit");
    } else {
      f.mesh.rollback();
      ++rolled_back;
      ASSERT_TRUE(state_of(f.mesh) == before) << "run " << run << " (" << done << " operations)";
      expect_invariants(f, "rollback");
    }
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(rolled_back, 40);
  EXPECT_GT(changes, 200);
  // A compaction with an open journal is refused.
  f.mesh.open_journal();
  EXPECT_THROW(f.mesh.compact(), std::logic_error);
  f.mesh.rollback();
}

// Levels nest: random operations, each level opened inside the last, with stores attached to
// the mesh's journal changed beside it (a value per vertex, an entry per edge, as the curve stage
// keeps its nodes). Rolling a level back restores the mesh and the stores as they were when that
// level opened, whatever the inner levels did and whether they were committed or rolled back.
TEST(MeshOperations, NestedJournalLevelsRollBackAlone) {
  Fixture f = make_grid(8, 7);
  mesh::JournaledVector<double> weight(f.mesh.journal());
  mesh::JournaledMap<std::uint64_t, int> label(f.mesh.journal());
  weight.assign(std::vector<double>(f.mesh.vertex_count(), 1.0));
  struct Level {
    MeshState mesh;
    std::vector<double> weights;
    std::map<std::uint64_t, int> labels;
  };
  std::set<std::uint64_t> keys;  // every key ever labelled
  const auto labels = [&] {
    std::map<std::uint64_t, int> out;
    for (const auto k : keys)
      if (const int* x = label.find(k)) out[k] = *x;
    return out;
  };
  std::mt19937 rng(77);
  std::vector<Level> open;
  int rolled_back = 0, committed = 0, deepest = 0;
  for (int step = 0; step < 600; ++step) {
    const unsigned action = rng() % 10;
    if (action < 3 && open.size() < 4) {
      open.push_back({state_of(f.mesh), weight.values(), labels()});
      f.mesh.open_journal();
      deepest = std::max(deepest, static_cast<int>(open.size()));
    } else if (action < 5 && !open.empty()) {
      f.mesh.rollback();
      ASSERT_TRUE(state_of(f.mesh) == open.back().mesh) << "step " << step << ", depth " << open.size();
      ASSERT_EQ(weight.values(), open.back().weights) << "step " << step;
      ASSERT_EQ(labels(), open.back().labels) << "step " << step;
      open.pop_back();
      ++rolled_back;
    } else if (action < 6 && !open.empty()) {
      f.mesh.commit();
      open.pop_back();
      ++committed;
    } else {
      const auto edges = edges_of(f.mesh);
      const auto& e = edges[std::uniform_int_distribution<std::size_t>(0, edges.size() - 1)(rng)];
      if (rng() % 2) split_edge(f.mesh, f.constraints, e[0], e[1], 10.0);
      else swap_edge(f.mesh, e[0], e[1], 1e9);
      weight.resize(f.mesh.vertex_count(), 0.5);
      weight.set(e[0], weight[e[0]] + 1);
      const auto key = mesh::edge_key(e[0], e[1]);
      keys.insert(key);
      if (rng() % 3) label.set(key, step);
      else label.erase(key);
    }
    EXPECT_EQ(f.mesh.journal_open(), !open.empty());
    if (HasFatalFailure()) return;
  }
  while (!open.empty()) f.mesh.commit(), open.pop_back();
  expect_invariants(f, "nested");
  EXPECT_GT(rolled_back, 50);
  EXPECT_GT(committed, 20);
  EXPECT_EQ(deepest, 4);
  EXPECT_THROW(f.mesh.commit(), std::logic_error);
}

// The element the curve stage starts from and the optimization foresees (mesh::curved_element):
// along the followed edge its map is the curve itself, at the matching parameter (the section is
// a cubic in its parameter, and the nodes at its thirds make the P3 edge reproduce it), whichever
// way the triangle runs along the edge; along every other edge it is the chord.
TEST(MeshOperations, TheCurvedElementFollowsItsCurveAndNothingElse) {
  Fixture f = make_grid(9, 3);
  const std::array<Vec2, 3> reference{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  int followed = 0, straight = 0, forwards = 0, backwards = 0;
  for (int t = 0; t < f.mesh.triangle_slots(); ++t) {
    const mesh::Triangle& tri = f.mesh.triangle(t);
    const int edge = mesh::followed_edge(f.mesh, tri);
    const geometry::P3Nodes p = mesh::curved_element(f.mesh, f.constraints, t);
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      for (double s : {0.1, 0.25, 0.5, 0.8}) {
        const Vec2 x = geometry::p3_map(p, (1 - s) * reference[i].x() + s * reference[(i + 1) % 3].x(),
                                        (1 - s) * reference[i].y() + s * reference[(i + 1) % 3].y());
        Vec2 expected = (1 - s) * f.mesh.point(a) + s * f.mesh.point(b);
        if (i == edge) {
          const mesh::EdgeFeature& e = *f.mesh.feature(a, b);
          const double ta = a < b ? e.t_lo : e.t_hi, tb = a < b ? e.t_hi : e.t_lo;
          expected = f.constraints.sections[e.source].eval(ta + s * (tb - ta));
        }
        EXPECT_LE((x - expected).norm(), 1e-12) << "triangle " << t << ", edge " << i << ", s " << s;
      }
      if (i == edge) ++followed, (a < b ? forwards : backwards)++;
      else ++straight;
    }
  }
  EXPECT_GT(followed, 10);
  EXPECT_GT(forwards, 3);
  EXPECT_GT(backwards, 3);
  EXPECT_GT(straight, 100);
}

TEST(MeshOperations, SplitOfAPrimaryEdgeLandsOnTheCurve) {
  Fixture f = make_grid(6, 4);
  for (const auto& [edge, feat] : f.mesh.sorted_features()) {
    if (feat.kind != EdgeKind::primary) continue;
    const int v = split_edge(f.mesh, f.constraints, edge[0], edge[1], 10.0);
    ASSERT_GE(v, 0);
    const VertexTag tag = f.mesh.tag(v);
    EXPECT_EQ(tag.kind, VertexKind::primary);
    EXPECT_DOUBLE_EQ(tag.t, 0.5 * (feat.t_lo + feat.t_hi));
    EXPECT_TRUE(tag.on_curve);
    EXPECT_LE((f.constraints.sections[0].eval(tag.t) - f.mesh.point(v)).norm(), 1e-15);
    break;
  }
  expect_invariants(f, "split");
}

TEST(MeshOperations, SecondaryVertexCannotLeaveTheEnvelope) {
  Fixture f = make_grid(8, 5);
  // A secondary vertex in the column: smoothing it many times keeps it within ε of x = 0.5.
  for (int round = 0; round < 50; ++round)
    for (int v = 0; v < f.mesh.vertex_count(); ++v) smooth_vertex(f.mesh, f.constraints, v);
  expect_invariants(f, "smoothing");
}

TEST(MeshOperations, SmoothingLowersTheEnergyOfAFreeVertex) {
  TriMesh m;
  // A hexagon around a badly placed centre.
  std::vector<int> ring;
  for (int k = 0; k < 6; ++k) {
    VertexTag tag;
    tag.kind = VertexKind::fixed;
    ring.push_back(m.add_vertex(Vec2(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)), tag));
  }
  const int c = m.add_vertex(Vec2(0.6, 0.1));
  for (int k = 0; k < 6; ++k) m.add_triangle(c, ring[k], ring[(k + 1) % 6]);
  Constraints constraints;
  for (int it = 0; it < 20; ++it) smooth_vertex(m, constraints, c);
  EXPECT_LE(m.point(c).norm(), 1e-6);
}

}  // namespace
}  // namespace curvemesh::mesh

namespace curvemesh::mesh {
namespace {

// An empty mesh in the box [−1, 2] × [−2, 2], its input the secondary segments of `envelope`.
Fixture around_segments(geometry::SegmentEnvelope envelope) {
  Fixture f;
  f.constraints.envelope = std::move(envelope);
  f.constraints.box.add(Vec2(-1, -2));
  f.constraints.box.add(Vec2(2, 2));
  f.constraints.max_turning = 10.0 * M_PI / 180;
  return f;
}

VertexTag tag_of_kind(VertexKind kind) {
  VertexTag tag;
  tag.kind = kind;
  return tag;
}

// A secondary chord a–b with a flat triangle a–b–x above it whose other sides are tagged too.
Fixture chord_beside_path(double x_height) {
  Fixture f = around_segments(geometry::SegmentEnvelope({{Vec2(0, 0), Vec2(1, 0)}}, 0.004));
  const VertexTag fixed = tag_of_kind(VertexKind::fixed), secondary = tag_of_kind(VertexKind::secondary);
  const int a = f.mesh.add_vertex(Vec2(0, 0), fixed), b = f.mesh.add_vertex(Vec2(1, 0), fixed);
  const int x = f.mesh.add_vertex(Vec2(0.5, x_height), secondary), y = f.mesh.add_vertex(Vec2(0.5, -1), VertexTag{});
  f.mesh.add_triangle(a, b, x);
  f.mesh.add_triangle(a, y, b);
  for (const auto& [p, q] : {std::pair{a, b}, std::pair{a, x}, std::pair{x, b}}) f.mesh.set_feature(p, q, {EdgeKind::secondary, -1, 0});
  return f;
}

TEST(MeshOperations, SecondaryChordIsReleasedOnlyWhenThePathBesideItStaysInTheEnvelope) {
  Fixture inside = chord_beside_path(0.001);
  EXPECT_TRUE(release_secondary_edge(inside.mesh, inside.constraints, 0, 1));
  EXPECT_EQ(inside.mesh.feature(0, 1), nullptr);
  EXPECT_NE(inside.mesh.feature(0, 2), nullptr);
  // x still has its secondary edges, so it stays secondary.
  EXPECT_EQ(inside.mesh.tag(2).kind, VertexKind::secondary);

  Fixture outside = chord_beside_path(0.01);  // the path a–x–b leaves the ε = 0.004 envelope
  EXPECT_FALSE(release_secondary_edge(outside.mesh, outside.constraints, 0, 1));
  EXPECT_NE(outside.mesh.feature(0, 1), nullptr);
}

// The chord a–b stands for curve 0, the path a–x–b beside it for curve 1, a polyline from a up to
// x, 10ε above the chord's middle, and down to b: the path is inside the union of the two
// curves' envelopes, not inside curve 0's. Released, the chord would leave curve 0's middle 10ε
// from any tagged edge; so it stays.
TEST(MeshOperations, SecondaryChordStaysWhenThePathBesideItFollowsAnotherCurve) {
  Fixture f = chord_beside_path(0.04);
  f.constraints.envelope = geometry::SegmentEnvelope(
      {{Vec2(0, 0), Vec2(1, 0)}, {Vec2(0, 0), Vec2(0.5, 0.04)}, {Vec2(0.5, 0.04), Vec2(1, 0)}}, 0.004, {0, 1, 1});
  f.mesh.set_feature(0, 1, {EdgeKind::secondary, 0, 0});
  f.mesh.set_feature(0, 2, {EdgeKind::secondary, 1, 1});
  f.mesh.set_feature(2, 1, {EdgeKind::secondary, 1, 2});
  EXPECT_FALSE(release_secondary_edge(f.mesh, f.constraints, 0, 1));
  ASSERT_NE(f.mesh.feature(0, 1), nullptr);
  // Were the path curve 0's own, the chord would go.
  f.mesh.set_feature(0, 2, {EdgeKind::secondary, 0, 1});
  f.mesh.set_feature(2, 1, {EdgeKind::secondary, 0, 2});
  f.constraints.envelope = geometry::SegmentEnvelope(
      {{Vec2(0, 0), Vec2(1, 0)}, {Vec2(0, 0), Vec2(0.5, 0.04)}, {Vec2(0.5, 0.04), Vec2(1, 0)}}, 0.004, {0, 0, 0});
  EXPECT_TRUE(release_secondary_edge(f.mesh, f.constraints, 0, 1));
  EXPECT_FALSE(f.mesh.structure_error());
}

// Vertex v on curve 0 (a–v–b along y = 0) collapses onto w, on curve 1 (a–w–b, 1.5ε above v):
// its edges would merge into curve 1's, inside the union of the two envelopes but not inside
// curve 0's, which would be left 1.5ε from the mesh. Refused; w 0.5ε above v, it goes.
TEST(MeshOperations, ASecondaryEdgeDoesNotMergeIntoAnotherCurvesEdgeOutsideItsOwnEnvelope) {
  for (const double height : {0.006, 0.002}) {
    Fixture f = around_segments(geometry::SegmentEnvelope(
        {{Vec2(0, 0), Vec2(1, 0)}, {Vec2(0, 0), Vec2(0.5, height)}, {Vec2(0.5, height), Vec2(1, 0)}}, 0.004, {0, 1, 1}));
    const VertexTag fixed = tag_of_kind(VertexKind::fixed), secondary = tag_of_kind(VertexKind::secondary);
    const int a = f.mesh.add_vertex(Vec2(0, 0), fixed), b = f.mesh.add_vertex(Vec2(1, 0), fixed);
    const int v = f.mesh.add_vertex(Vec2(0.5, 0), secondary), w = f.mesh.add_vertex(Vec2(0.5, height), secondary);
    const int below = f.mesh.add_vertex(Vec2(0.5, -1), fixed), above = f.mesh.add_vertex(Vec2(0.5, 1), fixed);
    for (const auto& t : {std::array{a, v, w}, std::array{v, b, w}, std::array{a, below, v}, std::array{v, below, b},
                          std::array{a, w, above}, std::array{w, b, above}})
      f.mesh.add_triangle(t[0], t[1], t[2]);
    f.mesh.set_feature(a, v, {EdgeKind::secondary, 0, 0});
    f.mesh.set_feature(v, b, {EdgeKind::secondary, 0, 0});
    f.mesh.set_feature(a, w, {EdgeKind::secondary, 1, 1});
    f.mesh.set_feature(w, b, {EdgeKind::secondary, 1, 2});
    ASSERT_FALSE(f.mesh.structure_error());
    EXPECT_EQ(collapse_edge(f.mesh, f.constraints, v, w, 1e9), height < 0.004) << height;
    EXPECT_FALSE(f.mesh.structure_error());
  }
}

// The same chord with x on no feature (a fixed point, say, or a free vertex) 1e-13 above it: the
// secondary tag moves onto a–x–b, once, and the flat triangle can then be swapped away.
TEST(MeshOperations, SecondaryChordMovesOntoAnUntaggedApexInsideTheEnvelope) {
  for (VertexKind kind : {VertexKind::fixed, VertexKind::free}) {
    Fixture f = chord_beside_path(1e-13);
    f.mesh.clear_feature(0, 2);
    f.mesh.clear_feature(2, 1);
    VertexTag tag;
    tag.kind = kind;
    f.mesh.set_tag(2, tag);
    ASSERT_TRUE(release_secondary_edge(f.mesh, f.constraints, 0, 1));
    EXPECT_EQ(f.mesh.feature(0, 1), nullptr);
    ASSERT_NE(f.mesh.feature(0, 2), nullptr);
    ASSERT_NE(f.mesh.feature(2, 1), nullptr);
    EXPECT_EQ(f.mesh.feature(0, 2)->kind, EdgeKind::secondary);
    EXPECT_EQ(f.mesh.tag(2).kind, kind == VertexKind::free ? VertexKind::secondary : VertexKind::fixed);
    // The short edges are not the triangle's longest: they do not move back onto a–b.
    EXPECT_FALSE(release_secondary_edge(f.mesh, f.constraints, 0, 2));
    EXPECT_FALSE(release_secondary_edge(f.mesh, f.constraints, 2, 1));
    EXPECT_EQ(f.mesh.feature(0, 1), nullptr);
    EXPECT_FALSE(f.mesh.structure_error());
  }
  // A primary x on its curve becomes a crossing (fixed); one still off its curve stays as it is.
  Fixture crossing = chord_beside_path(1e-13);
  crossing.mesh.clear_feature(0, 2);
  crossing.mesh.clear_feature(2, 1);
  VertexTag on;
  on.kind = VertexKind::primary;
  crossing.mesh.set_tag(2, on);
  EXPECT_TRUE(release_secondary_edge(crossing.mesh, crossing.constraints, 0, 1));
  EXPECT_EQ(crossing.mesh.tag(2).kind, VertexKind::fixed);
  // Not flat (1e-6 above a chord of length 1, inside ε all the same): nothing moves.
  Fixture raised = chord_beside_path(1e-6);
  raised.mesh.clear_feature(0, 2);
  raised.mesh.clear_feature(2, 1);
  raised.mesh.set_tag(2, VertexTag{});
  EXPECT_FALSE(release_secondary_edge(raised.mesh, raised.constraints, 0, 1));
  // Beyond the envelope, or with x off its primary curve, nothing moves.
  Fixture far = chord_beside_path(0.01);
  far.mesh.clear_feature(0, 2);
  far.mesh.clear_feature(2, 1);
  far.mesh.set_tag(2, VertexTag{});
  EXPECT_FALSE(release_secondary_edge(far.mesh, far.constraints, 0, 1));
  Fixture primary = chord_beside_path(1e-13);
  primary.mesh.clear_feature(0, 2);
  primary.mesh.clear_feature(2, 1);
  VertexTag off_curve;
  off_curve.kind = VertexKind::primary;
  off_curve.on_curve = false;
  primary.mesh.set_tag(2, off_curve);
  EXPECT_FALSE(release_secondary_edge(primary.mesh, primary.constraints, 0, 1));
}

}  // namespace
}  // namespace curvemesh::mesh

namespace curvemesh::mesh {
namespace {

// A vertex whose exact position rounds onto its neighbour's (two features 1e-20 apart) can
// never be rounded; collapsing it into that neighbour removes it, and the mesh keeps no exact
// vertex and stays valid (orientation is decided on what stays).
TEST(MeshOperations, AnExactVertexCollapsesIntoItsNeighbour) {
  TriMesh m;
  VertexTag fixed;
  fixed.kind = VertexKind::fixed;
  const int a = m.add_vertex(Vec2(0, 0), fixed), b = m.add_vertex(Vec2(1, 0), fixed);
  const int c = m.add_vertex(Vec2(1, 1), fixed), d = m.add_vertex(Vec2(0, 1), fixed);
  const int x = m.add_vertex(Vec2(0.5, 0.5));
  m.set_exact_position(x, ExactPoint(mpq_class(1, 2) + mpq_class(1, 100000) / mpq_class("100000000000000000"), mpq_class(1, 2)));
  const int y = m.add_vertex(Vec2(0.5, 0.5));  // x's double
  for (const Triangle& t : {Triangle{a, b, x}, Triangle{b, c, y}, Triangle{c, d, y}, Triangle{d, a, x},
                            Triangle{y, b, x}, Triangle{y, x, d}})
    m.add_triangle(t[0], t[1], t[2]);
  ASSERT_FALSE(m.structure_error()) << *m.structure_error();
  ASSERT_EQ(m.exact_vertex_count(), 1);
  Constraints constraints;
  ASSERT_TRUE(collapse_edge(m, constraints, x, y, 1e9));
  m.compact();
  EXPECT_EQ(m.exact_vertex_count(), 0);
  EXPECT_EQ(m.vertex_count(), 5);
  EXPECT_FALSE(m.structure_error());
}

}  // namespace
}  // namespace curvemesh::mesh
