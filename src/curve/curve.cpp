// curve(): step 1, then the steps of Builder in their order (steps 2 to 5, curve/builder.hpp),
// the statistics of the result and the compaction after step 4.
#include "curve/curve.hpp"

#include <chrono>
#include <unordered_map>

#include "curve/builder.hpp"

namespace curvemesh::curve {

namespace detail {

void Builder::run() {
  place_nodes();
  // Step 4: smoothing, then the local operations, where the curved triangles are worse than the
  // stop energy.
  s_.max_amips_before_smoothing = 0;
  for (std::size_t t = 0; t < triangle_nodes_.size(); ++t)
    s_.max_amips_before_smoothing = std::max(s_.max_amips_before_smoothing, energy(static_cast<int>(t)));
  const TriMesh& m = out_.linear;
  // Primary vertices the linear optimization could not bring onto their curve (Fig. 8): now
  // that edges bend, they may get there. A projection is kept only if nothing around it ends
  // worse (project): one refused is tried again after the smoothing and after the operations,
  // which change what is around it.
  const auto project_late = [&] {
    for (int v = 0; v < m.vertex_count(); ++v)
      if (!m.triangles_of(v).empty() && m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve)
        s_.late_projections += project(v);
  };
  project_late();
  smooth();
  project_late();
  // Step 5: the primary edges still straight, on their curve where nothing around them ends
  // worse, else fitted (fit). An earlier edge's repair may have removed a later one.
  for (const auto& [edge, f] : m.sorted_features()) {
    if (f.kind != EdgeKind::primary || !m.feature(edge[0], edge[1])) continue;
    const bool* curved = curved_.find(mesh::edge_key(edge[0], edge[1]));
    if (curved && !*curved && followable(m, edge[0], edge[1])) fit(edge[0], edge[1]);
  }
  improve();
  project_late();
  coarsen();
  // Order 2: the edges a late projection, a fit or a straightened edge left beyond the tolerance
  // are split, whatever the energy; step 4 then improves what the splits made worse.
  if (meet_tolerance() > 0) improve();
  finish();
  record_statistics();
}

// Steps 2 and 3: the nodes of every edge (on the curve where it can follow it), then each
// triangle with a curved edge certified (order 3: with the first certified centre candidate),
// its curved edge straightened where none is; then every triangle's nodes.
void Builder::place_nodes() {
  const TriMesh& m = out_.linear;
  out_.nodes.assign(m.vertex_count(), Vec2::Zero());
  vertex_node_.resize(m.vertex_count());
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
    if (quadratic()) {  // no centre to choose: the element is its edges'
      geometry::JacobianCheckOptions check;
      check.max_depth = o_.certificate_depth;
      const auto cert = geometry::certify_jacobian(p2_element(tri), check);
      if (cert.verdict == geometry::JacobianVerdict::positive) scaled[k] = cert.scaled_jacobian;
      else straighten(tri[curved], tri[(curved + 1) % 3]);
      continue;
    }
    geometry::P3Nodes p = element(tri);
    if (choose_centre(p, choice[k], scaled[k])) centre[k] = p[9];
    else straighten(tri[curved], tri[(curved + 1) % 3]);
  }
  // Final nodes and centres (triangles that lost their curved edge become straight).
  scaled_.assign(std::vector<double>(order.size(), 1.0));
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& tri = m.triangle(order[k]);
    std::array<int, 10> ids = corner_and_edge_nodes(tri);
    if (quadratic()) {
      triangle_nodes_.push_back(ids);
      if (curved_edge_of(tri) >= 0) scaled_.set(k, scaled[k]);
      else scaled_.set(k, certify(static_cast<int>(k)).value_or(-1.0));  // its middles are rounded
      continue;
    }
    ids[9] = static_cast<int>(nodes_.size());
    if (curved_edge_of(tri) >= 0) {
      s_.alternative_centres += choice[k] > 0;
      scaled_.set(k, scaled[k]);
      nodes_.push_back(centre[k]);
    } else {
      nodes_.push_back((m.point(tri[0]) + m.point(tri[1]) + m.point(tri[2])) / 3);
      // A straight element's nodes are rounded to doubles too: certify it like the others.
      geometry::P3Nodes p;
      for (int i = 0; i < 10; ++i) p[i] = nodes_[ids[i]];
      const auto cert = geometry::certify_jacobian(p);
      scaled_.set(k, cert.verdict == geometry::JacobianVerdict::positive ? cert.scaled_jacobian : -1.0);
    }
    triangle_nodes_.push_back(ids);
  }
}

// After finish(): the energies, validity and wedges of the triangles, the feature lines and the
// distances of the primary edges from their curves.
void Builder::record_statistics() {
  const TriMesh& m = out_.linear;
  std::vector<double> amips(out_.triangles.size());
  for (std::size_t t = 0; t < out_.triangles.size(); ++t) {
    const double e = amips[t] = energy(static_cast<int>(t));
    s_.max_amips = std::max(s_.max_amips, e);
    s_.mean_amips += e / static_cast<double>(out_.triangles.size());
    if (scaled_[t] <= 0) ++s_.invalid_triangles;
    if (curved_edge_of(m.triangle(static_cast<int>(t))) >= 0 || fitted_edge_of(m.triangle(static_cast<int>(t))) >= 0) {
      ++s_.curved_triangles;
      s_.min_scaled_jacobian = std::min(s_.min_scaled_jacobian, scaled_[t]);
    }
  }
  s_.wedges = wedges(out_, amips, o_.stop_amips);
  // Feature lines and edge statistics.
  for (const auto& [edge, f] : m.sorted_features()) {
    const auto [first, second] = edge_nodes(edge[0], edge[1]);
    out_.lines.push_back({{edge[0], edge[1], first, quadratic() ? -1 : second}, f.kind});
    if (f.kind != EdgeKind::primary) continue;
    ++s_.primary_edges;
    if (quadratic() && o_.tolerance > 0 && deviation(edge[0], edge[1]) > o_.tolerance) ++s_.beyond_tolerance;
    const auto key = mesh::edge_key(edge[0], edge[1]);
    const double distance = distance_to_curve(edge[0], edge[1], f, first, second);
    if (curved_.at(key)) {
      ++s_.curved_edges;
    } else if (fitted_.contains(key)) {
      ++s_.fitted_edges;
      s_.mean_fit_distance += distance;
    } else {
      ++s_.straight_primary_edges;
    }
    s_.max_distance = std::max(s_.max_distance, distance);
  }
  if (s_.fitted_edges > 0) s_.mean_fit_distance /= s_.fitted_edges;
}

// After step 4: the linear mesh compacted (dead triangles and removed vertices dropped), the
// curved triangles with it, and the nodes renumbered, vertices first in their new order, then
// every other node still used in its old order.
void Builder::finish() {
  TriMesh& m = out_.linear;
  std::vector<std::array<int, 10>> triangles;
  std::vector<double> scaled;
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t)) triangles.push_back(triangle_nodes_[t]), scaled.push_back(scaled_[t]);
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
  std::unordered_map<std::uint64_t, bool> curved, fitted;
  for (const auto& [edge, first] : edges) {
    const auto key = mesh::edge_key(edge[0], edge[1]), new_key = mesh::edge_key(remap[edge[0]], remap[edge[1]]);
    first_node[new_key] = node_id[first];
    curved[new_key] = curved_.at(key);
    if (fitted_.contains(key)) fitted[new_key] = true;
  }
  // The statistics read the compacted mesh from out_ (wedges) and from the stores alike.
  out_.nodes = nodes;
  out_.triangles = triangles;
  nodes_.assign(std::move(nodes));
  triangle_nodes_.assign(std::move(triangles));
  scaled_.assign(std::move(scaled));
  first_node_.assign(std::move(first_node));
  curved_.assign(std::move(curved));
  fitted_.assign(std::move(fitted));
  std::vector<int> vertex_node(m.vertex_count());
  for (int v = 0; v < m.vertex_count(); ++v) vertex_node[v] = v;
  vertex_node_.assign(std::move(vertex_node));
}

}  // namespace detail

CurvedMesh curve(mesh::TriMesh linear, const mesh::Constraints& constraints, const Options& options,
                 Stats* stats) {
  const auto start = std::chrono::steady_clock::now();
  Stats s;
  CurvedMesh out;
  out.order = options.order;
  s.split_triangles = detail::split_until_one_primary_edge(linear, constraints);
  if (options.order == 2) s.tolerance_splits = detail::split_beyond_tolerance(linear, constraints, options);
  linear.compact();
  out.linear = std::move(linear);
  detail::Builder(out, constraints, options, s).run();
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = s;
  return out;
}

}  // namespace curvemesh::curve
