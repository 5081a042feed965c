#include "pipeline/domain.hpp"

#include <algorithm>

#include "regions/faces.hpp"

namespace curvemesh::pipeline {

std::string domain_name(Domain domain) {
  return regions::domain_name(domain);
}

std::vector<std::string> domain_names() {
  std::vector<std::string> names;
  for (Domain d : regions::kDomains) names.emplace_back(regions::domain_name(d));
  return names;
}

std::optional<DomainMesh> cut_domain(const MeshedDrawing& drawing, Domain domain) {
  const std::vector<char> keep = regions::domain_triangles(drawing.classification, domain);
  if (std::count(keep.begin(), keep.end(), 1) == 0) return std::nullopt;
  DomainMesh out;
  out.mesh = regions::submesh(drawing.mesh, keep, &out.line_origin);
  return out;
}

// Why a domain came out empty. A drawing with strokes can still leave its painted domain empty:
// a stroke narrower than --min-stroke-width paints nothing in it
// (regions::ClassifyOptions::min_stroke_width).
std::string empty_domain_reason(Domain domain, bool has_fills, bool has_strokes) {
  if (domain == Domain::evenodd) return "no part of the box is enclosed by its curves";
  if (domain == Domain::outside) return "every part of the box is enclosed by its curves";
  // Filled outlines and still nothing kept: every triangle is mostly outside what they paint (a
  // triangle an outline crosses is decided on its own, regions/paint.hpp).
  if (has_fills)
    return "no triangle is mostly inside what its fills paint: filled outlines with no area (a filled open "
           "line), shapes too small beside the drawing's size, or clipped away; a smaller --edge-length and "
           "--mu keep small shapes";
  if (domain == Domain::filled) return "nothing of the drawing is filled";
  if (has_strokes)
    return "nothing of the drawing is filled, and its strokes are narrower than --min-stroke-width; a smaller "
           "--min-stroke-width keeps them";
  return "nothing of the drawing is filled or stroked";
}

io::HighOrderMesh used_nodes(const io::HighOrderMesh& mesh, std::vector<int>& node_origin) {
  return regions::submesh(mesh, std::vector<char>(mesh.triangle_count(), 1), nullptr, &node_origin);
}

}  // namespace curvemesh::pipeline
