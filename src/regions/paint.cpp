#include "regions/paint.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <span>
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
  bool by_majority = false;  // one triangle's: where they disagree, most of them decide
};

// The squared distance between two boxes (0 when they meet).
double squared_gap(const geometry::Box2& a, const geometry::Box2& b) {
  const double dx = std::max({a.min.x() - b.max.x(), 0.0, b.min.x() - a.max.x()});
  const double dy = std::max({a.min.y() - b.max.y(), 0.0, b.min.y() - a.max.y()});
  return dx * dx + dy * dy;
}

// Whether fill layer l covers the sample points s of face f. A face bounded by lines on the
// layer's outline lies on one side of it, and every sample says the same. Where the mesh follows
// the outline only within ε, the outline may cross the face, and the samples disagree: `split` is
// set (classify then decides the face triangle by triangle), and the sample farthest from the
// outline decides, each sample's distance bounded within a fifth of it. (Not the first sample
// more than ε from it: a secondary line may leave one curve for a neighbour's envelope, so a
// triangle can reach well into a thin shape drawn over the face.)
bool covers(const Outline& outline, const svg::FillLayer& layer, const FaceSamples& s,
            const ClassifyOptions& o, int l, int f, bool& split) {
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
  split = true;
  // The samples disagree: the one farthest from the outline decides, or for one triangle the
  // side most of its samples are on (most of its area: what is painted there), ties so.
  for (std::size_t i = 0; i < n; ++i)
    if (!asked[i]) ask(i);
  std::size_t best = n;
  int in = 0, decided = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!w[i].decided) continue;
    ++decided;
    in += inside(w[i].number, layer.rule);
    if (best == n || w[i].clearance > w[best].clearance) best = i;
  }
  if (s.by_majority && 2 * in != decided) return 2 * in > decided;
  return inside(w[best].number, layer.rule);
}

}  // namespace

bool too_narrow(const svg::FillLayer& layer, const ClassifyOptions& options) {
  return layer.stroke && layer.width < options.min_stroke_width;
}

namespace {

// The sample points of the triangles `ts`.
FaceSamples samples_of(const io::HighOrderMesh& mesh, std::span<const int> ts) {
  FaceSamples s;
  for (const int t : ts) add_samples(mesh, t, s.points);
  for (const geometry::Vec2& p : s.points) {
    s.box.add(p);
    s.spread = std::max(s.spread, (p - s.points[0]).norm());
  }
  return s;
}

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
        samples[f] = samples_of(mesh, std::span<const int>(m.data(), count));
      },
      1);
  return samples;
}

// The fill layers, their outlines and clip paths, and what classify decides with them.
class Painter {
 public:
  Painter(const std::vector<svg::FillLayer>& fills, const ClassifyOptions& options,
          const std::vector<svg::ClipPath>& clips)
      : fills_(fills), options_(options), clips_(clips), clip_outlines_(clips.size()) {
    outlines_.reserve(fills.size());
    for (const svg::FillLayer& layer : fills) outlines_.emplace_back(layer);
    for (std::size_t k = 0; k < clips.size(); ++k)
      for (const svg::FillLayer& shape : clips[k].shapes) clip_outlines_[k].emplace_back(shape);
  }

  struct Decision {
    int visible = -1, filled = -1;
    bool split = false;  // some outline runs between the samples
  };

  // The topmost layer covering the samples of face f: walk down the paint order, stop at the first
  // that covers (and under a stroke, go on to the first fill that does).
  Decision decide(const FaceSamples& s, int f) const {
    Decision d;
    for (int l = static_cast<int>(fills_.size()) - 1; l >= 0; --l) {
      if ((d.visible >= 0 && fills_[l].stroke) || too_narrow(fills_[l], options_)) continue;
      const auto& layer_clips = fills_[l].clips;
      if (covers(outlines_[l], fills_[l], s, options_, l, f, d.split) &&
          std::all_of(layer_clips.begin(), layer_clips.end(), [&](int k) { return in_clip(k, l, s, f, d.split); })) {
        if (d.visible < 0) d.visible = l;
        if (!fills_[l].stroke) {
          d.filled = l;
          break;
        }
      }
    }
    return d;
  }

 private:
  // SVG 1.1 §14.3.5: what a clip path lets through is the union of its children's insides.
  bool in_clip(int k, int l, const FaceSamples& s, int f, bool& split) const {
    for (std::size_t i = 0; i < clips_.at(k).shapes.size(); ++i)
      if (covers(clip_outlines_[k][i], clips_[k].shapes[i], s, options_, l, f, split)) return true;
    return false;
  }

  const std::vector<svg::FillLayer>& fills_;
  const ClassifyOptions& options_;
  const std::vector<svg::ClipPath>& clips_;
  std::vector<Outline> outlines_;
  std::vector<std::vector<Outline>> clip_outlines_;
};

}  // namespace

// Every face decided on its own, in parallel; a face that cannot be decided is reported as a
// serial sweep would report it, the first in the faces' order. A face an outline crosses (its
// samples disagree: the mesh follows that outline only within ε there, as along a stroke thinner
// than ε) is then decided triangle by triangle, each at its own samples, so that the part of the
// face inside a thin band is painted and the rest is not; a triangle that cannot be decided alone
// keeps its face's decision.
Classification classify(const io::HighOrderMesh& mesh, const std::vector<svg::FillLayer>& fills,
                        const ClassifyOptions& options, const std::vector<svg::ClipPath>& clips) {
  Classification c;
  c.faces = find_faces(mesh);
  const int face_count = c.faces.count();
  const std::vector<FaceSamples> samples = face_samples(mesh, c.faces);
  const Painter painter(fills, options, clips);
  std::vector<Painter::Decision> of_face(face_count);
  std::vector<std::exception_ptr> failed(face_count);
  base::for_each_part(
      face_count,
      [&](std::size_t f) {
        try {
          of_face[f] = painter.decide(samples[f], static_cast<int>(f));
        } catch (...) {
          failed[f] = std::current_exception();
        }
      },
      1);
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  const int n = mesh.triangle_count();
  c.visible.resize(n);
  c.filled.resize(n);
  std::vector<int> split;  // the triangles of split faces
  for (int t = 0; t < n; ++t) {
    const Painter::Decision& d = of_face[c.faces.of_triangle[t]];
    c.visible[t] = d.visible;
    c.filled[t] = d.filled;
    if (d.split) split.push_back(t);
  }
  base::for_each_part(split.size(), [&](std::size_t i) {
    const int t = split[i];
    try {
      FaceSamples s = samples_of(mesh, std::span<const int>(&t, 1));
      s.by_majority = true;
      const Painter::Decision d = painter.decide(s, c.faces.of_triangle[t]);
      c.visible[t] = d.visible;
      c.filled[t] = d.filled;
    } catch (const Undecided&) {
      // On an outline as far as doubles can tell: its face's decision stands.
    }
  });
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
    for (int t = 0; t < whole.triangle_count(); ++t) triangle_layer[t] = c.visible[t];

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
