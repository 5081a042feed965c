#include "curve/curve.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/LU>

#include "geometry/closest_point.hpp"
#include "geometry/p3_triangle.hpp"
#include "mesh/operations.hpp"

namespace curvemesh::curve {

namespace {

using mesh::EdgeKind;
using mesh::TriMesh;

// The union of two lists of ids, sorted, each once.
std::vector<int> sorted_union(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

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
    vertex_node_.resize(m.vertex_count());
    for (int v = 0; v < m.vertex_count(); ++v) out_.nodes[v] = m.point(v), vertex_node_[v] = v;
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
    scaled_.assign(order.size(), 1.0);
    for (std::size_t k = 0; k < order.size(); ++k) {
      const auto& tri = m.triangle(order[k]);
      std::array<int, 10> ids = corner_and_edge_nodes(tri);
      ids[9] = static_cast<int>(out_.nodes.size());
      if (curved_edge_of(tri) >= 0) {
        s_.alternative_centres += choice[k] > 0;
        scaled_[k] = scaled[k];
        out_.nodes.push_back(centre[k]);
      } else {
        out_.nodes.push_back((m.point(tri[0]) + m.point(tri[1]) + m.point(tri[2])) / 3);
        // A straight element's nodes are rounded to doubles too: certify it like the others.
        geometry::P3Nodes p;
        for (int i = 0; i < 10; ++i) p[i] = out_.nodes[ids[i]];
        const auto cert = geometry::certify_jacobian(p);
        scaled_[k] = cert.verdict == geometry::JacobianVerdict::positive ? cert.scaled_jacobian : -1.0;
      }
      out_.triangles.push_back(ids);
    }
    // Step 4: smoothing, then the local operations, where the curved triangles are worse than the
    // stop energy.
    s_.max_amips_before_smoothing = 0;
    for (std::size_t t = 0; t < out_.triangles.size(); ++t)
      s_.max_amips_before_smoothing = std::max(s_.max_amips_before_smoothing, energy(static_cast<int>(t)));
    // Primary vertices the linear optimization could not bring onto their curve (Fig. 8): now
    // that edges bend, they may get there.
    for (int v = 0; v < m.vertex_count(); ++v)
      if (m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve) s_.late_projections += project(v);
    smooth();
    // Step 5: the primary edges still straight. Bringing one onto its curve may leave a poor
    // (certified) triangle, which the operations below then improve.
    for (const auto& [edge, f] : m.sorted_features())
      if (f.kind == EdgeKind::primary && !curved_.at(mesh::edge_key(edge[0], edge[1])) && followable(m, edge[0], edge[1]))
        fit(edge[0], edge[1]);
    improve();
    finish();
    for (std::size_t t = 0; t < out_.triangles.size(); ++t) {
      const double e = energy(static_cast<int>(t));
      s_.max_amips = std::max(s_.max_amips, e);
      s_.mean_amips += e / static_cast<double>(out_.triangles.size());
      if (scaled_[t] <= 0) ++s_.invalid_triangles;
      if (curved_edge_of(m.triangle(static_cast<int>(t))) >= 0 || fitted_edge_of(m.triangle(static_cast<int>(t))) >= 0) {
        ++s_.curved_triangles;
        s_.min_scaled_jacobian = std::min(s_.min_scaled_jacobian, scaled_[t]);
      }
    }
    // Feature lines and edge statistics.
    for (const auto& [edge, f] : m.sorted_features()) {
      const auto [first, second] = edge_nodes(edge[0], edge[1]);
      out_.lines.push_back({{edge[0], edge[1], first, second}, f.kind});
      if (f.kind != EdgeKind::primary) continue;
      ++s_.primary_edges;
      const auto key = mesh::edge_key(edge[0], edge[1]);
      const double distance = distance_to_curve(edge[0], edge[1], f, first, second);
      if (curved_.at(key)) {
        ++s_.curved_edges;
      } else if (fitted_.count(key)) {
        ++s_.fitted_edges;
        s_.mean_fit_distance += distance;
      } else {
        ++s_.straight_primary_edges;
      }
      s_.max_distance = std::max(s_.max_distance, distance);
    }
    if (s_.fitted_edges > 0) s_.mean_fit_distance /= s_.fitted_edges;
  }

 private:
  // ----- Step 4: smoothing and local operations on the curved mesh -------------------------
  // Triangle t of the curved mesh is triangle slot t of out_.linear (compacted before curving;
  // the operations add slots and leave dead ones, which finish() drops from both).

  // The node of vertex v (a corner).
  Vec2& at(int v) { return out_.nodes[vertex_node_[v]]; }
  const Vec2& at(int v) const { return out_.nodes[vertex_node_[v]]; }

  geometry::P3Nodes nodes_of(int t) const {
    geometry::P3Nodes p;
    for (int i = 0; i < 10; ++i) p[i] = out_.nodes[out_.triangles[t][i]];
    return p;
  }
  double energy(int t) const { return geometry::p3_max_amips(nodes_of(t)); }

  // Up to max_smoothing_passes passes over the triangles above stop_amips: the free and
  // secondary corners of each (they move in the plane, their edges stay straight, secondary
  // ones inside the ε-envelope), its corners on curves (they slide
  // along their curve, their curved edges follow) and its centre node move where the worst
  // energy around them is lowest, by compass search; a move is kept only when every
  // triangle it changes is certified and the worst energy among them went down.
  void smooth() {
    for (int pass = 0; pass < o_.max_smoothing_passes; ++pass)
      if (smooth_pass() == 0) return;
  }

  // The alive triangles above the stop energy, worst first.
  std::vector<int> bad_triangles() const {
    std::vector<std::pair<double, int>> bad;
    for (std::size_t t = 0; t < out_.triangles.size(); ++t)
      if (out_.linear.alive(static_cast<int>(t)))
        if (const double e = energy(static_cast<int>(t)); e > o_.stop_amips) bad.push_back({-e, static_cast<int>(t)});
    std::sort(bad.begin(), bad.end());
    std::vector<int> out;
    for (const auto& [e, t] : bad) out.push_back(t);
    return out;
  }

  // One smoothing pass; returns the number of moves kept.
  int smooth_pass() {
    const std::vector<int> bad = bad_triangles();
    if (bad.empty()) return 0;
    std::vector<int> corners;
    for (int t : bad)
      for (int v : out_.linear.triangle(t)) corners.push_back(v);
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    int moved = 0;
    for (int v : corners) moved += move_corner(v);
    for (int t : bad) moved += smooth_centre(t);
    s_.smoothing_moves += moved;
    return moved;
  }

  // Passes over the triangles still above the stop energy after smoothing: for each, the swap
  // of one of its edges, else the collapse of one, else the split of one (longer edges first),
  // whichever first lowers the worst energy of the triangles it changes with every changed
  // triangle certified; then a smoothing pass. At most max_smoothing_passes passes.
  void improve() {
    for (int pass = 0; pass < o_.max_smoothing_passes; ++pass) {
      const std::vector<int> bad = bad_triangles();
      if (bad.empty()) return;
      int changed = 0;
      for (int t : bad)
        if (out_.linear.alive(t) && energy(t) > o_.stop_amips) changed += improve_triangle(t);
      changed += smooth_pass();
      if (changed == 0) return;
    }
  }

  int improve_triangle(int t) {
    TriMesh& m = out_.linear;
    const mesh::Triangle tri = m.triangle(t);
    std::array<std::array<int, 2>, 3> edges{{{tri[0], tri[1]}, {tri[1], tri[2]}, {tri[2], tri[0]}}};
    std::stable_sort(edges.begin(), edges.end(), [&](const auto& x, const auto& y) {
      return (at(x[0]) - at(x[1])).squaredNorm() > (at(y[0]) - at(y[1])).squaredNorm();
    });
    for (const auto& [a, b] : edges) {
      if (m.feature(a, b)) continue;
      if (try_operation(m.edge_triangles(a, b), [&]() -> std::optional<std::vector<int>> {
            std::vector<int> changed = m.edge_triangles(a, b);
            if (!mesh::swap_edge(m, a, b, std::numeric_limits<double>::infinity())) return std::nullopt;
            return changed;
          })) {
        ++s_.curved_swaps;
        return 1;
      }
    }
    for (const auto& [a, b] : edges)
      for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
        const std::vector<int> star = m.triangles_of(from);
        if (try_operation(star, [&]() -> std::optional<std::vector<int>> {
              std::vector<int> kept;
              for (int u : star) {
                const auto& corners = m.triangle(u);
                if (std::find(corners.begin(), corners.end(), to) == corners.end()) kept.push_back(u);
              }
              if (!mesh::collapse_edge(m, c_, from, to, std::numeric_limits<double>::infinity())) return std::nullopt;
              return kept;
            })) {
          ++s_.curved_collapses;
          return 1;
        }
      }
    // Splits: one edge, or two (the triangle's corner between them cut off: a thin corner
    // between a curve and another feature needs both its sides shortened), the new vertices
    // moved where their stars are best before the outcome is judged.
    const auto split = [&](int a, int b) {
      const int mid = mesh::split_edge(m, c_, a, b, std::numeric_limits<double>::infinity());
      // A primary vertex left on the chord would leave its curve's edges straight.
      return mid >= 0 && !(m.tag(mid).kind == mesh::VertexKind::primary && !m.tag(mid).on_curve) ? mid : -1;
    };
    for (const auto& [a, b] : edges) {
      if (try_operation(m.edge_triangles(a, b), [&]() -> std::optional<std::vector<int>> {
            const int mid = split(a, b);
            if (mid < 0) return std::nullopt;
            return m.triangles_of(mid);
          })) {
        ++s_.curved_splits;
        return 1;
      }
    }
    for (int i = 0; i < 3; ++i) {
      // The corner tri[i] between edges (tri[i], tri[i+1]) and (tri[i+2], tri[i]).
      const int a = tri[i], b = tri[(i + 1) % 3], c = tri[(i + 2) % 3];
      const std::vector<int> before = sorted_union(m.edge_triangles(a, b), m.edge_triangles(c, a));
      if (try_operation(before, [&]() -> std::optional<std::vector<int>> {
            const int m1 = split(a, b);
            const int m2 = m1 < 0 ? -1 : split(c, a);
            if (m2 < 0) return std::nullopt;
            return sorted_union(m.triangles_of(m1), m.triangles_of(m2));
          })) {
        s_.curved_splits += 2;
        return 1;
      }
    }
    return 0;
  }

  // Tries a local operation of the linear mesh on the curved mesh. `operation` changes
  // out_.linear (under its journal) and returns the triangles it changed or made, or nothing if
  // it refused. Those triangles get their P3 nodes (new edges on their curve where they can
  // follow it, centres chosen as in step 2) and new vertices settle; the operation is kept only
  // if none of them has two primary edges and, compared with `before` (the triangles it
  // replaces), fewer of them are uncertified (validity first: triangles flat to round-off leave
  // a mesh that cannot be written), or all are certified and their worst energy is lower.
  // Otherwise everything is put back.
  template <class Operation>
  bool try_operation(const std::vector<int>& before, const Operation& operation) {
    TriMesh& m = out_.linear;
    double worst_before = 0;
    int invalid_before = 0;
    std::vector<std::uint64_t> old_edges;
    struct Saved {
      int t;
      std::array<int, 10> ids;
      double scaled;
    };
    std::vector<Saved> saved;
    for (int t : before) {
      worst_before = std::max(worst_before, energy(t));
      invalid_before += scaled_[t] <= 0;
      saved.push_back({t, out_.triangles[t], scaled_[t]});
      const auto& tri = m.triangle(t);
      for (int i = 0; i < 3; ++i) old_edges.push_back(mesh::edge_key(tri[i], tri[(i + 1) % 3]));
    }
    const std::size_t nodes0 = out_.nodes.size(), vertices0 = vertex_node_.size(), slots0 = out_.triangles.size();
    const int moves0 = s_.smoothing_moves;
    new_edges_.clear();
    m.open_journal();
    const std::optional<std::vector<int>> after = operation();
    bool ok = after.has_value();
    if (ok) {
      for (int v = static_cast<int>(vertices0); v < m.vertex_count(); ++v) {
        vertex_node_.push_back(static_cast<int>(out_.nodes.size()));
        out_.nodes.push_back(m.point(v));
      }
      out_.triangles.resize(m.triangle_slots());
      scaled_.resize(m.triangle_slots(), -1.0);
      for (int t : *after) ok = ok && place_triangle(t);
      for (int v = static_cast<int>(vertices0); ok && v < m.vertex_count(); ++v) settle_vertex(v, *after);
      if (ok) {
        double worst_after = 0;
        int invalid_after = 0;
        std::vector<std::optional<double>> certified;
        for (int t : *after) {
          worst_after = std::max(worst_after, energy(t));
          certified.push_back(certify(t));
          invalid_after += !certified.back();
        }
        ok = invalid_after < invalid_before || (invalid_after == 0 && worst_after < worst_before);
        if (ok)
          for (std::size_t k = 0; k < after->size(); ++k) scaled_[(*after)[k]] = certified[k].value_or(-1.0);
      }
    }
    if (!ok) {
      m.rollback();
      for (const auto key : new_edges_) first_node_.erase(key), curved_.erase(key);
      out_.nodes.resize(nodes0);
      vertex_node_.resize(vertices0);
      out_.triangles.resize(slots0);
      scaled_.resize(slots0);
      for (const Saved& x : saved) out_.triangles[x.t] = x.ids, scaled_[x.t] = x.scaled;
      s_.smoothing_moves = moves0;
      new_edges_.clear();
      return false;
    }
    m.commit();
    new_edges_.clear();
    // Edges the operation removed lose their nodes (a later operation may make them again).
    for (const auto key : old_edges) {
      const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
      if (m.edge_triangles(a, b).empty()) first_node_.erase(key), curved_.erase(key), fitted_.erase(key);
    }
    return true;
  }

  // Corner v moves to where its star is best, as its kind allows: free vertices in the plane,
  // secondary ones in the plane while their secondary edges stay in the ε-envelope, primary ones
  // on their curve along it; others, and the ends of a fitted edge (its bend was fitted for where
  // they are), stay. Returns 1 if it moved.
  int move_corner(int v) {
    const mesh::VertexTag& tag = out_.linear.tag(v);
    if (on_fitted_edge(v)) return 0;
    if (tag.kind == mesh::VertexKind::free || tag.kind == mesh::VertexKind::secondary) return smooth_corner(v);
    if (tag.kind == mesh::VertexKind::primary && tag.on_curve) return smooth_curve_corner(v);
    return 0;
  }

  // A vertex made by a split moves (move_corner), then the centres of `triangles` do.
  void settle_vertex(int v, const std::vector<int>& triangles) {
    move_corner(v);
    for (int t : triangles) smooth_centre(t);
  }

  // Gives triangle t (changed by an operation) its nodes: its edges' (made where new), a new
  // centre. False if it has two primary edges (step 1 gave every triangle at most one).
  bool place_triangle(int t) {
    const TriMesh& m = out_.linear;
    const mesh::Triangle tri = m.triangle(t);
    if (primary_edges_of(m, tri) > 1) return false;
    for (int i = 0; i < 3; ++i) add_edge(tri[i], tri[(i + 1) % 3]);
    std::array<int, 10> ids = corner_and_edge_nodes(tri);
    ids[9] = static_cast<int>(out_.nodes.size());
    out_.nodes.push_back((at(tri[0]) + at(tri[1]) + at(tri[2])) / 3);
    out_.triangles[t] = ids;
    if (curved_edge_of(tri) >= 0) choose_centre_of(t);
    return true;
  }

  // After step 4: the linear mesh compacted (dead triangles and removed vertices dropped), the
  // curved triangles with it, and the nodes renumbered, vertices first in their new order, then
  // every other node still used in its old order.
  void finish() {
    TriMesh& m = out_.linear;
    std::vector<std::array<int, 10>> triangles;
    std::vector<double> scaled;
    for (int t = 0; t < m.triangle_slots(); ++t)
      if (m.alive(t)) triangles.push_back(out_.triangles[t]), scaled.push_back(scaled_[t]);
    // Edge data, keyed by the new vertex numbers (the renumbering keeps the vertices' order).
    std::vector<std::pair<std::array<int, 2>, int>> edges;
    for (int t = 0; t < m.triangle_slots(); ++t) {
      if (!m.alive(t)) continue;
      const auto& tri = m.triangle(t);
      for (int i = 0; i < 3; ++i) {
        const int a = std::min(tri[i], tri[(i + 1) % 3]), b = std::max(tri[i], tri[(i + 1) % 3]);
        edges.push_back({{a, b}, first_node_.at(mesh::edge_key(a, b))});  // inner edges twice
      }
    }
    const std::vector<int> remap = m.compact();
    std::vector<int> node_id(out_.nodes.size(), -1);
    int next = 0;
    for (std::size_t v = 0; v < remap.size(); ++v)
      if (remap[v] >= 0) node_id[vertex_node_[v]] = remap[v], ++next;
    std::vector<char> used(out_.nodes.size(), 0);
    for (const auto& ids : triangles)
      for (int id : ids) used[id] = 1;
    for (std::size_t id = 0; id < out_.nodes.size(); ++id)
      if (used[id] && node_id[id] < 0) node_id[id] = next++;
    std::vector<Vec2> nodes(next);
    for (std::size_t id = 0; id < out_.nodes.size(); ++id)
      if (node_id[id] >= 0) nodes[node_id[id]] = out_.nodes[id];
    for (auto& ids : triangles)
      for (int& id : ids) id = node_id[id];
    std::unordered_map<std::uint64_t, int> first_node;
    std::unordered_map<std::uint64_t, bool> curved;
    std::unordered_set<std::uint64_t> fitted;
    for (const auto& [edge, first] : edges) {
      const auto key = mesh::edge_key(edge[0], edge[1]), new_key = mesh::edge_key(remap[edge[0]], remap[edge[1]]);
      first_node[new_key] = node_id[first];
      curved[new_key] = curved_.at(key);
      if (fitted_.count(key)) fitted.insert(new_key);
    }
    out_.nodes = std::move(nodes);
    out_.triangles = std::move(triangles);
    scaled_ = std::move(scaled);
    first_node_ = std::move(first_node);
    curved_ = std::move(curved);
    fitted_ = std::move(fitted);
    vertex_node_.resize(m.vertex_count());
    for (int v = 0; v < m.vertex_count(); ++v) vertex_node_[v] = v;
  }

  // The nodes of some triangles, to put back when a move is refused.
  using Snapshot = std::vector<std::pair<int, Vec2>>;
  Snapshot snapshot(const std::vector<int>& triangles) const {
    Snapshot saved;
    for (int t : triangles)
      for (int id : out_.triangles[t]) saved.push_back({id, out_.nodes[id]});
    return saved;
  }
  void restore(const Snapshot& saved) {
    for (const auto& [id, x] : saved) out_.nodes[id] = x;
  }

  // Certifies every one of `triangles`; only if all are certified, records their scaled
  // Jacobians and returns true.
  bool certify_all(const std::vector<int>& triangles) {
    std::vector<double> scaled;
    for (int t : triangles) {
      const auto cert = certify(t);
      if (!cert) return false;
      scaled.push_back(*cert);
    }
    for (std::size_t k = 0; k < triangles.size(); ++k) scaled_[triangles[k]] = scaled[k];
    return true;
  }

  // Whether v's triangles stay counter-clockwise (exactly, as straight triangles) with v at p.
  bool corners_valid_with(int v, const Vec2& p) const {
    const TriMesh& m = out_.linear;
    for (int t : m.triangles_of(v)) {
      const auto& tri = m.triangle(t);
      if (m.orientation_with(tri[0], tri[1], tri[2], v, p) <= 0) return false;
    }
    return true;
  }

  // Whether v's secondary edges stay inside the ε-envelope of the secondary input with v at p
  // (invariant 2 of §4.1).
  bool secondary_edges_inside_with(int v, const Vec2& p) const {
    const TriMesh& m = out_.linear;
    if (m.tag(v).kind != mesh::VertexKind::secondary) return true;
    for (int w : m.neighbours(v)) {
      const mesh::EdgeFeature* f = m.feature(v, w);
      if (f && f->kind == EdgeKind::secondary && !c_.envelope.contains(p, m.point(w))) return false;
    }
    return true;
  }

  // The largest of `measure` (energy, badness) over v's triangles.
  template <class Measure>
  double star_worst(int v, const Measure& measure) const {
    double worst = 0;
    for (int t : out_.linear.triangles_of(v)) worst = std::max(worst, measure(t));
    return worst;
  }

  // Where free corner v should go: compass search, from where it is and a first step of a quarter
  // of its shortest edge, on the worst `measure` around it (its nodes placed by place_corner);
  // positions that would turn a corner triangle over are out. Leaves every node as it was.
  template <class Measure>
  Vec2 search_corner(int v, const Measure& measure) {
    const TriMesh& m = out_.linear;
    double shortest = std::numeric_limits<double>::infinity();
    for (int w : m.neighbours(v)) shortest = std::min(shortest, (m.point(w) - m.point(v)).norm());
    const Snapshot saved = snapshot(m.triangles_of(v));
    return compass_search(at(v), 0.25 * shortest, [&](const Vec2& p) {
      if (!corners_valid_with(v, p) || !secondary_edges_inside_with(v, p)) return std::numeric_limits<double>::infinity();
      place_corner(v, p);
      const double worst = star_worst(v, measure);
      restore(saved);
      return worst;
    });
  }

  // Compass search: from x0 with the first step h, in 8 directions, halving h when none lowers
  // `objective`; returns the best point found.
  template <class Objective>
  Vec2 compass_search(const Vec2& x0, double h, const Objective& objective) const {
    Vec2 x = x0;
    double best = objective(x0);
    for (int halvings = 0; halvings < 12;) {
      bool improved = false;
      for (int d = 0; d < 8; ++d) {
        const double angle = d * std::numbers::pi / 4;
        const Vec2 y = x + h * Vec2(std::cos(angle), std::sin(angle));
        const double e = objective(y);
        if (e < best) best = e, x = y, improved = true;
      }
      if (!improved) h *= 0.5, ++halvings;
    }
    return x;
  }

  // Places the nodes that depend on corner v's position (and, on a curve, on its parameter): v,
  // the inner nodes of its edges (curved ones on their curve, at thirds of their parameter
  // interval; straight ones at thirds), and the centres of its triangles (straight: the
  // centroid; curved: the candidate of lowest badness, certified later).
  void place_corner(int v, const Vec2& p) {
    at(v) = p;
    const TriMesh& m = out_.linear;
    for (int t : m.triangles_of(v)) {
      const auto& ids = out_.triangles[t];
      const auto& tri = m.triangle(t);
      for (int i = 0; i < 3; ++i) {
        const int a = tri[i], b = tri[(i + 1) % 3];
        if (a != v && b != v) continue;
        if (curved_.at(mesh::edge_key(a, b))) {
          place_on_curve(std::min(a, b), std::max(a, b));
        } else {
          out_.nodes[ids[3 + 2 * i]] = (2 * at(a) + at(b)) / 3;
          out_.nodes[ids[4 + 2 * i]] = (at(a) + 2 * at(b)) / 3;
        }
      }
      if (curved_edge_of(tri) < 0) {
        out_.nodes[ids[9]] = (at(tri[0]) + at(tri[1]) + at(tri[2])) / 3;
        continue;
      }
      choose_centre_of(t);
    }
  }

  // The two neighbours of primary vertex v along its section, and their parameters.
  struct CurveNeighbours {
    int x = -1, y = -1;
    double tx = 0, ty = 0;
  };

  // A primary corner at parameter t of its curve: its tag and the parameters of its two edges
  // along the curve follow.
  void place_on_curve_at(int v, const CurveNeighbours& n, double t) {
    TriMesh& m = out_.linear;
    mesh::VertexTag tag = m.tag(v);
    tag.t = t;
    m.set_tag(v, tag);
    for (int w : {n.x, n.y}) {
      mesh::EdgeFeature f = *m.feature(v, w);
      (v < w ? f.t_lo : f.t_hi) = t;
      m.set_feature(v, w, f);
    }
    place_corner(v, c_.sections[tag.section].eval(t));
  }

  bool curve_neighbours(int v, CurveNeighbours& n) const {
    const TriMesh& m = out_.linear;
    const mesh::VertexTag& tag = m.tag(v);
    int found = 0;
    for (int t : m.triangles_of(v))
      for (int w : m.triangle(t)) {
        const mesh::EdgeFeature* f = w == v ? nullptr : m.feature(v, w);
        if (!f || f->kind != EdgeKind::primary || f->source != tag.section || w == n.x || w == n.y) continue;
        const double tw = w < v ? f->t_lo : f->t_hi;
        if (found == 0) n.x = w, n.tx = tw;
        else if (found == 1) n.y = w, n.ty = tw;
        ++found;
      }
    return found == 2;
  }

  // A primary corner (on its curve, inside its section) slides along the curve between its two
  // curve neighbours; the curve's turning per edge no longer matters once the edges are curved
  // (§4.2), only the certificate does.
  int smooth_curve_corner(int v) {
    TriMesh& m = out_.linear;
    const mesh::VertexTag tag0 = m.tag(v);
    CurveNeighbours n;
    if (!curve_neighbours(v, n)) return 0;
    const auto& star = m.triangles_of(v);
    const auto energy_of = [&](int t) { return energy(t); };
    const Snapshot saved = snapshot(star);
    const mesh::EdgeFeature fx = *m.feature(v, n.x), fy = *m.feature(v, n.y);
    const auto undo = [&] {
      restore(saved);
      m.set_tag(v, tag0);
      m.set_feature(v, n.x, fx);
      m.set_feature(v, n.y, fy);
    };
    const mesh::SectionCurve& curve = c_.sections[tag0.section];
    const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
    const auto objective = [&](double t) {
      if (!(t > lo + margin && t < hi - margin) || !corners_valid_with(v, curve.eval(t)))
        return std::numeric_limits<double>::infinity();
      place_on_curve_at(v, n, t);
      const double e = star_worst(v, energy_of);
      undo();
      return e;
    };
    const double before = star_worst(v, energy_of);
    double t = tag0.t, best = before, h = 0.25 * std::min(t - lo, hi - t);
    for (int halvings = 0; halvings < 12;) {
      bool improved = false;
      for (const double step : {h, -h})
        if (const double e = objective(t + step); e < best) best = e, t += step, improved = true;
      if (!improved) h *= 0.5, ++halvings;
    }
    if (t == tag0.t || !(best < before)) return 0;
    place_on_curve_at(v, n, t);
    if (!certify_all(star)) {
      undo();
      return 0;
    }
    m.set_position(v, at(v));
    return 1;
  }

  // Moves primary vertex v, still off its curve, to its closest point on the curve (between its
  // two curve neighbours); its edges along the curve become curved where their other end is on
  // the curve too. Kept only if the corners' triangles stay counter-clockwise and every changed
  // triangle is certified.
  int project(int v) {
    TriMesh& m = out_.linear;
    const mesh::VertexTag tag0 = m.tag(v);
    CurveNeighbours n;
    if (!curve_neighbours(v, n)) return 0;
    const mesh::SectionCurve& curve = c_.sections[tag0.section];
    const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
    const geometry::ClosestPoint cp = geometry::closest_point(curve.piece, m.point(v));
    const double t = std::clamp(curve.t0 + cp.t * (curve.t1 - curve.t0), lo + margin, hi - margin);
    const Vec2 p = curve.eval(t);
    if (!corners_valid_with(v, p)) return 0;
    const auto& star = m.triangles_of(v);
    const Snapshot saved = snapshot(star);
    const mesh::EdgeFeature fx = *m.feature(v, n.x), fy = *m.feature(v, n.y);
    mesh::VertexTag tag = tag0;
    tag.on_curve = true;
    m.set_tag(v, tag);
    for (int w : {n.x, n.y}) curved_[mesh::edge_key(v, w)] = followable(m, v, w);
    place_on_curve_at(v, n, t);
    if (!certify_all(star)) {
      restore(saved);
      m.set_tag(v, tag0);
      m.set_feature(v, n.x, fx);
      m.set_feature(v, n.y, fy);
      for (int w : {n.x, n.y}) curved_[mesh::edge_key(v, w)] = false;
      return 0;
    }
    m.set_position(v, p);
    return 1;
  }

  int smooth_corner(int v) {
    TriMesh& m = out_.linear;
    const auto& star = m.triangles_of(v);
    const auto energy_of = [&](int t) { return energy(t); };
    const Snapshot saved = snapshot(star);  // everything the move can change
    const Vec2 x0 = m.point(v);
    const double before = star_worst(v, energy_of);
    const Vec2 x = search_corner(v, energy_of);
    if (x == x0) return 0;
    place_corner(v, x);
    if (!(star_worst(v, energy_of) < before) || !certify_all(star)) {
      restore(saved);
      return 0;
    }
    m.set_position(v, x);
    return 1;
  }

  int smooth_centre(int t) {
    auto& centre = out_.nodes[out_.triangles[t][9]];
    const Vec2 x0 = centre;
    const double before = energy(t);
    geometry::P3Nodes q = nodes_of(t);
    double size = 0;
    for (int i = 0; i < 3; ++i) size = std::max(size, (q[i] - q[(i + 1) % 3]).norm());
    const Vec2 x = compass_search(x0, 0.05 * size, [&](const Vec2& p) {
      q[9] = p;
      return geometry::p3_max_amips(q);
    });
    q[9] = x;
    if (x == x0 || !(geometry::p3_max_amips(q) < before)) return 0;
    centre = x;
    const auto cert = certify(t);
    if (!cert) {
      centre = x0;
      return 0;
    }
    scaled_[t] = *cert;
    return 1;
  }

  // The scaled Jacobian of triangle t if it is certified positive.
  std::optional<double> certify(int t) const {
    geometry::JacobianCheckOptions check;
    check.max_depth = o_.certificate_depth;
    const auto result = geometry::certify_jacobian(nodes_of(t), check);
    if (result.verdict != geometry::JacobianVerdict::positive) return std::nullopt;
    return result.scaled_jacobian;
  }

  // ----- Step 5: edges that could not follow their curve exactly --------------------------------

  // How far triangle t is from valid, or how good it is: its worst AMIPS energy when det J > 0 at
  // every point of the order-6 lattice, else 1e12 less the smallest det J there over the squared
  // longest side (lower is better either way; only a certificate decides validity).
  double badness(int t) const {
    const geometry::P3Nodes p = nodes_of(t);
    double lo = std::numeric_limits<double>::infinity();
    for (int j = 0; j <= 6; ++j)
      for (int k = 0; j + k <= 6; ++k) lo = std::min(lo, geometry::p3_jacobian(p, j / 6.0, k / 6.0).determinant());
    if (lo > 0) return geometry::p3_max_amips(p);
    double side = 0;
    for (int i = 0; i < 3; ++i) side = std::max(side, (p[i] - p[(i + 1) % 3]).squaredNorm());
    return 1e12 - (side > 0 ? lo / side : -1e6);
  }

  // The centre of triangle t (its edge nodes placed) among the candidates: the lowest badness.
  void choose_centre_of(int t) {
    geometry::P3Nodes q = nodes_of(t);
    Vec2& centre = out_.nodes[out_.triangles[t][9]];
    double best = std::numeric_limits<double>::infinity();
    for (const Vec2& c : centre_candidates(q)) {
      const Vec2 keep = centre;
      centre = c;
      if (const double b = badness(t); b < best) best = b;
      else centre = keep;
    }
  }

  // §4.2 step 5 for primary edge (a, b), whose triangles cannot be certified with the edge on its
  // curve. First the edge is put on its curve and the centre nodes and the free opposite corners
  // move (compass search on badness) until both triangles are certified; failing that, the edge's
  // two inner nodes are fitted: the largest blend s·(curve) + (1 − s)·(chord) with both triangles
  // certified and within the stop energy (or the straight edge's), s by bisection (the
  // least-squares fit to the curve along the one direction in which the straight edge is known to
  // be valid). The remaining distance is recorded in the stats.
  void fit(int a, int b) {
    TriMesh& m = out_.linear;
    const auto key = mesh::edge_key(a, b);
    const int lo = std::min(a, b), hi = std::max(a, b);
    const std::vector<int> triangles = m.edge_triangles(a, b);
    // Everything that can change: the triangles of the edge and the stars of their free corners.
    std::vector<int> touched = triangles, movable;
    for (int t : triangles)
      for (int v : m.triangle(t))
        if (v != a && v != b && m.tag(v).kind == mesh::VertexKind::free) {
          movable.push_back(v);
          touched.insert(touched.end(), m.triangles_of(v).begin(), m.triangles_of(v).end());
        }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    const Snapshot saved = snapshot(touched);
    std::vector<Vec2> positions;
    for (int v : movable) positions.push_back(m.point(v));
    const auto undo = [&] {
      restore(saved);
      for (std::size_t k = 0; k < movable.size(); ++k) m.set_position(movable[k], positions[k]);
    };

    // On the curve, with the centres and the free corners moved.
    curved_[key] = true;
    place_on_curve(lo, hi);
    for (int t : triangles) choose_centre_of(t);
    for (int v : movable) {
      const Vec2 x = search_corner(v, [&](int t) { return badness(t); });
      place_corner(v, x);
      m.set_position(v, x);  // the next corner's orientation checks see this one where it is now
    }
    for (int t : triangles) choose_centre_of(t);
    if (certify_all(touched)) return;
    undo();
    curved_[key] = false;

    // The fit: the largest blend towards the curve with both triangles certified and no worse
    // than the stop energy or the straight edge's (the bare validity limit would leave an element
    // next to degenerate there).
    double allowed = o_.stop_amips;
    for (int t : triangles) allowed = std::max(allowed, energy(t));
    const auto acceptable = [&] {
      for (int t : triangles)
        if (!(energy(t) <= allowed)) return false;
      return certify_all(touched);
    };
    const auto [first, second] = edge_nodes(lo, hi);
    const Vec2 straight1 = out_.nodes[first], straight2 = out_.nodes[second];
    place_on_curve(lo, hi);
    const Vec2 curve1 = out_.nodes[first], curve2 = out_.nodes[second];
    const auto blend = [&](double w) {
      out_.nodes[first] = straight1 + w * (curve1 - straight1);
      out_.nodes[second] = straight2 + w * (curve2 - straight2);
      for (int t : triangles) choose_centre_of(t);
    };
    // certify_all records the scaled Jacobians of each accepted blend: the last one is `good`.
    double good = 0, bad = 1;
    for (int k = 0; k < 12; ++k) {
      const double w = 0.5 * (good + bad);
      blend(w);
      (acceptable() ? good : bad) = w;
    }
    if (good == 0) {
      undo();
      return;
    }
    blend(good);
    fitted_.insert(key);
  }

  bool on_fitted_edge(int v) const {
    if (fitted_.empty()) return false;
    for (int w : out_.linear.neighbours(v))
      if (fitted_.count(mesh::edge_key(v, w))) return true;
    return false;
  }

  int fitted_edge_of(const mesh::Triangle& tri) const {
    for (int i = 0; i < 3; ++i)
      if (fitted_.count(mesh::edge_key(tri[i], tri[(i + 1) % 3]))) return i;
    return -1;
  }

  // ----- Steps 2 and 3 ------------------------------------------------------------------------
  void add_edge(int a, int b) {
    const auto key = mesh::edge_key(a, b);
    if (first_node_.count(key)) return;
    new_edges_.push_back(key);
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
    const Vec2 &a = at(lo), &b = at(hi);
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

  // The node ids of a triangle's corners and edges in Gmsh's order (the centre, ids[9], is left
  // to the caller).
  std::array<int, 10> corner_and_edge_nodes(const mesh::Triangle& tri) const {
    std::array<int, 10> ids{};
    for (int i = 0; i < 3; ++i) {
      ids[i] = vertex_node_[tri[i]];
      const auto [first, second] = edge_nodes(tri[i], tri[(i + 1) % 3]);
      ids[3 + 2 * i] = first;
      ids[4 + 2 * i] = second;
    }
    return ids;
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
    const std::array<int, 10> ids = corner_and_edge_nodes(tri);
    geometry::P3Nodes p;
    for (int i = 0; i < 9; ++i) p[i] = out_.nodes[ids[i]];
    p[9] = (p[0] + p[1] + p[2]) / 3;
    return p;
  }

  // The centre that reproduces quadratic maps exactly first: with it the map's cubic part is as
  // small as the edges allow, which finite elements on the mesh need for their full order (with
  // the paper's centre, the average of the other nine nodes, P2 on a disk converges at L2 rate
  // 2.65 instead of 3; fem/convergence.hpp). Where that map is not certified, the paper's centre,
  // then the corners' centroid.
  // Sets p[9] to the first certified one (its index in `choice`, its scaled Jacobian in
  // `scaled`) and returns true, or returns false.
  static std::array<Vec2, 3> centre_candidates(const geometry::P3Nodes& p) {
    const Vec2 sum_corners = p[0] + p[1] + p[2];
    Vec2 sum_edges = Vec2::Zero();
    for (int i = 3; i < 9; ++i) sum_edges += p[i];
    return {sum_edges / 4 - sum_corners / 6, (sum_corners + sum_edges) / 9, sum_corners / 3};
  }

  bool choose_centre(geometry::P3Nodes& p, int& choice, double& scaled) const {
    const std::array<Vec2, 3> centres = centre_candidates(p);
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
    const Vec2 &p0 = at(a), &p1 = out_.nodes[first], &p2 = out_.nodes[second], &p3 = at(b);
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
  // Where each vertex's node is in out_.nodes: the vertex's own index until step 4 adds vertices
  // (finish() puts the vertices first again).
  std::vector<int> vertex_node_;
  std::unordered_map<std::uint64_t, int> first_node_;
  std::unordered_map<std::uint64_t, bool> curved_;
  std::vector<double> scaled_;  // per triangle: its scaled Jacobian, or −1 if not certified
  std::unordered_set<std::uint64_t> fitted_;  // primary edges fitted (step 5), not on their curve
  std::vector<std::uint64_t> new_edges_;      // edges made during the operation being tried
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
