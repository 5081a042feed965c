// The exact constrained triangulation on hand-made and nasty inputs. Validity is checked here with
// GMP rationals on the stored coordinates (not through the mesh's own predicate): every triangle
// counter-clockwise, the triangles tile the box exactly, every input segment is covered by tagged
// edges lying on it.
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <cmath>
#include <map>
#include <random>

#include "pipeline/parameters.hpp"
#include "triangulate/arrangement.hpp"
#include "triangulate/triangulate.hpp"

namespace curvemesh::triangulate {
namespace {

using geometry::ExactPoint;
using geometry::Vec2;

mpq_class cross(const ExactPoint& a, const ExactPoint& b, const ExactPoint& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

features::Features make_features(const std::vector<std::array<Vec2, 2>>& segments, const std::vector<Vec2>& points = {}) {
  features::Features f;
  for (const auto& s : segments) {
    f.segments.push_back({s[0], s[1], -1, 0, 1, {}});
    f.box.add(s[0]);
    f.box.add(s[1]);
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    f.points.push_back({points[i], int(i)});
    f.box.add(points[i]);
  }
  f.lengths = pipeline::resolve({}, f.box.diagonal()).features;
  return f;
}

// The stage with the paper's box margin, resolved as the pipeline does.
Result triangulate(const features::Features& f) {
  return triangulate::triangulate(f, pipeline::resolve({}, f.box.diagonal()).triangulate);
}

// Every structural and geometric property the stage promises, checked independently.
void expect_valid(const Result& r, const features::Features& f) {
  const mesh::TriMesh& m = r.mesh;
  ASSERT_FALSE(m.structure_error()) << *m.structure_error();
  mpq_class area = 0;
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    const mpq_class a = cross(m.exact_or_double(tri[0]), m.exact_or_double(tri[1]), m.exact_or_double(tri[2]));
    ASSERT_GT(sgn(a), 0) << "triangle " << t << " is not counter-clockwise";
    area += a;
  }
  // The triangles tile the box: their doubled areas add up to the box's, exactly.
  const ExactPoint lo(r.box.min), hi(r.box.max);
  EXPECT_EQ(area, 2 * (hi.x - lo.x) * (hi.y - lo.y));
  // Every secondary input segment is covered by the edges tagged with it, which lie on it
  // (up to the rounding of crossing vertices: one unit in the last place of the coordinates).
  std::map<int, double> covered;
  for (const auto& [e, feature] : m.sorted_features()) {
    if (feature.kind != mesh::EdgeKind::secondary) continue;
    const features::Segment& s = f.segments[feature.source];
    const Vec2 p = m.point(e[0]), q = m.point(e[1]);
    const Vec2 dir = (s.b - s.a).normalized();
    const double tol = 4e-16 * r.box.diagonal();
    for (const Vec2& x : {p, q}) {
      const Vec2 d = x - s.a;
      EXPECT_LE(std::abs(d.x() * dir.y() - d.y() * dir.x()), tol);
    }
    covered[feature.source] += (q - p).norm();
  }
  for (std::size_t k = 0; k < f.segments.size(); ++k) {
    const double len = (f.segments[k].b - f.segments[k].a).norm();
    if (len == 0) continue;
    // An overlapped part may be tagged with an earlier segment; never more than the segment.
    EXPECT_LE(covered[int(k)], len * (1 + 1e-12) + 1e-300);
  }
  EXPECT_EQ(r.stats.exact_vertices, m.exact_vertex_count());
  EXPECT_EQ(r.stats.triangles, m.triangle_count());
}

TEST(Triangulate, CrossingSegmentsMeetAtOneExactVertex) {
  const auto f = make_features({{Vec2(0, 0), Vec2(1, 1)}, {Vec2(0, 1), Vec2(1, 0)}});
  const Result r = triangulate(f);
  expect_valid(r, f);
  EXPECT_EQ(r.mesh.vertex_count(), 4 + 4 + 1);
  EXPECT_EQ(r.stats.crossing_vertices, 1);
  EXPECT_EQ(r.stats.method, Method::rounded);
  int at_centre = 0;
  for (int v = 0; v < r.mesh.vertex_count(); ++v)
    if (r.mesh.point(v) == Vec2(0.5, 0.5)) {
      ++at_centre;
      EXPECT_EQ(r.mesh.neighbours(v).size(), 4u);
    }
  EXPECT_EQ(at_centre, 1);
  // Four secondary sub-edges and the box sides.
  int secondary = 0, boundary = 0;
  for (const auto& [e, feature] : r.mesh.sorted_features()) {
    secondary += feature.kind == mesh::EdgeKind::secondary;
    boundary += feature.kind == mesh::EdgeKind::boundary;
  }
  EXPECT_EQ(secondary, 4);
  EXPECT_EQ(boundary, 4);  // the box sides, which nothing touches
}

TEST(Triangulate, BoxHasTheDocumentedMargin) {
  const auto f = make_features({{Vec2(0, 0), Vec2(3, 4)}});
  pipeline::Parameters p;
  p.box_margin_rel = 0.1;
  const Result r = triangulate::triangulate(f, pipeline::resolve(p, f.box.diagonal()).triangulate);
  expect_valid(r, f);
  EXPECT_DOUBLE_EQ(r.box.min.x(), -0.5);
  EXPECT_DOUBLE_EQ(r.box.max.y(), 4.5);
}

TEST(Triangulate, ManySegmentsThroughOnePoint) {
  std::vector<std::array<Vec2, 2>> star;
  for (int k = 0; k < 60; ++k) {
    const double a = 2 * M_PI * k / 120;  // diameters: they all cross near the origin
    star.push_back({Vec2(std::cos(a), std::sin(a)), Vec2(-std::cos(a), -std::sin(a))});
  }
  const auto f = make_features(star);
  const Result r = triangulate(f);
  expect_valid(r, f);
  EXPECT_GT(r.stats.crossing_vertices, 0);
}

TEST(Triangulate, OverlappingCollinearSegments) {
  const auto f = make_features({{Vec2(0, 0), Vec2(1, 0)},
                                {Vec2(0.25, 0), Vec2(0.75, 0)},
                                {Vec2(0.5, 0), Vec2(2, 0)},
                                {Vec2(2, 0), Vec2(0, 0)}});  // the whole run again, reversed
  const Result r = triangulate(f);
  expect_valid(r, f);
  // The union [0, 2] is tagged exactly once, split at 0.25, 0.5, 0.75, 1.
  double tagged = 0;
  int pieces = 0;
  for (const auto& [e, feature] : r.mesh.sorted_features())
    if (feature.kind == mesh::EdgeKind::secondary) {
      tagged += (r.mesh.point(e[1]) - r.mesh.point(e[0])).norm();
      ++pieces;
    }
  EXPECT_DOUBLE_EQ(tagged, 2.0);
  EXPECT_EQ(pieces, 5);
}

TEST(Triangulate, SegmentsShorterThan1e12OfTheDiagonal) {
  const auto f = make_features({{Vec2(0, 0), Vec2(1, 1)},
                                {Vec2(0.5, 0.5), Vec2(0.5 + 1e-13, 0.5)},
                                {Vec2(0.2, 0.7), Vec2(0.2, 0.7 + 1e-13)},
                                {Vec2(0.3, 0.3), Vec2(0.3, 0.3)}});
  const Result r = triangulate(f);
  expect_valid(r, f);
}

TEST(Triangulate, PointsOnSegmentsSplitThem) {
  const auto f = make_features({{Vec2(0, 0), Vec2(1, 0)}, {Vec2(0, 0), Vec2(1, 1)}}, {Vec2(0.5, 0), Vec2(0.25, 0.25), Vec2(0.5, 0.7)});
  const Result r = triangulate(f);
  expect_valid(r, f);
  int isolated = 0;
  for (int v = 0; v < r.mesh.vertex_count(); ++v)
    if (r.mesh.tag(v).isolated) {
      ++isolated;
      EXPECT_EQ(r.mesh.tag(v).kind, mesh::VertexKind::fixed);
    }
  EXPECT_EQ(isolated, 3);
  int secondary = 0;
  for (const auto& [e, feature] : r.mesh.sorted_features()) secondary += feature.kind == mesh::EdgeKind::secondary;
  EXPECT_EQ(secondary, 4);
}

// Scaling the input by a power of two changes no rounding: the same mesh, scaled.
TEST(Triangulate, ScaledCopiesGiveTheSameMesh) {
  std::vector<std::array<Vec2, 2>> base;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 40; ++k) base.push_back({Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))});
  const Result r0 = triangulate(make_features(base));
  for (double scale : {std::ldexp(1.0, -20), std::ldexp(1.0, 20), 1e-6, 1e6}) {
    std::vector<std::array<Vec2, 2>> scaled;
    for (const auto& s : base) scaled.push_back({s[0] * scale, s[1] * scale});
    const auto f = make_features(scaled);
    const Result r = triangulate(f);
    expect_valid(r, f);
    EXPECT_EQ(r.mesh.vertex_count(), r0.mesh.vertex_count()) << scale;
    EXPECT_EQ(r.mesh.triangle_count(), r0.mesh.triangle_count()) << scale;
    if (std::log2(scale) == std::round(std::log2(scale))) {
      for (int v = 0; v < r.mesh.vertex_count(); ++v) EXPECT_EQ(r.mesh.point(v), r0.mesh.point(v) * scale);
    }
  }
}

// Many nearly parallel segments cross in a cluster of points closer than a double's spacing:
// some crossings cannot be rounded yet. Those keep exact positions, and only those.
TEST(Triangulate, UnroundableCrossingsKeepExactPositions) {
  std::vector<std::array<Vec2, 2>> fan;
  for (int k = 0; k < 12; ++k)
    fan.push_back({Vec2(0, 0.1 + k * 1e-17), Vec2(1, 0.1 + (12 - k) * 3e-17 + 1e-16 * (k % 3))});
  fan.push_back({Vec2(0.5, 0), Vec2(0.5 + 1e-16, 1)});
  const auto f = make_features(fan);
  const Result r = triangulate(f);
  expect_valid(r, f);
  EXPECT_GT(r.stats.crossing_vertices, 0);
  EXPECT_GT(r.stats.exact_vertices, 0);  // the case this test is about does arise
  // Crossings that round onto each other: the triangulation is built at the exact positions.
  EXPECT_EQ(r.stats.method, Method::exact_crossings);
  for (int v = 0; v < r.mesh.vertex_count(); ++v) {
    if (!r.mesh.has_exact(v)) continue;
    // Kept exact only because its nearest double inverts or flattens an incident triangle.
    const Vec2 p = geometry::nearest_double(r.mesh.exact(v));
    bool inverts = false;
    for (int t : r.mesh.triangles_of(v)) {
      const auto& tri = r.mesh.triangle(t);
      ExactPoint c[3];
      for (int i = 0; i < 3; ++i) c[i] = tri[i] == v ? ExactPoint(p) : r.mesh.exact_or_double(tri[i]);
      inverts |= sgn(cross(c[0], c[1], c[2])) <= 0;
    }
    EXPECT_TRUE(inverts) << "vertex " << v << " could have been rounded";
  }
}

// An input of secondary segments and isolated points inside the box [-1, n + 1]^2.
detail::Input arrangement_input(const std::vector<std::array<Vec2, 2>>& segments, const std::vector<Vec2>& points, double n) {
  detail::Input in;
  for (const Vec2& c : {Vec2(-1, -1), Vec2(n + 1, -1), Vec2(n + 1, n + 1), Vec2(-1, n + 1)}) in.points.push_back({c, true, false});
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const int a = int(in.points.size());
    in.points.push_back({segments[k][0], false, false});
    in.points.push_back({segments[k][1], false, false});
    in.constraints.push_back({mesh::EdgeKind::secondary, int(k), -1, a, a + 1});
  }
  for (const Vec2& p : points) in.points.push_back({p, true, true});
  for (int side = 0; side < 4; ++side) in.constraints.push_back({mesh::EdgeKind::boundary, side, -1, side, (side + 1) % 4});
  return in;
}

// The same fan through the arrangement alone: the crossings that cannot be rounded are held at
// their exact positions, the others rounded, and the result is the arrangement CGAL's exact
// constructions find (as many vertices, pieces and triangles), counter-clockwise at the positions
// it gives (exactly, with GMP).
TEST(Triangulate, CrossingsThatCannotBeRoundedAreHeldExact) {
  std::vector<std::array<Vec2, 2>> segs;
  for (int k = 0; k < 12; ++k)
    segs.push_back({Vec2(0, 0.1 + k * 1e-17), Vec2(1, 0.1 + (12 - k) * 3e-17 + 1e-16 * (k % 3))});
  segs.push_back({Vec2(0.5, 0), Vec2(0.5 + 1e-16, 1)});
  // Away from the fan, two segments cross at a point no double holds, which rounds safely.
  segs.push_back({Vec2(1.2, 0.1), Vec2(1.7, 0.9)});
  segs.push_back({Vec2(1.2, 0.8), Vec2(1.9, 0.15)});
  const detail::Input in = arrangement_input(segs, {}, 1);
  const std::optional<detail::Triangulation> t = detail::triangulate_arrangement(in);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->method, Method::exact_crossings);
  const detail::Triangulation exact = detail::triangulate_exact(in);
  EXPECT_EQ(t->vertices.size(), exact.vertices.size());
  EXPECT_EQ(t->pieces.size(), exact.pieces.size());
  EXPECT_EQ(t->triangles.size(), exact.triangles.size());
  int held = 0, rounded = 0;
  for (const auto& v : t->vertices) {
    if (v.input) continue;
    (v.exact_needed ? held : rounded) += 1;
  }
  EXPECT_GT(held, 0);
  EXPECT_EQ(rounded, 1);  // not every crossing: only those that cannot be rounded
  const auto at = [&](int v) { return t->vertices[v].exact_needed ? t->vertices[v].exact : ExactPoint(t->vertices[v].approx); };
  for (const auto& tri : t->triangles) EXPECT_GT(sgn(cross(at(tri[0]), at(tri[1]), at(tri[2]))), 0);
}

TEST(Triangulate, PrimarySectionsTagVerticesWithTheirParameter) {
  features::Features f;
  features::Section s;
  s.curve = 3;
  s.t0 = 0;
  s.t1 = 1;
  s.piece = geometry::CubicBezier(Vec2(0, 0), Vec2(0.3, 0.4), Vec2(0.7, 0.4), Vec2(1, 0));
  for (int i = 0; i <= 6; ++i) {
    s.ts.push_back(i / 6.0);
    s.polyline.push_back(s.piece.eval(i / 6.0));
  }
  f.sections.push_back(s);
  // A secondary segment crossing the polyline edge between vertices 1 and 2.
  const Vec2 mid = 0.5 * (s.polyline[1] + s.polyline[2]);
  f.segments.push_back({mid + Vec2(0.05, -0.2), mid + Vec2(-0.05, 0.2), 8, 0, 1, {}});
  for (const Vec2& p : s.polyline) f.box.add(p);
  f.box.add(f.segments[0].a);
  f.box.add(f.segments[0].b);
  f.lengths = pipeline::resolve({}, f.box.diagonal()).features;
  const Result r = triangulate(f);
  expect_valid(r, f);
  const mesh::TriMesh& m = r.mesh;
  int primary_vertices = 0, ends = 0;
  for (int v = 0; v < m.vertex_count(); ++v) {
    for (int i = 0; i <= 6; ++i)
      if (m.point(v) == s.polyline[i]) {
        if (i == 0 || i == 6) {
          EXPECT_EQ(m.tag(v).kind, mesh::VertexKind::fixed);
          ++ends;
        } else {
          EXPECT_EQ(m.tag(v).kind, mesh::VertexKind::primary);
          EXPECT_EQ(m.tag(v).section, 0);
          EXPECT_EQ(m.tag(v).t, s.ts[i]);
          EXPECT_TRUE(m.tag(v).on_curve);
          ++primary_vertices;
        }
      }
  }
  EXPECT_EQ(primary_vertices, 5);
  EXPECT_EQ(ends, 2);
  // Seven primary sub-edges (six polyline edges, one split by the crossing); their parameter
  // intervals tile [0, 1] and increase along the curve.
  std::vector<std::pair<double, double>> intervals;
  for (const auto& [e, feature] : m.sorted_features())
    if (feature.kind == mesh::EdgeKind::primary) {
      EXPECT_EQ(feature.curve, 3);
      EXPECT_EQ(feature.source, 0);
      intervals.push_back(std::minmax(feature.t_lo, feature.t_hi));
    }
  ASSERT_EQ(intervals.size(), 7u);
  std::sort(intervals.begin(), intervals.end());
  EXPECT_EQ(intervals.front().first, 0.0);
  EXPECT_EQ(intervals.back().second, 1.0);
  for (std::size_t i = 0; i + 1 < intervals.size(); ++i) EXPECT_EQ(intervals[i].second, intervals[i + 1].first);
  // The crossing with the secondary segment is a primary vertex off the curve (on the chord,
  // parameter interpolated): it may slide along the curve, its secondary edges kept in the envelope.
  int crossings = 0;
  for (int v = 0; v < m.vertex_count(); ++v) {
    bool secondary = false;
    for (int w : m.neighbours(v))
      if (const auto* e = m.feature(v, w); e && e->kind == mesh::EdgeKind::secondary) secondary = true;
    if (!secondary || m.tag(v).kind == mesh::VertexKind::secondary) continue;
    ++crossings;
    EXPECT_EQ(m.tag(v).kind, mesh::VertexKind::primary);
    EXPECT_EQ(m.tag(v).section, 0);
    EXPECT_FALSE(m.tag(v).on_curve);
    EXPECT_GT(m.tag(v).t, 0.0);
    EXPECT_LT(m.tag(v).t, 1.0);
  }
  EXPECT_EQ(crossings, 1);
}

TEST(Triangulate, Deterministic) {
  std::vector<std::array<Vec2, 2>> segs;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 200; ++k) segs.push_back({Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))});
  const auto f = make_features(segs);
  const Result a = triangulate(f), b = triangulate(f);
  ASSERT_EQ(a.mesh.vertex_count(), b.mesh.vertex_count());
  ASSERT_EQ(a.mesh.triangle_slots(), b.mesh.triangle_slots());
  for (int v = 0; v < a.mesh.vertex_count(); ++v) EXPECT_EQ(a.mesh.point(v), b.mesh.point(v));
  for (int t = 0; t < a.mesh.triangle_slots(); ++t) EXPECT_EQ(a.mesh.triangle(t), b.mesh.triangle(t));
  EXPECT_EQ(a.mesh.sorted_features().size(), b.mesh.sorted_features().size());
  expect_valid(a, f);
}

TEST(Triangulate, EmptyAndSinglePointInputsGiveABox) {
  features::Features empty;
  empty.lengths = pipeline::resolve({}, 0).features;
  const Result r = triangulate(empty);
  expect_valid(r, empty);
  EXPECT_EQ(r.mesh.triangle_count(), 2);
  const auto one = make_features({}, {Vec2(3, 4)});
  const Result p = triangulate(one);
  expect_valid(p, one);
  EXPECT_EQ(p.mesh.triangle_count(), 4);
}

// The two ways to the arrangement (arrangement.hpp), compared on one input: CGAL's exact
// constructions are the reference. The rounded path must succeed and find the same vertices (at
// most a few units in the last place apart), the same pieces with the same constraints on each,
// the same ends of every constraint, and as many triangles.
void expect_same_arrangement(const detail::Input& in) {
  const std::optional<detail::Triangulation> rounded = detail::triangulate_arrangement(in);
  ASSERT_TRUE(rounded.has_value());
  EXPECT_EQ(rounded->method, Method::rounded);
  const detail::Triangulation exact = detail::triangulate_exact(in);
  ASSERT_EQ(rounded->vertices.size(), exact.vertices.size());
  ASSERT_EQ(rounded->triangles.size(), exact.triangles.size());
  // Vertices matched by position: distinct vertices of these inputs are far apart.
  std::vector<int> to_exact(rounded->vertices.size(), -1);
  std::vector<char> used(exact.vertices.size(), 0);
  for (std::size_t v = 0; v < rounded->vertices.size(); ++v) {
    const detail::ArrangementVertex& a = rounded->vertices[v];
    EXPECT_FALSE(a.exact_needed);
    for (std::size_t w = 0; w < exact.vertices.size(); ++w) {
      const detail::ArrangementVertex& b = exact.vertices[w];
      if ((a.approx - b.approx).norm() > 1e-12 || used[w]) continue;
      to_exact[v] = int(w);
      used[w] = 1;
      EXPECT_EQ(a.input, b.input);
      EXPECT_EQ(a.fixed, b.fixed);
      EXPECT_EQ(a.isolated, b.isolated);
      break;
    }
    ASSERT_GE(to_exact[v], 0) << "no exact vertex at " << a.approx.transpose();
  }
  const auto pieces = [](const detail::Triangulation& t, const std::vector<int>* map) {
    std::map<std::pair<int, int>, std::vector<int>> out;
    for (const detail::Piece& p : t.pieces) {
      const int u = map ? (*map)[p.u] : p.u, w = map ? (*map)[p.w] : p.w;
      std::vector<int> cs(t.piece_constraints.begin() + p.first, t.piece_constraints.begin() + p.last);
      std::sort(cs.begin(), cs.end());
      EXPECT_TRUE(out.emplace(std::pair{std::min(u, w), std::max(u, w)}, cs).second) << "a piece twice";
    }
    return out;
  };
  EXPECT_EQ(pieces(*rounded, &to_exact), pieces(exact, nullptr));
  ASSERT_EQ(rounded->constraint_ends.size(), exact.constraint_ends.size());
  for (std::size_t c = 0; c < exact.constraint_ends.size(); ++c) {
    const auto& e = rounded->constraint_ends[c];
    if (e[0] < 0) {
      EXPECT_EQ(exact.constraint_ends[c][0], -1) << c;
    } else {
      EXPECT_EQ((std::array{to_exact[e[0]], to_exact[e[1]]}), exact.constraint_ends[c]) << c;
    }
  }
}

// Segments between the points of a 5 x 5 integer grid: collinear overlaps, segments repeated in
// either direction, T-junctions, many segments through one crossing, ends on crossings, crossings
// at rationals that no double holds; and isolated grid points, some on segments.
TEST(Triangulate, RoundedPathFindsTheExactArrangementOfGridSegments) {
  for (unsigned seed = 1; seed <= 25; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> g(0, 4);
    std::vector<std::array<Vec2, 2>> segs;
    for (int k = 0; k < 30; ++k) segs.push_back({Vec2(g(rng), g(rng)), Vec2(g(rng), g(rng))});
    std::vector<Vec2> points;
    for (int k = 0; k < 5; ++k) points.push_back(Vec2(g(rng), g(rng)));
    SCOPED_TRACE(seed);
    expect_same_arrangement(arrangement_input(segs, points, 4));
  }
}

TEST(Triangulate, RoundedPathFindsTheExactArrangementOfRandomSegments) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::array<Vec2, 2>> segs;
  for (int k = 0; k < 300; ++k) segs.push_back({Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))});
  expect_same_arrangement(arrangement_input(segs, {}, 1));
}

}  // namespace
}  // namespace curvemesh::triangulate
