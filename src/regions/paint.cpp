#include "regions/paint.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "geometry/p3_triangle.hpp"
#include "regions/winding.hpp"

namespace curvemesh::regions {

namespace {

// Points inside triangle t: the images of its centroid and of the points halfway from it to the
// corners (a certified cubic map is one to one, so they are inside the curved triangle). Four,
// so that a face an outline crosses (where the mesh follows it only within ε) has points on
// both sides, and one lying exactly on an outline (drawings on an integer grid) has others.
void add_samples(const io::HighOrderMesh& mesh, int t, std::vector<geometry::Vec2>& out) {
  static constexpr double kReference[4][2] = {{1.0 / 3, 1.0 / 3}, {1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
  const auto tri = mesh.triangle(t);
  if (mesh.order == 3) {
    geometry::P3Nodes nodes;
    for (int i = 0; i < 10; ++i) nodes[i] = mesh.nodes[tri[i]];
    for (const auto& uv : kReference) out.push_back(geometry::p3_map(nodes, uv[0], uv[1]));
    return;
  }
  const geometry::Vec2 &a = mesh.nodes[tri[0]], &b = mesh.nodes[tri[1]], &c = mesh.nodes[tri[2]];
  for (const auto& uv : kReference) out.push_back(a + uv[0] * (b - a) + uv[1] * (c - a));
}

double corner_area(const io::HighOrderMesh& mesh, int t) {
  const auto tri = mesh.triangle(t);
  return geometry::cross(mesh.nodes[tri[1]] - mesh.nodes[tri[0]], mesh.nodes[tri[2]] - mesh.nodes[tri[0]]) / 2;
}

// Triangles sampled per face: its largest first.
constexpr int kSamples = 12;

}  // namespace

Classification classify(const io::HighOrderMesh& mesh, const std::vector<svg::FillLayer>& fills,
                        const ClassifyOptions& options) {
  Classification c;
  c.faces = find_faces(mesh);
  const int face_count = c.faces.count();
  // Each face's sample triangles, largest first (ties by index: deterministic).
  std::vector<std::vector<int>> members(face_count);
  for (int t = 0; t < mesh.triangle_count(); ++t) members[c.faces.of_triangle[t]].push_back(t);
  std::vector<double> area(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) area[t] = corner_area(mesh, t);
  std::vector<std::vector<geometry::Vec2>> samples(face_count);
  for (int f = 0; f < face_count; ++f) {
    std::vector<int>& m = members[f];
    const auto count = std::min<std::size_t>(kSamples, m.size());
    std::partial_sort(m.begin(), m.begin() + count, m.end(),
                      [&](int a, int b) { return area[a] != area[b] ? area[a] > area[b] : a < b; });
    for (std::size_t i = 0; i < count; ++i) add_samples(mesh, m[i], samples[f]);
  }
  std::vector<Outline> outlines;
  outlines.reserve(fills.size());
  for (const svg::FillLayer& layer : fills) outlines.emplace_back(layer);
  c.visible.assign(face_count, -1);
  for (int f = 0; f < face_count; ++f) {
    // The topmost covering layer: walk down the paint order, stop at the first that covers.
    for (int l = static_cast<int>(fills.size()) - 1; l >= 0; --l) {
      const svg::FillLayer& layer = fills[l];
      // Far outside the layer's box (the usual case): wound around by none of its loops.
      if (!samples[f].empty() && layer.bounds.squared_distance(samples[f][0]) >= options.clearance * options.clearance)
        continue;
      Winding best;
      bool any = false;
      for (const geometry::Vec2& p : samples[f]) {
        const Winding w = outlines[l].winding(p, options.resolution, options.clearance);
        if (!w.decided) continue;
        if (!any || w.clearance > best.clearance) best = w, any = true;
        if (w.clearance >= options.clearance) break;
      }
      if (!any) throw Undecided(l, f);
      if (inside(best.number, layer.rule)) {
        c.visible[f] = l;
        break;
      }
    }
  }
  return c;
}

int Painted::region_of(int triangle) const {
  const int physical = mesh.triangle_physical.at(triangle);
  return physical - 1;
}

Painted paint(const io::HighOrderMesh& whole, const Classification& c, const svg::FeatureSoup& soup, Domain domain,
              bool tag_regions) {
  Painted out;
  const std::vector<char> keep = domain_triangles(c, domain);
  const bool classified = !c.visible.empty();
  std::vector<int> triangle_layer(whole.triangle_count(), -1);
  if (classified)
    for (int t = 0; t < whole.triangle_count(); ++t) triangle_layer[t] = c.visible[c.faces.of_triangle[t]];

  io::HighOrderMesh tagged = whole;
  if (tag_regions) {
    // Regions by (element, fill) in paint order of their first layer, the background first.
    std::map<std::pair<int, std::string>, int> index;
    std::vector<int> region_of_layer(soup.fills.size(), -1);
    bool background = false;
    for (int t = 0; t < whole.triangle_count(); ++t)
      if (keep[t] && triangle_layer[t] < 0) background = true;
    std::vector<char> used(soup.fills.size(), 0);
    for (int t = 0; t < whole.triangle_count(); ++t)
      if (keep[t] && triangle_layer[t] >= 0) used[triangle_layer[t]] = 1;
    if (background) {
      Region r;
      r.name = "background";
      out.regions.push_back(r);
    }
    for (std::size_t l = 0; l < soup.fills.size(); ++l) {
      if (!used[l]) continue;
      const svg::FillLayer& layer = soup.fills[l];
      const auto [it, inserted] =
          index.try_emplace({layer.source, layer.fill.to_string()}, static_cast<int>(out.regions.size()));
      if (inserted) {
        Region r;
        const svg::SourceElement& e = soup.sources.at(layer.source);
        r.name = !e.id.empty() ? e.id : e.tag + "#" + std::to_string(e.index);
        r.fill = layer.fill;
        r.source = layer.source;
        out.regions.push_back(r);
      }
      region_of_layer[l] = it->second;
    }
    // The same element painted in two colours (through <use>): its names stay apart.
    std::map<std::string, int> seen;
    for (Region& r : out.regions)
      if (const int n = seen[r.name]++; n > 0) r.name += "@" + std::to_string(n + 1);
    tagged.physical_names.clear();
    for (const auto& [key, name] : whole.physical_names)
      if (key.first == 1) tagged.physical_names[key] = name;
    for (std::size_t i = 0; i < out.regions.size(); ++i) {
      out.regions[i].physical = static_cast<int>(i) + 1;
      tagged.physical_names[{2, out.regions[i].physical}] = out.regions[i].name;
    }
    // Region i has physical tag i + 1; the background, when there is one, is region 0.
    for (int t = 0; t < whole.triangle_count(); ++t) {
      const int l = triangle_layer[t];
      tagged.triangle_physical[t] = l < 0 ? 1 : region_of_layer[l] + 1;
    }
  }
  out.mesh = submesh(tagged, keep, nullptr, &out.node_origin);
  for (int t = 0; t < whole.triangle_count(); ++t) {
    if (!keep[t]) continue;
    out.face.push_back(c.faces.of_triangle[t]);
    out.layer.push_back(triangle_layer[t]);
  }
  if (tag_regions)
    for (int t = 0; t < out.mesh.triangle_count(); ++t) {
      Region& r = out.regions[out.region_of(t)];
      ++r.triangles;
      r.area += triangle_area(out.mesh, t);
    }
  return out;
}

}  // namespace curvemesh::regions
