#include "io/features_json.hpp"

#include <numbers>

#include "io/svg_writer.hpp"

namespace curvemesh::io {

void add_features_json(const features::Features& f, nlohmann::ordered_json& j) {
  using nlohmann::ordered_json;
  ordered_json sections = ordered_json::array();
  std::size_t primary = 0, primary_edges = 0;
  for (const features::Section& s : f.sections) {
    ordered_json p = ordered_json::array(), poly = ordered_json::array();
    for (const auto& q : s.piece.p) p.push_back(q.x()), p.push_back(q.y());
    for (const auto& v : s.polyline) poly.push_back({v.x(), v.y()});
    const bool is_primary = s.kind == features::Kind::primary;
    primary += is_primary;
    if (is_primary) primary_edges += s.polyline.size() - 1;
    sections.push_back({{"curve", s.curve},
                        {"t", {s.t0, s.t1}},
                        {"p", std::move(p)},
                        {"kind", is_primary ? "primary" : "secondary"},
                        {"straight", s.straight},
                        {"polyline", std::move(poly)},
                        {"ts", s.ts}});
  }
  j["sections"] = std::move(sections);
  ordered_json segments = ordered_json::array();
  for (const features::Segment& s : f.segments)
    segments.push_back(
        {{"a", {s.a.x(), s.a.y()}}, {"b", {s.b.x(), s.b.y()}}, {"curve", s.curve}, {"t", {s.t0, s.t1}}});
  j["segments"] = std::move(segments);
  ordered_json points = ordered_json::array(), point_sources = ordered_json::array();
  for (const features::IsolatedPoint& p : f.points) {
    points.push_back({p.p.x(), p.p.y()});
    point_sources.push_back(p.source);
  }
  j["feature_points"] = std::move(points);
  j["feature_point_sources"] = std::move(point_sources);
  const features::Lengths& l = f.lengths;
  j["parameters"] = {{"d", l.d},          {"mu", l.mu},
                     {"epsilon", l.epsilon}, {"eps_m", l.eps_m},
                     {"l", l.edge},       {"l_m", l.min_edge},
                     {"alpha_deg", l.alpha_rad * 180 / std::numbers::pi},
                     {"junction_angle_deg", l.junction_angle_rad * 180 / std::numbers::pi},
                     {"features", l.features}};
  j["counts"] = {{"sections", f.sections.size()},       {"primary_sections", primary},
                 {"primary_edges", primary_edges},      {"secondary_segments", f.segments.size()},
                 {"feature_points", f.points.size()},   {"degenerate_curves", f.degenerate_curves},
                 {"straight_curves", f.straight_curves}};
}

std::string features_to_svg(const features::Features& f) {
  SvgWriter w(f.box);
  for (const features::Section& s : f.sections)
    if (s.kind == features::Kind::primary) w.cubic(s.piece, "#d62728");
  for (const features::Segment& s : f.segments) w.segment(s.a, s.b, "#2ca02c");
  for (const features::IsolatedPoint& p : f.points) w.dot(p.p, "#000000");
  return w.finish();
}

}  // namespace curvemesh::io
