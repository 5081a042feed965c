// Step 6 of the curve stage (curve/coarsen.cpp): primary edges
// collapsed along their curves once the triangles are curved, invariant 3 (α per edge) no longer
// held there. The same optimized linear mesh is curved with the step and without it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "curve/curve.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh {
namespace {

// An ellipse as a path of four quarter cubics (control arm 4/3·(√2 − 1)): four curves. (A
// <circle> is 36 cubics within 1e-9 of it, and coarsening along a curve keeps its ends.)
std::string ellipse_path(double cx, double cy, double rx, double ry) {
  const double k = 0.5522847498307936;
  const double p[13][2] = {{rx, 0},   {rx, k * ry},   {k * rx, ry},   {0, ry},   {-k * rx, ry},
                           {-rx, k * ry}, {-rx, 0},   {-rx, -k * ry}, {-k * rx, -ry}, {0, -ry},
                           {k * rx, -ry}, {rx, -k * ry}, {rx, 0}};
  std::ostringstream d;
  d.precision(17);
  d << "<path d=\"M " << cx + p[0][0] << " " << cy + p[0][1];
  for (int i = 1; i < 13; ++i) d << (i % 3 == 1 ? " C " : " ") << cx + p[i][0] << " " << cy + p[i][1];
  d << " Z\" fill=\"none\" stroke=\"black\"/>";
  return d.str();
}

// Circles of several radii, an open wave and an ellipse in a 400 x 300 drawing: curves bending at
// every scale, whose primary edges the linear stage keeps at α of turning each.
std::string curves() {
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 400 300\">";
  for (const auto& [cx, cy, r] :
       {std::array<double, 3>{100, 100, 60}, {300, 90, 30}, {300, 200, 12}, {90, 240, 25}})
    s += ellipse_path(cx, cy, r, r);
  s += "<path d=\"M 160 250 C 190 180 220 320 250 250 S 310 180 340 250\" fill=\"none\" stroke=\"black\"/>";
  s += ellipse_path(200, 150, 40, 15);
  return s + "</svg>";
}

struct Curved {
  curve::CurvedMesh mesh;
  curve::Stats stats;
};

Curved curve_it(const pipeline::Result& r, bool coarsen) {
  curve::Options o = r.resolved.curve;
  if (!coarsen) o.coarsen_edge_length = 0;
  Curved c;
  c.mesh = curve::curve(r.linear, r.constraints, o, &c.stats);
  return c;
}

double longest_edge(const curve::CurvedMesh& c) {
  double longest = 0;
  for (int t = 0; t < c.linear.triangle_slots(); ++t) {
    if (!c.linear.alive(t)) continue;
    const auto& tri = c.linear.triangle(t);
    for (int i = 0; i < 3; ++i)
      longest = std::max(longest, (c.linear.point(tri[i]) - c.linear.point(tri[(i + 1) % 3])).norm());
  }
  return longest;
}

TEST(CurveCoarsen, FewerEdgesAlongTheCurvesEachOnItsCurveCertifiedAndWithinTheBound) {
  Parameters p;
  const pipeline::Result r = pipeline::run(pipeline::Source::svg(curves(), "curves"), p,
                                           pipeline::RunOptions(pipeline::Stage::optimize));
  const Curved without = curve_it(r, false), with = curve_it(r, true);
  const double l = r.resolved.curve.coarsen_edge_length;
  ASSERT_GT(l, 0);
  EXPECT_EQ(without.stats.coarsening_collapses, 0);
  EXPECT_GT(with.stats.coarsening_collapses, 0);
  // Coarser: a third fewer edges along the curves at least (the circles alone have 36 each at α).
  EXPECT_LT(with.stats.primary_edges, 2 * without.stats.primary_edges / 3);
  EXPECT_LT(with.mesh.triangles.size(), without.mesh.triangles.size());
  // Every triangle certified, every primary edge on its curve, nothing straight or fitted.
  EXPECT_EQ(with.stats.invalid_triangles, 0);
  EXPECT_EQ(with.stats.curved_edges, with.stats.primary_edges);
  EXPECT_EQ(with.stats.straight_primary_edges, 0);
  EXPECT_EQ(with.stats.fitted_edges, 0);
  // The energy bound: a collapse leaves what it changes at most max(the stop energy, the worst it
  // replaced), so the mesh's worst is at most max(the stop energy, the worst without the step).
  EXPECT_LE(with.stats.max_amips, std::max(r.resolved.curve.coarsen_amips, without.stats.max_amips));
  // No edge longer than 5/3 of l, unless it was there before.
  EXPECT_LE(longest_edge(with.mesh), std::max(5.0 / 3.0 * l, longest_edge(without.mesh)) * (1 + 1e-12));

  // The primary edges: inner nodes on the curve at thirds of the edge's parameter interval (the
  // cubic through them is the curve's own piece), each covering less than π of turning, and some
  // more than α — what invariant 3 forbade in the linear mesh.
  const double alpha = r.constraints.max_turning;
  double most_turning = 0;
  int lines = 0;
  for (const curve::FeatureLine& line : with.mesh.lines) {
    if (line.kind != mesh::EdgeKind::primary) continue;
    ++lines;
    const int a = line.nodes[0], b = line.nodes[1];
    const mesh::EdgeFeature* f = with.mesh.linear.feature(a, b);
    ASSERT_NE(f, nullptr);
    const mesh::SectionCurve& section = r.constraints.sections[f->source];
    const double ta = a < b ? f->t_lo : f->t_hi, tb = a < b ? f->t_hi : f->t_lo;
    const double turning = section.turning(ta, tb);
    EXPECT_LT(turning, std::numbers::pi);
    most_turning = std::max(most_turning, turning);
    for (int k = 0; k < 4; ++k) {
      const double t = ta + (tb - ta) * k / 3.0;
      EXPECT_LT((with.mesh.nodes[line.nodes[k == 0   ? 0
                                            : k == 3 ? 1
                                                     : k + 1]] -
                 section.eval(t))
                    .norm(),
                1e-9 * r.resolved.d)
          << "node " << k << " of primary edge " << a << "-" << b;
    }
  }
  EXPECT_EQ(lines, with.stats.primary_edges);
  EXPECT_GT(most_turning, 1.5 * alpha);

  // The pipeline runs the step: its mesh is this one.
  const pipeline::Result full = pipeline::run(pipeline::Source::svg(curves(), "curves"), p);
  ASSERT_TRUE(full.curved.has_value());
  EXPECT_EQ(full.curved->triangles.size(), with.mesh.triangles.size());
  EXPECT_EQ(full.curve_stats.coarsening_collapses, with.stats.coarsening_collapses);
}

}  // namespace
}  // namespace curvemesh
