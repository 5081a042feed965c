#include "fem/diffuse.hpp"

#include <chrono>
#include <numeric>
#include <stdexcept>
#include <string>

#include "fem/assembly.hpp"

namespace curvemesh::fem {

namespace {

// Components of the unknowns linked by triangles.
std::vector<int> components(const Space& space, int triangles) {
  std::vector<int> parent(space.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (int t = 0; t < triangles; ++t) {
    const auto d = space.dofs(t);
    for (std::size_t i = 1; i < d.size(); ++i) {
      const int a = find(d[0]), b = find(d[i]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  for (int i = 0; i < space.size(); ++i) parent[i] = find(i);
  return parent;
}

}  // namespace

DiffusionMesh cut_along_curves(const MeshedDrawing& drawing, const std::vector<SideColours>& colours) {
  const io::HighOrderMesh& mesh = drawing.mesh;
  auto coloured = [&](int l) {
    const int physical = mesh.line_physical[l], curve = drawing.line_curve[l];
    if (curve >= static_cast<int>(colours.size()))
      throw std::invalid_argument("cut_along_curves: a line lies on curve " + std::to_string(curve) + " of " +
                                  std::to_string(colours.size()) + " coloured");
    return (physical == io::kPhysicalPrimary || physical == io::kPhysicalSecondary) && curve >= 0;
  };
  DiffusionMesh out;
  std::vector<char> cut(mesh.line_count(), 0);
  for (int l = 0; l < mesh.line_count(); ++l) cut[l] = coloured(l), out.cut_lines += cut[l];
  out.cut = cut_open(mesh, cut);

  // Triangle t lies on the right (on screen) of its edge e walked from corner e to corner e + 1
  // when its map keeps orientation: det J > 0 is counter-clockwise in the numbers, which y down
  // shows clockwise. The line's node 0 → 1 runs along its curve when line_forward says so.
  const Geometry geometry(mesh);
  const auto lines = edge_lines(mesh);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const int l = lines[t][e];
      if (l < 0 || !cut[l]) continue;
      Vec2 x;
      Eigen::Matrix2d j;
      geometry.map(t, Vec2(1.0 / 3, 1.0 / 3), x, j);
      const bool right_of_edge = j.determinant() > 0;
      const bool along_line = tri[e] == mesh.line(l)[0];
      const bool right_of_curve = (right_of_edge == along_line) == static_cast<bool>(drawing.line_forward[l]);
      const SideColours& c = colours[drawing.line_curve[l]];
      out.sides.push_back({t, e, right_of_curve ? c.right : c.left});
    }
  }
  return out;
}

Rgb DiffusionResult::at(const Space& space, int t, const Vec2& xi) const {
  const Eigen::VectorXd phi = space.basis().values(xi);
  const auto d = space.dofs(t);
  Rgb c{0, 0, 0};
  for (int i = 0; i < space.local_size(); ++i)
    for (int k = 0; k < 3; ++k) c[k] += channel[k][d[i]] * phi(i);
  return c;
}

DiffusionResult diffuse(const Geometry& geometry, const Space& space, const std::vector<ColouredEdge>& sides,
                        const DiffuseOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const int n = space.size();
  DiffusionResult r;
  r.unknowns = n;
  const SparseMatrix a = stiffness_matrix(geometry, space);

  // Held values: the mean of the colours of the edges an unknown is on.
  Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(n, 3);
  std::vector<int> count(n, 0);
  for (const ColouredEdge& s : sides) {
    const auto d = space.dofs(s.triangle);
    for (int i : space.edge_local_dofs(s.edge)) {
      for (int k = 0; k < 3; ++k) sum(d[i], k) += s.colour[k];
      ++count[d[i]];
    }
  }
  // A component no coloured edge touches would leave the solution's constant free (a singular
  // system): it takes the background colour instead.
  const std::vector<int> component = components(space, geometry.triangle_count());
  std::vector<char> held(n, 0);
  for (int i = 0; i < n; ++i)
    if (count[i] > 0) held[component[i]] = 1;
  // The three channels share which unknowns are held: one pattern, a column of values each.
  std::vector<char> fixed(n, 0);
  Eigen::MatrixX3d values = Eigen::MatrixX3d::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    if (count[i] > 0) {
      fixed[i] = 1;
      values.row(i) = sum.row(i) / count[i];
      ++r.fixed;
    } else if (!held[component[i]]) {
      fixed[i] = 1;
      for (int k = 0; k < 3; ++k) values(i, k) = options.background[k];
    }
  }
  for (int i = 0; i < n; ++i) r.background_components += component[i] == i && !held[i];
  const auto t1 = Clock::now();
  r.assembly_seconds = std::chrono::duration<double>(t1 - t0).count();
  const Eigen::MatrixXd x = solve(a, Eigen::MatrixXd::Zero(n, 3), fixed, values, true);
  for (int k = 0; k < 3; ++k) r.channel[k] = x.col(k);
  r.solve_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
  return r;
}

}  // namespace curvemesh::fem
