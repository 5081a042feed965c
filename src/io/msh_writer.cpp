#include "io/msh_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/parallel.hpp"
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
    char buf[24];
    out_.append(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
    return *this;
  }
  Text& operator<<(int v) { return *this << long(v); }
  Text& operator<<(std::size_t v) { return *this << long(v); }
  // 17 significant digits, as printf's %.17g writes them (to_chars with a precision is defined
  // as printf in the C locale), without printf's cost of parsing a format.
  Text& operator<<(double v) {
    char buf[32];
    out_.append(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 17).ptr);
    return *this;
  }
  Text& operator<<(const geometry::Box2& b) {
    return *this << b.min.x() << " " << b.min.y() << " 0 " << b.max.x() << " " << b.max.y() << " 0";
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

// Appends line(i, text) for i = 0 … n−1: the lines formatted side by side in blocks, each into a
// text of its own, and the blocks appended in order (the same bytes as one loop; printing the
// coordinates' 17 digits is most of the writing). A few blocks at a time, so that what waits to
// be appended stays small beside the file.
template <class Line>
void append_lines(Text& t, std::size_t n, const Line& line) {
  constexpr std::size_t kBlock = 1024, kBlocksAtOnce = 16;
  std::vector<std::string> blocks(kBlocksAtOnce);
  for (std::size_t first = 0; first < n; first += kBlock * kBlocksAtOnce) {
    const std::size_t count = std::min(kBlocksAtOnce, (n - first + kBlock - 1) / kBlock);
    base::for_each_part(
        count,
        [&](std::size_t b) {
          Text local;
          const std::size_t begin = first + b * kBlock, end = std::min(n, begin + kBlock);
          for (std::size_t i = begin; i < end; ++i) line(i, local);
          blocks[b] = local.take();
        },
        1);
    for (std::size_t b = 0; b < count; ++b) {
      t << blocks[b];
      std::string().swap(blocks[b]);
    }
  }
}

// The elements of one geometric entity of the file: the elements of one dimension that are in the
// same physical groups.
struct Group {
  int dim;
  std::vector<int> physicals;  // ascending; empty: in no physical group
  int entity;                  // the entity's tag
  std::vector<int> elements;
  geometry::Box2 box;
};

// The triangles by physical tag, ascending, keeping their order within each group.
std::vector<Group> group_triangles(const std::vector<int>& physical) {
  std::map<int, std::vector<int>> by_tag;
  for (int e = 0; e < static_cast<int>(physical.size()); ++e) by_tag[physical[e]].push_back(e);
  std::vector<Group> groups;
  for (auto& [tag, elements] : by_tag)
    groups.push_back(Group{2, tag > 0 ? std::vector<int>{tag} : std::vector<int>{}, 0, std::move(elements), {}});
  return groups;
}

// The physical groups line l is written in; nothing when it is not written. With `boundary_only`
// only the lines on the border are written, each in one group (a reader that takes one group per
// line, as deal.II does, refuses more): its lowest further group above `border` (the drawn element
// it lies on, the first when several), else its line_physical (a side of the box).
std::optional<std::vector<int>> line_tags(const HighOrderMesh& m, int l, bool boundary_only) {
  std::vector<int> tags = m.groups_of_line(l);
  if (!boundary_only) return tags;
  if (std::find(tags.begin(), tags.end(), kPhysicalBorder) == tags.end()) return std::nullopt;
  const auto element = std::upper_bound(tags.begin(), tags.end(), kPhysicalBorder);
  if (element != tags.end()) return std::vector<int>{*element};
  if (m.line_physical[l] > 0) return std::vector<int>{m.line_physical[l]};
  return std::vector<int>{};
}

// The lines by the set of their physical groups, sets in ascending (lexicographic) order, keeping
// the lines' order within each: one entity per set, so that 4.1 lists a line once however many
// groups it is in.
std::vector<Group> group_lines(const HighOrderMesh& m, bool boundary_only) {
  std::map<std::vector<int>, std::vector<int>> by_tags;
  for (int l = 0; l < m.line_count(); ++l)
    if (auto tags = line_tags(m, l, boundary_only)) by_tags[std::move(*tags)].push_back(l);
  std::vector<Group> groups;
  for (auto& [tags, elements] : by_tags) groups.push_back(Group{1, tags, 0, std::move(elements), {}});
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

// The file's entities: curves numbered 1.. in the order of their sets of groups, surfaces 1.. in
// the order of their tags. All nodes sit on surface 1, so its box holds them all; with no
// triangles it is there to hold them, in no group.
struct Entities {
  std::vector<Group> curves, surfaces;
  std::vector<const Group*> with_elements;  // in file order: lines, then triangles
  std::size_t elements = 0;                 // elements written (2.2: a line once per group)
};

Entities entities(const HighOrderMesh& m, const MshOptions& options) {
  Entities out;
  out.curves = group_lines(m, options.boundary_only);
  out.surfaces = group_triangles(m.triangle_physical);
  for (std::size_t c = 0; c < out.curves.size(); ++c) {
    Group& g = out.curves[c];
    g.entity = static_cast<int>(c) + 1;
    for (int e : g.elements) add_nodes(g.box, m, m.line(e));
  }
  if (out.surfaces.empty()) out.surfaces.push_back(Group{2, {}, 0, {}, {}});
  for (std::size_t s = 0; s < out.surfaces.size(); ++s) {
    Group& g = out.surfaces[s];
    g.entity = static_cast<int>(s) + 1;
    if (s == 0) {
      for (const geometry::Vec2& p : m.nodes) g.box.add(p);
    } else {
      for (int e : g.elements) add_nodes(g.box, m, m.triangle(e));
    }
  }
  for (std::vector<Group>* list : {&out.curves, &out.surfaces})
    for (Group& g : *list) {
      if (g.box.empty()) g.box.add(geometry::Vec2::Zero());
      if (g.elements.empty()) continue;
      out.with_elements.push_back(&g);
      const std::size_t copies = options.version == 22 ? std::max<std::size_t>(g.physicals.size(), 1) : 1;
      out.elements += g.elements.size() * copies;
    }
  return out;
}

// $PhysicalNames: every named group some written element is in, by dimension and tag.
void write_names(Text& t, const HighOrderMesh& m, const Entities& entities) {
  std::set<std::pair<int, int>> used;
  for (const Group* g : entities.with_elements)
    for (int tag : g->physicals) used.insert({g->dim, tag});
  std::vector<std::string> names;
  for (const auto& key : used)
    if (const auto name = m.physical_names.find(key); name != m.physical_names.end())
      names.push_back(std::to_string(key.first) + " " + std::to_string(key.second) + " \"" + quotable(name->second) +
                      "\"\n");
  if (names.empty()) return;
  t << "$PhysicalNames\n" << names.size() << "\n";
  for (const std::string& line : names) t << line;
  t << "$EndPhysicalNames\n";
}

int type_of(const HighOrderMesh& m, const Group& g) {
  return (g.dim == 1 ? kLineType : kTriangleType)[m.order - 1];
}

std::span<const int> nodes_of(const HighOrderMesh& m, const Group& g, int e) {
  return g.dim == 1 ? m.line(e) : m.triangle(e);
}

// 2.2 has one physical tag per element: an element in several groups is written once per group,
// each copy with its own element number and its own elementary entity (numbered on in file order),
// so that a reader that takes groups from elements (GetFEM, meshio) and one that takes them from
// elementary entities (Gmsh) both find it once in each group.
void write_body22(Text& t, const HighOrderMesh& m, const Entities& entities) {
  const std::size_t n = m.nodes.size();
  t << "$Nodes\n" << n << "\n";
  append_lines(t, n, [&](std::size_t v, Text& line) {
    line << v + 1 << " " << m.nodes[v].x() << " " << m.nodes[v].y() << " 0\n";
  });
  t << "$EndNodes\n$Elements\n" << entities.elements << "\n";
  long id = 1;
  int curve = 0;
  for (const Group* g : entities.with_elements) {
    const std::vector<int> physicals = g->physicals.empty() ? std::vector<int>{0} : g->physicals;
    for (int physical : physicals) {
      const int entity = g->dim == 1 ? ++curve : g->entity;
      append_lines(t, g->elements.size(), [&, first = id](std::size_t i, Text& line) {
        line << first + long(i) << " " << type_of(m, *g) << " 2 " << physical << " " << entity;
        for (int v : nodes_of(m, *g, g->elements[i])) line << " " << v + 1;
        line << "\n";
      });
      id += long(g->elements.size());
    }
  }
  t << "$EndElements\n";
}

void write_body41(Text& t, const HighOrderMesh& m, const Entities& entities) {
  t << "$Entities\n0 " << entities.curves.size() << " " << entities.surfaces.size() << " 0\n";
  for (const std::vector<Group>* list : {&entities.curves, &entities.surfaces})
    for (const Group& g : *list) {
      t << g.entity << " " << g.box << " " << g.physicals.size();
      for (int tag : g.physicals) t << " " << tag;
      t << " 0\n";
    }
  t << "$EndEntities\n";
  // Node tags are 1..n without a gap, node i being tag i + 1: readers that index nodes by tag
  // (dolfinx's gmshio) need it.
  const std::size_t n = m.nodes.size();
  t << "$Nodes\n1 " << n << " 1 " << n << "\n2 1 0 " << n << "\n";
  append_lines(t, n, [](std::size_t v, Text& line) { line << v + 1 << "\n"; });
  append_lines(t, n, [&](std::size_t v, Text& line) { line << m.nodes[v].x() << " " << m.nodes[v].y() << " 0\n"; });
  t << "$EndNodes\n";
  const std::size_t elements = entities.elements;
  t << "$Elements\n" << entities.with_elements.size() << " " << elements << " 1 " << elements << "\n";
  long id = 1;
  for (const Group* g : entities.with_elements) {
    t << g->dim << " " << g->entity << " " << type_of(m, *g) << " " << g->elements.size() << "\n";
    append_lines(t, g->elements.size(), [&, first = id](std::size_t i, Text& line) {
      line << first + long(i);
      for (int v : nodes_of(m, *g, g->elements[i])) line << " " << v + 1;
      line << "\n";
    });
    id += long(g->elements.size());
  }
  t << "$EndElements\n";
}

}  // namespace

std::string msh_string(const HighOrderMesh& m, const MshOptions& options) {
  if (options.version != 41 && options.version != 22)
    throw std::logic_error("msh: unsupported version " + std::to_string(options.version));
  if (auto error = m.structure_error()) throw std::logic_error("msh: " + *error);
  const Entities e = entities(m, options);
  Text t;
  t << (options.version == 22 ? "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                              : "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  write_names(t, m, e);
  if (options.version == 22)
    write_body22(t, m, e);
  else
    write_body41(t, m, e);
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
