#include "mesh/curved_form.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "mesh/curved_element.hpp"

namespace curvemesh::mesh {

CurvedForm::CurvedForm(TriMesh& m, const Constraints& c, int order)
    : m_(m),
      c_(c),
      order_(order),
      nodes_(m.journal()),
      triangle_nodes_(m.journal()),
      vertex_node_(m.journal()),
      first_node_(m.journal()),
      follows_(m.journal()),
      scaled_(m.journal()),
      fitted_(m.journal()) {
  std::vector<Vec2> corners(m.vertex_count());
  std::vector<int> vertex_node(m.vertex_count());
  for (int v = 0; v < m.vertex_count(); ++v) corners[v] = m.point(v), vertex_node[v] = v;
  nodes_.assign(std::move(corners));
  vertex_node_.assign(std::move(vertex_node));
  // Edge nodes, in the order triangles first meet their edges (deterministic).
  for (int t = 0; t < m.triangle_slots(); ++t) {
    if (!m.alive(t)) continue;
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) add_edge(tri[i], tri[(i + 1) % 3]);
  }
}

geometry::P3Nodes CurvedForm::p3(int t) const {
  geometry::P3Nodes p;
  for (int i = 0; i < 10; ++i) p[i] = nodes_[triangle_nodes_[t][i]];
  return p;
}

geometry::P2Nodes CurvedForm::p2(int t) const {
  geometry::P2Nodes p;
  for (int i = 0; i < 6; ++i) p[i] = nodes_[triangle_nodes_[t][i]];
  return p;
}

double CurvedForm::energy(int t, double bound) const {
  return quadratic() ? geometry::p2_max_amips(p2(t), bound) : geometry::p3_max_amips(p3(t), bound);
}

namespace {

// Badness from the lattice values of nodes p (CurvedForm::badness).
template <class Nodes>
double badness_of(const Nodes& p, const geometry::P3LatticeValues& v) {
  if (v.min_det > 0) return v.max_amips;
  double side = 0;
  for (int i = 0; i < 3; ++i) side = std::max(side, (p[i] - p[(i + 1) % 3]).squaredNorm());
  return 1e12 - (side > 0 ? v.min_det / side : -1e6);
}

}  // namespace

double CurvedForm::badness(int t) const {
  if (quadratic()) {
    const geometry::P2Nodes p = p2(t);
    return badness_of(p, geometry::p2_lattice_values(p));
  }
  const geometry::P3Nodes p = p3(t);
  return badness_of(p, geometry::p3_lattice_values(p));
}

std::optional<double> CurvedForm::certify(int t, int depth) const {
  geometry::JacobianCheckOptions check;
  check.max_depth = depth;
  const auto result =
      quadratic() ? geometry::certify_jacobian(p2(t), check) : geometry::certify_jacobian(p3(t), check);
  if (result.verdict != geometry::JacobianVerdict::positive) return std::nullopt;
  return result.scaled_jacobian;
}

std::pair<int, int> CurvedForm::edge_nodes(int a, int b) const {
  const int n = first_node_.at(edge_key(a, b));
  if (quadratic()) return {n, n};
  return a < b ? std::pair{n, n + 1} : std::pair{n + 1, n};
}

std::array<int, 10> CurvedForm::corner_and_edge_nodes(const Triangle& tri) const {
  std::array<int, 10> ids{};
  if (quadratic()) ids.fill(-1);
  for (int i = 0; i < 3; ++i) {
    ids[i] = vertex_node_[tri[i]];
    const auto [first, second] = edge_nodes(tri[i], tri[(i + 1) % 3]);
    if (quadratic()) {
      ids[3 + i] = first;
      continue;
    }
    ids[3 + 2 * i] = first;
    ids[4 + 2 * i] = second;
  }
  return ids;
}

bool CurvedForm::follows(int a, int b) const {
  const bool* f = follows_.find(edge_key(a, b));
  return f && *f;
}

int CurvedForm::curved_edge_of(const Triangle& tri) const {
  for (int i = 0; i < 3; ++i)
    if (follows(tri[i], tri[(i + 1) % 3])) return i;
  return -1;
}

int CurvedForm::fitted_edge_of(const Triangle& tri) const {
  for (int i = 0; i < 3; ++i)
    if (fitted(tri[i], tri[(i + 1) % 3])) return i;
  return -1;
}

bool CurvedForm::on_fitted_edge(int v) const {
  if (fitted_.empty()) return false;
  for (int w : m_.neighbours(v))
    if (fitted(v, w)) return true;
  return false;
}

void CurvedForm::push_triangle(const Triangle& tri, const Vec2& centre, double scaled) {
  std::array<int, 10> ids = corner_and_edge_nodes(tri);
  if (!quadratic()) {
    ids[9] = static_cast<int>(nodes_.size());
    nodes_.push_back(centre);
  }
  triangle_nodes_.push_back(ids);
  scaled_.push_back(scaled);
}

void CurvedForm::add_edge(int a, int b) {
  const auto key = edge_key(a, b);
  if (first_node_.contains(key)) return;
  const int lo = std::min(a, b), hi = std::max(a, b);
  first_node_.set(key, static_cast<int>(nodes_.size()));
  nodes_.push_back(Vec2::Zero());
  if (!quadratic()) nodes_.push_back(Vec2::Zero());
  const bool curved = followable(m_, lo, hi);
  follows_.set(key, curved);
  if (curved)
    place_on_curve(lo, hi);
  else
    place_straight(lo, hi);
}

void CurvedForm::place_straight(int lo, int hi) {
  place_inner_nodes(lo, hi, nodes_on_chord(at(lo), at(hi), order_));
}

void CurvedForm::place_on_curve(int lo, int hi) {
  const EdgeFeature& f = *m_.feature(lo, hi);
  place_inner_nodes(lo, hi, nodes_on_curve(c_.sections[f.source], f.t_lo, f.t_hi, order_));
}

void CurvedForm::place_inner_nodes(int lo, int hi, const std::array<Vec2, 2>& inner) {
  const int n = first_node_.at(edge_key(lo, hi));
  nodes_.set(n, inner[0]);
  if (!quadratic()) nodes_.set(n + 1, inner[1]);
}

void CurvedForm::straighten(int a, int b) {
  const auto key = edge_key(a, b);
  if (!follows_.at(key)) return;
  follows_.set(key, false);
  place_straight(std::min(a, b), std::max(a, b));
}

void CurvedForm::place_corner(int v, const Vec2& p) {
  nodes_.set(vertex_node_[v], p);
  for (int t : m_.triangles_of(v)) {
    const auto& ids = triangle_nodes_[t];
    const auto& tri = m_.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (a != v && b != v) continue;
      if (follows_.at(edge_key(a, b))) {
        place_on_curve(std::min(a, b), std::max(a, b));
      } else if (quadratic()) {
        place_straight(std::min(a, b), std::max(a, b));
      } else {
        nodes_.set(ids[3 + 2 * i], (2 * at(a) + at(b)) / 3);
        nodes_.set(ids[4 + 2 * i], (at(a) + 2 * at(b)) / 3);
      }
    }
    if (quadratic()) continue;
    if (curved_edge_of(tri) < 0) {
      nodes_.set(ids[9], (at(tri[0]) + at(tri[1]) + at(tri[2])) / 3);
      continue;
    }
    choose_centre(t);
  }
}

// p3_lattice_values's max_amips is p3_max_amips's value, bit for bit (same lattice, same order),
// so the energy returned is energy(t)'s.
double CurvedForm::choose_centre(int t) {
  if (quadratic()) {
    const geometry::P3LatticeValues v = geometry::p2_lattice_values(p2(t));
    return v.min_det > 0 ? v.max_amips : std::numeric_limits<double>::quiet_NaN();
  }
  geometry::P3Nodes q = p3(t);
  double best = std::numeric_limits<double>::infinity();
  double energy = std::numeric_limits<double>::quiet_NaN();
  std::optional<Vec2> chosen;
  for (const Vec2& c : geometry::p3_centre_candidates(q)) {
    q[9] = c;
    const geometry::P3LatticeValues v = geometry::p3_lattice_values(q);
    if (const double b = badness_of(q, v); b < best) {
      best = b;
      energy = v.min_det > 0 ? v.max_amips : std::numeric_limits<double>::quiet_NaN();
      chosen = c;
    }
  }
  if (chosen) nodes_.set(triangle_nodes_[t][9], *chosen);
  return energy;
}

bool CurvedForm::adopt(int first_new_vertex, const std::vector<int>& triangles, std::vector<double>& known) {
  for (int v = first_new_vertex; v < m_.vertex_count(); ++v) {
    vertex_node_.push_back(static_cast<int>(nodes_.size()));
    nodes_.push_back(m_.point(v));
  }
  triangle_nodes_.resize(m_.triangle_slots());
  scaled_.resize(m_.triangle_slots(), -1.0);
  known.assign(triangles.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const int t = triangles[k];
    const Triangle tri = m_.triangle(t);
    int primary = 0;
    for (int i = 0; i < 3; ++i) primary += is_primary(m_, tri[i], tri[(i + 1) % 3]);
    if (primary > 1) return false;
    for (int i = 0; i < 3; ++i) add_edge(tri[i], tri[(i + 1) % 3]);
    std::array<int, 10> ids = corner_and_edge_nodes(tri);
    if (!quadratic()) {
      ids[9] = static_cast<int>(nodes_.size());
      nodes_.push_back((at(tri[0]) + at(tri[1]) + at(tri[2])) / 3);
    }
    triangle_nodes_.set(t, ids);
    if (curved_edge_of(tri) >= 0) known[k] = choose_centre(t);
  }
  return true;
}

void CurvedForm::forget_edges(const std::vector<std::uint64_t>& edges) {
  for (const auto key : edges) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    if (m_.edge_triangles(a, b).empty()) first_node_.erase(key), follows_.erase(key), fitted_.erase(key);
  }
}

CurvedForm::Snapshot CurvedForm::snapshot(const std::vector<int>& triangles) const {
  Snapshot saved;
  for (int t : triangles)
    for (int id : triangle_nodes_[t])
      if (id >= 0) saved.push_back({id, nodes_[id]});
  return saved;
}

void CurvedForm::restore(const Snapshot& saved) {
  for (const auto& [id, x] : saved) nodes_.set(id, x);
}

void CurvedForm::compact() {
  std::vector<std::array<int, 10>> triangles;
  std::vector<double> scaled;
  for (int t = 0; t < m_.triangle_slots(); ++t)
    if (m_.alive(t)) triangles.push_back(triangle_nodes_[t]), scaled.push_back(scaled_[t]);
  // Edge data, keyed by the new vertex numbers (the renumbering keeps the vertices' order).
  std::vector<std::pair<std::array<int, 2>, int>> edges;
  for (int t = 0; t < m_.triangle_slots(); ++t) {
    if (!m_.alive(t)) continue;
    const auto& tri = m_.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const int a = std::min(tri[i], tri[(i + 1) % 3]), b = std::max(tri[i], tri[(i + 1) % 3]);
      edges.push_back({{a, b}, first_node_.at(edge_key(a, b))});  // inner edges twice
    }
  }
  const std::vector<int> remap = m_.compact();
  std::vector<int> node_id(nodes_.size(), -1);
  int next = 0;
  for (std::size_t v = 0; v < remap.size(); ++v)
    if (remap[v] >= 0) node_id[vertex_node_[v]] = remap[v], ++next;
  std::vector<char> used(nodes_.size(), 0);
  for (const auto& ids : triangles)
    for (int id : ids)
      if (id >= 0) used[id] = 1;
  for (std::size_t id = 0; id < nodes_.size(); ++id)
    if (used[id] && node_id[id] < 0) node_id[id] = next++;
  std::vector<Vec2> nodes(next);
  for (std::size_t id = 0; id < nodes_.size(); ++id)
    if (node_id[id] >= 0) nodes[node_id[id]] = nodes_[id];
  for (auto& ids : triangles)
    for (int& id : ids)
      if (id >= 0) id = node_id[id];
  std::unordered_map<std::uint64_t, int> first_node;
  std::unordered_map<std::uint64_t, bool> follows, fitted;
  for (const auto& [edge, first] : edges) {
    const auto key = edge_key(edge[0], edge[1]), new_key = edge_key(remap[edge[0]], remap[edge[1]]);
    first_node[new_key] = node_id[first];
    follows[new_key] = follows_.at(key);
    if (fitted_.contains(key)) fitted[new_key] = true;
  }
  nodes_.assign(std::move(nodes));
  triangle_nodes_.assign(std::move(triangles));
  scaled_.assign(std::move(scaled));
  first_node_.assign(std::move(first_node));
  follows_.assign(std::move(follows));
  fitted_.assign(std::move(fitted));
  std::vector<int> vertex_node(m_.vertex_count());
  for (int v = 0; v < m_.vertex_count(); ++v) vertex_node[v] = v;
  vertex_node_.assign(std::move(vertex_node));
}

}  // namespace curvemesh::mesh
