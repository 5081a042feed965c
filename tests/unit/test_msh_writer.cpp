// The .msh writer: parsed back here (counts, exact coordinates, connectivity, groups), and, when
// the system Python has them, loaded by Gmsh and meshio.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <tuple>
#include <sstream>

#include "io/mesh_svg.hpp"
#include "io/msh_reader.hpp"
#include "io/msh_writer.hpp"
#include "scratch_dir.hpp"

namespace curvemesh::io {
namespace {

using geometry::Vec2;
using mesh::EdgeFeature;
using mesh::EdgeKind;

// A unit square cut by its diagonal into two triangles, plus a dead triangle; box sides tagged,
// the diagonal primary. Coordinates that need all 17 digits.
mesh::TriMesh square() {
  mesh::TriMesh m;
  m.add_vertex(Vec2(0, 0));
  m.add_vertex(Vec2(1.0 / 3, 0));
  m.add_vertex(Vec2(1.0 / 3, 0.1));
  m.add_vertex(Vec2(0, 0.1));
  m.add_vertex(Vec2(0.2, 0.05));
  const int dead = m.add_triangle(0, 1, 4);
  m.remove_triangle(dead);
  m.add_triangle(0, 1, 2);
  m.add_triangle(0, 2, 3);
  for (int s = 0; s < 4; ++s) m.set_feature(s, (s + 1) % 4, EdgeFeature{EdgeKind::boundary, -1, s, 0, 0});
  m.set_feature(0, 2, EdgeFeature{EdgeKind::primary, 0, 0, 0.0, 1.0});
  return m;
}

std::string section(const std::string& text, const std::string& name) {
  const auto a = text.find("$" + name + "\n"), b = text.find("$End" + name + "\n");
  EXPECT_NE(a, std::string::npos) << name;
  EXPECT_NE(b, std::string::npos) << name;
  return text.substr(a + name.size() + 2, b - a - name.size() - 2);
}

TEST(MshWriter, Version41RoundTrips) {
  const std::string text = msh_string(square());
  EXPECT_EQ(section(text, "MeshFormat"), "4.1 0 8\n");
  EXPECT_EQ(section(text, "PhysicalNames"), "3\n1 1 \"primary\"\n1 3 \"boundary\"\n2 4 \"domain\"\n");
  std::istringstream nodes(section(text, "Nodes"));
  long blocks, n, lo, hi, dim, tag, param, count;
  nodes >> blocks >> n >> lo >> hi >> dim >> tag >> param >> count;
  EXPECT_EQ(blocks, 1);
  EXPECT_EQ(n, 5);
  EXPECT_EQ(count, 5);
  for (int i = 1; i <= 5; ++i) {
    long id;
    nodes >> id;
    EXPECT_EQ(id, i);
  }
  const mesh::TriMesh m = square();
  for (int v = 0; v < 5; ++v) {
    std::string x, y, z;
    nodes >> x >> y >> z;
    EXPECT_EQ(std::strtod(x.c_str(), nullptr), m.point(v).x());
    EXPECT_EQ(std::strtod(y.c_str(), nullptr), m.point(v).y());
    EXPECT_EQ(z, "0");
  }
  std::istringstream el(section(text, "Elements"));
  long eblocks, total, emin, emax;
  el >> eblocks >> total >> emin >> emax;
  EXPECT_EQ(eblocks, 3);  // primary lines, boundary lines, triangles
  EXPECT_EQ(total, 1 + 4 + 2);
  EXPECT_EQ(emin, 1);
  EXPECT_EQ(emax, 7);
  EXPECT_THAT(text, testing::HasSubstr("2 1 2 2\n6 1 2 3\n7 1 3 4\n"));  // alive triangles only, 1-based
  EXPECT_THAT(text, testing::HasSubstr("1 1 1 1\n1 1 3\n"));             // the primary diagonal
}

TEST(MshWriter, Version22) {
  const std::string text = msh_string(square(), {22});
  EXPECT_EQ(section(text, "MeshFormat"), "2.2 0 8\n");
  EXPECT_THAT(section(text, "Nodes"), testing::StartsWith("5\n1 0 0 0\n2 0.33333333333333331 0 0\n"));
  EXPECT_THAT(section(text, "Elements"), testing::StartsWith("7\n1 1 2 1 1 1 3\n"));
  EXPECT_THAT(text, testing::HasSubstr("7 2 2 4 1 1 3 4\n"));
}

TEST(MshWriter, RefusesExactVerticesAndUnknownVersions) {
  mesh::TriMesh m = square();
  EXPECT_THROW(msh_string(m, {30}), std::logic_error);
  m.set_exact_position(4, geometry::ExactPoint(mpq_class(1, 5), mpq_class(1, 3)));
  EXPECT_THROW(msh_string(m), std::logic_error);
}

TEST(MshWriter, Deterministic) { EXPECT_EQ(msh_string(square()), msh_string(square())); }

TEST(MshWriter, GmshAndMeshioReadBothVersions) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no system python";
  if (std::system("/usr/bin/python3 -c 'import gmsh, meshio' 2>/dev/null") != 0) GTEST_SKIP() << "gmsh or meshio missing";
  const testing_support::ScratchDir dir;
  for (int version : {41, 22}) {
    const auto path = dir / ("writer_" + std::to_string(version) + ".msh");
    write_msh(square(), path, {version});
    const std::string script =
        "import sys, gmsh, meshio\n"
        "m = meshio.read(sys.argv[1])\n"
        "assert sum(len(c.data) for c in m.cells if c.type == 'triangle') == 2, m\n"
        "gmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0); gmsh.open(sys.argv[1])\n"
        "types, tags, nodes = gmsh.model.mesh.getElements(2)\n"
        "assert list(types) == [2] and len(tags[0]) == 2, (types, tags)\n"
        "assert len(gmsh.model.getPhysicalGroups(1)) == 2\n"
        "gmsh.finalize()\n";
    const auto script_path = path + ".py";
    std::ofstream(script_path) << script;
    EXPECT_EQ(std::system(("/usr/bin/python3 " + script_path + " " + path).c_str()), 0) << "version " << version;
  }
}

// The square with the diagonal in two further groups (6 "a", 7 "b"), the box sides on the border,
// the bottom side also in group 8 "c".
HighOrderMesh grouped() {
  HighOrderMesh m = linear_mesh(square());
  m.line_groups.assign(m.line_count(), {});
  for (int l = 0; l < m.line_count(); ++l) {
    if (m.line_physical[l] == kPhysicalPrimary) m.line_groups[l] = {6, 7};
    if (m.line_physical[l] != kPhysicalBoundary) continue;
    m.line_groups[l] = {kPhysicalBorder};
    const auto ends = m.line(l);
    if (m.nodes[ends[0]].y() == 0 && m.nodes[ends[1]].y() == 0) m.line_groups[l].push_back(8);
  }
  m.physical_names[{1, 6}] = "a";
  m.physical_names[{1, 7}] = "b";
  m.physical_names[{1, 8}] = "c";
  return m;
}

TEST(MshWriter, ALineInSeveralGroupsIsOneElementIn41AndOnePerGroupIn22) {
  const HighOrderMesh m = grouped();
  const std::string v41 = msh_string(m);
  EXPECT_EQ(section(v41, "PhysicalNames"),
            "7\n1 1 \"primary\"\n1 3 \"boundary\"\n1 5 \"border\"\n1 6 \"a\"\n1 7 \"b\"\n1 8 \"c\"\n2 4 \"domain\"\n");
  // One entity per set of groups: {1 6 7}, {3 5}, {3 5 8}; each line once.
  const std::string entities = section(v41, "Entities");
  EXPECT_THAT(entities, testing::StartsWith("0 3 1 0\n"));
  EXPECT_THAT(entities, testing::HasSubstr(" 3 1 6 7 0\n"));
  EXPECT_THAT(entities, testing::HasSubstr(" 2 3 5 0\n"));
  EXPECT_THAT(entities, testing::HasSubstr(" 3 3 5 8 0\n"));
  EXPECT_THAT(section(v41, "Elements"), testing::StartsWith("4 7 1 7\n"));
  // 2.2: the diagonal three times, the bottom side three times, the other sides twice.
  EXPECT_THAT(section(msh_string(m, {22}), "Elements"), testing::StartsWith(std::to_string(3 + 3 + 3 * 2 + 2) + "\n"));
  // Read back: the same lines in the same groups (in the file's order: by entity).
  const HighOrderMesh back = parse_msh(v41);
  const auto lines = [](const HighOrderMesh& h) {
    std::multiset<std::tuple<int, int, std::vector<int>>> out;
    for (int l = 0; l < h.line_count(); ++l) out.insert({h.line(l)[0], h.line(l)[1], h.groups_of_line(l)});
    return out;
  };
  EXPECT_EQ(lines(back), lines(m));
  EXPECT_EQ(msh_string(back), v41);
}

TEST(MshWriter, BoundaryOnlyWritesTheBorderInOneGroupEach) {
  MshOptions o;
  o.boundary_only = true;
  for (int version : {41, 22}) {
    o.version = version;
    const std::string text = msh_string(grouped(), o);
    // The bottom side in "c", the three others in "boundary"; no diagonal, no "border".
    EXPECT_EQ(section(text, "PhysicalNames"), "3\n1 3 \"boundary\"\n1 8 \"c\"\n2 4 \"domain\"\n");
    EXPECT_THAT(section(text, "Elements"), testing::StartsWith(version == 41 ? "3 6 1 6\n" : "6\n"));
    if (version == 41) {
      EXPECT_THAT(section(text, "Entities"), testing::StartsWith("0 2 1 0\n"));
      EXPECT_THAT(section(text, "Entities"), testing::Not(testing::HasSubstr(" 2 3 ")));
    }
  }
}

TEST(MshWriter, GmshAndMeshioSeeEveryGroupOfALine) {
  if (std::system("/usr/bin/python3 -c 'import gmsh, meshio' 2>/dev/null") != 0) GTEST_SKIP() << "gmsh or meshio missing";
  const testing_support::ScratchDir dir;
  for (int version : {41, 22}) {
    const auto path = dir / ("groups_" + std::to_string(version) + ".msh");
    write_msh(grouped(), path, {version});
    // Per group: how many line elements Gmsh puts in it, and (4.1) meshio's cell sets.
    const std::string script =
        "import sys, gmsh, meshio\n"
        "gmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0); gmsh.open(sys.argv[1])\n"
        "count = {}\n"
        "for d, t in gmsh.model.getPhysicalGroups(1):\n"
        "    name = gmsh.model.getPhysicalName(d, t)\n"
        "    count[name] = sum(len(gmsh.model.mesh.getElements(1, e)[1][0])\n"
        "                      for e in gmsh.model.getEntitiesForPhysicalGroup(d, t))\n"
        "gmsh.finalize()\n"
        "assert count == {'primary': 1, 'boundary': 4, 'border': 4, 'a': 1, 'b': 1, 'c': 1}, count\n"
        "if sys.argv[2] == '41':\n"
        "    m = meshio.read(sys.argv[1])\n"
        "    sets = {k: sum(len(x) for x in v if x is not None) for k, v in m.cell_sets.items() if k in count}\n"
        "    assert sets == count, sets\n";
    const auto script_path = path + ".py";
    std::ofstream(script_path) << script;
    EXPECT_EQ(std::system(("/usr/bin/python3 " + script_path + " " + path + " " + std::to_string(version)).c_str()), 0)
        << "version " << version;
  }
}

// The node and element lines are formatted side by side in blocks of lines: on a mesh of many
// blocks, every line is where one loop would put it, and every coordinate is printf's %.17g,
// whatever the double (subnormal, huge, negative zero, integral).
TEST(MshWriter, LinesInBlocksAreTheLinesOfOneLoopWithPrintfsDigits) {
  const std::vector<double> special{1.0 / 3, 0.1, -0.0, 5e-324, 2.2250738585072014e-308, 1e300,
                                    -1.7976931348623157e308, 123456789.123456789, 1e17, 0.5, 42};
  HighOrderMesh m;
  m.order = 1;
  std::uint64_t state = 12345;
  const auto next = [&state] {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return static_cast<double>(state >> 11) * 0x1p-53 * 2 - 1;
  };
  for (int v = 0; v < 40000; ++v)
    m.nodes.push_back(v < 2 * int(special.size()) ? Vec2(special[v / 2], special[special.size() - 1 - v / 2])
                                                  : Vec2(next() * 1e3, next() * 1e-3));
  for (int t = 0; t + 2 < int(m.nodes.size()); t += 2) {
    m.triangles.insert(m.triangles.end(), {t, t + 1, t + 2});
    m.triangle_physical.push_back(4);
  }
  const auto g = [](double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  std::string coordinates, numbered, tags, elements41, elements22;
  for (std::size_t v = 0; v < m.nodes.size(); ++v) {
    const std::string xy = g(m.nodes[v].x()) + " " + g(m.nodes[v].y()) + " 0\n";
    coordinates += xy;
    numbered += std::to_string(v + 1) + " " + xy;
    tags += std::to_string(v + 1) + "\n";
  }
  for (int t = 0; t < m.triangle_count(); ++t) {
    const auto n = m.triangle(t);
    const std::string corners = " " + std::to_string(n[0] + 1) + " " + std::to_string(n[1] + 1) + " " +
                                std::to_string(n[2] + 1) + "\n";
    elements41 += std::to_string(t + 1) + corners;
    elements22 += std::to_string(t + 1) + " 2 2 4 1" + corners;
  }
  const std::size_t n = m.nodes.size(), e = static_cast<std::size_t>(m.triangle_count());
  const std::string text41 = msh_string(m), text22 = msh_string(m, {22});
  EXPECT_EQ(section(text41, "Nodes"), "1 " + std::to_string(n) + " 1 " + std::to_string(n) + "\n2 1 0 " +
                                          std::to_string(n) + "\n" + tags + coordinates);
  EXPECT_EQ(section(text41, "Elements"), "1 " + std::to_string(e) + " 1 " + std::to_string(e) + "\n2 1 2 " +
                                             std::to_string(e) + "\n" + elements41);
  EXPECT_EQ(section(text22, "Nodes"), std::to_string(n) + "\n" + numbered);
  EXPECT_EQ(section(text22, "Elements"), std::to_string(e) + "\n" + elements22);
  // The special values are there, as printf writes them.
  EXPECT_THAT(coordinates, testing::HasSubstr("\n4.9406564584124654e-324 "));
  EXPECT_THAT(coordinates, testing::HasSubstr("\n-0 "));
  EXPECT_THAT(coordinates, testing::HasSubstr("\n1e+17 "));
}

TEST(MeshSvg, DrawsEveryEdgeOnce) {
  const std::string svg = mesh_svg(square());
  EXPECT_THAT(svg, testing::StartsWith("<?xml"));
  std::size_t red = 0, black = 0, grey = 0;
  for (std::size_t at = 0; (at = svg.find("stroke=\"#", at)) != std::string::npos; ++at) {
    red += svg.compare(at, 16, "stroke=\"#d00000\"") == 0;
    black += svg.compare(at, 16, "stroke=\"#000000\"") == 0;
    grey += svg.compare(at, 16, "stroke=\"#b0b0b0\"") == 0;
  }
  EXPECT_EQ(red, 1u);
  EXPECT_EQ(black, 4u);
  EXPECT_EQ(grey, 0u);  // every edge of this mesh is tagged
}

}  // namespace
}  // namespace curvemesh::io
