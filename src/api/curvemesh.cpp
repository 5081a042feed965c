// The public API's functions: each runs the pipeline (pipeline::run) or its check
// (pipeline/check.hpp) and hands out plain arrays; every failure leaves as curvemesh::Error.
#include <curvemesh/curvemesh.hpp>

#include "api/mesh_impl.hpp"
#include "io/msh_reader.hpp"
#include "pipeline/check.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"

#ifndef CURVEMESH_VERSION
#error "CURVEMESH_VERSION must be defined (the project's version, by src/CMakeLists.txt)"
#endif

namespace curvemesh {

namespace {

Mesh mesh_source(const pipeline::Source& source, const Parameters& parameters) {
  return make_mesh(api::translate_errors([&] {
    return mesh_impl(pipeline::run(source, parameters), source.kind == pipeline::Source::Kind::file ? source.path : "");
  }));
}

CheckReport report_of(const pipeline::MeshCheck& c) {
  CheckReport r;
  r.order = c.order;
  r.triangles = c.triangles;
  r.invalid = c.invalid;
  r.undecided = c.undecided;
  r.min_scaled_jacobian = c.min_scaled_jacobian;
  r.exact_fallbacks = c.exact_fallbacks;
  return r;
}

}  // namespace

const char* version() {
  return CURVEMESH_VERSION;
}

const char* tag_name(LineTag tag) {
  switch (tag) {
    case LineTag::primary:
      return "primary";
    case LineTag::secondary:
      return "secondary";
    case LineTag::boundary:
      return "boundary";
  }
  return "?";
}

Mesh mesh_file(const std::string& path, const Parameters& parameters) {
  return mesh_source(pipeline::Source::file(path), parameters);
}

Mesh mesh_svg(const std::string& svg_text, const Parameters& parameters, const std::string& name) {
  return mesh_source(pipeline::Source::svg(svg_text, name), parameters);
}

Mesh mesh_curves(const std::vector<Curve>& curves, const Parameters& parameters) {
  std::vector<std::array<geometry::Vec2, 4>> beziers;
  beziers.reserve(curves.size());
  for (const Curve& c : curves)
    beziers.push_back({geometry::Vec2(c[0][0], c[0][1]), geometry::Vec2(c[1][0], c[1][1]),
                       geometry::Vec2(c[2][0], c[2][1]), geometry::Vec2(c[3][0], c[3][1])});
  return mesh_source(pipeline::Source::beziers(beziers), parameters);
}

CheckReport check_file(const std::string& msh_path, const CheckOptions& options) {
  return api::translate_errors([&] {
    io::HighOrderMesh m;
    try {
      m = io::read_msh(msh_path, static_cast<std::uint64_t>(io::kDefaultMaxMshMb * 1048576.0),
                       "`curvemesh check --max-input-mb`");
    } catch (const io::MshError& e) {
      throw Error(Error::Kind::invalid_input, e.what());  // the message starts with the path
    }
    return report_of(pipeline::check_mesh(m, {.exact = options.exact, .threads = options.threads}));
  });
}

CheckReport check(const Mesh& mesh, const CheckOptions& options) {
  // The .msh file holds the nodes with 17 significant digits, which read back as the very same
  // doubles: checking the arrays is checking the file.
  return api::translate_errors([&] {
    if (mesh.order() == 0) return CheckReport{};  // a default-constructed Mesh
    io::HighOrderMesh m;
    m.order = mesh.order();
    m.nodes.reserve(mesh.node_count());
    for (const auto& [x, y] : mesh.nodes()) m.nodes.emplace_back(x, y);
    m.triangles.assign(mesh.triangles().begin(), mesh.triangles().end());
    return report_of(pipeline::check_mesh(m, {.exact = options.exact, .threads = options.threads}));
  });
}

}  // namespace curvemesh
