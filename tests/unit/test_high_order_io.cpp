// The P1/P2/P3 mesh files: .msh written and read back bit for bit, files written by Gmsh itself
// read as Gmsh reads them, malformed files refused with a message (never a crash), and the .vtu
// read by meshio with VTK's node order checked against VTK's reference coordinates.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <bit>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "io/msh_reader.hpp"
#include "io/msh_writer.hpp"
#include "io/vtu_writer.hpp"
#include "scratch_dir.hpp"

namespace curvemesh::io {
namespace {

using geometry::Vec2;
using testing_support::ScratchDir;

// The nodes of a triangle with integer lattice corners (multiples of p), in Gmsh's order.
std::vector<std::array<int, 2>> lattice_triangle(int p, std::array<std::array<int, 2>, 3> c) {
  std::vector<std::array<int, 2>> out(c.begin(), c.end());
  for (int e = 0; e < 3; ++e) {
    const auto a = c[e], b = c[(e + 1) % 3];
    for (int k = 1; k < p; ++k)
      out.push_back({(a[0] * (p - k) + b[0] * k) / p, (a[1] * (p - k) + b[1] * k) / p});
  }
  if (p == 3) out.push_back({(c[0][0] + c[1][0] + c[2][0]) / 3, (c[0][1] + c[1][1] + c[2][1]) / 3});
  return out;
}

// A 2×1 grid of squares, each cut by its diagonal: four triangles of order p sharing edge
// nodes. The bottom side is a boundary line, the first diagonal a primary line. With `bend`,
// the inner nodes of the bottom side move off the straight line (a curved edge); coordinates
// need all 17 digits.
HighOrderMesh grid(int p, bool bend = true) {
  HighOrderMesh m;
  m.order = p;
  std::map<std::array<int, 2>, int> index;
  const auto node = [&](std::array<int, 2> q) {
    const auto [it, added] = index.emplace(q, static_cast<int>(m.nodes.size()));
    if (added) {
      Vec2 x(q[0] / (3.0 * p), q[1] * 0.1 / p);
      if (bend && q[1] == 0 && q[0] % p != 0) x.y() -= 0.01 / 7;
      m.nodes.push_back(x);
    }
    return it->second;
  };
  const auto add = [&](std::array<std::array<int, 2>, 3> c, bool triangle, int physical) {
    std::vector<int> ids;
    if (triangle) {
      for (const auto& q : lattice_triangle(p, c)) ids.push_back(node(q));
      m.add_triangle(ids, physical);
    } else {
      ids = {node(c[0]), node(c[1])};
      for (int k = 1; k < p; ++k)
        ids.push_back(node({(c[0][0] * (p - k) + c[1][0] * k) / p, (c[0][1] * (p - k) + c[1][1] * k) / p}));
      m.add_line(ids, physical);
    }
  };
  // Lines in ascending physical tag, the order the writer groups them in.
  add({{{0, 0}, {p, p}, {}}}, false, kPhysicalPrimary);
  for (int s = 0; s < 2; ++s) {
    const int x0 = s * p, x1 = (s + 1) * p;
    add({{{x0, 0}, {x1, 0}, {x1, p}}}, true, kPhysicalDomain);
    add({{{x0, 0}, {x1, p}, {x0, p}}}, true, kPhysicalDomain);
    add({{{x0, 0}, {x1, 0}, {}}}, false, kPhysicalBoundary);
  }
  return m;
}

std::string section(const std::string& text, const std::string& name) {
  const auto a = text.find("$" + name + "\n"), b = text.find("$End" + name + "\n");
  if (a == std::string::npos || b == std::string::npos) return {};
  return text.substr(a + name.size() + 2, b - a - name.size() - 2);
}

void expect_same(const HighOrderMesh& a, const HighOrderMesh& b) {
  EXPECT_EQ(a.order, b.order);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t v = 0; v < a.nodes.size(); ++v) {
    EXPECT_EQ(a.nodes[v].x(), b.nodes[v].x()) << v;  // bit-identical, not close
    EXPECT_EQ(a.nodes[v].y(), b.nodes[v].y()) << v;
  }
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_physical, b.triangle_physical);
  EXPECT_EQ(a.lines, b.lines);
  EXPECT_EQ(a.line_physical, b.line_physical);
}

TEST(HighOrderMesh, Structure) {
  for (int p = 1; p <= 3; ++p) {
    const HighOrderMesh m = grid(p);
    EXPECT_EQ(m.structure_error(), std::nullopt);
    EXPECT_EQ(m.triangle_count(), 4);
    EXPECT_EQ(m.line_count(), 3);
    EXPECT_EQ(m.nodes.size(), std::size_t((2 * p + 1) * (p + 1)));  // each lattice point once
  }
  HighOrderMesh m = grid(2);
  m.triangles[7] = static_cast<int>(m.nodes.size());
  EXPECT_THAT(m.structure_error().value_or(""), testing::HasSubstr("triangle 1 refers to node"));
  m = grid(2);
  m.triangles.pop_back();
  EXPECT_THAT(m.structure_error().value_or(""), testing::HasSubstr("not a multiple of 6"));
  m = grid(2);
  m.line_physical.pop_back();
  EXPECT_THAT(m.structure_error().value_or(""), testing::HasSubstr("physical tags"));
  m = grid(2);
  m.order = 4;
  EXPECT_THAT(m.structure_error().value_or(""), testing::HasSubstr("order 4"));
  m = grid(3);
  m.nodes[5].x() = std::nan("");
  EXPECT_THAT(m.structure_error().value_or(""), testing::HasSubstr("non-finite"));
  EXPECT_THROW(msh_string(m), std::logic_error);
  EXPECT_THROW(grid(2).add_triangle(std::vector<int>{0, 1, 2}), std::logic_error);
}

TEST(HighOrderMsh, RoundTripsBitForBit) {
  for (int p = 1; p <= 3; ++p)
    for (int version : {41, 22}) {
      SCOPED_TRACE("order " + std::to_string(p) + ", version " + std::to_string(version));
      const HighOrderMesh m = grid(p);
      const std::string text = msh_string(m, {version});
      const HighOrderMesh back = parse_msh(text);
      expect_same(m, back);
      const std::map<std::pair<int, int>, std::string> used = {
          {{1, 1}, "primary"}, {{1, 3}, "boundary"}, {{2, 4}, "domain"}};
      EXPECT_EQ(back.physical_names, used);
      EXPECT_EQ(msh_string(back, {version}), text);  // and writing it again gives the same bytes
    }
}

TEST(HighOrderMsh, WritesEveryNodeOnce) {
  for (int version : {41, 22}) {
    const HighOrderMesh m = grid(3);
    std::istringstream nodes(section(msh_string(m, {version}), "Nodes"));
    long announced, blocks = 1, lo, hi;
    if (version == 41)
      nodes >> blocks >> announced >> lo >> hi;
    else
      nodes >> announced;
    EXPECT_EQ(blocks, 1);
    EXPECT_EQ(announced, 7 * 4);  // 28 lattice points for 4 triangles of 10 nodes and 3 lines
    std::string line;
    long entries = 0;
    std::getline(nodes, line);
    if (version == 41) std::getline(nodes, line);  // the block's header
    while (std::getline(nodes, line)) entries += version == 22 || line.find(' ') != std::string::npos;
    EXPECT_EQ(entries, announced);
  }
  const std::string text = msh_string(grid(3));
  EXPECT_THAT(text, testing::HasSubstr("$Elements\n3 7 1 7\n1 1 26 1\n"));  // primary cubic line
  EXPECT_THAT(text, testing::HasSubstr("2 1 21 4\n"));                      // the cubic triangles
}

TEST(HighOrderMsh, ReadsOtherWritersFiles) {
  // Tags that are neither contiguous nor sorted, a section we do not know, a point element,
  // CRLF line ends, and triangles in no physical group.
  const std::string v22 =
      "$MeshFormat\r\n2.2 0 8\r\n$EndMeshFormat\r\n$Comments\r\nanything $ at all\r\n$EndComments\r\n"
      "$PhysicalNames\n1\n1 7 \"outer rim\"\n$EndPhysicalNames\n"
      "$Nodes\n4\n30 1 0 0\n10 0 0 0\n200 0 1 0\n7 1 1 0\n$EndNodes\n"
      "$Elements\n4\n5 15 2 0 1 30\n9 1 2 7 3 10 30\n1 2 0 10 30 7\n2 2 2 0 1 10 7 200\n$EndElements\n";
  const HighOrderMesh m = parse_msh(v22);
  EXPECT_EQ(m.order, 1);
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.nodes[2], Vec2(0, 1));
  EXPECT_EQ(m.triangles, (std::vector<int>{1, 0, 3, 1, 3, 2}));
  EXPECT_EQ(m.triangle_physical, (std::vector<int>{0, 0}));
  EXPECT_EQ(m.lines, (std::vector<int>{1, 0}));
  EXPECT_EQ(m.line_physical, (std::vector<int>{7}));
  EXPECT_EQ(m.physical_names.at({1, 7}), "outer rim");

  const std::string v41 =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 1 1 0\n"
      "5 0 0 0 1 1 0 1 9 0\n2 0 0 0 1 1 0 2 11 12 1 -5\n$EndEntities\n"
      "$Nodes\n2 6 3 100\n2 2 0 4\n100\n3\n50\n60\n0 0 0\n2 0 0\n0 2 0\n1 1 0\n"
      "1 5 0 2\n70\n80\n1 0 0\n0 1 0\n$EndNodes\n"
      "$Elements\n2 2 1 2\n2 2 9 1\n1 100 3 50 70 60 80\n1 5 8 1\n2 100 3 70\n$EndElements\n";
  const HighOrderMesh q = parse_msh(v41);
  EXPECT_EQ(q.order, 2);
  EXPECT_EQ(q.nodes.size(), 6u);
  EXPECT_EQ(q.triangles, (std::vector<int>{0, 1, 2, 4, 3, 5}));
  EXPECT_EQ(q.triangle_physical, (std::vector<int>{11}));  // the entity's first physical tag
  EXPECT_EQ(q.lines, (std::vector<int>{0, 1, 4}));
  EXPECT_EQ(q.line_physical, (std::vector<int>{9}));
  EXPECT_TRUE(q.physical_names.empty());
}

// Small tags are looked up in a table, tags beyond what the text could number in a hash map: a
// mesh mixing both reads the same, and a tag defined twice is refused either way.
TEST(HighOrderMsh, NodeTagsOfAnySizeAreFound) {
  const std::string v22 =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
      "$Nodes\n4\n1000000000000 1 0 0\n2 0 0 0\n9223372036854775807 0 1 0\n2000 1 1 0\n$EndNodes\n"
      "$Elements\n2\n1 2 0 2 1000000000000 2000\n2 2 0 2 2000 9223372036854775807\n$EndElements\n";
  const HighOrderMesh m = parse_msh(v22);
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.triangles, (std::vector<int>{1, 0, 3, 1, 3, 2}));
  for (const std::string twice : {"2", "1000000000000"}) {
    const std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n" + twice +
                             " 0 0 0\n3 1 0 0\n" + twice + " 0 1 0\n$EndNodes\n$Elements\n0\n$EndElements\n";
    try {
      parse_msh(text);
      ADD_FAILURE() << "node " << twice << " defined twice was read";
    } catch (const MshError& e) {
      EXPECT_NE(std::string(e.what()).find("node " + twice + " is defined twice"), std::string::npos)
          << e.what();
    }
  }
}

std::string error_of(const std::string& text) {
  try {
    parse_msh(text);
  } catch (const MshError& e) {
    return e.what();
  }
  return "(no error)";
}

// Coordinates that are whole numbers are read without from_chars (every z of a planar mesh is
// "0"); each must be the double from_chars gives for the same word, bit for bit, sign of zero
// included, and a word that is not one must still reach from_chars and its message.
TEST(HighOrderMsh, WholeNumberCoordinatesAreTheValuesFromCharsGives) {
  const std::vector<std::string> words = {"0", "-0", "7", "-7", "000000000000012", "999999999999999",
                                          "-999999999999999", "1234567890123456", "9007199254740993",
                                          "12345678901234567890123", "5.", "-0.0", "3e2"};
  for (const std::string& w : words) {
    const std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 " + w + " " + w +
                             " 0\n$EndNodes\n$Elements\n0\n$EndElements\n";
    double expected = 0;
    ASSERT_EQ(std::from_chars(w.data(), w.data() + w.size(), expected).ec, std::errc()) << w;
    const HighOrderMesh m = parse_msh(text);
    ASSERT_EQ(m.nodes.size(), 1u) << w;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.nodes[0].x()), std::bit_cast<std::uint64_t>(expected)) << w;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.nodes[0].y()), std::bit_cast<std::uint64_t>(expected)) << w;
  }
  for (const std::string w : {"-", "--1", "1-", "12a", "+5"}) {
    const std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 " + w +
                             " 0 0\n$EndNodes\n$Elements\n0\n$EndElements\n";
    EXPECT_NE(error_of(text).find("expected a number (x), found '" + w + "'"), std::string::npos) << w;
  }
}

TEST(HighOrderMsh, RefusesMalformedFilesWithAMessage) {
  const std::string head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  const std::string nodes = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n";
  const std::string tri = "$Elements\n1\n1 2 2 4 1 1 2 3\n$EndElements\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "no $MeshFormat"},
      {"hello\n", "no $MeshFormat"},
      {std::string("$MeshFormat\n4.1 1 8\n\x01\0\0\0\n$EndMeshFormat\n$Nodes\n\xff\xfe\0\n$EndNodes\n", 61),
       "binary"},
      {"$MeshFormat\n4 0 8\n$EndMeshFormat\n", "version '4' is not supported"},
      {head + nodes, "no $Elements"},
      {head + "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0.5\n$EndNodes\n" + tri, "z = 0.5"},
      {head + "$Nodes\n3\n1 0 0 0\n2 nan 0 0\n3 0 1 0\n$EndNodes\n" + tri, "'nan' is not a finite number"},
      {head + "$Nodes\n3\n1 0 0 0\n2 1e999 0 0\n3 0 1 0\n$EndNodes\n" + tri, "not a finite number"},
      {head + "$Nodes\n3\n1 0 0 0\n2 1 0 0\n$EndNodes\n" + tri, "line 8: $Nodes: ends too early"},
      {head + "$Nodes\n3\n1 0 0 0\n1 1 0 0\n3 0 1 0\n$EndNodes\n" + tri, "node 1 is defined twice"},
      {head + "$Nodes\n3\n1 0 0 0\n0 1 0 0\n3 0 1 0\n$EndNodes\n" + tri, "node tag 0 is not positive"},
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 9\n$EndElements\n", "refers to node 9"},
      {head + nodes + "$Elements\n1\n1 3 2 4 1 1 2 3 1\n$EndElements\n", "type 3, not a triangle"},
      {head + nodes + "$Elements\n2\n1 2 2 4 1 1 2 3\n2 9 2 4 1 1 2 3 1 2 3\n$EndElements\n", "mixed orders"},
      {head + nodes + "$Elements\n2\n1 2 2 4 1 1 2 3\n2 8 2 4 1 1 2 3\n$EndElements\n",
       "lines of order 2 with triangles of order 1"},
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 3\n2 2 2 4 1 1 2 3\n$EndElements\n", "more data than"},
      {head + nodes + "$Elements\n-1\n$EndElements\n", "out of range"},
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 3\n", "not closed"},
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 x\n$EndElements\n",
       "expected an integer (node tag), found 'x'"},
      {head + nodes + "$Elements\n1\n$Nodes\n$EndElements\n", "not closed before"},
      {head + nodes + nodes + tri, "appears twice"},
      {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 1 1\n1\n0 0 0 0.5\n$EndNodes\n" + tri,
       "parametric nodes"},
      {"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 5 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 "
       "0\n$EndNodes\n" +
           tri,
       "announces 5 nodes"},
  };
  for (const auto& [text, message] : cases) EXPECT_THAT(error_of(text), testing::HasSubstr(message)) << text;
  EXPECT_THAT(error_of(head + nodes + tri), "(no error)");
}

// The line a message names is the line of the word, or of the section line, it is about: lines are
// counted only when a message needs them, so each way of failing is tried here.
TEST(HighOrderMsh, MessagesNameTheLineOfWhatTheyAreAbout) {
  const std::string head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  const std::string nodes = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n";
  const std::string tri = "$Elements\n1\n1 2 2 4 1 1 2 3\n$EndElements\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 x\n$EndElements\n", "line 12: $Elements: expected an integer"},
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 3\n", "line 12: $Elements: not closed: the file ends"},
      {head + nodes + "$Elements\n1\n1 2 2 4 1 1 2 3", "line 12: $Elements: not closed: the file ends"},
      {head + nodes + "$Elements\n1\n$Nodes\n$EndElements\n", "line 12: $Elements: not closed before '$Nodes'"},
      {head + nodes + nodes + tri, "line 15: $Nodes: the section appears twice"},
      {head + nodes + "$Elements\n2\n1 2 2 4 1 1 2 3\n2 8 2 4 1 1 2 3\n$EndElements\n",
       "line 11: $Elements: lines of order 2 with triangles of order 1"},
      {head + "$Nodes\n3\n1 0 0 0\n2 1. 0 0\n3 0 1e 0\n$EndNodes\n" + tri, "line 8: $Nodes: expected a number (y)"},
      {head + "$Nodes\n3\n1 0 0 0\n\n\n2 1 0 0\n3 0 1 0 7\n$EndNodes\n" + tri,
       "line 10: $Nodes: more data than its header announces, starting with '7'"},
      {head + "$PhysicalNames\n1\n2 1 \"a\n$b\"\n$EndPhysicalNames\n" + nodes + tri,
       "line 7: $PhysicalNames: not closed before '$b\"'"},
      {"junk\n$Nodes\n" + head + nodes + tri, "line 2: the file does not start with $MeshFormat"},
      {head + nodes + "$EndElements\n" + tri, "line 10: $Elements: unexpected '$EndElements'"},
  };
  for (const auto& [text, message] : cases) EXPECT_THAT(error_of(text), testing::HasSubstr(message)) << text;
  // A '$' that does not start its line starts no section; blanks before one that does are allowed.
  EXPECT_THAT(error_of(head + "$PhysicalNames\n1\n2 1 \"a$b\"\n$EndPhysicalNames\n" + nodes + tri), "(no error)");
  EXPECT_THAT(error_of(head + "  \t$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n \t$EndNodes  \r\n" + tri), "(no error)");
}

// Every prefix of a valid file and many corrupted copies: each parses or throws MshError.
TEST(HighOrderMsh, NeverCrashesOnDamagedFiles) {
  for (int version : {41, 22}) {
    const std::string text = msh_string(grid(2), {version});
    for (std::size_t cut = 0; cut < text.size(); ++cut) {
      try {
        parse_msh(std::string_view(text).substr(0, cut));
      } catch (const MshError&) {
      }
    }
    std::mt19937 random(version);
    const std::string alphabet = "0123456789 \n-.e$x\"";
    int refused = 0;
    for (int trial = 0; trial < 3000; ++trial) {
      std::string damaged = text;
      for (int k = 0; k < 3; ++k) {
        const std::size_t at = random() % damaged.size();
        switch (random() % 3) {
          case 0:
            damaged[at] = alphabet[random() % alphabet.size()];
            break;
          case 1:
            damaged.erase(at, 1 + random() % 8);
            break;
          default:
            damaged.insert(at, 1, alphabet[random() % alphabet.size()]);
            break;
        }
      }
      try {
        const HighOrderMesh m = parse_msh(damaged);
        EXPECT_EQ(m.structure_error(), std::nullopt);
      } catch (const MshError& e) {
        ++refused;
        EXPECT_GT(std::string(e.what()).size(), 10u);
      }
    }
    EXPECT_GT(refused, 1000);
  }
}

// read_msh with the limit `curvemesh check` has by default.
HighOrderMesh read_msh(const std::string& path) {
  return io::read_msh(path, static_cast<std::uint64_t>(kDefaultMaxMshMb * 1048576), "--max-input-mb");
}

// What read_msh throws for `path` with a limit of `max_bytes`, or "" when it reads it.
std::string read_error(const std::string& path, std::uint64_t max_bytes) {
  try {
    io::read_msh(path, max_bytes, "--max-input-mb");
  } catch (const MshError& e) {
    return e.what();
  }
  return "";
}

TEST(HighOrderMsh, ReadMshNamesThePath) {
  EXPECT_THROW(read_msh("/nonexistent/dir/x.msh"), MshError);
  const ScratchDir dir;
  const auto path = dir / "bad.msh";
  std::ofstream(path) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  try {
    read_msh(path);
    ADD_FAILURE() << "no error";
  } catch (const MshError& e) {
    EXPECT_THAT(e.what(), testing::StartsWith(path + ": no $Nodes"));
  }
  write_msh(grid(3), path, {22});
  expect_same(read_msh(path), grid(3));
}

TEST(HighOrderMsh, ReadMshRefusesWhatIsNotABoundedRegularFile) {
  const ScratchDir dir;
  const auto path = dir / "grid.msh";
  write_msh(grid(3), path, {41});
  const auto size = std::filesystem::file_size(path);
  EXPECT_EQ(read_error(path, size), "");
  // One byte over the limit: refused, the message starting with the path and naming the option.
  const std::string large = read_error(path, size - 1);
  EXPECT_THAT(large, testing::StartsWith(path + ": "));
  EXPECT_THAT(large, testing::HasSubstr("--max-input-mb"));
  // Not regular: refused without being read (a FIFO with no writer would block a plain open).
  EXPECT_THAT(read_error(dir / "", 1 << 20), testing::HasSubstr("a folder"));
  EXPECT_THAT(read_error("/dev/zero", 1 << 20), testing::HasSubstr("a character device"));
  const auto fifo = dir / "fifo.msh";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(read_error(fifo, 1 << 20), testing::HasSubstr("a FIFO"));
}

bool have_python(const char* modules) {
  if (!std::filesystem::exists("/usr/bin/python3")) return false;
  return std::system(("/usr/bin/python3 -c 'import " + std::string(modules) + "' 2>/dev/null").c_str()) == 0;
}

int run_python(const ScratchDir& dir, const std::string& script, const std::string& args) {
  const auto path = dir / "script.py";
  std::ofstream(path) << script;
  return std::system(("/usr/bin/python3 " + path + " " + args).c_str());
}

// Gmsh meshes a disk with P2 and P3 triangles and writes 4.1 and 2.2; then it opens each file
// again and lists, per triangle and per line, the coordinates of its nodes as it read them.
TEST(HighOrderMsh, ReadsFilesWrittenByGmsh) {
  if (!have_python("gmsh")) GTEST_SKIP() << "no python3-gmsh";
  const ScratchDir dir;
  const std::string script = R"(
import sys, gmsh
out, order, version, named = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), sys.argv[4] == '1'
gmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0)
gmsh.model.occ.addDisk(0.3, -0.2, 0, 1, 0.7); gmsh.model.occ.synchronize()
if named:
    gmsh.model.addPhysicalGroup(2, [1], 5); gmsh.model.setPhysicalName(2, 5, 'disk')
    gmsh.model.addPhysicalGroup(1, [1], 8); gmsh.model.setPhysicalName(1, 8, 'rim')
gmsh.option.setNumber('Mesh.MeshSizeMax', 0.3)
gmsh.model.mesh.generate(2); gmsh.model.mesh.setOrder(order)
gmsh.option.setNumber('Mesh.MshFileVersion', version)
gmsh.write(out + '.msh')
gmsh.clear(); gmsh.open(out + '.msh')
tags, coords, _ = gmsh.model.mesh.getNodes()
where = {int(t): (coords[3*i], coords[3*i+1]) for i, t in enumerate(tags)}
with open(out + '.txt', 'w') as f:
    for dim in (2, 1):
        types, _, nodes = gmsh.model.mesh.getElements(dim)
        for ty, ns in zip(types, nodes):
            n = gmsh.model.mesh.getElementProperties(ty)[3]
            f.write(f'{dim} {ty} {len(ns) // n} {n}\n')
            for i in range(0, len(ns), n):
                f.write(' '.join(f'{where[int(v)][0]!r} {where[int(v)][1]!r}' for v in ns[i:i+n]) + '\n')
gmsh.finalize()
)";
  for (int order : {2, 3})
    for (const char* version : {"4.1", "2.2"})
      for (int named : {0, 1}) {
        SCOPED_TRACE("order " + std::to_string(order) + ", version " + version + (named ? ", named" : ""));
        const auto base = dir / "gmsh_disk";
        ASSERT_EQ(
            run_python(dir, script,
                       base + " " + std::to_string(order) + " " + version + " " + std::to_string(named)),
            0);
        const HighOrderMesh m = read_msh(base + ".msh");
        EXPECT_EQ(m.order, order);
        std::ifstream reference(base + ".txt");
        int dim, type, count, size, seen_dims = 0;
        while (reference >> dim >> type >> count >> size) {
          seen_dims |= 1 << dim;
          EXPECT_EQ(type, dim == 2 ? (order == 2 ? 9 : 21) : (order == 2 ? 8 : 26));
          const int n = dim == 2 ? m.triangle_count() : m.line_count();
          ASSERT_EQ(n, count);
          ASSERT_EQ(size, dim == 2 ? m.triangle_size() : m.line_size());
          for (int e = 0; e < count; ++e) {
            const auto nodes = dim == 2 ? m.triangle(e) : m.line(e);
            for (int k = 0; k < size; ++k) {
              std::string x, y;
              reference >> x >> y;
              EXPECT_EQ(m.nodes[nodes[k]].x(), std::strtod(x.c_str(), nullptr));
              EXPECT_EQ(m.nodes[nodes[k]].y(), std::strtod(y.c_str(), nullptr));
            }
          }
        }
        EXPECT_EQ(seen_dims, 6);
        EXPECT_GT(m.triangle_count(), 20);
        if (named) {
          EXPECT_EQ(m.physical_names.at({2, 5}), "disk");
          EXPECT_EQ(m.physical_names.at({1, 8}), "rim");
          EXPECT_THAT(m.triangle_physical, testing::Each(5));
          EXPECT_THAT(m.line_physical, testing::Each(8));
        }
        // What we write of it Gmsh reads again with the same elements.
        write_msh(m, base + ".ours.msh");
        EXPECT_EQ(
            run_python(dir,
                       "import sys, gmsh\ngmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0)\n"
                       "gmsh.open(sys.argv[1])\n"
                       "t, e, _ = gmsh.model.mesh.getElements(2)\n"
                       "assert list(t) == [" +
                           std::to_string(order == 2 ? 9 : 21) +
                           "] and len(e[0]) == " + std::to_string(m.triangle_count()) +
                           ", (t, e)\n"
                           "assert len(gmsh.model.mesh.getNodes()[0]) == " +
                           std::to_string(m.nodes.size()) + "\n",
                       base + ".ours.msh"),
            0);
      }
}

TEST(HighOrderMsh, IndependentCheckerAcceptsWhatWeWrite) {
  if (!have_python("gmsh, meshio")) GTEST_SKIP() << "no python3-gmsh or python3-meshio";
  const std::string checker = std::string(CURVEMESH_EXAMPLES) + "/../tests/tools/msh_check.py";
  const ScratchDir dir;
  for (int p = 1; p <= 3; ++p)
    for (int version : {41, 22}) {
      const auto path = dir / (std::to_string(p) + "-" + std::to_string(version) + ".msh");
      write_msh(grid(p), path, {version});
      EXPECT_EQ(std::system(("/usr/bin/python3 " + checker + " " + path + " >/dev/null").c_str()), 0) << path;
    }
}

TEST(Vtu, MeshioReadsLagrangeTrianglesInVtkOrder) {
  // VTK's reference coordinates of the nodes of quadratic (vtkQuadraticTriangle) and Lagrange
  // triangles (vtkHigherOrderTriangle::SetParametricCoords), independently of our Gmsh order: on
  // an affine (unbent) mesh, node k of every cell must sit at the affine image of reference node k.
  const std::string script = R"(
import sys, meshio, numpy as np
path, order = sys.argv[1], int(sys.argv[2])
third = 1.0 / 3
ref = {1: [(0, 0), (1, 0), (0, 1)],
       2: [(0, 0), (1, 0), (0, 1), (.5, 0), (.5, .5), (0, .5)],
       3: [(0, 0), (1, 0), (0, 1), (third, 0), (2 * third, 0), (2 * third, third), (third, 2 * third),
           (0, 2 * third), (0, third), (third, third)]}[order]
m = meshio.read(path)
assert len(m.cells) == 1, m.cells
block = m.cells[0]
assert block.type == {1: 'triangle', 2: 'triangle6', 3: 'VTK_LAGRANGE_TRIANGLE'}[order], block.type
assert block.data.shape == (4, len(ref)), block.data.shape
for cell in block.data:
    p = m.points[cell][:, :2]
    for k, (r, s) in enumerate(ref):
        expect = p[0] + r * (p[1] - p[0]) + s * (p[2] - p[0])
        assert np.abs(p[k] - expect).max() < 1e-14, (k, p[k], expect)
assert list(m.cell_data['triangle'][0]) == [0, 1, 2, 3]
assert list(m.cell_data['physical'][0]) == [4, 4, 4, 4]
assert list(m.cell_data['quality'][0]) == [0.5, 0.25, 1.0 / 3, 1.0]
)";
  if (!have_python("meshio, numpy")) GTEST_SKIP() << "no python3-meshio";
  const ScratchDir dir;
  for (int p = 1; p <= 3; ++p) {
    const auto path = dir / ("p" + std::to_string(p) + ".vtu");
    write_vtu(grid(p, false), path, {{"quality", {0.5, 0.25, 1.0 / 3, 1.0}}});
    EXPECT_EQ(run_python(dir, script, path + " " + std::to_string(p)), 0) << path;
  }
  EXPECT_THROW(vtu_string(grid(2), {{"quality", {1.0}}}), std::logic_error);
  EXPECT_THROW(vtu_string(grid(2), {{"bad name", {1, 2, 3, 4}}}), std::logic_error);
  EXPECT_EQ(vtu_string(grid(3)), vtu_string(grid(3)));
}

}  // namespace
}  // namespace curvemesh::io
