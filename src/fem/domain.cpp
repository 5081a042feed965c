#include "fem/domain.hpp"
#include "mesh/union_find.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

namespace curvemesh::fem {

CutMesh cut_open(const io::HighOrderMesh& mesh, const std::vector<char>& cut) {
  const int n = mesh.triangle_count();
  const int size = mesh.triangle_size();
  const int per_edge = mesh.order - 1;  // inner nodes per edge
  const auto lines = edge_lines(mesh);
  const auto triangles_on = edge_triangles(mesh);
  auto is_cut = [&](int t, int e) { return lines[t][e] >= 0 && cut[lines[t][e]]; };

  // Corner copies: (triangle, corner) slots joined across edges that are not cut.
  mesh::UnionFind uf(3 * n);
  for (const auto& [edge, ts] : triangles_on) {
    const auto [t0, e0] = ts[0];
    if (is_cut(t0, e0)) continue;
    const auto tri0 = mesh.triangle(t0);
    for (std::size_t i = 1; i < ts.size(); ++i) {
      const auto [t1, e1] = ts[i];
      const auto tri1 = mesh.triangle(t1);
      for (int c0 : {e0, (e0 + 1) % 3})
        for (int c1 : {e1, (e1 + 1) % 3})
          if (tri0[c0] == tri1[c1]) uf.unite(3 * t0 + c0, 3 * t1 + c1);
    }
  }
  CutMesh out;
  out.mesh.order = mesh.order;
  out.mesh.physical_names = mesh.physical_names;
  out.mesh.nodes = mesh.nodes;
  out.node_origin.resize(mesh.nodes.size());
  std::iota(out.node_origin.begin(), out.node_origin.end(), 0);
  auto copy = [&](int node) {
    out.mesh.nodes.push_back(mesh.nodes[node]);
    out.node_origin.push_back(node);
    return static_cast<int>(out.mesh.nodes.size()) - 1;
  };
  // The first class of a node keeps its index; other classes get copies.
  std::map<int, int> class_node;     // class root -> node
  std::map<int, int> node_owner;     // node -> class root that kept it
  std::vector<int> tris(mesh.triangles);
  for (int t = 0; t < n; ++t)
    for (int c = 0; c < 3; ++c) {
      const int root = uf.find(3 * t + c), node = mesh.triangle(t)[c];
      auto it = class_node.find(root);
      if (it == class_node.end()) {
        const bool first = node_owner.emplace(node, root).second;
        it = class_node.emplace(root, first ? node : copy(node)).first;
      }
      tris[std::size_t(t) * size + c] = it->second;
    }
  // Inner edge nodes: on a cut edge, the second triangle gets copies.
  for (const auto& [edge, ts] : triangles_on) {
    const auto [t0, e0] = ts[0];
    if (!is_cut(t0, e0)) continue;
    for (std::size_t i = 1; i < ts.size(); ++i) {
      const auto [t1, e1] = ts[i];
      for (int k = 0; k < per_edge; ++k) {
        int& slot = tris[std::size_t(t1) * size + 3 + per_edge * e1 + k];
        slot = copy(slot);
      }
    }
  }
  out.mesh.triangles = tris;
  out.mesh.triangle_physical = mesh.triangle_physical;
  // Lines: a cut line once per side, with that side's nodes; others with the first triangle's.
  std::vector<int> buffer;
  std::vector<char> done(mesh.line_count(), 0);
  for (const auto& [edge, ts] : triangles_on) {
    const auto [t0, e0] = ts[0];
    const int l = lines[t0][e0];
    if (l < 0 || done[l]) continue;
    done[l] = 1;
    const auto line = mesh.line(l);
    for (std::size_t i = 0; i < (cut[l] ? ts.size() : 1); ++i) {
      const auto [t, e] = ts[i];
      const auto src = mesh.triangle(t);
      const int* dst = tris.data() + std::size_t(t) * size;
      // Map the line's nodes through this triangle: corners by position in the triangle, inner
      // nodes by the edge's direction in it.
      const bool same = src[e] == line[0];
      buffer.assign(line.size(), -1);
      buffer[0] = dst[same ? e : (e + 1) % 3];
      buffer[1] = dst[same ? (e + 1) % 3 : e];
      for (int k = 0; k < per_edge; ++k) buffer[2 + k] = dst[3 + per_edge * e + (same ? k : per_edge - 1 - k)];
      out.mesh.add_line(buffer, mesh.line_physical[l]);
      out.line_origin.push_back(l);
    }
  }
  // Lines on no triangle edge (should not happen) are dropped.
  return out;
}

}  // namespace curvemesh::fem
