#include "pipeline/output.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include "io/curved_mesh.hpp"
#include "io/mesh_svg.hpp"
#include "io/msh_writer.hpp"
#include "io/output_file.hpp"
#include "io/vtu_writer.hpp"
#include "io/xdmf_writer.hpp"
#include "regions/faces.hpp"
#include "regions/groups.hpp"
#include "svg/paint.hpp"

namespace curvemesh::pipeline {

namespace {

void require_mesh(const Result& r) {
  if (r.last < Stage::triangulate) throw std::logic_error("the pipeline stopped before making a mesh");
}

std::array<double, 3> rgb_of(const svg::Paint& p) {
  return {p.r / 255.0, p.g / 255.0, p.b / 255.0};
}

bool is_colour(const svg::Paint& p) {
  return p.kind == svg::Paint::Kind::color;
}

}  // namespace

const io::HighOrderMesh& high_order_mesh(const Result& r) {
  require_mesh(r);
  if (!r.output) throw std::logic_error("the pipeline's result has no output mesh: run() makes it");
  return *r.output;
}

io::HighOrderMesh make_output_mesh(const Result& r) {
  require_mesh(r);
  io::HighOrderMesh m = r.painted ? r.painted->mesh : r.curved ? io::curved_mesh(*r.curved) : io::linear_mesh(r.linear);
  regions::add_line_groups(m, line_elements(r, m), r.soup);
  return m;
}

nlohmann::ordered_json groups_json(const io::HighOrderMesh& mesh) {
  struct Measure {
    int count = 0;
    double size = 0;
  };
  std::map<std::pair<int, int>, Measure> groups;  // (dim, id)
  for (int l = 0; l < mesh.line_count(); ++l) {
    const double length = regions::line_length(mesh, l);
    for (int g : mesh.groups_of_line(l)) {
      Measure& m = groups[{1, g}];
      ++m.count;
      m.size += length;
    }
  }
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    if (mesh.triangle_physical[t] <= 0) continue;
    Measure& m = groups[{2, mesh.triangle_physical[t]}];
    ++m.count;
    m.size += regions::triangle_area(mesh, t);
  }
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [key, m] : groups) {
    const auto name = mesh.physical_names.find(key);
    const bool line = key.first == 1;
    out.push_back({{"dim", key.first},
                   {"id", key.second},
                   {"name", name != mesh.physical_names.end() ? name->second : ""},
                   {line ? "lines" : "triangles", m.count},
                   {line ? "length" : "area", m.size}});
  }
  return out;
}

std::vector<std::vector<int>> line_elements(const Result& r, const io::HighOrderMesh& mesh) {
  require_mesh(r);
  const mesh::TriMesh& corners = r.corners();
  // The shared pieces of each feature, by (kind, section or segment).
  std::map<std::pair<mesh::EdgeKind, int>, std::vector<const triangulate::SharedPiece*>> shared;
  for (const triangulate::SharedPiece& p : r.shared) shared[{p.kind, p.source}].push_back(&p);
  const auto source_of = [&](int curve) {
    return curve >= 0 && curve < static_cast<int>(r.soup.curves.size()) ? r.soup.curves[curve].source : -1;
  };
  std::vector<std::vector<int>> out(mesh.line_count());
  for (int l = 0; l < mesh.line_count(); ++l) {
    const auto ends = mesh.line(l);
    // A domain's mesh has its nodes renumbered: back to the whole mesh's (the corners' ids).
    const int a = r.painted ? r.painted->node_origin.at(ends[0]) : ends[0];
    const int b = r.painted ? r.painted->node_origin.at(ends[1]) : ends[1];
    const mesh::EdgeFeature* f = corners.feature(a, b);
    if (!f || (f->kind != mesh::EdgeKind::primary && f->kind != mesh::EdgeKind::secondary)) continue;
    std::vector<int> curves{f->curve};
    // Where along its feature the line's middle is: a curve parameter, or a fraction of a segment.
    double at = (f->t_lo + f->t_hi) / 2;
    if (f->kind == mesh::EdgeKind::secondary && f->source >= 0 &&
        f->source < static_cast<int>(r.features.segments.size())) {
      const features::Segment& s = r.features.segments[f->source];
      curves.insert(curves.end(), s.other_curves.begin(), s.other_curves.end());
      at = features::fraction_along(s, (corners.point(a) + corners.point(b)) / 2);
    }
    if (const auto it = shared.find({f->kind, f->source}); it != shared.end())
      for (const triangulate::SharedPiece* p : it->second)
        if (p->from <= at && at <= p->to) curves.insert(curves.end(), p->curves.begin(), p->curves.end());
    for (int c : curves)
      if (const int s = source_of(c); s >= 0) out[l].push_back(s);
    std::sort(out[l].begin(), out[l].end());
    out[l].erase(std::unique(out[l].begin(), out[l].end()), out[l].end());
  }
  return out;
}

std::vector<io::VtuCellScalars> cell_data(const Result& r) {
  std::vector<io::VtuCellScalars> out;
  if (!r.painted) return out;
  const regions::Painted& p = *r.painted;
  io::VtuCellScalars face{"face", {p.face.begin(), p.face.end()}};
  out.push_back(std::move(face));
  if (!p.regions.empty()) {
    // A tagged mesh's physical surface is its region.
    out.push_back({"region", {p.mesh.triangle_physical.begin(), p.mesh.triangle_physical.end()}});
  }
  return out;
}

namespace {

// Per line of `mesh`, the curve of the feature of its two ends in `corners`; node_origin (when
// given) takes a node of `mesh` to its number in the whole mesh, the corners' ids.
std::vector<int> curves_of_lines(const mesh::TriMesh& corners, const io::HighOrderMesh& mesh,
                                 const std::vector<int>* node_origin) {
  std::vector<int> out;
  out.reserve(mesh.line_count());
  for (int l = 0; l < mesh.line_count(); ++l) {
    const auto ends = mesh.line(l);
    const auto node = [&](int i) { return node_origin ? node_origin->at(i) : i; };
    const mesh::EdgeFeature* feature = corners.feature(node(ends[0]), node(ends[1]));
    out.push_back(feature ? feature->curve : -1);
  }
  return out;
}

}  // namespace

std::vector<int> line_curves(const Result& r, const io::HighOrderMesh& mesh) {
  require_mesh(r);
  // A domain's mesh has its nodes renumbered: back to the whole mesh's.
  return curves_of_lines(r.corners(), mesh, r.painted ? &r.painted->node_origin : nullptr);
}

void write_msh(const Result& r, const std::string& path, int version) {
  io::write_msh(high_order_mesh(r), path, io::MshOptions{version});
}

void write_xdmf(const Result& r, const std::string& path) {
  const std::string data = io::xdmf_data_path(path);
  const io::XdmfFiles files = io::xdmf_files(high_order_mesh(r), std::filesystem::path(data).filename().string());
  io::OutputFiles out;
  out.add(path, files.xml);
  out.add(data, files.data);
  out.commit();
}

void write_vtu(const Result& r, const std::string& path) {
  io::write_vtu(high_order_mesh(r), path, cell_data(r));
}

std::string mesh_svg(const Result& r) {
  require_mesh(r);
  if (r.painted) {
    // Each triangle in the colour of the element painted on it; a paint server's (gradient,
    // pattern) in light grey, the background left white.
    const regions::Painted& p = *r.painted;
    std::vector<std::string> fill(p.mesh.triangle_count());
    for (int t = 0; t < p.mesh.triangle_count(); ++t)
      if (p.layer[t] >= 0) {
        const svg::Paint& paint = r.soup.fills[p.layer[t]].fill;
        fill[t] = paint.kind == svg::Paint::Kind::color ? paint.to_string() : "#d8d8d8";
      }
    return io::mesh_svg(p.mesh, fill);
  }
  return r.curved ? io::mesh_svg(*r.curved) : io::mesh_svg(r.linear);
}

void write_svg(const Result& r, const std::string& path) {
  io::write_file_atomically(path, mesh_svg(r));
}

std::string stats_text(const Result& r) {
  // Names from the drawing (the input's path, regions' ids) are valid UTF-8 when the reader made
  // them; a path from the command line need not be: replaced rather than refused.
  return r.stats.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

std::optional<std::array<double, 3>> css_colour(const std::string& css) {
  const std::optional<svg::Paint> paint = svg::parse_color(css);
  if (!paint) return std::nullopt;
  return std::array<double, 3>{paint->r / 255.0, paint->g / 255.0, paint->b / 255.0};
}

std::vector<SideColours> curve_colours(const svg::FeatureSoup& soup) {
  std::vector<SideColours> out;
  out.reserve(soup.curves.size());
  for (const svg::SoupCurve& c : soup.curves) {
    const auto both = is_colour(c.stroke) ? rgb_of(c.stroke)
                      : is_colour(c.fill) ? rgb_of(c.fill)
                                          : std::array<double, 3>{0, 0, 0};
    out.push_back({is_colour(c.left) ? rgb_of(c.left) : both, is_colour(c.right) ? rgb_of(c.right) : both});
  }
  return out;
}

MeshedDrawing meshed_drawing(const Result& r) {
  if (!r.curved) throw std::logic_error("meshed_drawing: the pipeline did not curve the mesh");
  const curve::CurvedMesh& curved = *r.curved;
  MeshedDrawing out;
  out.mesh = io::curved_mesh(curved);
  out.line_curve = curves_of_lines(curved.linear, out.mesh, nullptr);  // the whole mesh: its own numbers
  out.diagonal = r.resolved.d;
  out.has_strokes = r.soup.has_stroke_areas();
  out.has_fills = r.soup.has_fills();
  out.colours = curve_colours(r.soup);
  out.classification = r.classification;
  if (out.classification.faces.of_triangle.empty()) out.classification.faces = regions::find_faces(out.mesh);
  for (const auto& [stage, s] : r.stats["seconds"].items()) out.seconds += s.get<double>();
  for (const curve::FeatureLine& line : curved.lines) {
    const int a = line.nodes[0], b = line.nodes[1];
    const auto feature = curved.linear.feature(a, b);
    // EdgeFeature's parameters are at the lower- and higher-numbered vertex. A secondary edge
    // has none (its vertices move within ε of the input): it follows its input segment, which runs
    // from the segment's t0 to its t1, when it points the same way.
    bool forward = true;
    if (feature && feature->kind == mesh::EdgeKind::primary)
      forward = (a < b) == (feature->t_lo < feature->t_hi);
    if (feature && feature->kind == mesh::EdgeKind::secondary && feature->source >= 0) {
      const features::Segment& s = r.features.segments[feature->source];
      const double along = (curved.linear.point(b) - curved.linear.point(a)).dot(s.b - s.a);
      forward = (along > 0) == (s.t0 <= s.t1);
    }
    out.line_forward.push_back(forward);
  }
  return out;
}

MeshedDrawing mesh_drawing(const Source& source, const Parameters& parameters) {
  Parameters curved = parameters;
  curved.order = 3;
  return meshed_drawing(run(source, curved));
}

}  // namespace curvemesh::pipeline
