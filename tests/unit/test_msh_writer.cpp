// The .msh writer: parsed back here (counts, exact coordinates, connectivity, groups), and, when
// the system Python has them, loaded by Gmsh and meshio.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/mesh_svg.hpp"
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
