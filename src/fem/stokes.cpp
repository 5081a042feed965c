#include "fem/stokes.hpp"
#include "mesh/union_find.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseQR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>

#include "fem/assembly.hpp"

namespace curvemesh::fem {

namespace {

// A column of the (column-normalized) divergence counts as dependent on the ones before it when
// its pivot in the rank-revealing QR is below this.
constexpr double kRankThreshold = 1e-10;

// One pressure unknown (the lowest) of every part of the mesh connected through pressure
// unknowns that has no border edge outside the conditions: there the velocity is given all
// around, and the pressure only up to a constant.
std::vector<int> closed_part_references(const io::HighOrderMesh& mesh, const Space& pressure,
                                        const std::vector<VelocityCondition>& conditions) {
  mesh::UnionFind parts(pressure.size());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto d = pressure.dofs(t);
    parts.unite(d[0], d[1]), parts.unite(d[0], d[2]);
  }
  std::set<std::pair<int, int>> given;
  for (const VelocityCondition& c : conditions) given.insert(c.edges.begin(), c.edges.end());
  std::vector<char> open(pressure.size(), 0);  // per part's root: has a natural border edge
  for (const auto& [t, e] : boundary_edges(mesh))
    if (!given.count({t, e})) open[parts.find(pressure.dofs(t)[e])] = 1;
  std::vector<int> out;
  for (int i = 0; i < pressure.size(); ++i)
    if (parts.find(i) == i && !open[i]) out.push_back(i);  // the root is its part's lowest unknown
  return out;
}

// More pressures the velocity cannot see. Taylor–Hood is stable on meshes whose triangles have a
// vertex off the border, which a drawing's mesh cut open along its curves does not promise: in a
// pocket of two triangles closed by walls, or a sliver between two curves, the free velocities
// are too few for the pressures around them, and pressure fields q with ∫ q div v = 0 for every
// free v make the system singular. They are the null space of Bᵀ (rows: free velocities,
// columns: pressures not yet held). Its columns fall into independent groups (pressures that
// share no free velocity do not interact); in each group a rank-revealing QR of the normalized
// columns finds the ones that depend on the others, and holding those at 0 leaves Bᵀ of full
// column rank, hence the system nonsingular. Their equations follow from the others' where the
// data are compatible (no flux through walls), so nothing else changes. Groups larger than
// `largest` columns are skipped; groups larger than `dense` get a sparse QR.
std::vector<int> dependent_pressures(const SparseMatrix& b, const Dirichlet& dirichlet, int nv, int largest,
                                     int dense) {
  const int np = static_cast<int>(b.rows());
  std::vector<int> column(np, -1), pressure_of;  // held pressures have no column
  for (int j = 0; j < np; ++j)
    if (!dirichlet.fixed[2 * nv + j])
      column[j] = static_cast<int>(pressure_of.size()), pressure_of.push_back(j);
  const int nc = static_cast<int>(pressure_of.size());
  // Bᵀ's columns as lists of (free velocity, value), normalized.
  std::vector<std::vector<std::pair<int, double>>> columns(nc);
  for (int v = 0; v < b.outerSize(); ++v) {
    if (dirichlet.fixed[v]) continue;
    for (SparseMatrix::InnerIterator it(b, v); it; ++it)
      if (column[it.row()] >= 0 && it.value() != 0) columns[column[it.row()]].emplace_back(v, it.value());
  }
  mesh::UnionFind groups(nc);
  std::vector<int> first_column(b.cols(), -1);  // per free velocity: a column that uses it
  for (int c = 0; c < nc; ++c) {
    double norm = 0;
    for (const auto& [v, x] : columns[c]) norm += x * x;
    norm = std::sqrt(norm);
    for (auto& [v, x] : columns[c]) {
      x /= norm;
      if (first_column[v] < 0)
        first_column[v] = c;
      else
        groups.unite(c, first_column[v]);
    }
  }
  std::map<int, std::vector<int>> members;
  for (int c = 0; c < nc; ++c) members[groups.find(c)].push_back(c);
  std::vector<int> out;
  for (const auto& [root, cols] : members) {
    const int n = static_cast<int>(cols.size());
    if (n > largest) continue;
    std::map<int, int> row;
    for (int c : cols)
      for (const auto& [v, x] : columns[c]) row.try_emplace(v, static_cast<int>(row.size()));
    if (row.empty()) {  // no free velocity touches these pressures at all
      for (int c : cols) out.push_back(pressure_of[c]);
      continue;
    }
    if (n > dense) {
      Triplets triplets;
      for (int k = 0; k < n; ++k)
        for (const auto& [v, x] : columns[cols[k]]) triplets.emplace_back(row[v], k, x);
      SparseMatrix m(static_cast<int>(row.size()), n);
      m.setFromTriplets(triplets.begin(), triplets.end());
      m.makeCompressed();
      Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>> qr;
      qr.setPivotThreshold(kRankThreshold);
      qr.compute(m);
      if (qr.info() != Eigen::Success) continue;
      for (int k = static_cast<int>(qr.rank()); k < n; ++k)
        out.push_back(pressure_of[cols[qr.colsPermutation().indices()[k]]]);
      continue;
    }
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(static_cast<int>(row.size()), n);
    for (int k = 0; k < n; ++k)
      for (const auto& [v, x] : columns[cols[k]]) m(row[v], k) = x;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
    qr.setThreshold(kRankThreshold);
    for (int k = static_cast<int>(qr.rank()); k < n; ++k)
      out.push_back(pressure_of[cols[qr.colsPermutation().indices()[k]]]);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The saddle-point system of Stokes flow, [[A, Bᵀ], [B, 0]], and its block B.
struct StokesSystem {
  SparseMatrix a, b;
};

// Unknowns: velocity (x, y) of P2 unknown i at 2i, 2i + 1, then the pressures from 2 nv on.
// B (np × 2 nv): B(j, 2i + c) = −∫ ψj ∂φi/∂xc.
StokesSystem assemble_stokes(const Geometry& geometry, const Space& velocity, const Space& pressure, double mu) {
  const int nv = velocity.size(), np = pressure.size();
  const int size = 2 * nv + np;
  const Quadrature q = triangle_quadrature(quadrature_degree(geometry, velocity));
  std::vector<Eigen::VectorXd> psi;  // P1 values at the quadrature points (no geometry needed)
  for (const Vec2& xi : q.points) psi.push_back(pressure.basis().values(xi));
  ElementValues ev;
  Triplets viscous_triplets, divergence_triplets;
  viscous_triplets.reserve(std::size_t(geometry.triangle_count()) * 72);
  divergence_triplets.reserve(std::size_t(geometry.triangle_count()) * 36);
  Eigen::MatrixXd viscous(6, 6);
  Eigen::MatrixXd divergence(3, 12);
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, velocity, q, t);
    viscous.setZero();
    divergence.setZero();
    for (int p = 0; p < ev.points(); ++p) {
      viscous.noalias() += (mu * ev.weight[p]) * ev.grad[p] * ev.grad[p].transpose();
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 6; ++i)
          for (int c = 0; c < 2; ++c) divergence(j, 2 * i + c) -= ev.weight[p] * psi[p](j) * ev.grad[p](i, c);
    }
    const auto dv = velocity.dofs(t);
    const auto dp = pressure.dofs(t);
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 6; ++k)
        for (int c = 0; c < 2; ++c)
          viscous_triplets.emplace_back(2 * dv[i] + c, 2 * dv[k] + c, viscous(i, k));
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 6; ++i)
        for (int c = 0; c < 2; ++c)
          divergence_triplets.emplace_back(dp[j], 2 * dv[i] + c, divergence(j, 2 * i + c));
  }
  StokesSystem out;
  out.b = SparseMatrix(np, 2 * nv);
  out.b.setFromTriplets(divergence_triplets.begin(), divergence_triplets.end());
  Triplets triplets = std::move(viscous_triplets);
  triplets.reserve(triplets.size() + 2 * out.b.nonZeros());
  for (int col = 0; col < out.b.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(out.b, col); it; ++it) {
      triplets.emplace_back(2 * nv + it.row(), col, it.value());
      triplets.emplace_back(col, 2 * nv + it.row(), it.value());
    }
  out.a = SparseMatrix(size, size);
  out.a.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

// The velocities the conditions prescribe, at the P2 unknowns of their edges.
void set_velocities(const Geometry& geometry, const Space& velocity, const std::vector<VelocityCondition>& conditions,
                    Dirichlet& dirichlet) {
  for (const VelocityCondition& condition : conditions)
    for (const auto& [t, e] : condition.edges) {
      const auto d = velocity.dofs(t);
      for (int i : velocity.edge_local_dofs(e)) {
        const Vec2 u = condition.velocity(geometry.map(t, velocity.reference_points()[i]));
        dirichlet.set(2 * d[i], u.x());
        dirichlet.set(2 * d[i] + 1, u.y());
      }
    }
}

}  // namespace

StokesResult stokes(const Geometry& geometry, const Space& velocity, const Space& pressure,
                    const std::vector<VelocityCondition>& conditions, const StokesOptions& options) {
  if (velocity.degree() != 2 || pressure.degree() != 1)
    throw std::invalid_argument("Stokes flow takes P2 velocity and P1 pressure (Taylor-Hood)");
  if (!(options.viscosity > 0) || !std::isfinite(options.viscosity))
    throw std::invalid_argument("the viscosity must be positive and finite");
  if (options.dense_group_limit < 0) throw std::invalid_argument("dense_group_limit must not be negative");
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const int nv = velocity.size(), np = pressure.size();
  const int size = 2 * nv + np;
  const double mu = options.viscosity;

  const StokesSystem system = assemble_stokes(geometry, velocity, pressure, mu);
  const SparseMatrix& a = system.a;
  const SparseMatrix& b = system.b;
  Dirichlet dirichlet(size);
  set_velocities(geometry, velocity, conditions, dirichlet);
  StokesResult r;
  r.velocity_unknowns = 2 * nv;
  r.pressure_unknowns = np;
  r.fixed_velocities = dirichlet.fixed_count();
  const std::vector<int> references = closed_part_references(geometry.mesh(), pressure, conditions);
  for (int j : references) dirichlet.set(2 * nv + j, 0.0);
  r.closed_parts = static_cast<int>(references.size());
  auto hold = [&](int largest) {
    const std::vector<int> more = dependent_pressures(b, dirichlet, nv, largest, options.dense_group_limit);
    for (int j : more) dirichlet.set(2 * nv + j, 0.0);
    r.dependent_pressures += static_cast<int>(more.size());
  };
  hold(options.dense_group_limit);
  const auto t1 = Clock::now();
  r.assembly_seconds = std::chrono::duration<double>(t1 - t0).count();

  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  Eigen::VectorXd x;
  try {
    x = solve(a, zero, dirichlet, false);
  } catch (const std::runtime_error&) {
    // The small groups were not all: look for dependent pressures in the large ones too.
    hold(np);
    x = solve(a, zero, dirichlet, false);
  }
  r.solve_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
  r.velocity = x.head(2 * nv);
  r.pressure = x.tail(np);
  return r;
}

}  // namespace curvemesh::fem
