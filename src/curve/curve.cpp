#include "curve/curve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>

#include "geometry/p3_triangle.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve {

namespace {

using mesh::EdgeKind;
using mesh::TriMesh;

bool is_primary(const TriMesh& m, int a, int b) {
  const mesh::EdgeFeature* f = m.feature(a, b);
  return f && f->kind == EdgeKind::primary;
}

int primary_edges_of(const TriMesh& m, const mesh::Triangle& tri) {
  int n = 0;
  for (int i = 0; i < 3; ++i) n += is_primary(m, tri[i], tri[(i + 1) % 3]);
  return n;
}

// Step 1. Splitting a non-primary edge of a triangle with two primary edges leaves one on each
// half; a triangle with three needs a primary split first. Interior midpoints always split
// validly; a split the invariants refuse is replaced by the next candidate edge.
int split_until_one_primary_edge(TriMesh& m, const mesh::Constraints& c) {
  int splits = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t) || primary_edges_of(m, m.triangle(t)) < 2) continue;
      const mesh::Triangle tri = m.triangle(t);
      std::array<std::array<int, 2>, 3> edges{{{tri[0], tri[1]}, {tri[1], tri[2]}, {tri[2], tri[0]}}};
      // Non-primary edges first, longer first.
      std::stable_sort(edges.begin(), edges.end(), [&](const auto& x, const auto& y) {
        const bool px = is_primary(m, x[0], x[1]), py = is_primary(m, y[0], y[1]);
        if (px != py) return !px;
        return (m.point(x[0]) - m.point(x[1])).squaredNorm() > (m.point(y[0]) - m.point(y[1])).squaredNorm();
      });
      for (const auto& [a, b] : edges) {
        if (mesh::split_edge(m, c, a, b, INFINITY) >= 0) {
          ++splits;
          changed = true;
          break;
        }
      }
    }
  }
  return splits;
}

// The parameters of a primary edge at its ends, oriented from `from` to `to`.
std::pair<double, double> parameters(const mesh::EdgeFeature& f, int from, int to) {
  return from < to ? std::pair{f.t_lo, f.t_hi} : std::pair{f.t_hi, f.t_lo};
}

// Whether the edge can follow its curve: both ends lie on it at their recorded parameters.
bool followable(const TriMesh& m, int a, int b) {
  if (!is_primary(m, a, b)) return false;
  for (int v : {a, b}) {
    const mesh::VertexTag& tag = m.tag(v);
    if (tag.kind == mesh::VertexKind::primary && !tag.on_curve) return false;
  }
  return true;
}

// The cubic through p0, p1, p2, p3 at s = 0, 1/3, 2/3, 1 (a P3 edge), at s.
Vec2 edge_point(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double s) {
  const double a = 3 * s, l0 = -(a - 1) * (a - 2) * (a - 3) / 6, l1 = a * (a - 2) * (a - 3) / 2,
               l2 = -a * (a - 1) * (a - 3) / 2, l3 = a * (a - 1) * (a - 2) / 6;
  return l0 * p0 + l1 * p1 + l2 * p2 + l3 * p3;
}

class Builder {
 public:
  Builder(CurvedMesh& out, const mesh::Constraints& c, const Options& o, Stats& s)
      : out_(out), c_(c), o_(o), s_(s) {}

  void run() {
    const TriMesh& m = out_.linear;
    out_.nodes.assign(m.vertex_count(), Vec2::Zero());
    for (int v = 0; v < m.vertex_count(); ++v) out_.nodes[v] = m.point(v);
    // Edge nodes, in the order triangles first meet their edges (deterministic).
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t)) continue;
      const auto& tri = m.triangle(t);
      for (int i = 0; i < 3; ++i) add_edge(tri[i], tri[(i + 1) % 3]);
    }
    // Triangles: certify those with a curved edge; straighten the edges that fail.
    std::vector<int> order;
    for (int t = 0; t < m.triangle_slots(); ++t)
      if (m.alive(t)) order.push_back(t);
    // A triangle has at most one curved edge, and straightening an edge changes no other edge:
    // the centre certified here stays valid unless the triangle's own curved edge is lost.
    std::vector<Vec2> centre(order.size());
    std::vector<int> choice(order.size(), -1);
    std::vector<double> scaled(order.size(), 1.0);
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto& tri = m.triangle(order[k]);
      const int curved = curved_edge_of(tri);
      if (curved < 0) continue;
      geometry::P3Nodes p = element(tri);
      if (choose_centre(p, choice[k], scaled[k])) centre[k] = p[9];
      else straighten(tri[curved], tri[(curved + 1) % 3]);
    }
    // Final nodes and centres (triangles that lost their curved edge become straight).
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto& tri = m.triangle(order[k]);
      std::array<int, 10> ids{};
      for (int i = 0; i < 3; ++i) {
        ids[i] = tri[i];
        const auto [first, second] = edge_nodes(tri[i], tri[(i + 1) % 3]);
        ids[3 + 2 * i] = first;
        ids[4 + 2 * i] = second;
      }
      ids[9] = static_cast<int>(out_.nodes.size());
      if (curved_edge_of(tri) >= 0) {
        ++s_.curved_triangles;
        s_.alternative_centres += choice[k] > 0;
        s_.min_scaled_jacobian = std::min(s_.min_scaled_jacobian, scaled[k]);
        out_.nodes.push_back(centre[k]);
      } else {
        out_.nodes.push_back((m.point(tri[0]) + m.point(tri[1]) + m.point(tri[2])) / 3);
        // A straight element's nodes are rounded to doubles too: certify it like the others.
        geometry::P3Nodes p;
        for (int i = 0; i < 10; ++i) p[i] = out_.nodes[ids[i]];
        s_.invalid_triangles += geometry::certify_jacobian(p).verdict != geometry::JacobianVerdict::positive;
      }
      out_.triangles.push_back(ids);
    }
    // Feature lines and edge statistics.
    for (const auto& [edge, f] : m.sorted_features()) {
      const auto [first, second] = edge_nodes(edge[0], edge[1]);
      out_.lines.push_back({{edge[0], edge[1], first, second}, f.kind});
      if (f.kind != EdgeKind::primary) continue;
      ++s_.primary_edges;
      const bool curved = curved_.at(mesh::edge_key(edge[0], edge[1]));
      (curved ? s_.curved_edges : s_.straight_primary_edges) += 1;
      s_.max_distance = std::max(s_.max_distance, distance_to_curve(edge[0], edge[1], f, first, second));
    }
  }

 private:
  void add_edge(int a, int b) {
    const auto key = mesh::edge_key(a, b);
    if (first_node_.count(key)) return;
    const int lo = std::min(a, b), hi = std::max(a, b);
    first_node_[key] = static_cast<int>(out_.nodes.size());
    out_.nodes.push_back(Vec2::Zero());
    out_.nodes.push_back(Vec2::Zero());
    const bool curved = followable(out_.linear, lo, hi);
    curved_[key] = curved;
    if (curved) place_on_curve(lo, hi); else place_straight(lo, hi);
  }

  void place_straight(int lo, int hi) {
    const int n = first_node_.at(mesh::edge_key(lo, hi));
    const Vec2 &a = out_.nodes[lo], &b = out_.nodes[hi];
    out_.nodes[n] = (2 * a + b) / 3;
    out_.nodes[n + 1] = (a + 2 * b) / 3;
  }

  // App. C: the curve at 1/3 and 2/3 of the edge's parameter interval.
  void place_on_curve(int lo, int hi) {
    const mesh::EdgeFeature& f = *out_.linear.feature(lo, hi);
    const mesh::SectionCurve& curve = c_.sections[f.source];
    const int n = first_node_.at(mesh::edge_key(lo, hi));
    out_.nodes[n] = curve.eval((2 * f.t_lo + f.t_hi) / 3);
    out_.nodes[n + 1] = curve.eval((f.t_lo + 2 * f.t_hi) / 3);
  }

  void straighten(int a, int b) {
    const auto key = mesh::edge_key(a, b);
    if (!curved_.at(key)) return;
    curved_[key] = false;
    place_straight(std::min(a, b), std::max(a, b));
  }

  // The two nodes of edge (a, b) in the order from a to b.
  std::pair<int, int> edge_nodes(int a, int b) const {
    const int n = first_node_.at(mesh::edge_key(a, b));
    return a < b ? std::pair{n, n + 1} : std::pair{n + 1, n};
  }

  // Index i of the triangle's curved edge (tri[i], tri[i+1]), or -1.
  int curved_edge_of(const mesh::Triangle& tri) const {
    for (int i = 0; i < 3; ++i)
      if (curved_.at(mesh::edge_key(tri[i], tri[(i + 1) % 3]))) return i;
    return -1;
  }

  geometry::P3Nodes element(const mesh::Triangle& tri) const {
    geometry::P3Nodes p;
    for (int i = 0; i < 3; ++i) {
      p[i] = out_.nodes[tri[i]];
      const auto [first, second] = edge_nodes(tri[i], tri[(i + 1) % 3]);
      p[3 + 2 * i] = out_.nodes[first];
      p[4 + 2 * i] = out_.nodes[second];
    }
    p[9] = (p[0] + p[1] + p[2]) / 3;
    return p;
  }

  // §4.2: the paper's centre (the average of the other nine nodes) first; where that map is not
  // certified, the centre that reproduces quadratic maps exactly, then the corners' centroid.
  // Sets p[9] to the first certified one (its index in `choice`, its scaled Jacobian in
  // `scaled`) and returns true, or returns false.
  bool choose_centre(geometry::P3Nodes& p, int& choice, double& scaled) const {
    const Vec2 sum_corners = p[0] + p[1] + p[2];
    Vec2 sum_edges = Vec2::Zero();
    for (int i = 3; i < 9; ++i) sum_edges += p[i];
    const std::array<Vec2, 3> centres{(sum_corners + sum_edges) / 9, sum_edges / 4 - sum_corners / 6, sum_corners / 3};
    for (int k = 0; k < 3; ++k) {
      p[9] = centres[k];
      geometry::JacobianCheckOptions check;
      check.max_depth = o_.certificate_depth;
      const auto result = geometry::certify_jacobian(p, check);
      if (result.verdict == geometry::JacobianVerdict::positive) {
        choice = k;
        scaled = result.scaled_jacobian;
        return true;
      }
    }
    return false;
  }

  // An upper bound of the distance from the edge to its curve: the edge's point and the curve's
  // point at the same fraction s of the edge (17 samples).
  double distance_to_curve(int a, int b, const mesh::EdgeFeature& f, int first, int second) const {
    const mesh::SectionCurve& curve = c_.sections[f.source];
    const auto [ta, tb] = parameters(f, a, b);
    const Vec2 &p0 = out_.nodes[a], &p1 = out_.nodes[first], &p2 = out_.nodes[second], &p3 = out_.nodes[b];
    double worst = 0;
    for (int i = 0; i <= 16; ++i) {
      const double s = i / 16.0;
      worst = std::max(worst, (edge_point(p0, p1, p2, p3, s) - curve.eval(ta + s * (tb - ta))).norm());
    }
    return worst;
  }

  CurvedMesh& out_;
  const mesh::Constraints& c_;
  const Options& o_;
  Stats& s_;
  std::unordered_map<std::uint64_t, int> first_node_;
  std::unordered_map<std::uint64_t, bool> curved_;
};

}  // namespace

CurvedMesh curve(TriMesh linear, const mesh::Constraints& constraints, const Options& options, Stats* stats) {
  const auto start = std::chrono::steady_clock::now();
  Stats s;
  CurvedMesh out;
  s.split_triangles = split_until_one_primary_edge(linear, constraints);
  linear.compact();
  out.linear = std::move(linear);
  Builder(out, constraints, options, s).run();
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = s;
  return out;
}

}  // namespace curvemesh::curve
