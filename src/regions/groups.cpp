#include "regions/groups.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <tuple>
#include <utility>

#include "regions/faces.hpp"

namespace curvemesh::regions {

namespace {

// Gives a name used before "@2", "@3", ... (each name counted in `seen`).
std::string unique_name(std::string name, std::map<std::string, int>& seen) {
  if (const int n = seen[name]++; n > 0) name.append(1, '@').append(std::to_string(n + 1));
  return name;
}

}  // namespace

std::string element_name(const svg::SourceElement& e) {
  return !e.id.empty() ? e.id : e.tag + "#" + std::to_string(e.index);
}

int element_group(int source) {
  return io::kFirstDrawingGroup + source;
}

int region_group(int key, int sources) {
  return io::kFirstDrawingGroup + sources + key;
}

RegionKeys region_keys(const svg::FeatureSoup& soup) {
  RegionKeys out;
  std::map<std::string, int> seen;
  out.names.push_back(unique_name("background", seen));
  out.source.push_back(-1);
  out.fill.emplace_back();
  std::map<std::tuple<int, std::string, bool>, int> index;  // (element, fill, stroke) -> key
  for (const svg::FillLayer& layer : soup.fills) {
    const auto [it, inserted] =
        index.try_emplace({layer.source, layer.fill.to_string(), layer.stroke}, static_cast<int>(out.names.size()));
    if (inserted) {
      const std::string name = element_name(soup.sources.at(layer.source));
      out.names.push_back(unique_name(layer.stroke ? name + ".stroke" : name, seen));
      out.source.push_back(layer.source);
      out.fill.push_back(layer.fill);
    }
    out.of_layer.push_back(it->second);
  }
  return out;
}

std::vector<char> border_lines(const io::HighOrderMesh& mesh) {
  // Every triangle's edges by their corners, sorted: an edge on one triangle appears once. (A
  // sorted array rather than a map of edges: this runs on every mesh given out.)
  const auto key = [](int a, int b) {
    return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
  };
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * std::size_t(mesh.triangle_count()));
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) edges.push_back(key(tri[e], tri[(e + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  std::vector<char> out(mesh.line_count(), 0);
  for (int l = 0; l < mesh.line_count(); ++l) {
    const auto ends = mesh.line(l);
    const auto [first, last] = std::equal_range(edges.begin(), edges.end(), key(ends[0], ends[1]));
    out[l] = last - first == 1;
  }
  return out;
}

void add_line_groups(io::HighOrderMesh& mesh, const std::vector<std::vector<int>>& elements,
                     const svg::FeatureSoup& soup) {
  const std::vector<char> border = border_lines(mesh);
  mesh.line_groups.assign(mesh.line_count(), {});
  std::vector<char> used(soup.sources.size(), 0);
  for (int l = 0; l < mesh.line_count(); ++l) {
    std::vector<int>& groups = mesh.line_groups[l];
    if (border[l]) groups.push_back(io::kPhysicalBorder);
    for (int s : elements.at(l)) {
      groups.push_back(element_group(s));
      used.at(s) = 1;
    }
    std::sort(groups.begin(), groups.end());
    groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  }
  // Names over every element, in source order, after the fixed names of lines.
  std::map<std::string, int> seen;
  for (const auto& [key, name] : mesh.physical_names)
    if (key.first == 1) ++seen[name];
  for (std::size_t s = 0; s < soup.sources.size(); ++s) {
    std::string name = unique_name(element_name(soup.sources[s]), seen);
    if (used[s]) mesh.physical_names[{1, element_group(static_cast<int>(s))}] = std::move(name);
  }
}

}  // namespace curvemesh::regions
