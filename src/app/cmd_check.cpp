// `curvemesh check`: certifies any 2D triangle mesh in a Gmsh .msh file (P1, P2 or P3; ours or
// not). Every element's Jacobian determinant is decided positive on the whole element with exact
// rationals on the coordinates as a reader of the file gets them; with the drawing, the largest
// distance from a primary feature edge to the nearest input curve is measured too.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/p3_triangle.hpp"
#include "io/high_order_mesh.hpp"
#include "io/msh_reader.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh::app {

namespace {

using geometry::P3NodesT;
using geometry::PointT;
using geometry::Vec2;

struct CheckArgs {
  std::string input, svg;
  bool json = false;
};

PointT<mpq_class> exact(const Vec2& p) { return {mpq_class(p.x()), mpq_class(p.y())}; }

// The element's map written as a P3 map, exactly: a P1 or P2 map is evaluated at the ten P3
// reference nodes (rational points), which gives the P3 nodes of the very same map.
P3NodesT<mpq_class> as_p3(const io::HighOrderMesh& m, std::size_t t) {
  const int per = m.triangle_size();
  const auto n = m.triangle(static_cast<int>(t));
  P3NodesT<mpq_class> out;
  if (m.order == 3) {
    for (int i = 0; i < 10; ++i) out[i] = exact(m.nodes[n[i]]);
    return out;
  }
  std::array<PointT<mpq_class>, 6> x;
  for (int i = 0; i < per; ++i) x[i] = exact(m.nodes[n[i]]);
  for (int i = 0; i < 10; ++i) {
    const mpq_class u(geometry::kP3ReferenceNodesTimes3[i][0], 3), v(geometry::kP3ReferenceNodesTimes3[i][1], 3);
    const mpq_class l0 = 1 - u - v, l1 = u, l2 = v;
    std::array<mpq_class, 6> w;
    if (m.order == 1) {
      w = {l0, l1, l2, 0, 0, 0};
    } else {  // Gmsh's 6-node triangle: corners, then the middles of edges 0-1, 1-2, 2-0
      w = {l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2, 4 * l2 * l0};
    }
    out[i] = {0, 0};
    for (int k = 0; k < per; ++k)
      for (int c = 0; c < 2; ++c) out[i][c] += w[k] * x[k][c];
  }
  return out;
}

geometry::P3Nodes to_double(const P3NodesT<mpq_class>& p) {
  geometry::P3Nodes out;
  for (int i = 0; i < 10; ++i) out[i] = Vec2(p[i][0].get_d(), p[i][1].get_d());
  return out;
}

// A point of line element `l` at s in [0, 1] (its nodes: the ends, then the inner ones in order).
Vec2 line_point(const io::HighOrderMesh& m, std::size_t l, double s) {
  const auto nodes = m.line(static_cast<int>(l));
  const int order = static_cast<int>(nodes.size()) - 1;
  std::vector<Vec2> p(order + 1);
  std::vector<double> at(order + 1);
  p[0] = m.nodes[nodes[0]];
  at[0] = 0;
  p[order] = m.nodes[nodes[1]];
  at[order] = 1;
  for (int i = 1; i < order; ++i) {
    p[i] = m.nodes[nodes[i + 1]];
    at[i] = double(i) / order;
  }
  Vec2 x = Vec2::Zero();
  for (int i = 0; i <= order; ++i) {
    double w = 1;
    for (int j = 0; j <= order; ++j)
      if (j != i) w *= (s - at[j]) / (at[i] - at[j]);
    x += w * p[i];
  }
  return x;
}

int run_check(const CheckArgs& args) {
  io::HighOrderMesh m;
  try {
    m = io::read_msh(args.input);
  } catch (const std::exception& e) {
    std::cerr << "curvemesh: " << args.input << ": " << e.what() << "\n";
    return kInvalidInput;
  }
  const std::size_t triangles = static_cast<std::size_t>(m.triangle_count());
  std::size_t invalid = 0, undecided = 0;
  double min_scaled = INFINITY;
  for (std::size_t t = 0; t < triangles; ++t) {
    const auto p = as_p3(m, t);
    const auto verdict = geometry::certify_jacobian_exact(p);
    invalid += verdict != geometry::JacobianVerdict::positive;
    undecided += verdict == geometry::JacobianVerdict::undecided;
    min_scaled = std::min(min_scaled, geometry::certify_jacobian(to_double(p)).scaled_jacobian);
  }
  nlohmann::ordered_json report;
  report["file"] = args.input;
  report["order"] = m.order;
  report["triangles"] = triangles;
  report["invalid"] = invalid;
  report["undecided"] = undecided;
  report["min_scaled_jacobian"] = triangles ? min_scaled : 0.0;

  if (!args.svg.empty()) {
    svg::FeatureSoup soup;
    try {
      soup = pipeline::run(pipeline::Source::file(args.svg), {}, pipeline::Stage::read).soup;
    } catch (const Error& e) {
      std::cerr << "curvemesh: " << e.what() << "\n";
      return exit_code(e);
    }
    geometry::Box2 box;
    for (const auto& c : soup.curves)
      for (const Vec2& q : c.bezier.p) box.add(q);
    // Curves by bounding box, for a cheap lower bound before the exact closest point.
    std::vector<geometry::Box2> boxes;
    for (const auto& c : soup.curves) {
      geometry::Box2 b;
      for (const Vec2& q : c.bezier.p) b.add(q);
      boxes.push_back(b);
    }
    const auto box_distance = [](const geometry::Box2& b, const Vec2& q) {
      const double dx = std::max({b.min.x() - q.x(), 0.0, q.x() - b.max.x()});
      const double dy = std::max({b.min.y() - q.y(), 0.0, q.y() - b.max.y()});
      return std::hypot(dx, dy);
    };
    double worst = 0;
    std::size_t primary_lines = 0;
    for (std::size_t l = 0; l < static_cast<std::size_t>(m.line_count()); ++l) {
      const auto name = m.physical_names.find({1, m.line_physical[l]});
      if (name == m.physical_names.end() || name->second != "primary") continue;
      ++primary_lines;
      for (int i = 0; i <= 8; ++i) {
        const Vec2 q = line_point(m, l, i / 8.0);
        double best = INFINITY;
        for (std::size_t c = 0; c < soup.curves.size(); ++c)
          if (box_distance(boxes[c], q) < best)
            best = std::min(best, geometry::closest_point(soup.curves[c].bezier, q).distance);
        worst = std::max(worst, best);
      }
    }
    report["primary_lines"] = primary_lines;
    report["max_feature_distance"] = worst;
    report["max_feature_distance_rel"] = box.diagonal() > 0 ? worst / box.diagonal() : 0.0;
  }

  if (args.json) {
    std::cout << report.dump() << "\n";
  } else {
    for (const auto& [k, v] : report.items()) std::cout << k << ": " << v << "\n";
    std::cout << (invalid ? "INVALID" : "OK") << "\n";
  }
  return invalid ? kInvalidInput : kOk;
}

}  // namespace

Runner add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Certify every element of a Gmsh .msh file exactly (a positive Jacobian)\n"
      "Certify a 2D triangle mesh in a Gmsh .msh file (4.1 or 2.2, ASCII; linear, quadratic or cubic "
      "triangles, from any program): the Jacobian determinant of every element is decided positive "
      "on the whole element with exact rational arithmetic on the coordinates as written. Prints the "
      "number of invalid elements and the smallest scaled Jacobian; with --svg, also the largest "
      "distance from a primary feature edge to the drawing's curves. Exit 1 if any element is invalid.");
  cmd->add_option("input", args->input, ".msh file to check")->required();
  cmd->add_option("--svg", args->svg, "the SVG drawing the mesh was made from: measure primary edges against its curves");
  cmd->add_flag("--json", args->json, "print one JSON object");
  return [args] { return run_check(*args); };
}

}  // namespace curvemesh::app
