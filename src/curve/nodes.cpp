// Steps 2 and 3 of curve(): the P3 nodes (edge nodes on the curve or at thirds of the chord,
// centres) or the P2 nodes (an edge's middle node on the curve or at the chord's middle), the
// Jacobian certificate of a triangle, and straightening an edge that fails it.
#include <Eigen/LU>

#include "curve/builder.hpp"

namespace curvemesh::curve::detail {

void Builder::add_edge(int a, int b) {
  const auto key = mesh::edge_key(a, b);
  if (first_node_.contains(key)) return;
  const int lo = std::min(a, b), hi = std::max(a, b);
  first_node_.set(key, static_cast<int>(nodes_.size()));
  nodes_.push_back(Vec2::Zero());
  if (!quadratic()) nodes_.push_back(Vec2::Zero());
  const bool curved = followable(out_.linear, lo, hi);
  curved_.set(key, curved);
  if (curved) place_on_curve(lo, hi); else place_straight(lo, hi);
}

void Builder::place_straight(int lo, int hi) {
  place_inner_nodes(lo, hi, mesh::nodes_on_chord(at(lo), at(hi), o_.order));
}

// On the curve as mesh::nodes_on_curve places them (App. C).
void Builder::place_on_curve(int lo, int hi) {
  const mesh::EdgeFeature& f = *out_.linear.feature(lo, hi);
  place_inner_nodes(lo, hi, mesh::nodes_on_curve(c_.sections[f.source], f.t_lo, f.t_hi, o_.order));
}

void Builder::place_inner_nodes(int lo, int hi, const std::array<Vec2, 2>& inner) {
  const int n = first_node_.at(mesh::edge_key(lo, hi));
  nodes_.set(n, inner[0]);
  if (!quadratic()) nodes_.set(n + 1, inner[1]);
}

void Builder::straighten(int a, int b) {
  const auto key = mesh::edge_key(a, b);
  if (!curved_.at(key)) return;
  curved_.set(key, false);
  place_straight(std::min(a, b), std::max(a, b));
}

// The node ids of a triangle's corners and edges in Gmsh's order (the centre, ids[9], is left
// to the caller). Order 2: the corners and the edges' middle nodes, the rest −1.
std::array<int, 10> Builder::corner_and_edge_nodes(const mesh::Triangle& tri) const {
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

// The two nodes of edge (a, b) in the order from a to b; order 2: its middle node twice.
std::pair<int, int> Builder::edge_nodes(int a, int b) const {
  const int n = first_node_.at(mesh::edge_key(a, b));
  if (quadratic()) return {n, n};
  return a < b ? std::pair{n, n + 1} : std::pair{n + 1, n};
}

// Index i of the triangle's curved edge (tri[i], tri[i+1]), or -1.
int Builder::curved_edge_of(const mesh::Triangle& tri) const {
  for (int i = 0; i < 3; ++i)
    if (curved_.at(mesh::edge_key(tri[i], tri[(i + 1) % 3]))) return i;
  return -1;
}

// The nodes of a triangle with its edges' nodes placed and the corners' centroid as centre.
geometry::P3Nodes Builder::element(const mesh::Triangle& tri) const {
  const std::array<int, 10> ids = corner_and_edge_nodes(tri);
  geometry::P3Nodes p;
  for (int i = 0; i < 9; ++i) p[i] = nodes_[ids[i]];
  p[9] = (p[0] + p[1] + p[2]) / 3;
  return p;
}

geometry::P2Nodes Builder::p2_element(const mesh::Triangle& tri) const {
  const std::array<int, 10> ids = corner_and_edge_nodes(tri);
  geometry::P2Nodes p;
  for (int i = 0; i < 6; ++i) p[i] = nodes_[ids[i]];
  return p;
}

// Sets p[9] to the first certified centre candidate (geometry::p3_centre_candidates; its index in
// `choice`, its scaled Jacobian in `scaled`) and returns true, or returns false. The candidate that
// reproduces quadratic maps exactly comes first: finite elements on the mesh need it for their
// full order (with the paper's centre, P2 on a disk converges at L2 rate 2.35 instead of 3;
// fem/convergence.hpp).
bool Builder::choose_centre(geometry::P3Nodes& p, int& choice, double& scaled) const {
  const std::array<Vec2, 3> centres = geometry::p3_centre_candidates(p);
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

namespace {

// Badness from the lattice values of nodes p (see Builder::badness).
template <class Nodes>
double badness_of(const Nodes& p, const geometry::P3LatticeValues& v) {
  if (v.min_det > 0) return v.max_amips;
  double side = 0;
  for (int i = 0; i < 3; ++i) side = std::max(side, (p[i] - p[(i + 1) % 3]).squaredNorm());
  return 1e12 - (side > 0 ? v.min_det / side : -1e6);
}

}  // namespace

// How far triangle t is from valid, or how good it is: its worst AMIPS energy when det J > 0 at
// every point of the order-6 lattice, else 1e12 less the smallest det J there over the squared
// longest side (lower is better either way; only a certificate decides validity).
double Builder::badness(int t) const {
  if (quadratic()) {
    const geometry::P2Nodes p = p2_nodes_of(t);
    return badness_of(p, geometry::p2_lattice_values(p));
  }
  const geometry::P3Nodes p = nodes_of(t);
  return badness_of(p, geometry::p3_lattice_values(p));
}

// The centre of triangle t (its edge nodes placed) among the candidates: the lowest badness.
// p3_lattice_values's max_amips is p3_max_amips's value, bit for bit (same lattice, same order).
// Order 2 has no centre node: only the energy, as for a chosen centre.
double Builder::choose_centre_of(int t) {
  if (quadratic()) {
    const geometry::P3LatticeValues v = geometry::p2_lattice_values(p2_nodes_of(t));
    return v.min_det > 0 ? v.max_amips : std::numeric_limits<double>::quiet_NaN();
  }
  geometry::P3Nodes q = nodes_of(t);
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

// The scaled Jacobian of triangle t if it is certified positive.
std::optional<double> Builder::certify(int t) const {
  geometry::JacobianCheckOptions check;
  check.max_depth = o_.certificate_depth;
  const auto result = quadratic() ? geometry::certify_jacobian(p2_nodes_of(t), check)
                                  : geometry::certify_jacobian(nodes_of(t), check);
  if (result.verdict != geometry::JacobianVerdict::positive) return std::nullopt;
  return result.scaled_jacobian;
}

// Certifies every one of `triangles`; only if all are certified, records their scaled
// Jacobians and returns true.
bool Builder::certify_all(const std::vector<int>& triangles) {
  std::vector<double> scaled;
  for (int t : triangles) {
    const auto cert = certify(t);
    if (!cert) return false;
    scaled.push_back(*cert);
  }
  for (std::size_t k = 0; k < triangles.size(); ++k) scaled_.set(triangles[k], scaled[k]);
  return true;
}

Builder::Snapshot Builder::snapshot(const std::vector<int>& triangles) const {
  Snapshot saved;
  for (int t : triangles)
    for (int id : triangle_nodes_[t])
      if (id >= 0) saved.push_back({id, nodes_[id]});
  return saved;
}

void Builder::restore(const Snapshot& saved) {
  for (const auto& [id, x] : saved) nodes_.set(id, x);
}

}  // namespace curvemesh::curve::detail
