// The wedges at fixed vertices of a finished curved mesh: where tagged lines (curves, secondary
// lines, the box) leave a fixed vertex at a small angle to each other, no triangle between them
// can be good, and the bound below says how good it can be at best.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "curve/curve.hpp"

namespace curvemesh::curve {

double wedge_amips_bound(double wedge) {
  if (!(wedge > 0)) return std::numeric_limits<double>::infinity();
  // k triangles of apex wedge / k with two equal sides: AMIPS (2 + 4 sin²(θ/2)) / (√3 sin θ),
  // smallest at θ = 60°; the best k is one of the two around wedge / 60°.
  const auto isosceles = [](double apex) {
    const double s = std::sin(apex / 2);
    return apex < std::numbers::pi ? (2 + 4 * s * s) / (std::sqrt(3.0) * std::sin(apex))
                                   : std::numeric_limits<double>::infinity();
  };
  const double k = std::max(1.0, std::floor(wedge / (std::numbers::pi / 3)));
  return std::min(isosceles(wedge / k), isosceles(wedge / (k + 1)));
}

namespace {

// The direction in which a P3 edge (nodes p0, p1 at 1/3, p2 at 2/3, p3) leaves p0.
double leaving_angle(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  const Vec2 d = -11 * p0 + 18 * p1 - 9 * p2 + 2 * p3;
  return std::atan2(d.y(), d.x());
}

// The direction in which a P2 edge (nodes p0, m at 1/2, p1) leaves p0.
double leaving_angle(const Vec2& p0, const Vec2& m, const Vec2& p1) {
  const Vec2 d = -3 * p0 + 4 * m - p1;
  return std::atan2(d.y(), d.x());
}

double turn(double from, double to) {  // counter-clockwise angle from one direction to another, in [0, 2π)
  double a = std::fmod(to - from, 2 * std::numbers::pi);
  return a < 0 ? a + 2 * std::numbers::pi : a;
}

}  // namespace

WedgeStats wedges(const CurvedMesh& mesh, const std::vector<double>& amips, double stop_amips) {
  const mesh::TriMesh& m = mesh.linear;
  const std::size_t n = mesh.triangles.size();
  WedgeStats s;
  // Per triangle: the bound of the wedge it lies in at one of its fixed corners (the worst), or 0.
  std::vector<double> bound(n, 0.0);
  // For each triangle corner: where its two edges leave the corner (the edge to the next corner
  // and the edge to the previous one), from the P3 nodes (Gmsh's order: edge i has nodes 3 + 2i,
  // 4 + 2i from corner i to corner i + 1) or the P2 ones (edge i has node 3 + i).
  const auto edge_out = [&](std::size_t t, int i) {  // corner i along edge (i, i + 1)
    const auto& ids = mesh.triangles[t];
    const int j = (i + 1) % 3;
    if (mesh.order == 2) return leaving_angle(mesh.nodes[ids[i]], mesh.nodes[ids[3 + i]], mesh.nodes[ids[j]]);
    return leaving_angle(mesh.nodes[ids[i]], mesh.nodes[ids[3 + 2 * i]], mesh.nodes[ids[4 + 2 * i]],
                         mesh.nodes[ids[j]]);
  };
  const auto edge_in = [&](std::size_t t, int i) {  // corner i along edge (i − 1, i), backwards
    const auto& ids = mesh.triangles[t];
    const int h = (i + 2) % 3;
    if (mesh.order == 2) return leaving_angle(mesh.nodes[ids[i]], mesh.nodes[ids[3 + h]], mesh.nodes[ids[h]]);
    return leaving_angle(mesh.nodes[ids[i]], mesh.nodes[ids[4 + 2 * h]], mesh.nodes[ids[3 + 2 * h]],
                         mesh.nodes[ids[h]]);
  };
  for (int v = 0; v < m.vertex_count(); ++v) {
    if (m.tag(v).kind != mesh::VertexKind::fixed) continue;
    // The tagged lines leaving v, by the angle at which they leave.
    std::vector<double> lines;
    struct Corner {
      std::size_t t;
      double middle;  // the direction halfway through the triangle's angle at v
    };
    std::vector<Corner> corners;
    for (int t : m.triangles_of(v)) {
      const auto& tri = m.triangle(t);
      const int i = static_cast<int>(std::find(tri.begin(), tri.end(), v) - tri.begin());
      const double out = edge_out(t, i), in = edge_in(t, i);
      // Counter-clockwise corners: the triangle lies turning from `out` to `in`.
      corners.push_back({static_cast<std::size_t>(t), out + 0.5 * turn(out, in)});
      if (const auto* f = m.feature(v, tri[(i + 1) % 3]); f && f->kind != mesh::EdgeKind::interior)
        lines.push_back(out);
    }
    if (lines.size() < 2) continue;
    std::sort(lines.begin(), lines.end());
    for (const Corner& c : corners) {
      // The wedge holding the triangle: from the last line at or before its middle, turning
      // counter-clockwise, to the next line.
      double from = lines.back(), wedge = 2 * std::numbers::pi;
      for (double a : lines) {
        const double w = turn(a, c.middle);
        if (w < turn(from, c.middle)) from = a;
      }
      for (double a : lines)
        if (const double w = turn(from, a); w > 0 && w < wedge) wedge = w;
      const double b = wedge_amips_bound(wedge);
      bound[c.t] = std::max(bound[c.t], b);
      if (wedge < s.smallest_wedge) s.smallest_wedge = wedge, s.smallest_wedge_bound = b;
    }
  }
  for (std::size_t t = 0; t < n; ++t) {
    if (bound[t] > stop_amips) {
      ++s.sharp_triangles;
      continue;
    }
    s.max_amips_elsewhere = std::max(s.max_amips_elsewhere, amips[t]);
  }
  return s;
}

}  // namespace curvemesh::curve
