#include "io/high_order_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace curvemesh::io {

std::map<std::pair<int, int>, std::string> HighOrderMesh::default_physical_names() {
  return {{{1, kPhysicalPrimary}, "primary"},
          {{1, kPhysicalSecondary}, "secondary"},
          {{1, kPhysicalBoundary}, "boundary"},
          {{1, kPhysicalBorder}, "border"},
          {{2, kPhysicalDomain}, "domain"}};
}

std::vector<int> HighOrderMesh::groups_of_line(int l) const {
  std::vector<int> out;
  if (line_physical.at(l) > 0) out.push_back(line_physical[l]);
  if (!line_groups.empty()) out.insert(out.end(), line_groups.at(l).begin(), line_groups[l].end());
  std::sort(out.begin(), out.end());
  return out;
}

void HighOrderMesh::add_triangle(std::span<const int> node_indices, int physical) {
  if (!order_ok() || static_cast<int>(node_indices.size()) != triangle_size())
    throw std::logic_error("HighOrderMesh: a triangle of order " + std::to_string(order) + " needs " +
                           std::to_string(triangle_size()) + " nodes, got " +
                           std::to_string(node_indices.size()));
  triangles.insert(triangles.end(), node_indices.begin(), node_indices.end());
  triangle_physical.push_back(physical);
}

void HighOrderMesh::add_line(std::span<const int> node_indices, int physical, std::vector<int> groups) {
  if (!order_ok() || static_cast<int>(node_indices.size()) != line_size())
    throw std::logic_error("HighOrderMesh: a line of order " + std::to_string(order) + " needs " +
                           std::to_string(line_size()) + " nodes, got " +
                           std::to_string(node_indices.size()));
  lines.insert(lines.end(), node_indices.begin(), node_indices.end());
  line_physical.push_back(physical);
  // line_groups stays empty until some line has a further group.
  if (!groups.empty() || !line_groups.empty()) {
    line_groups.resize(line_physical.size() - 1);
    line_groups.push_back(std::move(groups));
  }
}

std::optional<std::string> HighOrderMesh::structure_error() const {
  if (!order_ok()) return "order " + std::to_string(order) + " is not 1, 2 or 3";
  const auto n = static_cast<long>(nodes.size());
  for (long v = 0; v < n; ++v)
    if (!std::isfinite(nodes[v].x()) || !std::isfinite(nodes[v].y()))
      return "node " + std::to_string(v) + " has a non-finite coordinate";
  const auto check = [n](const char* what, const std::vector<int>& indices, int size,
                         const std::vector<int>& physical) -> std::optional<std::string> {
    if (indices.size() % size != 0)
      return std::string(what) + " array has " + std::to_string(indices.size()) +
             " entries, not a multiple of " + std::to_string(size);
    if (physical.size() != indices.size() / size)
      return std::string(what) + "s: " + std::to_string(indices.size() / size) + " elements but " +
             std::to_string(physical.size()) + " physical tags";
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (indices[i] < 0 || indices[i] >= n)
        return std::string(what) + " " + std::to_string(i / size) + " refers to node " +
               std::to_string(indices[i]) + " of " + std::to_string(n);
    for (std::size_t e = 0; e < physical.size(); ++e)
      if (physical[e] < 0)
        return std::string(what) + " " + std::to_string(e) + " has a negative physical tag";
    return std::nullopt;
  };
  if (auto e = check("triangle", triangles, triangle_size(), triangle_physical)) return e;
  if (auto e = check("line", lines, line_size(), line_physical)) return e;
  if (!line_groups.empty() && line_groups.size() != line_physical.size())
    return "lines: " + std::to_string(line_physical.size()) + " lines but " + std::to_string(line_groups.size()) +
           " lists of further groups";
  for (std::size_t l = 0; l < line_groups.size(); ++l)
    for (std::size_t i = 0; i < line_groups[l].size(); ++i) {
      const int g = line_groups[l][i];
      if (g <= 0 || g == line_physical[l] || (i > 0 && g <= line_groups[l][i - 1]))
        return "line " + std::to_string(l) + "'s further groups are not positive, ascending and apart from its " +
               "physical tag";
    }
  for (const auto& [key, name] : physical_names)
    if (key.first != 1 && key.first != 2)
      return "physical name \"" + name + "\" has dimension " + std::to_string(key.first);
  return std::nullopt;
}

HighOrderMesh linear_mesh(const mesh::TriMesh& m) {
  if (m.exact_vertex_count() > 0)
    throw std::logic_error(std::to_string(m.exact_vertex_count()) + " vertices have no double position yet");
  HighOrderMesh out;
  out.order = 1;
  out.nodes.reserve(m.vertex_count());
  for (int v = 0; v < m.vertex_count(); ++v) out.nodes.push_back(m.point(v));
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t)) out.add_triangle(m.triangle(t), kPhysicalDomain);
  for (const auto& [e, f] : m.sorted_features()) {
    switch (f.kind) {
      case mesh::EdgeKind::primary:
        out.add_line(e, kPhysicalPrimary);
        break;
      case mesh::EdgeKind::secondary:
        out.add_line(e, kPhysicalSecondary);
        break;
      case mesh::EdgeKind::boundary:
        out.add_line(e, kPhysicalBoundary);
        break;
      default:
        break;
    }
  }
  return out;
}

}  // namespace curvemesh::io
