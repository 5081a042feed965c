// curvemesh::Mesh: the arrays of a finished mesh, and writing it with the command line's writers.
#include <algorithm>
#include <cctype>

#include "api/mesh_impl.hpp"
#include "base/files.hpp"
#include "io/high_order_mesh.hpp"
#include "io/xdmf_writer.hpp"
#include "pipeline/output.hpp"

namespace curvemesh {

namespace {

// A default-constructed Mesh has no Impl: it reads as an empty one.
const Mesh::Impl& of(const std::shared_ptr<const Mesh::Impl>& impl) {
  static const Mesh::Impl empty;
  return impl ? *impl : empty;
}

LineTag tag_of(int physical) {
  switch (physical) {
    case io::kPhysicalPrimary:
      return LineTag::primary;
    case io::kPhysicalSecondary:
      return LineTag::secondary;
    case io::kPhysicalBoundary:
      return LineTag::boundary;
  }
  throw std::logic_error("a feature line in physical group " + std::to_string(physical));
}

// The path's extension, lower-cased: ".msh", ".vtu", ...; empty when it has none.
std::string extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

}  // namespace

Mesh make_mesh(std::shared_ptr<const Mesh::Impl> impl) {
  Mesh m;
  m.impl_ = std::move(impl);
  return m;
}

std::shared_ptr<const Mesh::Impl> mesh_impl(pipeline::Result result, std::string input_path) {
  auto impl = std::make_shared<Mesh::Impl>();
  const io::HighOrderMesh& m = pipeline::high_order_mesh(result);
  impl->order = m.order;
  impl->nodes.reserve(m.nodes.size());
  for (const geometry::Vec2& p : m.nodes) impl->nodes.push_back({p.x(), p.y()});
  impl->triangles.assign(m.triangles.begin(), m.triangles.end());
  impl->lines.assign(m.lines.begin(), m.lines.end());
  impl->line_tags.reserve(m.line_physical.size());
  for (int physical : m.line_physical) impl->line_tags.push_back(tag_of(physical));
  impl->triangle_groups = m.triangle_physical;
  impl->line_groups.reserve(m.line_physical.size());
  for (int l = 0; l < m.line_count(); ++l) impl->line_groups.push_back(m.groups_of_line(l));
  // The groups as the run listed them for its statistics.
  for (const auto& g : result.stats.at("groups"))
    impl->groups.push_back(Group{g.at("dim").get<int>(), g.at("id").get<int>(), g.at("name").get<std::string>()});
  const std::vector<int> curves = pipeline::line_curves(result, m);
  impl->line_curves.assign(curves.begin(), curves.end());
  impl->stats_json = pipeline::stats_text(result);
  impl->stats_json.pop_back();  // the file's final newline
  impl->warnings = result.warnings;
  impl->input_path = std::move(input_path);
  impl->result.emplace(std::move(result));
  return impl;
}

int Mesh::order() const {
  return of(impl_).order;
}
std::size_t Mesh::node_count() const {
  return of(impl_).nodes.size();
}
std::size_t Mesh::triangle_count() const {
  const Impl& m = of(impl_);
  return m.order ? m.triangles.size() / nodes_per_triangle() : 0;
}
std::size_t Mesh::line_count() const {
  return of(impl_).line_tags.size();
}
const std::vector<std::array<double, 2>>& Mesh::nodes() const {
  return of(impl_).nodes;
}
const std::vector<std::int64_t>& Mesh::triangles() const {
  return of(impl_).triangles;
}
int Mesh::nodes_per_triangle() const {
  const int order = of(impl_).order;
  return order ? (order + 1) * (order + 2) / 2 : 0;
}
const std::vector<std::int64_t>& Mesh::lines() const {
  return of(impl_).lines;
}
int Mesh::nodes_per_line() const {
  const int order = of(impl_).order;
  return order ? order + 1 : 0;
}
const std::vector<LineTag>& Mesh::line_tags() const {
  return of(impl_).line_tags;
}
const std::vector<std::int64_t>& Mesh::line_curves() const {
  return of(impl_).line_curves;
}
const std::vector<int>& Mesh::triangle_groups() const {
  return of(impl_).triangle_groups;
}
const std::vector<std::vector<int>>& Mesh::line_groups() const {
  return of(impl_).line_groups;
}
const std::vector<Group>& Mesh::groups() const {
  return of(impl_).groups;
}
const std::string& Mesh::stats_json() const {
  return of(impl_).stats_json;
}
const std::vector<std::string>& Mesh::warnings() const {
  return of(impl_).warnings;
}

void Mesh::write(const std::string& path, int msh_version) const {
  const Impl& m = of(impl_);
  if (!m.result)
    throw Error(Error::Kind::output, path + ": nothing to write: the Mesh is empty (default-constructed)");
  const std::string ext = extension(path);
  std::vector<base::NamedPath> outputs{{"path", path}};
  if (ext == ".xdmf") outputs.push_back({"the XDMF file's data", io::xdmf_data_path(path)});
  if (!m.input_path.empty())
    if (const std::string clash = base::output_clash({{"drawing", m.input_path}}, outputs); !clash.empty())
      throw Error(Error::Kind::invalid_parameters, clash);
  api::translate_errors([&] {
    if (ext == ".msh") {
      if (msh_version != 41 && msh_version != 22)
        throw Error(Error::Kind::invalid_parameters,
                    "--msh-version (" + std::to_string(msh_version) + ") must be 41 or 22");
      pipeline::write_msh(*m.result, path, msh_version);
    } else if (ext == ".vtu") {
      pipeline::write_vtu(*m.result, path);
    } else if (ext == ".xdmf") {
      if (!io::xdmf_order_supported(m.order))
        throw Error(Error::Kind::invalid_parameters,
                    path + ": XDMF has no triangle of order " + std::to_string(m.order) +
                        " (dolfinx reads orders 1 and 2 from it): mesh with order 2 or 1, or write .msh");
      pipeline::write_xdmf(*m.result, path);
    } else if (ext == ".svg") {
      pipeline::write_svg(*m.result, path);
    } else {
      throw Error(Error::Kind::output,
                  path + ": cannot tell the format from the extension (.msh, .vtu, .xdmf or .svg)");
    }
  });
}

}  // namespace curvemesh
