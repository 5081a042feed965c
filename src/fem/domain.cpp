#include "fem/domain.hpp"
#include "mesh/union_find.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <utility>

namespace curvemesh::fem {

namespace {

using EdgeTriangles = std::map<std::pair<int, int>, std::vector<std::pair<int, int>>>;

// What cut_open works from: each triangle edge's line, the triangles on each edge, the cut.
struct Cut {
  const io::HighOrderMesh& mesh;
  const std::vector<char>& cut;
  std::vector<std::array<int, 3>> lines = edge_lines(mesh);
  EdgeTriangles triangles_on = edge_triangles(mesh);
  bool is_cut(int t, int e) const { return lines[t][e] >= 0 && cut[lines[t][e]]; }
};

// Corner copies: (triangle, corner) slots joined across edges that are not cut.
mesh::UnionFind corner_classes(const Cut& k) {
  mesh::UnionFind uf(3 * k.mesh.triangle_count());
  for (const auto& [edge, ts] : k.triangles_on) {
    const auto [t0, e0] = ts[0];
    if (k.is_cut(t0, e0)) continue;
    const auto tri0 = k.mesh.triangle(t0);
    for (std::size_t i = 1; i < ts.size(); ++i) {
      const auto [t1, e1] = ts[i];
      const auto tri1 = k.mesh.triangle(t1);
      for (int c0 : {e0, (e0 + 1) % 3})
        for (int c1 : {e1, (e1 + 1) % 3})
          if (tri0[c0] == tri1[c1]) uf.unite(3 * t0 + c0, 3 * t1 + c1);
    }
  }
  return uf;
}

// A copy of `node` appended to out's nodes; its index.
int copy_node(const io::HighOrderMesh& mesh, int node, CutMesh& out) {
  out.mesh.nodes.push_back(mesh.nodes[node]);
  out.node_origin.push_back(node);
  return static_cast<int>(out.mesh.nodes.size()) - 1;
}

// The triangles' node lists of the cut mesh: the first class of a corner node keeps its index,
// other classes get copies; on a cut edge, the second triangle gets copies of the inner nodes.
std::vector<int> cut_triangles(const Cut& k, CutMesh& out) {
  const io::HighOrderMesh& mesh = k.mesh;
  const int size = mesh.triangle_size(), per_edge = mesh.order - 1;
  mesh::UnionFind uf = corner_classes(k);
  std::map<int, int> class_node;  // class root -> node
  std::map<int, int> node_owner;  // node -> class root that kept it
  std::vector<int> tris(mesh.triangles);
  for (int t = 0; t < mesh.triangle_count(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int root = uf.find(3 * t + c), node = mesh.triangle(t)[c];
      auto it = class_node.find(root);
      if (it == class_node.end()) {
        const bool first = node_owner.emplace(node, root).second;
        it = class_node.emplace(root, first ? node : copy_node(mesh, node, out)).first;
      }
      tris[std::size_t(t) * size + c] = it->second;
    }
  for (const auto& [edge, ts] : k.triangles_on) {
    const auto [t0, e0] = ts[0];
    if (!k.is_cut(t0, e0)) continue;
    for (std::size_t i = 1; i < ts.size(); ++i) {
      const auto [t1, e1] = ts[i];
      for (int j = 0; j < per_edge; ++j) {
        int& slot = tris[std::size_t(t1) * size + 3 + per_edge * e1 + j];
        slot = copy_node(mesh, slot, out);
      }
    }
  }
  return tris;
}

// Lines: a cut line once per side, with that side's nodes; others with the first triangle's.
// Lines on no triangle edge (should not happen) are dropped.
void cut_lines(const Cut& k, CutMesh& out) {
  const io::HighOrderMesh& mesh = k.mesh;
  const int size = mesh.triangle_size(), per_edge = mesh.order - 1;
  std::vector<int> buffer;
  std::vector<char> done(mesh.line_count(), 0);
  for (const auto& [edge, ts] : k.triangles_on) {
    const auto [t0, e0] = ts[0];
    const int l = k.lines[t0][e0];
    if (l < 0 || done[l]) continue;
    done[l] = 1;
    const auto line = mesh.line(l);
    for (std::size_t i = 0; i < (k.cut[l] ? ts.size() : 1); ++i) {
      const auto [t, e] = ts[i];
      const auto src = mesh.triangle(t);
      const int* dst = out.mesh.triangles.data() + std::size_t(t) * size;
      // Map the line's nodes through this triangle: corners by position in the triangle, inner
      // nodes by the edge's direction in it.
      const bool same = src[e] == line[0];
      buffer.assign(line.size(), -1);
      buffer[0] = dst[same ? e : (e + 1) % 3];
      buffer[1] = dst[same ? (e + 1) % 3 : e];
      for (int j = 0; j < per_edge; ++j) buffer[2 + j] = dst[3 + per_edge * e + (same ? j : per_edge - 1 - j)];
      out.mesh.add_line(buffer, mesh.line_physical[l]);
      out.line_origin.push_back(l);
    }
  }
}

}  // namespace

CutMesh cut_open(const io::HighOrderMesh& mesh, const std::vector<char>& cut) {
  const Cut k{mesh, cut};
  CutMesh out;
  out.mesh.order = mesh.order;
  out.mesh.physical_names = mesh.physical_names;
  out.mesh.nodes = mesh.nodes;
  out.node_origin.resize(mesh.nodes.size());
  std::iota(out.node_origin.begin(), out.node_origin.end(), 0);
  out.mesh.triangles = cut_triangles(k, out);
  out.mesh.triangle_physical = mesh.triangle_physical;
  cut_lines(k, out);
  return out;
}

}  // namespace curvemesh::fem
