#include "io/msh_writer.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "io/output_file.hpp"

namespace curvemesh::io {

namespace {

class Text {
 public:
  Text& operator<<(const char* s) {
    out_ += s;
    return *this;
  }
  Text& operator<<(const std::string& s) {
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
  Text& operator<<(const geometry::Box2& b) {
    return *this << b.min.x() << " " << b.min.y() << " 0 " << b.max.x() << " " << b.max.y() << " 0";
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

// The elements of one physical group of one dimension: one geometric entity in the file.
struct Group {
  int dim;
  int physical;  // 0: in no physical group
  int entity;    // the entity's tag
  std::vector<int> elements;
  geometry::Box2 box;
};

// Groups elements by physical tag, ascending, keeping their order within each group.
std::vector<Group> group_by_physical(int dim, const std::vector<int>& physical) {
  std::vector<int> tags = physical;
  std::sort(tags.begin(), tags.end());
  tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
  std::vector<Group> groups;
  for (int tag : tags) groups.push_back(Group{dim, tag, 0, {}, {}});
  for (int e = 0; e < static_cast<int>(physical.size()); ++e) {
    const auto at = std::lower_bound(tags.begin(), tags.end(), physical[e]) - tags.begin();
    groups[at].elements.push_back(e);
  }
  return groups;
}

void add_nodes(geometry::Box2& box, const HighOrderMesh& m, std::span<const int> element) {
  for (int v : element) box.add(m.nodes[v]);
}

constexpr int kLineType[] = {1, 8, 26}, kTriangleType[] = {2, 9, 21};

// A physical name as the format can hold it between its double quotes on one line: a quote and the
// control characters (an element's id may hold any of them) written as \xNN.
std::string quotable(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const auto b = static_cast<unsigned char>(c);
    if (c == '"' || b < 0x20 || b == 0x7f) {
      char escape[5];
      std::snprintf(escape, sizeof escape, "\\x%02x", b);
      out += escape;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string msh_string(const HighOrderMesh& m, const MshOptions& options) {
  if (options.version != 41 && options.version != 22)
    throw std::logic_error("msh: unsupported version " + std::to_string(options.version));
  if (auto error = m.structure_error()) throw std::logic_error("msh: " + *error);

  // Curve entities are tagged by their physical group (an unnamed group gets the next free
  // tag); surface entities are numbered from 1. All nodes sit on surface 1, so its box holds
  // them all; with no triangles it is there to hold them, in no group.
  std::vector<Group> curves = group_by_physical(1, m.line_physical);
  std::vector<Group> surfaces = group_by_physical(2, m.triangle_physical);
  const int free_curve_tag = curves.empty() ? 1 : std::max(curves.back().physical, 0) + 1;
  for (Group& g : curves) {
    g.entity = g.physical > 0 ? g.physical : free_curve_tag;
    for (int e : g.elements) add_nodes(g.box, m, m.line(e));
  }
  if (surfaces.empty()) surfaces.push_back(Group{2, 0, 0, {}, {}});
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    Group& g = surfaces[s];
    g.entity = static_cast<int>(s) + 1;
    if (s == 0) {
      for (const geometry::Vec2& p : m.nodes) g.box.add(p);
    } else {
      for (int e : g.elements) add_nodes(g.box, m, m.triangle(e));
    }
  }
  for (Group& g : curves)
    if (g.box.empty()) g.box.add(geometry::Vec2::Zero());
  for (Group& g : surfaces)
    if (g.box.empty()) g.box.add(geometry::Vec2::Zero());

  std::vector<const Group*> element_groups;  // in file order: lines, then triangles
  for (const Group& g : curves) element_groups.push_back(&g);
  for (const Group& g : surfaces)
    if (!g.elements.empty()) element_groups.push_back(&g);
  std::size_t elements = 0;
  for (const Group* g : element_groups) elements += g->elements.size();
  const auto type_of = [&m](const Group& g) { return (g.dim == 1 ? kLineType : kTriangleType)[m.order - 1]; };
  const auto nodes_of = [&m](const Group& g, int e) { return g.dim == 1 ? m.line(e) : m.triangle(e); };

  Text t;
  t << (options.version == 22 ? "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                              : "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  std::vector<std::string> names;
  for (const Group* g : element_groups) {
    const auto name = m.physical_names.find({g->dim, g->physical});
    if (g->physical > 0 && name != m.physical_names.end())
      names.push_back(std::to_string(g->dim) + " " + std::to_string(g->physical) + " \"" + quotable(name->second) +
                      "\"\n");
  }
  if (!names.empty()) {
    t << "$PhysicalNames\n" << names.size() << "\n";
    for (const std::string& line : names) t << line;
    t << "$EndPhysicalNames\n";
  }
  const std::size_t n = m.nodes.size();

  if (options.version == 22) {
    t << "$Nodes\n" << n << "\n";
    for (std::size_t v = 0; v < n; ++v)
      t << v + 1 << " " << m.nodes[v].x() << " " << m.nodes[v].y() << " 0\n";
    t << "$EndNodes\n$Elements\n" << elements << "\n";
    long id = 1;
    for (const Group* g : element_groups)
      for (int e : g->elements) {
        t << id++ << " " << type_of(*g) << " 2 " << g->physical << " " << g->entity;
        for (int v : nodes_of(*g, e)) t << " " << v + 1;
        t << "\n";
      }
    t << "$EndElements\n";
    return t.take();
  }

  t << "$Entities\n0 " << curves.size() << " " << surfaces.size() << " 0\n";
  for (const std::vector<Group>* list : {&curves, &surfaces})
    for (const Group& g : *list) {
      t << g.entity << " " << g.box;
      if (g.physical > 0)
        t << " 1 " << g.physical << " 0\n";
      else
        t << " 0 0\n";
    }
  t << "$EndEntities\n";
  t << "$Nodes\n1 " << n << " 1 " << n << "\n2 1 0 " << n << "\n";
  for (std::size_t v = 0; v < n; ++v) t << v + 1 << "\n";
  for (std::size_t v = 0; v < n; ++v) t << m.nodes[v].x() << " " << m.nodes[v].y() << " 0\n";
  t << "$EndNodes\n";
  t << "$Elements\n" << element_groups.size() << " " << elements << " 1 " << elements << "\n";
  long id = 1;
  for (const Group* g : element_groups) {
    t << g->dim << " " << g->entity << " " << type_of(*g) << " " << g->elements.size() << "\n";
    for (int e : g->elements) {
      t << id++;
      for (int v : nodes_of(*g, e)) t << " " << v + 1;
      t << "\n";
    }
  }
  t << "$EndElements\n";
  return t.take();
}

void write_msh(const HighOrderMesh& mesh, const std::string& path, const MshOptions& options) {
  write_file_atomically(path, msh_string(mesh, options));
}

std::string msh_string(const mesh::TriMesh& m, const MshOptions& options) {
  if (options.version != 41 && options.version != 22)
    throw std::logic_error("msh: unsupported version " + std::to_string(options.version));
  return msh_string(linear_mesh(m), options);
}

void write_msh(const mesh::TriMesh& mesh, const std::string& path, const MshOptions& options) {
  write_file_atomically(path, msh_string(mesh, options));
}

}  // namespace curvemesh::io
