#include "regions/faces.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <queue>
#include <span>
#include <stdexcept>
#include <utility>

#include "mesh/union_find.hpp"

namespace curvemesh::regions {

namespace {

using EdgeKey = std::pair<int, int>;
EdgeKey key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

bool cuts(const io::HighOrderMesh& mesh, int line) {
  return line >= 0 &&
         (mesh.line_physical[line] == io::kPhysicalPrimary || mesh.line_physical[line] == io::kPhysicalSecondary);
}

}  // namespace

std::vector<std::array<int, 3>> edge_lines(const io::HighOrderMesh& mesh) {
  std::map<EdgeKey, int> line_of;
  for (int l = 0; l < mesh.line_count(); ++l) line_of.emplace(key(mesh.line(l)[0], mesh.line(l)[1]), l);
  std::vector<std::array<int, 3>> out(mesh.triangle_count(), {-1, -1, -1});
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const auto it = line_of.find(key(tri[e], tri[(e + 1) % 3]));
      if (it != line_of.end()) out[t][e] = it->second;
    }
  }
  return out;
}

std::map<EdgeKey, std::vector<std::pair<int, int>>> edge_triangles(const io::HighOrderMesh& mesh) {
  std::map<EdgeKey, std::vector<std::pair<int, int>>> out;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) out[key(tri[e], tri[(e + 1) % 3])].emplace_back(t, e);
  }
  return out;
}

Faces find_faces(const io::HighOrderMesh& mesh) {
  const int n = mesh.triangle_count();
  const auto lines = edge_lines(mesh);
  const auto triangles_on = edge_triangles(mesh);
  mesh::UnionFind uf(n);
  for (const auto& [edge, ts] : triangles_on)
    for (std::size_t i = 1; i < ts.size(); ++i)
      if (!cuts(mesh, lines[ts[0].first][ts[0].second])) uf.unite(ts[0].first, ts[i].first);
  Faces f;
  f.of_triangle.assign(n, -1);
  std::map<int, int> index;  // root -> face, in order of first triangle
  for (int t = 0; t < n; ++t) {
    auto [it, inserted] = index.try_emplace(uf.find(t), static_cast<int>(index.size()));
    f.of_triangle[t] = it->second;
  }
  const int count = static_cast<int>(index.size());
  // Face adjacency across lines; depth by breadth-first search from the border faces.
  std::vector<std::vector<int>> next(count);
  std::vector<char> border(count, 0);
  for (const auto& [edge, ts] : triangles_on) {
    if (ts.size() == 1) border[f.of_triangle[ts[0].first]] = 1;
    for (std::size_t i = 1; i < ts.size(); ++i) {
      const int a = f.of_triangle[ts[0].first], b = f.of_triangle[ts[i].first];
      if (a != b) next[a].push_back(b), next[b].push_back(a);
    }
  }
  f.depth.assign(count, -1);
  std::queue<int> queue;
  for (int i = 0; i < count; ++i)
    if (border[i]) f.depth[i] = 0, queue.push(i);
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop();
    for (int j : next[i])
      if (f.depth[j] < 0) f.depth[j] = f.depth[i] + 1, queue.push(j);
  }
  for (int& d : f.depth)
    if (d < 0) d = 0;  // not reachable from the border (no border at all): treat as outside
  return f;
}

const char* domain_name(Domain domain) {
  switch (domain) {
    case Domain::box:
      return "box";
    case Domain::filled:
      return "filled";
    case Domain::evenodd:
      return "evenodd";
    case Domain::painted:
      return "painted";
    case Domain::outside:
      return "outside";
  }
  return "?";
}

std::vector<char> domain_triangles(const Classification& c, Domain domain) {
  const std::vector<int>& face = c.faces.of_triangle;
  std::vector<char> keep(face.size(), 1);
  for (std::size_t t = 0; t < face.size(); ++t) {
    if (domain == Domain::evenodd) keep[t] = c.faces.depth[face[t]] % 2 == 1;
    if (domain == Domain::outside) keep[t] = c.faces.depth[face[t]] % 2 == 0;
    if (domain == Domain::filled) keep[t] = c.filled.at(t) >= 0;
    if (domain == Domain::painted) keep[t] = c.visible.at(t) >= 0;
  }
  return keep;
}

io::HighOrderMesh submesh(const io::HighOrderMesh& mesh, const std::vector<char>& keep, std::vector<int>* line_origin,
                          std::vector<int>* node_origin) {
  if (line_origin) line_origin->clear();
  if (node_origin) node_origin->clear();
  io::HighOrderMesh out;
  out.order = mesh.order;
  out.physical_names = mesh.physical_names;
  std::vector<int> renumber(mesh.nodes.size(), -1);
  auto node = [&](int i) {
    if (renumber[i] < 0) {
      renumber[i] = static_cast<int>(out.nodes.size());
      out.nodes.push_back(mesh.nodes[i]);
      if (node_origin) node_origin->push_back(i);
    }
    return renumber[i];
  };
  std::vector<int> buffer;
  const auto lines = edge_lines(mesh);
  std::vector<char> line_kept(mesh.line_count(), 0);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    if (!keep[t]) continue;
    buffer.clear();
    for (int i : mesh.triangle(t)) buffer.push_back(node(i));
    out.add_triangle(buffer, mesh.triangle_physical[t]);
    for (int l : lines[t])
      if (l >= 0) line_kept[l] = 1;
  }
  for (int l = 0; l < mesh.line_count(); ++l) {
    if (!line_kept[l]) continue;
    buffer.clear();
    for (int i : mesh.line(l)) buffer.push_back(node(i));
    out.add_line(buffer, mesh.line_physical[l], mesh.line_groups.empty() ? std::vector<int>{} : mesh.line_groups[l]);
    if (line_origin) line_origin->push_back(l);
  }
  return out;
}

namespace {

// The point and the derivative at s of the polynomial curve through p[0..n] at s = 0, 1/n, ..., 1
// (an edge of a mesh of order n): its Lagrange basis on the equispaced nodes, differentiated.
std::pair<geometry::Vec2, geometry::Vec2> equispaced_curve(std::span<const geometry::Vec2> p, double s) {
  const int order = static_cast<int>(p.size()) - 1;
  geometry::Vec2 x = geometry::Vec2::Zero(), dx = geometry::Vec2::Zero();
  for (int i = 0; i <= order; ++i) {
    const double si = double(i) / order;
    double value = 1, slope = 0;
    for (int j = 0; j <= order; ++j) {
      if (j == i) continue;
      const double sj = double(j) / order, denom = si - sj;
      slope = slope * (s - sj) / denom + value / denom;
      value *= (s - sj) / denom;
    }
    x += value * p[i];
    dx += slope * p[i];
  }
  return {x, dx};
}

}  // namespace

double line_length(const io::HighOrderMesh& mesh, int l) {
  const auto line = mesh.line(l);
  const int order = mesh.order;
  if (order == 1) return (mesh.nodes[line[1]] - mesh.nodes[line[0]]).norm();
  // The line's nodes sit at s = 0, 1, then 1/order, ..., (order-1)/order: the polynomial through
  // them, differentiated (Lagrange basis), its speed integrated.
  static constexpr double kPoint[5] = {0.046910077030668004, 0.23076534494715845, 0.5, 0.76923465505284155,
                                       0.95308992296933200};
  static constexpr double kWeight[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                        0.23931433524968324, 0.11846344252809454};
  if (order < 1 || order > 3) throw std::logic_error("a mesh of order " + std::to_string(order));
  std::array<geometry::Vec2, 4> nodes;  // order ≤ 3
  const std::span<geometry::Vec2> p(nodes.data(), std::size_t(order) + 1);
  p[0] = mesh.nodes[line[0]];
  p[order] = mesh.nodes[line[1]];
  for (int k = 1; k < order; ++k) p[k] = mesh.nodes[line[1 + k]];
  double length = 0;
  for (int q = 0; q < 5; ++q) length += kWeight[q] * equispaced_curve(p, kPoint[q]).second.norm();
  return length;
}

double triangle_area(const io::HighOrderMesh& mesh, int t) {
  const auto tri = mesh.triangle(t);
  const int order = mesh.order;
  // Green: area = ½ ∮ (x dy − y dx). Each edge is the polynomial of degree `order` through its
  // nodes at s = 0, 1/order, ..., 1; the integrand has degree 2·order − 1 ≤ 5, which the
  // three-point Gauss–Legendre rule integrates exactly.
  static constexpr double kPoint[3] = {0.11270166537925831148, 0.5, 0.88729833462074168852};
  static constexpr double kWeight[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  double twice = 0;
  if (order < 1 || order > 3) throw std::logic_error("a mesh of order " + std::to_string(order));
  std::array<geometry::Vec2, 4> nodes;  // order ≤ 3
  const std::span<geometry::Vec2> p(nodes.data(), std::size_t(order) + 1);
  for (int e = 0; e < 3; ++e) {
    p[0] = mesh.nodes[tri[e]];
    p[order] = mesh.nodes[tri[(e + 1) % 3]];
    for (int k = 1; k < order; ++k) p[k] = mesh.nodes[tri[3 + (order - 1) * e + (k - 1)]];
    for (int q = 0; q < 3; ++q) {
      const auto [x, dx] = equispaced_curve(p, kPoint[q]);
      twice += kWeight[q] * geometry::cross(x, dx);
    }
  }
  return twice / 2;
}

}  // namespace curvemesh::regions
