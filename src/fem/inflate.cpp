#include "fem/inflate.hpp"

#include <chrono>

#include "fem/assembly.hpp"

namespace curvemesh::fem {

InflateResult inflate(const Geometry& geometry, const Space& space, double load) {
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  const int n = space.size();
  const SparseMatrix m = mass_matrix(geometry, space);
  const SparseMatrix k = stiffness_matrix(geometry, space);
  const Eigen::VectorXd f = load_vector(geometry, space, [load](const Vec2&) { return load; });
  // Unknowns: w first (0..n-1), then u (n..2n-1).
  Triplets triplets;
  triplets.reserve(m.nonZeros() + 2 * k.nonZeros());
  for (int c = 0; c < n; ++c) {
    for (SparseMatrix::InnerIterator it(m, c); it; ++it) triplets.emplace_back(it.row(), c, it.value());
    for (SparseMatrix::InnerIterator it(k, c); it; ++it) {
      triplets.emplace_back(it.row(), n + c, -it.value());
      triplets.emplace_back(n + it.row(), c, -it.value());
    }
  }
  SparseMatrix a(2 * n, 2 * n);
  a.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * n);
  b.tail(n) = -f;
  Dirichlet dirichlet(2 * n);
  Dirichlet border(n);
  set_on_edges(geometry, space, boundary_edges(geometry.mesh()), [](const Vec2&) { return 0.0; }, border);
  for (int i = 0; i < n; ++i)
    if (border.fixed[i]) dirichlet.set(n + i, 0.0);
  InflateResult r;
  r.unknowns = 2 * n;
  auto t1 = Clock::now();
  r.assembly_seconds = std::chrono::duration<double>(t1 - t0).count();
  const Eigen::VectorXd x = solve(a, b, dirichlet, false);
  r.solve_seconds = std::chrono::duration<double>(Clock::now() - t1).count();
  r.w = x.head(n);
  r.height = x.tail(n);
  return r;
}

}  // namespace curvemesh::fem
