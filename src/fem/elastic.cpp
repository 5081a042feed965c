#include "fem/elastic.hpp"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <stdexcept>

#include "fem/output.hpp"

namespace curvemesh::fem {

Lame lame_parameters(double youngs_modulus, double poisson_ratio) {
  if (!(youngs_modulus > 0) || !(poisson_ratio > -1) || !(poisson_ratio < 0.5))
    throw std::invalid_argument("Young's modulus must be positive and Poisson's ratio in (-1, 0.5)");
  const double e = youngs_modulus, nu = poisson_ratio;
  return {e / (2 * (1 + nu)), e * nu / ((1 + nu) * (1 - 2 * nu))};
}

double neo_hookean_energy(const Lame& m, const Eigen::Matrix2d& f) {
  const double log_j = std::log(f.determinant());
  return 0.5 * m.mu * (f.squaredNorm() - 2) - m.mu * log_j + 0.5 * m.lambda * log_j * log_j;
}

Eigen::Matrix2d neo_hookean_stress(const Lame& m, const Eigen::Matrix2d& f) {
  const Eigen::Matrix2d h = f.inverse().transpose();
  return m.mu * (f - h) + m.lambda * std::log(f.determinant()) * h;
}

namespace {

// dP for P = μ (F − H) + λ ln J H with H = F⁻ᵀ: dH = −H dFᵀ H and d ln J = H : dF, so
// dP = μ dF + (μ − λ ln J) H dFᵀ H + λ (H : dF) H.
Eigen::Matrix2d stress_derivative(const Lame& m, const Eigen::Matrix2d& h, double log_j, const Eigen::Matrix2d& df) {
  return m.mu * df + (m.mu - m.lambda * log_j) * h * df.transpose() * h + m.lambda * h.cwiseProduct(df).sum() * h;
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

Eigen::Matrix2d neo_hookean_stress_derivative(const Lame& m, const Eigen::Matrix2d& f, const Eigen::Matrix2d& df) {
  return stress_derivative(m, f.inverse().transpose(), std::log(f.determinant()), df);
}

NeoHookean::NeoHookean(const Geometry& geometry, const Space& space, std::vector<char> clamped, ElasticOptions options)
    : geometry_(geometry), space_(space), clamped_(std::move(clamped)), options_(options) {
  if (static_cast<int>(clamped_.size()) != space.size())
    throw std::invalid_argument("NeoHookean: one clamped flag per unknown of the space");
  const int degree =
      options_.quadrature_degree > 0 ? options_.quadrature_degree : fem::quadrature_degree(geometry, space);
  quadrature_ = triangle_quadrature(degree);
  const LagrangeBasis map_basis(geometry.order());
  Eigen::VectorXd v;
  Eigen::MatrixX2d g;
  for (const Vec2& xi : quadrature_.points) {
    map_basis.evaluate(xi, v, g);
    map_gradients_.push_back(g);
    space.basis().evaluate(xi, v, g);
    basis_gradients_.push_back(g);
  }
  // The body force is constant: its work is a fixed linear form, assembled once.
  load_ = Eigen::VectorXd::Zero(size());
  const Quadrature q = quadrature_;
  ElementValues ev;
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, space, q, t);
    const auto d = space.dofs(t);
    for (int p = 0; p < ev.points(); ++p)
      for (int a = 0; a < space.local_size(); ++a)
        for (int c = 0; c < 2; ++c) load_[2 * d[a] + c] += ev.weight[p] * ev.value[p](a) * options_.body_force[c];
  }
}

template <class Visit>
bool NeoHookean::for_each_point(const Eigen::VectorXd& u, Visit visit) const {
  const io::HighOrderMesh& mesh = geometry_.mesh();
  const int n = space_.local_size();
  Eigen::MatrixX2d nodes(mesh.triangle_size(), 2), local_u(n, 2), g(n, 2);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto tri = mesh.triangle(t);
    for (int i = 0; i < mesh.triangle_size(); ++i) nodes.row(i) = mesh.nodes[tri[i]].transpose();
    const auto d = space_.dofs(t);
    for (int a = 0; a < n; ++a) local_u.row(a) << u[2 * d[a]], u[2 * d[a] + 1];
    for (int p = 0; p < quadrature_.size(); ++p) {
      const Eigen::Matrix2d j = nodes.transpose() * map_gradients_[p];  // ∂x/∂ξ
      const double det = j.determinant();
      g.noalias() = basis_gradients_[p] * j.inverse();  // ∇x φ = J⁻ᵀ ∇ξ φ, as rows
      const Eigen::Matrix2d f = Eigen::Matrix2d::Identity() + local_u.transpose() * g;
      if (!(f.determinant() > 0)) return false;
      visit(t, quadrature_.weights[p] * std::abs(det), g, f);
    }
  }
  return true;
}

double NeoHookean::energy(const Eigen::VectorXd& u, double load) const {
  double internal = 0;
  const Lame& m = options_.material;
  const bool ok = for_each_point(u, [&](int, double w, const Eigen::MatrixX2d&, const Eigen::Matrix2d& f) {
    internal += w * neo_hookean_energy(m, f);
  });
  if (!ok) return std::numeric_limits<double>::infinity();
  return internal - load * load_.dot(u);
}

bool NeoHookean::admissible(const Eigen::VectorXd& u) const {
  return for_each_point(u, [](int, double, const Eigen::MatrixX2d&, const Eigen::Matrix2d&) {});
}

Eigen::VectorXd NeoHookean::residual(const Eigen::VectorXd& u, double load) const {
  Eigen::VectorXd r = -load * load_;
  const Lame& m = options_.material;
  Eigen::MatrixX2d local(space_.local_size(), 2);
  // Where det F <= 0 the stress has no value: the residual is NaN (the line search never goes there).
  const bool ok = for_each_point(u, [&](int t, double w, const Eigen::MatrixX2d& g, const Eigen::Matrix2d& f) {
    // R_(a,i) = ∫ P_ij ∂_j φ_a: the rows of G Pᵀ.
    local.noalias() = w * g * neo_hookean_stress(m, f).transpose();
    const auto d = space_.dofs(t);
    for (int a = 0; a < space_.local_size(); ++a) r[2 * d[a]] += local(a, 0), r[2 * d[a] + 1] += local(a, 1);
  });
  if (!ok) r.setConstant(std::numeric_limits<double>::quiet_NaN());
  return r;
}

SparseMatrix NeoHookean::assemble_tangent(const Eigen::VectorXd& u, const std::vector<int>& index, int size) const {
  const Lame& m = options_.material;
  const int n = space_.local_size();
  Eigen::MatrixXd k(2 * n, 2 * n);
  Triplets triplets;
  triplets.reserve(std::size_t(geometry_.triangle_count()) * 4 * n * n);
  int current = -1;
  auto flush = [&] {
    if (current < 0) return;
    const auto d = space_.dofs(current);
    for (int a = 0; a < 2 * n; ++a) {
      const int row = index[2 * d[a / 2] + a % 2];
      if (row < 0) continue;
      for (int b = 0; b < 2 * n; ++b) {
        const int col = index[2 * d[b / 2] + b % 2];
        if (col >= 0) triplets.emplace_back(row, col, k(a, b));
      }
    }
  };
  // K_(a,i),(b,k) = ∫ ∂_j φ_a A_ijkl ∂_l φ_b with A = ∂P/∂F, from dP above:
  // A_ijkl = μ δ_ik δ_jl + (μ − λ ln J) H_il H_kj + λ H_ij H_kl.
  std::vector<std::array<double, 8>> contracted(n);  // per b: Σ_l A_ijkl ∂_l φ_b at (i, j, k)
  const bool ok = for_each_point(u, [&](int t, double w, const Eigen::MatrixX2d& g, const Eigen::Matrix2d& f) {
    if (t != current) {
      flush();
      current = t;
      k.setZero();
    }
    const Eigen::Matrix2d h = f.inverse().transpose();
    const double c = m.mu - m.lambda * std::log(f.determinant());
    double a[2][2][2][2];
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int q = 0; q < 2; ++q)
          for (int l = 0; l < 2; ++l)
            a[i][j][q][l] = (i == q && j == l ? m.mu : 0.0) + c * h(i, l) * h(q, j) + m.lambda * h(i, j) * h(q, l);
    for (int b = 0; b < n; ++b)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          for (int q = 0; q < 2; ++q)
            contracted[b][4 * i + 2 * j + q] = a[i][j][q][0] * g(b, 0) + a[i][j][q][1] * g(b, 1);
    for (int p = 0; p < n; ++p) {
      const double gx = w * g(p, 0), gy = w * g(p, 1);
      for (int b = 0; b < n; ++b) {
        const auto& cb = contracted[b];
        for (int i = 0; i < 2; ++i)
          for (int q = 0; q < 2; ++q) k(2 * p + i, 2 * b + q) += gx * cb[4 * i + q] + gy * cb[4 * i + 2 + q];
      }
    }
  });
  if (!ok) throw std::domain_error("NeoHookean::tangent: det F <= 0 at a quadrature point");
  flush();
  SparseMatrix a(size, size);
  a.setFromTriplets(triplets.begin(), triplets.end());
  return a;
}

SparseMatrix NeoHookean::tangent(const Eigen::VectorXd& u) const {
  std::vector<int> index(size());
  for (int i = 0; i < size(); ++i) index[i] = i;
  return assemble_tangent(u, index, size());
}

namespace {

using Cholesky = Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower>;

// The free unknowns (not clamped) and the map between them and all unknowns.
struct FreeUnknowns {
  std::vector<int> index;  // per unknown: its place among the free ones, −1 when clamped
  std::vector<int> free;   // per free unknown: the unknown
  Eigen::VectorXd restrict(const Eigen::VectorXd& full) const {
    Eigen::VectorXd out(free.size());
    for (std::size_t i = 0; i < free.size(); ++i) out[i] = full[free[i]];
    return out;
  }
  Eigen::VectorXd expand(const Eigen::VectorXd& part, int n) const {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
    for (std::size_t i = 0; i < free.size(); ++i) out[free[i]] = part[i];
    return out;
  }
};

// The Newton step: the exact tangent's first; where it is not positive definite (the
// factorisation fails) or its step is no descent direction (round-off in a nearly singular one),
// K + τ diag(K) with τ growing tenfold, from a tenth of the last shift that worked (the tangent
// changes little between steps). Sets it.shift; returns the step and its slope ∇Π·d (not negative
// when no shift up to 1e8 gave a descent direction).
std::pair<Eigen::VectorXd, double> descent_step(Cholesky& cholesky, const SparseMatrix& tangent,
                                                const Eigen::VectorXd& r, double last_shift, NewtonIteration& it) {
  const Eigen::Index m = tangent.rows();
  Eigen::VectorXd step;
  double slope = 0;
  SparseMatrix diagonal;
  for (;;) {
    if (it.shift == 0) {
      cholesky.factorize(tangent);
    } else {
      if (diagonal.size() == 0) {
        diagonal.resize(m, m);
        diagonal.reserve(Eigen::VectorXi::Constant(m, 1));
        for (Eigen::Index i = 0; i < m; ++i) diagonal.insert(i, i) = std::max(std::abs(tangent.coeff(i, i)), 1e-300);
      }
      cholesky.factorize(tangent + it.shift * diagonal);
    }
    if (cholesky.info() == Eigen::Success) {
      step = cholesky.solve(-r);
      slope = r.dot(step);
      if (slope < 0) break;
    }
    it.shift = it.shift == 0 ? std::max(1e-8, 0.1 * last_shift) : 10 * it.shift;
    if (it.shift > 1e8) break;
  }
  return {step, slope};
}

// A point along the step accepted by the line search.
struct Accepted {
  Eigen::VectorXd u, residual;
  double energy = 0, alpha = 0;
};

// Backtracking on Π from u (energy e, residual norm `residual_norm`) along `step` (slope ∇Π·d);
// det F <= 0 gives Π = +∞ and is never accepted. Near the solution the full step lowers Π by less
// than Π's round-off (`flat`): there a step that lowers the residual without raising Π beyond its
// round-off is taken. Sets it.backtracks.
std::optional<Accepted> line_search(const NeoHookean& p, const FreeUnknowns& unknowns, const Eigen::VectorXd& u,
                                    const Eigen::VectorXd& step, double e, double slope, double load,
                                    NewtonIteration& it) {
  const ElasticOptions& o = p.options();
  const bool flat = -slope <= 1e-11 * std::abs(e);
  double alpha = 1;
  for (it.backtracks = 0; it.backtracks <= o.max_backtracks; ++it.backtracks, alpha *= 0.5) {
    Eigen::VectorXd trial = u + alpha * step;
    const double trial_e = p.energy(trial, load);
    if (!std::isfinite(trial_e)) continue;
    const bool armijo = trial_e <= e + o.armijo * alpha * slope;
    if (!armijo && !(flat && trial_e - e <= 1e-12 * (std::abs(e) + std::abs(trial_e)))) continue;
    Eigen::VectorXd trial_r = unknowns.restrict(p.residual(trial, load));
    if (armijo || trial_r.norm() < it.residual) return Accepted{std::move(trial), std::move(trial_r), trial_e, alpha};
  }
  return std::nullopt;
}

}  // namespace

// Newton's method with a line search on Π, the load applied in equal steps; the tangent factored
// by CHOLMOD's LLᵀ, which fails on a matrix that is not positive definite (its automatic choice may
// be an LDLᵀ, which factors indefinite matrices without a word); simplicial, which is faster than
// supernodal here at every size measured (2 000 to 45 000 unknowns).
ElasticResult NeoHookean::solve() const {
  const auto start = Clock::now();
  ElasticResult result;
  const int n = size();
  result.unknowns = n;
  FreeUnknowns unknowns{std::vector<int>(n, -1), {}};
  for (int i = 0; i < n; ++i)
    if (!fixed(i)) unknowns.index[i] = static_cast<int>(unknowns.free.size()), unknowns.free.push_back(i);
  const int m = static_cast<int>(unknowns.free.size());
  result.free_unknowns = m;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  result.displacement = u;
  const double r0 = unknowns.restrict(load_).norm();  // R(0) = −f: the scale the tolerance is relative to
  result.initial_residual = r0;
  const double target = options_.tolerance * r0;
  if (m == 0 || r0 == 0) {
    result.converged = true;
    result.iterations.push_back({1, 0, 0.0, 0.0, 0.0, 0, 0.0});
    result.seconds = seconds_since(start);
    return result;
  }
  Cholesky cholesky;
  cholesky.setMode(Eigen::CholmodSimplicialLLt);
  cholesky.cholmod().print = 0;  // a failed factorisation is expected (an indefinite tangent), not news
  bool analysed = false;
  const auto stop = [&](const NewtonIteration& it, std::string why, double e) {  // where it stands, saying why
    result.iterations.push_back(it);
    result.failure = std::move(why);
    result.displacement = u;
    result.energy = e;
    result.seconds = seconds_since(start);
    return result;
  };
  double last_shift = 0;
  const int steps = std::max(1, options_.load_steps);
  for (int s = 1; s <= steps; ++s) {
    const double load = double(s) / steps;
    auto t = Clock::now();
    double e = energy(u, load);
    Eigen::VectorXd r = unknowns.restrict(residual(u, load));
    result.assembly_seconds += seconds_since(t);
    for (int k = 0;; ++k) {
      NewtonIteration it{s, k, r.norm(), e, 0.0, 0, 0.0};
      if (it.residual <= target) {
        result.iterations.push_back(it);
        break;
      }
      if (!std::isfinite(it.residual) || k == options_.max_iterations)
        return stop(it, std::isfinite(it.residual) ? "no convergence in " + std::to_string(k) + " Newton iterations"
                                                    : "the residual is not finite", e);
      t = Clock::now();
      const SparseMatrix tangent = assemble_tangent(u, unknowns.index, m);
      result.assembly_seconds += seconds_since(t);
      t = Clock::now();
      if (!analysed) cholesky.analyzePattern(tangent), analysed = true;
      const auto [step, slope] = descent_step(cholesky, tangent, r, last_shift, it);
      result.factor_seconds += seconds_since(t);
      if (it.shift > 0) last_shift = it.shift;
      if (!(slope < 0)) return stop(it, "the tangent could not be made positive definite", e);
      t = Clock::now();
      std::optional<Accepted> next = line_search(*this, unknowns, u, unknowns.expand(step, n), e, slope, load, it);
      result.assembly_seconds += seconds_since(t);
      if (!next) return stop(it, "the line search found no step that lowers the energy", e);
      it.step_length = next->alpha;
      result.iterations.push_back(it);
      u = std::move(next->u);
      e = next->energy;
      r = std::move(next->residual);
    }
  }
  result.converged = true;
  result.displacement = u;
  result.energy = energy(u, 1.0);
  result.seconds = seconds_since(start);
  return result;
}

std::vector<char> hang_from_top(const Geometry& geometry, const Space& space, double band) {
  const io::HighOrderMesh& mesh = geometry.mesh();
  const int nt = mesh.triangle_count();
  // Pieces: triangles connected through shared edges (union–find).
  std::vector<int> parent(nt);
  for (int t = 0; t < nt; ++t) parent[t] = t;
  auto find = [&](int t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  std::map<std::pair<int, int>, int> edge_owner;
  for (int t = 0; t < nt; ++t) {
    const auto tri = mesh.triangle(t);
    for (int e = 0; e < 3; ++e) {
      const int a = tri[e], b = tri[(e + 1) % 3];
      auto [it, inserted] = edge_owner.try_emplace({std::min(a, b), std::max(a, b)}, t);
      if (!inserted) parent[find(t)] = find(it->second);
    }
  }
  const std::vector<Vec2> position = space.positions(geometry);
  const std::vector<std::pair<int, int>> border = boundary_edges(mesh);
  std::map<int, double> top;  // per piece, the smallest y of its border
  for (const auto& [t, e] : border) {
    const auto d = space.dofs(t);
    for (int i : space.edge_local_dofs(e)) {
      auto [it, inserted] = top.try_emplace(find(t), position[d[i]].y());
      if (!inserted) it->second = std::min(it->second, position[d[i]].y());
    }
  }
  std::vector<char> clamped(space.size(), 0);
  std::map<int, int> topmost;  // per piece, its highest border unknown
  for (const auto& [t, e] : border) {
    const auto d = space.dofs(t);
    const int piece = find(t);
    for (int i : space.edge_local_dofs(e)) {
      if (position[d[i]].y() <= top[piece] + band) clamped[d[i]] = 1;
      auto [it, inserted] = topmost.try_emplace(piece, d[i]);
      if (position[d[i]].y() < position[it->second].y()) it->second = d[i];
    }
  }
  // A piece held by no whole border edge (a rounded or pointed top: a point, or a point and an
  // edge's middle) could swing about it, or nearly: it also hangs by the border edges through
  // its topmost point.
  std::map<int, char> holds_an_edge;
  for (const auto& [t, e] : border) {
    const auto d = space.dofs(t);
    const std::vector<int> local = space.edge_local_dofs(e);
    if (std::all_of(local.begin(), local.end(), [&](int i) { return clamped[d[i]] != 0; })) holds_an_edge[find(t)] = 1;
  }
  for (const auto& [t, e] : border) {
    const int piece = find(t);
    if (holds_an_edge[piece]) continue;
    const auto d = space.dofs(t);
    const std::vector<int> local = space.edge_local_dofs(e);
    if (std::none_of(local.begin(), local.end(), [&](int i) { return d[i] == topmost[piece]; })) continue;
    for (int i : local) clamped[d[i]] = 1;
  }
  return clamped;
}

bool displacement_at(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u, const Vec2& x,
                     Vec2& value) {
  const io::HighOrderMesh& mesh = geometry.mesh();
  const double tol = 1e-9;
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    Vec2 lo = mesh.nodes[mesh.triangle(t)[0]], hi = lo;
    for (int i : mesh.triangle(t)) lo = lo.cwiseMin(mesh.nodes[i]), hi = hi.cwiseMax(mesh.nodes[i]);
    // A curved edge bulges less than a quarter of the nodes' box beyond it in a valid triangle.
    const Vec2 grow = (hi - lo) * (mesh.order > 1 ? 0.25 : 0.0) + Vec2::Constant(tol * (hi - lo).norm());
    if ((x - (lo - grow)).minCoeff() < 0 || ((hi + grow) - x).minCoeff() < 0) continue;
    Vec2 xi;
    if (!geometry.inverse(t, x, xi)) continue;
    if (xi.x() < -tol || xi.y() < -tol || xi.x() + xi.y() > 1 + tol) continue;
    value = Vec2(value_at(space, u, t, xi, 2, 0), value_at(space, u, t, xi, 2, 1));
    return true;
  }
  return false;
}

double displacement_l2_norm(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u) {
  const Quadrature q = triangle_quadrature(quadrature_degree(geometry, space));
  ElementValues ev;
  double sum = 0;
  for (int t = 0; t < geometry.triangle_count(); ++t) {
    ev.compute(geometry, space, q, t);
    const auto d = space.dofs(t);
    for (int p = 0; p < ev.points(); ++p) {
      Vec2 v = Vec2::Zero();
      for (int a = 0; a < space.local_size(); ++a) v += ev.value[p](a) * Vec2(u[2 * d[a]], u[2 * d[a] + 1]);
      sum += ev.weight[p] * v.squaredNorm();
    }
  }
  return std::sqrt(sum);
}

DeformedMesh deformed_mesh(const Geometry& geometry, const Space& space, const Eigen::VectorXd& u) {
  const io::HighOrderMesh& mesh = geometry.mesh();
  DeformedMesh out;
  if (mesh.order >= 2) {
    out.mesh = mesh;
  } else {
    // Order 2 over the same corners: one new node per edge, at its midpoint.
    out.mesh.order = 2;
    out.mesh.nodes = mesh.nodes;
    out.mesh.physical_names = mesh.physical_names;
    std::map<std::pair<int, int>, int> midpoint;
    auto node_between = [&](int a, int b) {
      auto [it, inserted] = midpoint.try_emplace({std::min(a, b), std::max(a, b)}, int(out.mesh.nodes.size()));
      if (inserted) out.mesh.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
      return it->second;
    };
    for (int t = 0; t < mesh.triangle_count(); ++t) {
      const auto tri = mesh.triangle(t);
      const int nodes[6] = {tri[0], tri[1], tri[2], node_between(tri[0], tri[1]), node_between(tri[1], tri[2]),
                            node_between(tri[2], tri[0])};
      out.mesh.add_triangle(nodes, mesh.triangle_physical[t]);
    }
    for (int l = 0; l < mesh.line_count(); ++l) {
      const auto line = mesh.line(l);
      const auto it = midpoint.find({std::min(line[0], line[1]), std::max(line[0], line[1])});
      if (it == midpoint.end()) continue;  // not an edge of the domain's triangles
      const int nodes[3] = {line[0], line[1], it->second};
      out.mesh.add_line(nodes, mesh.line_physical[l]);
    }
  }
  // u at each node, from a triangle it belongs to (u is continuous).
  const std::vector<Vec2> ref = reference_nodes(out.mesh.order);
  out.displacement.assign(out.mesh.nodes.size() * 3, 0.0);
  for (int t = 0; t < out.mesh.triangle_count(); ++t) {
    const auto tri = out.mesh.triangle(t);
    for (std::size_t k = 0; k < ref.size(); ++k)
      for (int c = 0; c < 2; ++c) out.displacement[std::size_t(tri[k]) * 3 + c] = value_at(space, u, t, ref[k], 2, c);
  }
  for (std::size_t i = 0; i < out.mesh.nodes.size(); ++i)
    out.mesh.nodes[i] += Vec2(out.displacement[3 * i], out.displacement[3 * i + 1]);
  return out;
}

}  // namespace curvemesh::fem
