#include "regions/paint.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <stdexcept>
#include <utility>

#include "base/parallel.hpp"
#include "geometry/p2_triangle.hpp"
#include "geometry/p3_triangle.hpp"
#include "regions/groups.hpp"
#include "regions/winding.hpp"

namespace curvemesh::regions {

namespace {

// Points inside triangle t: the images of its centroid and of the points halfway from it to the
// corners (a certified curved map is one to one, so they are inside the curved triangle). Four,
// so that a face an outline crosses (where the mesh follows it only within ε) has points on
// both sides, and one lying exactly on an outline (drawings on an integer grid) has others.
void add_samples(const io::HighOrderMesh& mesh, int t, std::vector<geometry::Vec2>& out) {
  static constexpr double kReference[4][2] = {
      {1.0 / 3, 1.0 / 3}, {1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
  const auto tri = mesh.triangle(t);
  if (mesh.order == 3) {
    geometry::P3Nodes nodes;
    for (int i = 0; i < 10; ++i) nodes[i] = mesh.nodes[tri[i]];
    for (const auto& uv : kReference) out.push_back(geometry::p3_map(nodes, uv[0], uv[1]));
    return;
  }
  if (mesh.order == 2) {
    geometry::P2Nodes nodes;
    for (int i = 0; i < 6; ++i) nodes[i] = mesh.nodes[tri[i]];
    for (const auto& uv : kReference) out.push_back(geometry::p2_map(nodes, uv[0], uv[1]));
    return;
  }
  const geometry::Vec2 &a = mesh.nodes[tri[0]], &b = mesh.nodes[tri[1]], &c = mesh.nodes[tri[2]];
  for (const auto& uv : kReference) out.push_back(a + uv[0] * (b - a) + uv[1] * (c - a));
}

double corner_area(const io::HighOrderMesh& mesh, int t) {
  const auto tri = mesh.triangle(t);
  return geometry::cross(mesh.nodes[tri[1]] - mesh.nodes[tri[0]], mesh.nodes[tri[2]] - mesh.nodes[tri[0]]) /
         2;
}

// Triangles sampled per face: its largest first.
constexpr int kSamples = 12;

// A face's sample points.
struct FaceSamples {
  std::vector<geometry::Vec2> points;
  geometry::Box2 box;  // of the points
  double spread = 0;   // the largest distance between the first point and another
};

// The squared distance between two boxes (0 when they meet).
double squared_gap(const geometry::Box2& a, const geometry::Box2& b) {
  const double dx = std::max({a.min.x() - b.max.x(), 0.0, b.min.x() - a.max.x()});
  const double dy = std::max({a.min.y() - b.max.y(), 0.0, b.min.y() - a.max.y()});
  return dx * dx + dy * dy;
}

// Whether fill layer l covers face f. A face bounded by lines on the layer's outline lies on one
// side of it, and every sample says the same. Where the mesh follows the outline only within ε,
// the outline may cross the face; and as a secondary line may leave one curve for a neighbour's
// envelope, a sample farther than ε from the outline can still lie on the side the face is not
// (a triangle reaching into a thin shape drawn over the face). So the face is decided at its
// sample farthest from the outline, each sample's distance bounded within a fifth of it.
bool covers(const Outline& outline, const svg::FillLayer& layer, const FaceSamples& s,
            const ClassifyOptions& o, int l, int f) {
  // Every sample outside the layer's box: wound around by none of its loops.
  if (s.points.empty() || squared_gap(s.box, layer.bounds) > 0) return false;
  // A sample farther from the outline than from every other sample says for all of them: no
  // clearance beyond twice the spread is needed.
  const double wanted = std::max(2 * s.spread, o.clearance);
  const std::size_t n = s.points.size();
  std::vector<Winding> w(n);
  std::vector<char> asked(n, 0);
  const auto ask = [&](std::size_t i) {
    asked[i] = 1;
    if (const double gap2 = layer.bounds.squared_distance(s.points[i]); gap2 > 0)
      w[i].clearance = std::sqrt(gap2);  // outside the box: winding 0
    else
      w[i] = outline.winding(s.points[i], o.resolution, wanted);
  };
  // First the samples no earlier answer covers (a sample closer to an asked one than its
  // clearance is on its side): where they all agree, so do the rest.
  int side = -1;  // -1 none yet, else whether inside
  bool disagree = false;
  for (std::size_t i = 0; i < n; ++i) {
    const geometry::Vec2& p = s.points[i];
    bool covered = false;
    for (std::size_t j = 0; j < i && !covered; ++j)
      covered = asked[j] && w[j].decided && (p - s.points[j]).norm() < w[j].clearance;
    if (covered) continue;
    ask(i);
    if (!w[i].decided) continue;
    const bool in = inside(w[i].number, layer.rule);
    if (w[i].clearance > (p - s.points[0]).norm() + s.spread) return in;  // covers every sample
    disagree = disagree || (side >= 0 && side != int(in));
    side = in;
  }
  if (side < 0) throw Undecided(l, f);
  if (!disagree) return side;
  // The samples disagree: the one farthest from the outline decides.
  for (std::size_t i = 0; i < n; ++i)
    if (!asked[i]) ask(i);
  std::size_t best = n;
  for (std::size_t i = 0; i < n; ++i)
    if (w[i].decided && (best == n || w[i].clearance > w[best].clearance)) best = i;
  return inside(w[best].number, layer.rule);
}

}  // namespace

bool too_narrow(const svg::FillLayer& layer, const ClassifyOptions& options) {
  return layer.stroke && layer.width < options.min_stroke_width;
}

namespace {

// Each face's samples: its largest triangles' (ties by index: deterministic), face by face in
// parallel.
std::vector<FaceSamples> face_samples(const io::HighOrderMesh& mesh, const Faces& faces) {
  const int face_count = faces.count();
  std::vector<std::vector<int>> members(face_count);
  for (int t = 0; t < mesh.triangle_count(); ++t) members[faces.of_triangle[t]].push_back(t);
  std::vector<double> area(mesh.triangle_count());
  base::for_each_part(area.size(), [&](std::size_t t) { area[t] = corner_area(mesh, static_cast<int>(t)); });
  std::vector<FaceSamples> samples(face_count);
  base::for_each_part(
      face_count,
      [&](std::size_t f) {
        std::vector<int>& m = members[f];
        const auto count = std::min<std::size_t>(kSamples, m.size());
        std::partial_sort(m.begin(), m.begin() + count, m.end(),
                          [&](int a, int b) { return area[a] != area[b] ? area[a] > area[b] : a < b; });
        FaceSamples& s = samples[f];
        for (std::size_t i = 0; i < count; ++i) add_samples(mesh, m[i], s.points);
        for (const geometry::Vec2& p : s.points) {
          s.box.add(p);
          s.spread = std::max(s.spread, (p - s.points[0]).norm());
        }
      },
      1);
  return samples;
}

}  // namespace

// Every face decided on its own, in parallel; a face that cannot be decided is reported as a
// serial sweep would report it, the first in the faces' order.
Classification classify(const io::HighOrderMesh& mesh, const std::vector<svg::FillLayer>& fills,
                        const ClassifyOptions& options, const std::vector<svg::ClipPath>& clips) {
  Classification c;
  c.faces = find_faces(mesh);
  const int face_count = c.faces.count();
  const std::vector<FaceSamples> samples = face_samples(mesh, c.faces);
  std::vector<Outline> outlines;
  outlines.reserve(fills.size());
  for (const svg::FillLayer& layer : fills) outlines.emplace_back(layer);
  std::vector<std::vector<Outline>> clip_outlines(clips.size());
  for (std::size_t k = 0; k < clips.size(); ++k)
    for (const svg::FillLayer& shape : clips[k].shapes) clip_outlines[k].emplace_back(shape);
  // SVG 1.1 §14.3.5: what a clip path lets through is the union of its children's insides.
  const auto in_clip = [&](int k, int l, int f) {
    for (std::size_t s = 0; s < clips.at(k).shapes.size(); ++s)
      if (covers(clip_outlines[k][s], clips[k].shapes[s], samples[f], options, l, f)) return true;
    return false;
  };
  c.visible.assign(face_count, -1);
  c.filled.assign(face_count, -1);
  // The topmost covering layer: walk down the paint order, stop at the first that covers (and
  // under a stroke, go on to the first fill that does).
  const auto decide = [&](int f) {
    for (int l = static_cast<int>(fills.size()) - 1; l >= 0; --l) {
      if ((c.visible[f] >= 0 && fills[l].stroke) || too_narrow(fills[l], options)) continue;
      const auto& layer_clips = fills[l].clips;
      if (covers(outlines[l], fills[l], samples[f], options, l, f) &&
          std::all_of(layer_clips.begin(), layer_clips.end(), [&](int k) { return in_clip(k, l, f); })) {
        if (c.visible[f] < 0) c.visible[f] = l;
        if (!fills[l].stroke) {
          c.filled[f] = l;
          break;
        }
      }
    }
  };
  std::vector<std::exception_ptr> failed(face_count);
  base::for_each_part(
      face_count,
      [&](std::size_t f) {
        try {
          decide(static_cast<int>(f));
        } catch (...) {
          failed[f] = std::current_exception();
        }
      },
      1);
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  return c;
}

int Painted::region_of(int triangle) const {
  // Regions are listed by ascending physical tag.
  const int physical = mesh.triangle_physical.at(triangle);
  const auto it = std::lower_bound(regions.begin(), regions.end(), physical,
                                   [](const Region& r, int p) { return r.physical < p; });
  if (it == regions.end() || it->physical != physical) throw std::logic_error("a triangle in no region");
  return static_cast<int>(it - regions.begin());
}

namespace {

// Tags the triangles of `whole` by region (regions/groups.hpp: numbered by the whole drawing, so
// that a region's tag and name do not depend on the domain) and lists the regions the kept
// triangles show, by tag.
io::HighOrderMesh tag_by_region(const io::HighOrderMesh& whole, const std::vector<int>& triangle_layer,
                                const std::vector<char>& keep, const svg::FeatureSoup& soup,
                                std::vector<Region>& regions) {
  const RegionKeys keys = region_keys(soup);
  const int sources = static_cast<int>(soup.sources.size());
  io::HighOrderMesh tagged = whole;
  std::vector<char> shown(keys.names.size(), 0);
  for (int t = 0; t < whole.triangle_count(); ++t) {
    const int l = triangle_layer[t];
    const int key = l < 0 ? 0 : keys.of_layer[l];
    tagged.triangle_physical[t] = region_group(key, sources);
    if (keep[t]) shown[key] = 1;
  }
  tagged.physical_names.clear();
  for (const auto& [key, name] : whole.physical_names)
    if (key.first == 1) tagged.physical_names[key] = name;
  for (std::size_t k = 0; k < keys.names.size(); ++k) {
    if (!shown[k]) continue;
    Region r;
    r.physical = region_group(static_cast<int>(k), sources);
    r.name = keys.names[k];
    r.fill = keys.fill[k];
    r.source = keys.source[k];
    tagged.physical_names[{2, r.physical}] = r.name;
    regions.push_back(std::move(r));
  }
  return tagged;
}

}  // namespace

Painted paint(const io::HighOrderMesh& whole, const Classification& c, const svg::FeatureSoup& soup,
              Domain domain, bool tag_regions) {
  Painted out;
  const std::vector<char> keep = domain_triangles(c, domain);
  const bool classified = !c.visible.empty();
  std::vector<int> triangle_layer(whole.triangle_count(), -1);
  if (classified)
    for (int t = 0; t < whole.triangle_count(); ++t) triangle_layer[t] = c.visible[c.faces.of_triangle[t]];

  const io::HighOrderMesh tagged =
      tag_regions ? tag_by_region(whole, triangle_layer, keep, soup, out.regions) : whole;
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
