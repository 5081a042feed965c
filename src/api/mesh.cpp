// curvemesh::Mesh: the arrays of a finished mesh, and writing it with the command line's writers.
#include <algorithm>
#include <cctype>

#include "api/mesh_impl.hpp"
#include "base/files.hpp"
#include "io/high_order_mesh.hpp"
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
  const io::HighOrderMesh m = pipeline::high_order_mesh(result);
  impl->order = m.order;
  impl->nodes.reserve(m.nodes.size());
  for (const geometry::Vec2& p : m.nodes) impl->nodes.push_back({p.x(), p.y()});
  impl->triangles.assign(m.triangles.begin(), m.triangles.end());
  impl->lines.assign(m.lines.begin(), m.lines.end());
  impl->line_tags.reserve(m.line_physical.size());
  for (int physical : m.line_physical) impl->line_tags.push_back(tag_of(physical));
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
  if (!m.input_path.empty())
    if (const std::string clash = base::output_clash({{"drawing", m.input_path}}, {{"path", path}}); !clash.empty())
      throw Error(Error::Kind::invalid_parameters, clash);
  api::translate_errors([&] {
    if (ext == ".msh") {
      if (msh_version != 41 && msh_version != 22)
        throw Error(Error::Kind::invalid_parameters,
                    "--msh-version (" + std::to_string(msh_version) + ") must be 41 or 22");
      pipeline::write_msh(*m.result, path, msh_version);
    } else if (ext == ".vtu") {
      pipeline::write_vtu(*m.result, path);
    } else if (ext == ".svg") {
      pipeline::write_svg(*m.result, path);
    } else {
      throw Error(Error::Kind::output,
                  path + ": cannot tell the format from the extension (.msh, .vtu or .svg)");
    }
  });
}

}  // namespace curvemesh
