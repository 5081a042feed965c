#include "io/soup_json.hpp"

namespace curvemesh::io {

nlohmann::ordered_json soup_to_json(const svg::FeatureSoup& soup) {
  using nlohmann::ordered_json;
  ordered_json j;
  const geometry::Box2 box = soup.bounds();
  j["bbox"] = box.empty() ? ordered_json::array() : ordered_json::array({box.min.x(), box.min.y(), box.max.x(), box.max.y()});
  ordered_json curves = ordered_json::array();
  for (const svg::SoupCurve& c : soup.curves) {
    ordered_json p = ordered_json::array();
    for (const auto& q : c.bezier.p) p.push_back(q.x()), p.push_back(q.y());
    curves.push_back({{"p", std::move(p)}, {"source", c.source}, {"stroke", c.stroke.to_string()}, {"fill", c.fill.to_string()}});
    if (c.arc >= 0) curves.back()["arc"] = c.arc;  // the cubics of one arc (SoupCurve::arc)
  }
  j["curves"] = std::move(curves);
  ordered_json points = ordered_json::array(), point_sources = ordered_json::array();
  for (const svg::SoupPoint& p : soup.points) {
    points.push_back({p.p.x(), p.p.y()});
    point_sources.push_back(p.source);
  }
  j["points"] = std::move(points);
  j["point_sources"] = std::move(point_sources);
  ordered_json sources = ordered_json::array();
  for (const svg::SourceElement& s : soup.sources)
    sources.push_back({{"tag", s.tag}, {"id", s.id}, {"index", s.index}, {"line", s.line}});
  j["sources"] = std::move(sources);
  j["warnings"] = soup.warnings;
  return j;
}

}  // namespace curvemesh::io
