#include "pipeline/domain.hpp"

#include <algorithm>

#include "regions/faces.hpp"

namespace curvemesh::pipeline {

std::vector<std::string> domain_names() { return {"inside", "evenodd", "outside", "filled", "all", "box"}; }

std::optional<DomainMesh> cut_domain(const MeshedDrawing& drawing, const std::string& name) {
  // inside and all are the older names of evenodd and box; outside is evenodd's complement.
  const std::string base = name == "all" ? "box" : name == "inside" || name == "outside" ? "evenodd" : name;
  const std::optional<Domain> domain = regions::domain_named(base);
  if (!domain) return std::nullopt;
  std::vector<char> keep = regions::domain_triangles(drawing.classification, *domain);
  if (name == "outside")
    for (char& k : keep) k = !k;
  if (std::count(keep.begin(), keep.end(), 1) == 0) return std::nullopt;
  DomainMesh out;
  out.mesh = regions::submesh(drawing.mesh, keep, &out.line_origin);
  return out;
}

io::HighOrderMesh used_nodes(const io::HighOrderMesh& mesh, std::vector<int>& node_origin) {
  return regions::submesh(mesh, std::vector<char>(mesh.triangle_count(), 1), nullptr, &node_origin);
}

}  // namespace curvemesh::pipeline
