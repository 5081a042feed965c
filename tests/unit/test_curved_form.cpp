// The curved form of a mesh (mesh/curved_form.hpp): after any sequence of local operations it
// holds, for every triangle, the element App. C's rule gives (checked against
// mesh::curved_element, which computes it from the linear mesh alone), shared edges share their
// nodes, and journal levels nested three deep each take back the mesh and its nodes alone.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "grid_fixture.hpp"
#include "mesh/curved_element.hpp"
#include "mesh/curved_form.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::mesh {
namespace {

using fixture::Fixture;
using fixture::make_grid;

// Everything the form holds that a caller can read, per alive triangle (its corners in the mesh,
// its nodes' positions) and per edge (whether it follows its curve, its node ids).
struct FormState {
  std::map<int, std::pair<Triangle, std::vector<Vec2>>> triangles;
  std::map<std::uint64_t, std::pair<bool, std::pair<int, int>>> edges;
  bool operator==(const FormState&) const = default;
};

FormState state_of(const TriMesh& m, const CurvedForm& form) {
  FormState s;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const geometry::P3Nodes p = form.p3(t);
    s.triangles[t] = {m.triangle(t), std::vector<Vec2>(p.begin(), p.end())};
    for (int i = 0; i < 3; ++i) {
      const int a = m.triangle(t)[i], b = m.triangle(t)[(i + 1) % 3];
      s.edges[edge_key(a, b)] = {form.follows(a, b), form.edge_nodes(std::min(a, b), std::max(a, b))};
    }
  }
  return s;
}

// One random split, swap or collapse, its triangles given to the form; false (and nothing changed,
// the caller rolls back) when the mesh or the form refuses it.
bool random_operation(Fixture& f, CurvedForm& form, std::mt19937& rng) {
  TriMesh& m = f.mesh;
  std::vector<std::array<int, 2>> edges;
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t))
      for (int i = 0; i < 3; ++i) edges.push_back({m.triangle(t)[i], m.triangle(t)[(i + 1) % 3]});
  const auto [a, b] = edges[std::uniform_int_distribution<std::size_t>(0, edges.size() - 1)(rng)];
  const int vertices = m.vertex_count();
  std::vector<int> changed;
  switch (rng() % 3) {
    case 0: {
      const int mid = split_edge(m, f.constraints, a, b, 1e9);
      if (mid < 0) return false;
      changed = m.triangles_of(mid);
      break;
    }
    case 1:
      changed = m.edge_triangles(a, b);
      if (!swap_edge(m, a, b, 1e9)) return false;
      break;
    default:
      for (int u : m.triangles_of(a))
        if (std::find(m.triangle(u).begin(), m.triangle(u).end(), b) == m.triangle(u).end())
          changed.push_back(u);
      if (!collapse_edge(m, f.constraints, a, b, 1e9)) return false;
  }
  std::vector<double> known;
  return form.adopt(vertices, changed, known);
}

// Every alive triangle's element is App. C's: corners, edge nodes on the curve along an edge that
// follows it and on the chord elsewhere (mesh::curved_element), the centre one of the candidates
// where an edge follows a curve and the centroid otherwise; an edge's nodes are the same ids from
// both its triangles.
void expect_the_element_rule(const Fixture& f, const CurvedForm& form, int step) {
  const TriMesh& m = f.mesh;
  std::map<std::uint64_t, std::pair<int, int>> edge_ids;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const Triangle& tri = m.triangle(t);
    const int followed = form.curved_edge_of(tri);
    ASSERT_EQ(followed, followed_edge(m, tri)) << "step " << step << ", triangle " << t;
    const geometry::P3Nodes expected = curved_element(m, f.constraints, t, followed);
    const geometry::P3Nodes p = form.p3(t);
    for (int i = 0; i < 9; ++i)
      ASSERT_LE((p[i] - expected[i]).norm(), 1e-14)
          << "step " << step << ", triangle " << t << ", node " << i;
    if (followed < 0) {
      ASSERT_LE((p[9] - expected[9]).norm(), 1e-14) << "step " << step << ", triangle " << t;
    } else {
      const auto candidates = geometry::p3_centre_candidates(expected);
      ASSERT_TRUE(std::find(candidates.begin(), candidates.end(), p[9]) != candidates.end())
          << "step " << step;
    }
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      const auto ids = form.edge_nodes(std::min(a, b), std::max(a, b));
      const auto [it, inserted] = edge_ids.try_emplace(edge_key(a, b), ids);
      ASSERT_TRUE(inserted || it->second == ids) << "step " << step << ": edge nodes not shared";
    }
  }
}

// Every triangle of the fixture given its nodes, centres chosen where an edge follows a curve.
void give_every_triangle_its_nodes(const Fixture& f, CurvedForm& form) {
  for (int t = 0; t < f.mesh.triangle_slots(); ++t) {
    const Triangle& tri = f.mesh.triangle(t);
    form.push_triangle(tri, (f.mesh.point(tri[0]) + f.mesh.point(tri[1]) + f.mesh.point(tri[2])) / 3, 1.0);
    if (form.curved_edge_of(tri) >= 0) form.choose_centre(t);
  }
}

TEST(CurvedForm, EveryOperationLeavesTheElementOfAppendixC) {
  Fixture f = make_grid(9, 5);
  CurvedForm form(f.mesh, f.constraints, 3);
  give_every_triangle_its_nodes(f, form);
  expect_the_element_rule(f, form, -1);
  std::mt19937 rng(11);
  int kept = 0, refused = 0;
  for (int step = 0; step < 400; ++step) {
    f.mesh.open_journal();
    const FormState before = state_of(f.mesh, form);
    if (random_operation(f, form, rng)) {
      f.mesh.commit();
      ++kept;
    } else {
      f.mesh.rollback();
      ASSERT_TRUE(state_of(f.mesh, form) == before) << "step " << step;
      ++refused;
    }
    expect_the_element_rule(f, form, step);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(kept, 100);
  EXPECT_GT(refused, 10);
}

// A proposal, its repair and a proposal inside the repair: each level taken back alone leaves the
// mesh and its curved form exactly as they were when it opened.
TEST(CurvedForm, NestedLevelsTakeBackTheNodesWithTheMesh) {
  Fixture f = make_grid(8, 3);
  CurvedForm form(f.mesh, f.constraints, 3);
  give_every_triangle_its_nodes(f, form);
  std::mt19937 rng(29);
  std::vector<FormState> open;
  int rolled_back = 0, deepest = 0;
  for (int step = 0; step < 500; ++step) {
    const unsigned action = rng() % 10;
    if (action < 3 && open.size() < 3) {
      open.push_back(state_of(f.mesh, form));
      f.mesh.open_journal();
      deepest = std::max(deepest, static_cast<int>(open.size()));
    } else if (action < 5 && !open.empty()) {
      f.mesh.rollback();
      ASSERT_TRUE(state_of(f.mesh, form) == open.back()) << "step " << step << ", depth " << open.size();
      open.pop_back();
      ++rolled_back;
    } else if (action < 6 && !open.empty()) {
      f.mesh.commit();
      open.pop_back();
    } else if (!open.empty()) {
      // An operation inside the innermost level, or a corner moved (a smoothing step).
      if (rng() % 2) {
        f.mesh.open_journal();
        if (random_operation(f, form, rng))
          f.mesh.commit();
        else
          f.mesh.rollback();
      } else {
        const int v = static_cast<int>(rng() % f.mesh.vertex_count());
        if (!f.mesh.triangles_of(v).empty() && f.mesh.tag(v).kind == VertexKind::free)
          form.place_corner(v, form.at(v) + Vec2(1e-4, -1e-4));
      }
    }
  }
  EXPECT_GT(rolled_back, 40);
  EXPECT_EQ(deepest, 3);
}

}  // namespace
}  // namespace curvemesh::mesh
