// The optimizer lists every edge once (its mean edge length, splits, collapses and swaps all go
// through that list). The list asks for hull edges only where both ends are on the box and checks
// with Euler's formula that none was missed; these meshes test that shortcut and its fallback
// against the edges counted here from the triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>

#include "optimize/optimize.hpp"

namespace curvemesh::optimize {
namespace {

using mesh::TriMesh;
using mesh::VertexKind;
using mesh::VertexTag;

double mean_edge_length_counted_here(const TriMesh& m) {
  std::set<std::pair<int, int>> edges;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(tri[i], tri[(i + 1) % 3]));
  }
  double sum = 0;
  for (const auto& [a, b] : edges) sum += (m.point(a) - m.point(b)).norm();
  return sum / static_cast<double>(edges.size());
}

// An (n+1)² grid on [0, n]², each square cut along the diagonal that alternates, so that hull
// edges run both up and down in vertex order. With `tag_box`, the border is tagged as the
// triangulation tags the box (boundary edges, boundary vertices, fixed corners); without, every
// vertex is free. Squares in `holes` are left out.
TriMesh grid(int n, bool tag_box, const std::set<std::pair<int, int>>& holes = {}) {
  TriMesh m;
  const auto at = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      VertexTag tag;
      const bool side_x = i == 0 || i == n, side_y = j == 0 || j == n;
      if (tag_box && (side_x || side_y)) tag.kind = side_x && side_y ? VertexKind::fixed : VertexKind::boundary;
      m.add_vertex(geometry::Vec2(i, j), tag);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (holes.count({i, j})) continue;
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.add_triangle(a, b, c);
        m.add_triangle(a, c, d);
      } else {
        m.add_triangle(a, b, d);
        m.add_triangle(b, c, d);
      }
    }
  if (tag_box)
    for (int k = 0; k < n; ++k) {
      m.set_feature(at(k, 0), at(k + 1, 0), {mesh::EdgeKind::boundary, -1, 0});
      m.set_feature(at(n, k), at(n, k + 1), {mesh::EdgeKind::boundary, -1, 1});
      m.set_feature(at(k, n), at(k + 1, n), {mesh::EdgeKind::boundary, -1, 2});
      m.set_feature(at(0, k), at(0, k + 1), {mesh::EdgeKind::boundary, -1, 3});
    }
  return m;
}

TEST(OptimizeEdges, TheBoxHullIsFoundFromItsTags) {
  const TriMesh m = grid(4, true);
  ASSERT_FALSE(m.structure_error());
  EXPECT_NEAR(measure(m).mean_edge_length, mean_edge_length_counted_here(m), 1e-12);
}

TEST(OptimizeEdges, AHullWithoutTagsIsFoundByTheFallback) {
  const TriMesh m = grid(4, false);
  ASSERT_FALSE(m.structure_error());
  EXPECT_NEAR(measure(m).mean_edge_length, mean_edge_length_counted_here(m), 1e-12);
}

TEST(OptimizeEdges, AMeshWithAHoleIsNotADiskAndKeepsEveryEdge) {
  // The box is tagged, but the hole's border is a hull with no tag, and V - E + T = 0.
  const TriMesh m = grid(4, true, {{1, 1}, {1, 2}});
  ASSERT_FALSE(m.structure_error());
  EXPECT_NEAR(measure(m).mean_edge_length, mean_edge_length_counted_here(m), 1e-12);
}

}  // namespace
}  // namespace curvemesh::optimize
