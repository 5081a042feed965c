#include "io/msh_writer.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "io/output_file.hpp"

namespace curvemesh::io {

namespace {

struct Group {
  int tag;
  const char* name;
  std::vector<std::array<int, 2>> lines;  // vertex indices, lower first
};

class Text {
 public:
  Text& operator<<(const char* s) {
    out_ += s;
    return *this;
  }
  Text& operator<<(long v) {
    out_ += std::to_string(v);
    return *this;
  }
  Text& operator<<(int v) { return *this << long(v); }
  Text& operator<<(std::size_t v) { return *this << long(v); }
  Text& operator<<(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out_ += buf;
    return *this;
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

geometry::Box2 box_of(const mesh::TriMesh& m, const std::vector<std::array<int, 2>>* lines) {
  geometry::Box2 box;
  if (lines) {
    for (const auto& l : *lines) box.add(m.point(l[0])), box.add(m.point(l[1]));
  } else {
    for (int v = 0; v < m.vertex_count(); ++v) box.add(m.point(v));
  }
  if (box.empty()) box.add(geometry::Vec2::Zero());
  return box;
}

void physical_names(Text& t, const std::vector<Group>& groups) {
  t << "$PhysicalNames\n" << groups.size() + 1 << "\n";
  for (const Group& g : groups) t << "1 " << g.tag << " \"" << g.name << "\"\n";
  t << "2 " << kPhysicalDomain << " \"domain\"\n$EndPhysicalNames\n";
}

}  // namespace

std::string msh_string(const mesh::TriMesh& m, const MshOptions& options) {
  if (options.version != 41 && options.version != 22)
    throw std::logic_error("msh: unsupported version " + std::to_string(options.version));
  if (m.exact_vertex_count() > 0)
    throw std::logic_error("msh: " + std::to_string(m.exact_vertex_count()) + " vertices have no double position yet");

  std::vector<Group> all = {{kPhysicalPrimary, "primary", {}}, {kPhysicalSecondary, "secondary", {}}, {kPhysicalBoundary, "boundary", {}}};
  for (const auto& [e, f] : m.sorted_features()) {
    switch (f.kind) {
      case mesh::EdgeKind::primary: all[0].lines.push_back(e); break;
      case mesh::EdgeKind::secondary: all[1].lines.push_back(e); break;
      case mesh::EdgeKind::boundary: all[2].lines.push_back(e); break;
      default: break;
    }
  }
  std::vector<Group> groups;
  for (Group& g : all)
    if (!g.lines.empty()) groups.push_back(std::move(g));
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(m.triangle_count());
  for (int t = 0; t < m.triangle_slots(); ++t)
    if (m.alive(t)) triangles.push_back(m.triangle(t));
  std::size_t lines = 0;
  for (const Group& g : groups) lines += g.lines.size();
  const int n = m.vertex_count();

  Text t;
  if (options.version == 22) {
    t << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    physical_names(t, groups);
    t << "$Nodes\n" << n << "\n";
    for (int v = 0; v < n; ++v) t << v + 1 << " " << m.point(v).x() << " " << m.point(v).y() << " 0\n";
    t << "$EndNodes\n$Elements\n" << lines + triangles.size() << "\n";
    long id = 1;
    for (const Group& g : groups)
      for (const auto& l : g.lines) t << id++ << " 1 2 " << g.tag << " " << g.tag << " " << l[0] + 1 << " " << l[1] + 1 << "\n";
    for (const auto& tri : triangles)
      t << id++ << " 2 2 " << kPhysicalDomain << " 1 " << tri[0] + 1 << " " << tri[1] + 1 << " " << tri[2] + 1 << "\n";
    t << "$EndElements\n";
    return t.take();
  }

  t << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  physical_names(t, groups);
  // One curve entity per group (its tag is the group's), one surface; no points.
  t << "$Entities\n0 " << groups.size() << " 1 0\n";
  for (const Group& g : groups) {
    const geometry::Box2 b = box_of(m, &g.lines);
    t << g.tag << " " << b.min.x() << " " << b.min.y() << " 0 " << b.max.x() << " " << b.max.y() << " 0 1 " << g.tag << " 0\n";
  }
  const geometry::Box2 b = box_of(m, nullptr);
  t << "1 " << b.min.x() << " " << b.min.y() << " 0 " << b.max.x() << " " << b.max.y() << " 0 1 " << kPhysicalDomain << " 0\n";
  t << "$EndEntities\n";
  // All nodes in one block on the surface.
  t << "$Nodes\n1 " << n << " 1 " << n << "\n2 1 0 " << n << "\n";
  for (int v = 0; v < n; ++v) t << v + 1 << "\n";
  for (int v = 0; v < n; ++v) t << m.point(v).x() << " " << m.point(v).y() << " 0\n";
  t << "$EndNodes\n";
  const std::size_t elements = lines + triangles.size();
  t << "$Elements\n" << groups.size() + 1 << " " << elements << " 1 " << elements << "\n";
  long id = 1;
  for (const Group& g : groups) {
    t << "1 " << g.tag << " 1 " << g.lines.size() << "\n";
    for (const auto& l : g.lines) t << id++ << " " << l[0] + 1 << " " << l[1] + 1 << "\n";
  }
  t << "2 1 2 " << triangles.size() << "\n";
  for (const auto& tri : triangles) t << id++ << " " << tri[0] + 1 << " " << tri[1] + 1 << " " << tri[2] + 1 << "\n";
  t << "$EndElements\n";
  return t.take();
}

void write_msh(const mesh::TriMesh& mesh, const std::string& path, const MshOptions& options) {
  write_file_atomically(path, msh_string(mesh, options));
}

}  // namespace curvemesh::io
