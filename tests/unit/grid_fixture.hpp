#pragma once
// A jittered grid mesh with every kind of tag (a primary curve row, a secondary column, the box
// border) and a check of every invariant on it that does not trust the mesh's own predicates
// (orientation with GMP rationals computed here): for the property tests of the operations and
// of the passes built on them.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "mesh/constraints.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::mesh::fixture {

using geometry::CubicBezier;

inline int exact_sign(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  const mpq_class det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return sgn(det);
}

// A jittered (n+1)² grid on the unit square. Row `curve_row` lies on a gently curved primary
// section, column `n / 2` is a secondary segment (x = 0.5), the border is tagged boundary.
struct Fixture {
  TriMesh mesh;
  Constraints constraints;
  std::map<int, Vec2> fixed_positions;
};

inline Fixture make_grid(int n, unsigned seed) {
  Fixture f;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2 / n, 0.2 / n);
  const int curve_row = n / 3, secondary_column = n / 2;
  SectionCurve curve;
  curve.piece = CubicBezier(Vec2(0, 0.3), Vec2(0.35, 0.36), Vec2(0.65, 0.26), Vec2(1, 0.32));
  curve.t0 = 0.0;
  curve.t1 = 1.0;
  f.constraints.sections.push_back(curve);
  f.constraints.envelope = geometry::SegmentEnvelope({{Vec2(0.5, 0.0), Vec2(0.5, 1.0)}}, 0.004);
  f.constraints.box.add(Vec2(0, 0));
  f.constraints.box.add(Vec2(1, 1));
  f.constraints.max_turning = 10.0 * M_PI / 180;

  std::vector<int> id((n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = double(i) / n;
      Vec2 p(u, double(j) / n);
      VertexTag tag;
      const bool border_x = i == 0 || i == n, border_y = j == 0 || j == n;
      if (border_x && border_y) {
        tag.kind = VertexKind::fixed;
      } else if (j == curve_row) {
        // The curve is parametrised by u here only approximately; put the vertex on it.
        p = curve.eval(u);
        tag.kind = (border_x || i == secondary_column) ? VertexKind::fixed : VertexKind::primary;
        tag.section = 0;
        tag.t = u;
      } else if (border_x || border_y) {
        tag.kind = VertexKind::boundary;
        tag.side = j == 0 ? 0 : i == n ? 1 : j == n ? 2 : 3;
      } else if (i == secondary_column) {
        tag.kind = VertexKind::secondary;
      } else {
        p += Vec2(jitter(rng), jitter(rng));
      }
      id[j * (n + 1) + i] = f.mesh.add_vertex(p, tag);
      if (tag.kind == VertexKind::fixed) f.fixed_positions[id[j * (n + 1) + i]] = p;
    }
  const auto at = [&](int i, int j) { return id[j * (n + 1) + i]; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        f.mesh.add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        f.mesh.add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      } else {
        f.mesh.add_triangle(at(i, j), at(i + 1, j), at(i, j + 1));
        f.mesh.add_triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  for (int k = 0; k < n; ++k) {
    f.mesh.set_feature(at(k, 0), at(k + 1, 0), {EdgeKind::boundary, -1, 0});
    f.mesh.set_feature(at(n, k), at(n, k + 1), {EdgeKind::boundary, -1, 1});
    f.mesh.set_feature(at(k, n), at(k + 1, n), {EdgeKind::boundary, -1, 2});
    f.mesh.set_feature(at(0, k), at(0, k + 1), {EdgeKind::boundary, -1, 3});
    const int a = at(k, curve_row), b = at(k + 1, curve_row);
    const double ta = double(k) / n, tb = double(k + 1) / n;
    f.mesh.set_feature(a, b, {EdgeKind::primary, 0, 0, a < b ? ta : tb, a < b ? tb : ta});
    if (k != curve_row && k + 1 != curve_row)
      f.mesh.set_feature(at(secondary_column, k), at(secondary_column, k + 1), {EdgeKind::secondary, -1, 0});
  }
  // The secondary column crosses the curve row: its two edges there are tagged too.
  f.mesh.set_feature(at(secondary_column, curve_row - 1), at(secondary_column, curve_row), {EdgeKind::secondary, -1, 0});
  f.mesh.set_feature(at(secondary_column, curve_row), at(secondary_column, curve_row + 1), {EdgeKind::secondary, -1, 0});
  return f;
}

// Every invariant, checked independently of the mesh's own bookkeeping where it matters.
inline void expect_invariants(const Fixture& f, const std::string& after) {
  const TriMesh& m = f.mesh;
  const auto error = m.structure_error();
  ASSERT_FALSE(error) << after << ": " << *error;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    ASSERT_EQ(exact_sign(m.exact_or_double(tri[0]), m.exact_or_double(tri[1]), m.exact_or_double(tri[2])), 1)
        << after << ": triangle " << t << " not counter-clockwise";
  }
  for (const auto& [edge, feat] : m.sorted_features()) {
    const Vec2 a = m.point(edge[0]), b = m.point(edge[1]);
    switch (feat.kind) {
      case EdgeKind::secondary:
        // Within ε of x = 0.5 (the single input segment): checked directly.
        ASSERT_LE(std::abs(a.x() - 0.5), 0.004) << after;
        ASSERT_LE(std::abs(b.x() - 0.5), 0.004) << after;
        break;
      case EdgeKind::primary:
        ASSERT_LE(f.constraints.sections[0].turning(feat.t_lo, feat.t_hi), f.constraints.max_turning + 1e-9) << after;
        break;
      case EdgeKind::boundary: {
        const int axis = (feat.source == 0 || feat.source == 2) ? 1 : 0;
        const double value = (feat.source == 0 || feat.source == 3) ? 0.0 : 1.0;
        ASSERT_EQ(a[axis], value) << after;
        ASSERT_EQ(b[axis], value) << after;
        break;
      }
      default:
        FAIL() << "an interior edge carries a tag";
    }
  }
  for (int v = 0; v < m.vertex_count(); ++v) {
    if (m.triangles_of(v).empty()) continue;
    const VertexTag& tag = m.tag(v);
    if (tag.kind == VertexKind::primary && tag.on_curve) {
      ASSERT_LE((f.constraints.sections[0].eval(tag.t) - m.point(v)).norm(), 1e-12) << after << ": vertex " << v;
    }
  }
  for (const auto& [v, p] : f.fixed_positions) ASSERT_EQ(m.point(v), p) << after << ": fixed vertex moved";
}

inline std::vector<std::array<int, 2>> edges_of(const TriMesh& m) {
  std::vector<std::array<int, 2>> out;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i)
      if (tri[i] < tri[(i + 1) % 3]) out.push_back({tri[i], tri[(i + 1) % 3]});
      else if (m.edge_triangles(tri[i], tri[(i + 1) % 3]).size() == 1) out.push_back({tri[(i + 1) % 3], tri[i]});
  }
  return out;
}

}  // namespace curvemesh::mesh::fixture
