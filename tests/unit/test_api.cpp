// The public C++ API (include/curvemesh/curvemesh.hpp): the arrays' shapes and ranges, the line
// tags and the input curve under each line, files byte-identical to the command line's writers,
// the errors it throws (kind and message), and the check on good and inverted meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <curvemesh/curvemesh.hpp>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "io/xdmf_writer.hpp"
#include "pipeline/output.hpp"
#include "pipeline/pipeline.hpp"
#include "scratch_dir.hpp"

namespace curvemesh {
namespace {

using testing_support::ScratchDir;

const std::string kExamples = CURVEMESH_EXAMPLES;
const std::string kShapes = kExamples + "/overlapping-shapes.svg";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The kind and message of the Error `f` throws; fails the test when it throws none or another type.
template <class F>
std::pair<Error::Kind, std::string> error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return {e.kind(), e.what()};
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a curvemesh::Error: " << e.what();
    return {Error::Kind::internal, ""};
  }
  ADD_FAILURE() << "nothing thrown";
  return {Error::Kind::internal, ""};
}

// A circle of radius r about (cx, cy) as four cubic arcs, the reader's way.
std::vector<Curve> circle(double cx, double cy, double r) {
  const double k = 4.0 / 3.0 * std::tan(M_PI / 8) * r;
  const auto p = [&](double x, double y) { return std::array<double, 2>{cx + x, cy + y}; };
  return {{p(r, 0), p(r, k), p(k, r), p(0, r)},
          {p(0, r), p(-k, r), p(-r, k), p(-r, 0)},
          {p(-r, 0), p(-r, -k), p(-k, -r), p(0, -r)},
          {p(0, -r), p(k, -r), p(r, -k), p(r, 0)}};
}

std::array<double, 2> bezier_point(const Curve& c, double t) {
  const double s = 1 - t, w[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
  std::array<double, 2> x{0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 2; ++k) x[k] += w[i] * c[i][k];
  return x;
}

// The distance from q to curve c: the best of 1000 samples, refined by golden-section search.
double distance_to(const Curve& c, const std::array<double, 2>& q) {
  const auto at = [&](double t) {
    const auto x = bezier_point(c, t);
    return std::hypot(x[0] - q[0], x[1] - q[1]);
  };
  const int n = 1000;
  int best = 0;
  for (int i = 1; i <= n; ++i)
    if (at(double(i) / n) < at(double(best) / n)) best = i;
  double a = std::max(0.0, (best - 1.0) / n), b = std::min(1.0, (best + 1.0) / n);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 100; ++k) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    (at(x1) < at(x2) ? b : a) = at(x1) < at(x2) ? x2 : x1;
  }
  return at((a + b) / 2);
}

void expect_well_formed(const Mesh& m, int order) {
  const int per_triangle = (order + 1) * (order + 2) / 2, per_line = order + 1;
  EXPECT_EQ(m.order(), order);
  EXPECT_EQ(m.nodes_per_triangle(), per_triangle);
  EXPECT_EQ(m.nodes_per_line(), per_line);
  EXPECT_GT(m.triangle_count(), 0u);
  EXPECT_GT(m.line_count(), 0u);
  EXPECT_EQ(m.nodes().size(), m.node_count());
  EXPECT_EQ(m.triangles().size(), m.triangle_count() * per_triangle);
  EXPECT_EQ(m.lines().size(), m.line_count() * per_line);
  EXPECT_EQ(m.line_tags().size(), m.line_count());
  EXPECT_EQ(m.line_curves().size(), m.line_count());
  const auto n = static_cast<std::int64_t>(m.node_count());
  for (std::int64_t id : m.triangles()) ASSERT_TRUE(id >= 0 && id < n) << id;
  for (std::int64_t id : m.lines()) ASSERT_TRUE(id >= 0 && id < n) << id;
  for (const auto& [x, y] : m.nodes()) ASSERT_TRUE(std::isfinite(x) && std::isfinite(y));
  // Every triangle's nodes distinct; every line's too.
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const std::set<std::int64_t> ids(m.triangles().begin() + t * per_triangle,
                                     m.triangles().begin() + (t + 1) * per_triangle);
    ASSERT_EQ(ids.size(), std::size_t(per_triangle)) << "triangle " << t;
  }
  std::set<LineTag> tags(m.line_tags().begin(), m.line_tags().end());
  EXPECT_TRUE(tags.count(LineTag::boundary));
  for (std::size_t l = 0; l < m.line_count(); ++l) {
    if (m.line_tags()[l] == LineTag::boundary)
      EXPECT_EQ(m.line_curves()[l], -1) << "line " << l;
    else
      EXPECT_GE(m.line_curves()[l], 0) << "line " << l;
  }
}

TEST(Api, VersionAndTagNames) {
  EXPECT_STREQ(version(), "0.1.0");
  EXPECT_STREQ(tag_name(LineTag::primary), "primary");
  EXPECT_STREQ(tag_name(LineTag::secondary), "secondary");
  EXPECT_STREQ(tag_name(LineTag::boundary), "boundary");
}

TEST(Api, CurvedMeshArrays) {
  const Mesh m = mesh_file(kShapes);
  expect_well_formed(m, 3);
  const std::set<LineTag> tags(m.line_tags().begin(), m.line_tags().end());
  EXPECT_TRUE(tags.count(LineTag::primary));
  EXPECT_TRUE(tags.count(LineTag::secondary));  // the crossings make some
  EXPECT_NE(m.stats_json().find("\"curve\""), std::string::npos);
  EXPECT_NE(m.stats_json().find("overlapping-shapes.svg"), std::string::npos);
  EXPECT_TRUE(m.warnings().empty());
}

TEST(Api, LinearMeshArrays) {
  Parameters p;
  p.order = 1;
  const Mesh m = mesh_file(kShapes, p);
  expect_well_formed(m, 1);
  EXPECT_EQ(m.stats_json().find("\"curve\""), std::string::npos);
  EXPECT_NE(m.stats_json().find("\"max_edge_distance\""), std::string::npos);
}

TEST(Api, QuadraticMeshArrays) {
  Parameters p;
  p.order = 2;
  const Mesh m = mesh_file(kShapes, p);
  expect_well_formed(m, 2);
  const std::set<LineTag> tags(m.line_tags().begin(), m.line_tags().end());
  EXPECT_TRUE(tags.count(LineTag::primary));
  EXPECT_NE(m.stats_json().find("\"tolerance_splits\""), std::string::npos);
  p.order = 4;
  EXPECT_EQ(error_of([&] { mesh_file(kShapes, p); }).first, Error::Kind::invalid_parameters);
  p.order = 2;
  p.curve_tolerance_rel = -1;
  EXPECT_EQ(error_of([&] { mesh_file(kShapes, p); }).first, Error::Kind::invalid_parameters);
}

// -l means what it says: away from features the edges are about l long. Two short segments at
// opposite corners of a 100 × 100 drawing (d = 100√2) and a small circle near one of them leave
// the middle empty; the mean length of the edges with no end on a feature line (or the box) is
// within [0.8, 1.25] l d. (With small targets the optimizer used to stop while it was still
// refining, each pass splitting twice as many edges as the one before: at l = 0.01 the edges
// were 1.5 l long.)
TEST(Api, TargetEdgeLengthHoldsAwayFromFeatures) {
  const std::string svg =
      R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">)"
      R"(<path d="M 0 0 L 1 0" stroke="black" fill="none"/><path d="M 99 100 L 100 100" stroke="black" fill="none"/>)"
      R"(<circle cx="20" cy="20" r="5" stroke="black" fill="none"/></svg>)";
  const double d = 100 * std::sqrt(2.0);
  for (const double l : {0.01, 0.02, 0.05}) {
    Parameters p;
    p.order = 1;
    p.edge_length_rel = l;
    const Mesh m = mesh_svg(svg, p);
    std::set<std::int64_t> on_features(m.lines().begin(), m.lines().end());
    std::set<std::pair<std::int64_t, std::int64_t>> edges;
    const auto& t = m.triangles();
    for (std::size_t k = 0; k < t.size(); k += 3)
      for (int i = 0; i < 3; ++i) {
        const std::int64_t a = t[k + i], b = t[k + (i + 1) % 3];
        if (!on_features.count(a) && !on_features.count(b)) edges.insert(std::minmax(a, b));
      }
    double sum = 0;
    for (const auto& [a, b] : edges)
      sum += std::hypot(m.nodes()[a][0] - m.nodes()[b][0], m.nodes()[a][1] - m.nodes()[b][1]);
    ASSERT_GT(edges.size(), 300u) << "l = " << l;
    const double mean = sum / static_cast<double>(edges.size()) / (l * d);
    EXPECT_GE(mean, 0.8) << "l = " << l;
    EXPECT_LE(mean, 1.25) << "l = " << l;
  }
}

// The same drawing through the API and through the pipeline as `curvemesh mesh` runs it: the
// same arrays as high_order_mesh, and every file byte for byte the same.
TEST(Api, SameMeshAndFilesAsTheCommandLine) {
  const ScratchDir dir;
  for (const bool linear : {false, true}) {
    Parameters p;
    p.order = linear ? 1 : 3;
    p.edge_length_rel = 0.04;
    const Mesh m = mesh_file(kShapes, p);
    const pipeline::Result r = pipeline::run(pipeline::Source::file(kShapes), p);
    const io::HighOrderMesh h = pipeline::high_order_mesh(r);
    ASSERT_EQ(m.node_count(), h.nodes.size());
    for (std::size_t i = 0; i < h.nodes.size(); ++i) {
      ASSERT_EQ(m.nodes()[i][0], h.nodes[i].x());
      ASSERT_EQ(m.nodes()[i][1], h.nodes[i].y());
    }
    EXPECT_TRUE(
        std::equal(m.triangles().begin(), m.triangles().end(), h.triangles.begin(), h.triangles.end()));
    EXPECT_TRUE(std::equal(m.lines().begin(), m.lines().end(), h.lines.begin(), h.lines.end()));

    const std::string tag = linear ? "linear" : "curved";
    m.write(dir / (tag + "-api.msh"));
    pipeline::write_msh(r, dir / (tag + "-cli.msh"));
    m.write(dir / (tag + "-api22.msh"), 22);
    pipeline::write_msh(r, dir / (tag + "-cli22.msh"), 22);
    m.write(dir / (tag + "-api.vtu"));
    pipeline::write_vtu(r, dir / (tag + "-cli.vtu"));
    m.write(dir / (tag + "-api.svg"));
    pipeline::write_svg(r, dir / (tag + "-cli.svg"));
    for (const std::string ext : {".msh", "22.msh", ".vtu", ".svg"}) {
      const std::string api = read_file(dir / (tag + "-api" + ext)),
                        cli = read_file(dir / (tag + "-cli" + ext));
      EXPECT_FALSE(api.empty()) << tag << ext;
      EXPECT_TRUE(api == cli) << tag << ext << " differs";
    }
    // The extension is read without regard to case.
    m.write(dir / (tag + "-upper.MSH"));
    EXPECT_TRUE(read_file(dir / (tag + "-upper.MSH")) == read_file(dir / (tag + "-cli.msh")));
  }
}

// The groups a solver selects by: the physical groups of the mesh the command line writes, with
// the ids and names `--stats` lists, whatever the domain.
TEST(Api, GroupsAreTheFilesPhysicalGroups) {
  for (const Domain domain : {Domain::box, Domain::filled}) {
    Parameters p;
    p.order = 2;
    p.regions = true;
    p.domain = domain;
    const Mesh m = mesh_file(kShapes, p);
    const pipeline::Result r = pipeline::run(pipeline::Source::file(kShapes), p);
    const io::HighOrderMesh& h = pipeline::high_order_mesh(r);
    EXPECT_EQ(m.triangle_groups(), h.triangle_physical);
    ASSERT_EQ(m.line_groups().size(), m.line_count());
    std::map<int, std::size_t> lines_in, triangles_in;
    for (std::size_t l = 0; l < m.line_count(); ++l) {
      const std::vector<int>& g = m.line_groups()[l];
      ASSERT_FALSE(g.empty());
      EXPECT_TRUE(std::is_sorted(g.begin(), g.end()));
      EXPECT_EQ(g.front(), 1 + static_cast<int>(m.line_tags()[l]));  // primary 1, secondary 2, boundary 3
      std::vector<int> file = h.groups_of_line(static_cast<int>(l));
      std::sort(file.begin(), file.end());
      EXPECT_EQ(g, file);
      for (int id : g) ++lines_in[id];
    }
    for (int id : m.triangle_groups()) ++triangles_in[id];
    // Every group once, named, and the same as the statistics list.
    const nlohmann::json stats = nlohmann::json::parse(m.stats_json())["groups"];
    ASSERT_EQ(m.groups().size(), stats.size());
    for (std::size_t i = 0; i < stats.size(); ++i) {
      const Group& g = m.groups()[i];
      EXPECT_EQ(g.dimension, stats[i]["dim"].get<int>());
      EXPECT_EQ(g.id, stats[i]["id"].get<int>());
      EXPECT_EQ(g.name, stats[i]["name"].get<std::string>());
      EXPECT_FALSE(g.name.empty());
      if (g.dimension == 1)
        EXPECT_EQ(lines_in[g.id], stats[i]["lines"].get<std::size_t>()) << g.name;
      else
        EXPECT_EQ(triangles_in[g.id], stats[i]["triangles"].get<std::size_t>()) << g.name;
    }
    EXPECT_EQ(std::count_if(m.groups().begin(), m.groups().end(), [](const Group& g) { return g.dimension == 2; }),
              static_cast<std::ptrdiff_t>(triangles_in.size()));
  }
}

// XDMF: the command line's two files, both or neither; no cubic triangle.
TEST(Api, WritesXdmfAsTheCommandLine) {
  const ScratchDir dir;
  Parameters p;
  p.order = 2;
  p.regions = true;
  const Mesh m = mesh_file(kShapes, p);
  const pipeline::Result r = pipeline::run(pipeline::Source::file(kShapes), p);
  std::filesystem::create_directory(dir / "api");
  std::filesystem::create_directory(dir / "cli");
  m.write(dir / "api/m.XDMF");
  const io::XdmfFiles cli = io::xdmf_files(pipeline::high_order_mesh(r), "m.h5");
  EXPECT_TRUE(read_file(dir / "api/m.XDMF") == cli.xml);
  EXPECT_TRUE(read_file(dir / "api/m.h5") == cli.data);

  p.order = 3;
  const Mesh cubic = mesh_file(kShapes, p);
  const auto [kind, message] = error_of([&] { cubic.write(dir / "cubic.xdmf"); });
  EXPECT_EQ(kind, Error::Kind::invalid_parameters);
  EXPECT_NE(message.find("order 3"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(dir / "cubic.xdmf"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cubic.h5"));
  // The data file may not be the drawing either.
  const ScratchDir drawings;
  std::filesystem::copy_file(kShapes, drawings / "d.h5");
  p.order = 2;
  const Mesh of_h5 = mesh_file(drawings / "d.h5", p);
  EXPECT_EQ(error_of([&] { of_h5.write(drawings / "d.xdmf"); }).first, Error::Kind::invalid_parameters);
  EXPECT_FALSE(std::filesystem::exists(drawings / "d.xdmf"));
}

// Curves given by their control points: each primary line lies on the curve line_curves names.
TEST(Api, LineCurvesNameTheCurveUnderEachLine) {
  std::vector<Curve> curves = circle(0, 0, 1);
  for (const Curve& c : circle(3, 0.5, 0.7)) curves.push_back(c);
  for (const bool linear : {false, true}) {
    Parameters p;
    p.order = linear ? 1 : 3;
    const Mesh m = mesh_curves(curves, p);
    expect_well_formed(m, linear ? 1 : 3);
    EXPECT_NE(m.stats_json().find("<curves>"), std::string::npos);
    std::set<std::int64_t> seen;
    for (std::size_t l = 0; l < m.line_count(); ++l) {
      if (m.line_tags()[l] == LineTag::boundary) continue;
      const std::int64_t c = m.line_curves()[l];
      ASSERT_TRUE(c >= 0 && c < std::int64_t(curves.size())) << c;
      seen.insert(c);
      if (m.line_tags()[l] != LineTag::primary) continue;
      for (int k = 0; k < m.nodes_per_line(); ++k) {
        const auto& q = m.nodes()[m.lines()[l * m.nodes_per_line() + k]];
        EXPECT_LT(distance_to(curves[c], q), 1e-6) << "line " << l << " node " << k << " on curve " << c;
      }
    }
    EXPECT_EQ(seen.size(), curves.size());  // every curve has lines on it
  }
}

TEST(Api, BadSvgThrowsTheReadersMessage) {
  auto [kind, message] = error_of([] { mesh_svg("<svg", {}, "bad.svg"); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_EQ(message, "bad.svg: line 1: not well-formed XML: Error parsing start element tag");
  std::tie(kind, message) =
      error_of([] { mesh_svg("<svg xmlns='http://www.w3.org/2000/svg'><path d='M 0 0 L 1e999 0'/></svg>"); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_EQ(message,
            "<svg>: line 1, <path>: bad path data: number '1e999' is too large for a double at offset 8");
  std::tie(kind, message) = error_of([] { mesh_file(kExamples + "/no-such-drawing.svg"); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_NE(message.find("no-such-drawing.svg"), std::string::npos) << message;
}

TEST(Api, WarningsOfTheReader) {
  const Mesh m =
      mesh_svg("<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><image/></svg>");
  EXPECT_GT(m.triangle_count(), 0u);  // the canvas alone
  ASSERT_EQ(m.warnings().size(), 2u);
  EXPECT_NE(m.warnings()[0].find("<image>"), std::string::npos) << m.warnings()[0];
  EXPECT_EQ(m.warnings()[1], "nothing is drawn; meshing the canvas alone");
}

TEST(Api, InvalidParametersAreRefused) {
  Parameters p;
  p.epsilon_rel = 1e-4;
  auto [kind, message] = error_of([&] { mesh_file(kShapes, p); });
  EXPECT_EQ(kind, Error::Kind::invalid_parameters);
  EXPECT_EQ(message, "--epsilon (0.0001) must be at least --mu (0.001)");
  p = Parameters{};
  p.edge_length_rel = std::numeric_limits<double>::quiet_NaN();
  std::tie(kind, message) = error_of([&] { mesh_curves(circle(0, 0, 1), p); });
  EXPECT_EQ(kind, Error::Kind::invalid_parameters);
  EXPECT_EQ(message, "--edge-length (nan) must be a positive number");
}

TEST(Api, CurvesThatAreNotFiniteAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf, -inf}) {
    std::vector<Curve> curves = circle(0, 0, 1);
    curves[2][1][1] = bad;
    const auto [kind, message] = error_of([&] { mesh_curves(curves); });
    EXPECT_EQ(kind, Error::Kind::invalid_input);
    EXPECT_EQ(message.find("<curves>: curve 2 has a coordinate that is not a finite number"), 0u) << message;
  }
  // Finite, but too large to mesh in doubles (its diagonal would overflow).
  auto [kind, message] = error_of([] { mesh_curves(circle(0, 0, 1e200)); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_EQ(
      message,
      "<curves>: the drawing reaches a coordinate of 1e+200, beyond 1e+100: too large to mesh in double "
      "precision; scale it down");
  // Too small: lengths relative to its size would underflow.
  std::tie(kind, message) = error_of([] { mesh_curves(circle(0, 0, 1e-160)); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_EQ(message,
            "<curves>: the drawing is 2.8e-160 across, smaller than 1e-100: too small to mesh in double "
            "precision; scale it up");
  // Nothing at all.
  std::tie(kind, message) = error_of([] { mesh_curves({}); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_NE(message.find("nothing to mesh"), std::string::npos) << message;
}

TEST(Api, CheckCertifiesTheMeshAndItsFile) {
  const ScratchDir dir;
  for (const int order : {3, 2, 1}) {
    Parameters p;
    p.order = order;
    const Mesh m = mesh_file(kExamples + "/square-with-hole.svg", p);
    const CheckReport r = check(m);
    EXPECT_EQ(r.order, order);
    EXPECT_EQ(r.triangles, m.triangle_count());
    EXPECT_EQ(r.invalid, 0u);
    EXPECT_EQ(r.undecided, 0u);
    EXPECT_GT(r.min_scaled_jacobian, 0);
    EXPECT_LE(r.min_scaled_jacobian, 1);
    m.write(dir / "m.msh");
    const CheckReport f = check_file(dir / "m.msh");
    EXPECT_EQ(f.order, r.order);
    EXPECT_EQ(f.triangles, r.triangles);
    EXPECT_EQ(f.invalid, 0u);
    EXPECT_EQ(f.min_scaled_jacobian, r.min_scaled_jacobian);
    EXPECT_EQ(f.exact_fallbacks, r.exact_fallbacks);
    // Every element in rationals: the same verdict and figure.
    for (const CheckReport& e : {check(m, {.exact = true}), check_file(dir / "m.msh", {.exact = true})}) {
      EXPECT_EQ(e.order, r.order);
      EXPECT_EQ(e.triangles, r.triangles);
      EXPECT_EQ(e.invalid, 0u);
      EXPECT_EQ(e.undecided, 0u);
      EXPECT_EQ(e.min_scaled_jacobian, r.min_scaled_jacobian);
      EXPECT_EQ(e.exact_fallbacks, e.triangles);
    }
  }
}

// A cubic triangle folded by an edge node pushed beyond the opposite side, and the same triangle
// straight (tests/cli/curved_test.py has the same two).
TEST(Api, CheckFileFindsAnInvertedElement) {
  const ScratchDir dir;
  const auto write = [&](const std::string& name, const std::array<double, 2>& ninth) {
    std::ofstream f(dir / name);
    const double third = 1.0 / 3, two = 2.0 / 3;
    const std::array<std::array<double, 2>, 10> nodes{{{0, 0},
                                                       {1, 0},
                                                       {0, 1},
                                                       {third, 0},
                                                       {two, 0},
                                                       {two, third},
                                                       {third, two},
                                                       {0, two},
                                                       ninth,
                                                       {third, third}}};
    f.precision(17);
    f << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n";
    for (int i = 0; i < 10; ++i) f << i + 1 << " " << nodes[i][0] << " " << nodes[i][1] << " 0\n";
    f << "$EndNodes\n$Elements\n1\n1 21 2 4 1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n";
  };
  write("folded.msh", {0.8, 0.8});
  write("straight.msh", {0, 1.0 / 3});
  const CheckReport folded = check_file(dir / "folded.msh");
  EXPECT_EQ(folded.order, 3);
  EXPECT_EQ(folded.triangles, 1u);
  EXPECT_EQ(folded.invalid, 1u);
  EXPECT_LT(folded.min_scaled_jacobian, 0);
  EXPECT_EQ(folded.exact_fallbacks, 0u);  // folded far beyond rounding: the doubles decide
  EXPECT_EQ(check_file(dir / "folded.msh", {.exact = true}).invalid, 1u);
  const CheckReport straight = check_file(dir / "straight.msh");
  EXPECT_EQ(straight.invalid, 0u);
  EXPECT_GT(straight.min_scaled_jacobian, 0.99);

  // Quadratic triangles, decided on their own degree-2 determinant: straight, folded (edge 0-1's
  // middle beyond the opposite corner), and positive although a Bernstein coefficient is negative
  // (tests/unit/test_p2_triangle.cpp's element, which only subdivision decides).
  const auto write_p2 = [&](const std::string& name, const std::array<std::array<double, 2>, 6>& nodes) {
    std::ofstream f(dir / name);
    f << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n";
    for (int i = 0; i < 6; ++i) f << i + 1 << " " << nodes[i][0] << " " << nodes[i][1] << " 0\n";
    f << "$EndNodes\n$Elements\n1\n1 9 2 4 1 1 2 3 4 5 6\n$EndElements\n";
  };
  write_p2("p2-straight.msh", {{{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}}});
  write_p2("p2-folded.msh", {{{0, 0}, {1, 0}, {0, 1}, {0.5, 1.5}, {0.5, 0.5}, {0, 0.5}}});
  write_p2("p2-subtle.msh", {{{0, 0}, {40, 0}, {0, 40}, {18, 9}, {15, 22}, {-7, 10}}});
  for (const auto& [name, invalid] : {std::pair{"p2-straight.msh", 0u}, {"p2-folded.msh", 1u}, {"p2-subtle.msh", 0u}}) {
    const CheckReport r = check_file(dir / name);
    EXPECT_EQ(r.order, 2) << name;
    EXPECT_EQ(r.invalid, invalid) << name;
    EXPECT_EQ(r.undecided, 0u) << name;
    EXPECT_EQ(r.min_scaled_jacobian > 0, invalid == 0) << name;
  }

  {
    std::ofstream f(dir / "broken.msh");
    f << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n";
  }
  auto [kind, message] = error_of([&] { check_file(dir / "broken.msh"); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_EQ(message, dir / "broken.msh" + ": line 6: $Nodes: not closed: the file ends inside it");
  std::tie(kind, message) = error_of([&] { check_file(dir / "missing.msh"); });
  EXPECT_EQ(kind, Error::Kind::invalid_input);
  EXPECT_EQ(message, dir / "missing.msh" + ": cannot open the file (No such file or directory)");
}

TEST(Api, WriteFailures) {
  const ScratchDir dir;
  Parameters p;
  p.order = 1;
  const Mesh m = mesh_file(kExamples + "/square-with-hole.svg", p);
  auto [kind, message] = error_of([&] { m.write(dir / "no-such-folder/m.msh"); });
  EXPECT_EQ(kind, Error::Kind::output);
  EXPECT_NE(message.find("no-such-folder/m.msh"), std::string::npos) << message;
  std::tie(kind, message) = error_of([&] { m.write(dir / "m.obj"); });
  EXPECT_EQ(kind, Error::Kind::output);
  EXPECT_NE(message.find("m.obj"), std::string::npos) << message;
  std::tie(kind, message) = error_of([&] { m.write(dir / "m.msh", 40); });
  EXPECT_EQ(kind, Error::Kind::invalid_parameters);
  EXPECT_EQ(message, "--msh-version (40) must be 41 or 22");
  EXPECT_FALSE(std::ifstream(dir / "m.msh").good());  // nothing written
}

TEST(Api, DefaultConstructedMeshIsEmpty) {
  const Mesh m;
  EXPECT_EQ(m.order(), 0);
  EXPECT_EQ(m.node_count(), 0u);
  EXPECT_EQ(m.triangle_count(), 0u);
  EXPECT_EQ(m.line_count(), 0u);
  EXPECT_TRUE(m.nodes().empty() && m.triangles().empty() && m.lines().empty() && m.line_tags().empty());
  EXPECT_EQ(check(m).triangles, 0u);
  const ScratchDir dir;
  EXPECT_EQ(error_of([&] { m.write(dir / "m.msh"); }).first, Error::Kind::output);
}

TEST(Api, MeshesShareTheirData) {
  const Mesh a = mesh_curves(circle(0, 0, 1));
  const Mesh b = a;  // a copy shares the arrays
  EXPECT_EQ(&a.nodes(), &b.nodes());
  EXPECT_EQ(b.triangle_count(), a.triangle_count());
}

}  // namespace
}  // namespace curvemesh
