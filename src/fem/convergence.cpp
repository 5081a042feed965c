#include "fem/convergence.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "fem/assembly.hpp"
#include "fem/domain.hpp"
#include "fem/drawing.hpp"
#include "pipeline/output.hpp"

namespace curvemesh::fem {

std::string disk_svg() {
  std::ostringstream s;
  s.precision(17);
  const int arcs = 32;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"-1.2 -1.2 2.4 2.4\">\n<path fill=\"none\" stroke=\"black\" d=\"M 1 0";
  for (int i = 1; i <= arcs; ++i) {
    const double a = 2 * std::numbers::pi * i / arcs;
    s << " A 1 1 0 0 1 " << (i == arcs ? 1.0 : std::cos(a)) << " " << (i == arcs ? 0.0 : std::sin(a));
  }
  s << " Z\"/>\n</svg>\n";
  return s.str();
}

double convergence_rate(const std::vector<double>& x, const std::vector<double>& y) {
  const int n = static_cast<int>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

namespace {

double exact(const Vec2& p) { return (1 - p.squaredNorm()) * std::exp(p.x()) * std::cos(p.y()); }
Vec2 exact_gradient(const Vec2& p) {
  const double phi = 1 - p.squaredNorm(), w = std::exp(p.x()) * std::cos(p.y()), s = std::exp(p.x()) * std::sin(p.y());
  return {-2 * p.x() * w + phi * w, -2 * p.y() * w - phi * s};
}
// −Δu for u = φ w with φ = 1 − r² (Δφ = −4) and w = eˣ cos y harmonic: −(wΔφ + 2∇φ·∇w).
double source(const Vec2& p) {
  const double w = std::exp(p.x()) * std::cos(p.y()), s = std::exp(p.x()) * std::sin(p.y());
  return 4 * w + 4 * p.x() * w - 4 * p.y() * s;
}

ConvergenceLevel solve_level(const io::HighOrderMesh& disk) {
  const auto start = std::chrono::steady_clock::now();
  const Geometry geometry(disk);
  const Space space(disk, 2);
  const SparseMatrix k = stiffness_matrix(geometry, space);
  const Eigen::VectorXd b = load_vector(geometry, space, source);
  Dirichlet dirichlet(space.size());
  set_on_edges(geometry, space, boundary_edges(disk), [](const Vec2&) { return 0.0; }, dirichlet);
  const Eigen::VectorXd u = solve(k, b, dirichlet, true);
  ConvergenceLevel level;
  level.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  level.triangles = disk.triangle_count();
  level.unknowns = space.size();
  level.l2 = l2_error(geometry, space, u, exact);
  level.h1 = h1_error(geometry, space, u, exact_gradient);
  double sum = 0;
  for (int t = 0; t < disk.triangle_count(); ++t)
    for (int e = 0; e < 3; ++e) sum += (disk.nodes[disk.triangle(t)[e]] - disk.nodes[disk.triangle(t)[(e + 1) % 3]]).norm();
  level.h = sum / (3.0 * disk.triangle_count());
  return level;
}

void rates(ConvergenceSeries& s) {
  std::vector<double> h, l2, h1;
  for (const auto& l : s.levels) h.push_back(l.h), l2.push_back(l.l2), h1.push_back(l.h1);
  s.rate_l2 = convergence_rate(h, l2);
  s.rate_h1 = convergence_rate(h, h1);
}

}  // namespace

ConvergenceResult poisson_convergence(const ConvergenceOptions& options) {
  ConvergenceResult result;
  for (double l : options.edge_lengths_rel) {
    pipeline::Parameters parameters = options.parameters;
    parameters.edge_length_rel = l;
    const MeshedDrawing meshed = pipeline::mesh_drawing(pipeline::Source::svg(disk_svg(), "<disk>"), parameters);
    result.mesh_seconds += meshed.seconds;
    const std::vector<char> keep =
        regions::domain_triangles({regions::find_faces(meshed.mesh), {}, {}}, regions::Domain::evenodd);
    const io::HighOrderMesh curved = submesh(meshed.mesh, keep);
    const io::HighOrderMesh straight = straight_mesh(curved);
    for (auto [mesh, series] : {std::pair{&curved, &result.p3_geometry}, std::pair{&straight, &result.p1_geometry}}) {
      ConvergenceLevel level = solve_level(*mesh);
      level.edge_length_rel = l;
      series->levels.push_back(level);
    }
  }
  rates(result.p3_geometry);
  rates(result.p1_geometry);
  return result;
}

}  // namespace curvemesh::fem
