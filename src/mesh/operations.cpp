#include "mesh/operations.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/container/small_vector.hpp>
#include <cmath>
#include <limits>
#include <span>

#include "geometry/amips.hpp"
#include "geometry/bezier_analysis.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/vec2.hpp"
#include "mesh/invariants.hpp"

namespace curvemesh::mesh {

double SectionCurve::turning(double ta, double tb) const {
  const double lo = std::min(ta, tb), hi = std::max(ta, tb);
  const double a = std::clamp(local(lo), 0.0, 1.0), b = std::clamp(local(hi), 0.0, 1.0);
  return monotone ? geometry::end_tangent_angle(piece, a, b) : geometry::turning_angle(piece, a, b);
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Orientation of (x, y, p) for a point p that is not (yet) a vertex; exact.
int orientation_new(const TriMesh& m, int x, int y, const Vec2& p) {
  if (!m.has_exact(x) && !m.has_exact(y)) return geometry::orientation(m.point(x), m.point(y), p);
  return geometry::orientation(m.exact_or_double(x), m.exact_or_double(y), ExactPoint(p));
}

// The parameter a primary edge (a, b) stores at its endpoint x (x is a or b).
double param_at(const EdgeFeature& f, int a, int b, int x) { return x == std::min(a, b) ? f.t_lo : f.t_hi; }

void set_param_at(EdgeFeature& f, int a, int b, int x, double t) { (x == std::min(a, b) ? f.t_lo : f.t_hi) = t; }

EdgeFeature primary_edge(const EdgeFeature& like, int a, double ta, int b, double tb) {
  EdgeFeature f = like;
  f.t_lo = a < b ? ta : tb;
  f.t_hi = a < b ? tb : ta;
  return f;
}

// The corner after x in triangle tri, counter-clockwise.
int next_corner(const Triangle& tri, int x) { return tri[0] == x ? tri[1] : tri[1] == x ? tri[2] : tri[0]; }
int prev_corner(const Triangle& tri, int x) { return tri[0] == x ? tri[2] : tri[1] == x ? tri[0] : tri[1]; }

// The triangle with directed edge a -> b (counter-clockwise), and its third corner; -1 if none.
std::pair<int, int> triangle_left_of(const TriMesh& m, int a, int b) {
  for (int t : m.triangles_of(a))
    if (next_corner(m.triangle(t), a) == b) return {t, prev_corner(m.triangle(t), a)};
  return {-1, -1};
}

double max_amips_of(const TriMesh& m, std::span<const int> triangles) {
  double e = 0;
  for (int t : triangles) {
    const auto& tri = m.triangle(t);
    e = std::max(e, geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])));
  }
  return e;
}

// The summed and the largest AMIPS energy of v's triangles with v at p (the sum infinite if one
// is not positive in doubles), in one pass.
struct StarEnergy {
  double sum = 0, max = 0;
};
StarEnergy star_energy(const TriMesh& m, int v, const Vec2& p) {
  StarEnergy e;
  for (int t : m.triangles_of(v)) {
    const auto& tri = m.triangle(t);
    const double a = geometry::amips(p, m.point(next_corner(tri, v)), m.point(prev_corner(tri, v)));
    e.sum += a;
    e.max = std::max(e.max, a);
  }
  return e;
}

// Whether v's star with v at p has a smaller summed energy than `sum` and no triangle above
// `max`: star_energy's verdict, but it stops at the first triangle that decides it (the energies
// are positive, so the running sum never decreases). Most positions a line search tries fail.
bool star_improves(const TriMesh& m, int v, const Vec2& p, double sum, double max) {
  double e = 0;
  for (int t : m.triangles_of(v)) {
    const auto& tri = m.triangle(t);
    const double a = geometry::amips(p, m.point(next_corner(tri, v)), m.point(prev_corner(tri, v)));
    if (!(a <= max)) return false;
    e += a;
    if (!(e < sum)) return false;
  }
  return true;
}

geometry::AmipsDerivatives star_derivatives(const TriMesh& m, int v, const Vec2& p) {
  geometry::AmipsDerivatives sum;
  for (int t : m.triangles_of(v)) {
    const auto& tri = m.triangle(t);
    const auto d = geometry::amips_derivatives(p, m.point(next_corner(tri, v)), m.point(prev_corner(tri, v)));
    sum.energy += d.energy;
    sum.gradient += d.gradient;
    sum.hessian += d.hessian;
  }
  return sum;
}

// The two primary edges of a primary vertex: the neighbours along its section and their params.
struct CurveNeighbours {
  int x = -1, y = -1;
  double tx = 0, ty = 0;
};
bool curve_neighbours(const TriMesh& m, int v, CurveNeighbours& out) {
  const VertexTag& tag = m.tag(v);
  int found = 0;
  for (const TaggedEdge& e : m.tagged_edges(v)) {
    const EdgeFeature& f = e.feature;
    const int w = e.other;
    if (f.kind != EdgeKind::primary || f.source != tag.section) continue;
    if (found == 0) out.x = w, out.tx = param_at(f, v, w, w);
    else if (found == 1) out.y = w, out.ty = param_at(f, v, w, w);
    ++found;
  }
  return found == 2;
}

// Moves a primary vertex to parameter t (on the curve) if every invariant allows it.
bool try_curve_move(TriMesh& m, const Constraints& c, int v, const CurveNeighbours& n, double t) {
  const SectionCurve& curve = c.sections[m.tag(v).section];
  const Vec2 p = curve.eval(t);
  if (!p.allFinite()) return false;
  if (curve.turning(n.tx, t) > turning_limit(c)) return false;
  if (curve.turning(t, n.ty) > turning_limit(c)) return false;
  if (!star_valid_at(m, v, p) || !secondary_edges_inside(m, c, v, p)) return false;
  m.set_position(v, p);
  VertexTag tag = m.tag(v);
  tag.t = t;
  tag.on_curve = true;
  m.set_tag(v, tag);
  for (int w : {n.x, n.y}) {
    EdgeFeature f = *m.feature(v, w);
    set_param_at(f, v, w, v, t);
    m.set_feature(v, w, f);
  }
  return true;
}

// The neighbours of a boundary vertex along its side.
bool side_neighbours(const TriMesh& m, int v, int& x, int& y) {
  x = y = -1;
  for (const TaggedEdge& e : m.tagged_edges(v))
    if (e.feature.kind == EdgeKind::boundary) (x < 0 ? x : y) = e.other;
  return x >= 0 && y >= 0;
}

}  // namespace

int split_edge(TriMesh& m, const Constraints& c, int a, int b, double energy_bound) {
  // Named without structured bindings: the lambdas below use them, which clang before 16 refuses.
  const std::pair<int, int> left = triangle_left_of(m, a, b), right = triangle_left_of(m, b, a);
  const int t1 = left.first, cc = left.second, t2 = right.first, d = right.second;
  if (t1 < 0 && t2 < 0) return -1;
  const EdgeFeature* found = m.feature(a, b);
  const EdgeFeature f = found ? *found : EdgeFeature{};

  const auto valid = [&](const Vec2& p) {
    if (!p.allFinite()) return false;
    if (t1 >= 0 && (orientation_new(m, cc, a, p) <= 0 || orientation_new(m, b, cc, p) <= 0)) return false;
    if (t2 >= 0 && (orientation_new(m, d, b, p) <= 0 || orientation_new(m, a, d, p) <= 0)) return false;
    return true;
  };

  // The largest energy of the four (two on the box) new triangles with the new vertex at p.
  const auto new_energy = [&](const Vec2& p) {
    double e = 0;
    if (t1 >= 0) e = std::max({e, geometry::amips(m.point(a), p, m.point(cc)), geometry::amips(p, m.point(b), m.point(cc))});
    if (t2 >= 0) e = std::max({e, geometry::amips(m.point(b), p, m.point(d)), geometry::amips(p, m.point(a), m.point(d))});
    return e;
  };
  std::vector<int> old_triangles;
  for (int t : {t1, t2})
    if (t >= 0) old_triangles.push_back(t);
  const double old_energy = max_amips_of(m, old_triangles);

  Vec2 p = 0.5 * (m.point(a) + m.point(b));
  VertexTag tag;
  double ta = 0, tb = 0, tm = 0;
  switch (f.kind) {
    case EdgeKind::primary: {
      // §4.1: the new vertex goes to the middle of the curve's parameter interval if it can.
      ta = param_at(f, a, b, a);
      tb = param_at(f, a, b, b);
      tm = 0.5 * (ta + tb);
      tag.kind = VertexKind::primary;
      tag.section = f.source;
      tag.t = tm;
      const Vec2 on_curve = c.sections[f.source].eval(tm);
      tag.on_curve = valid(on_curve) && new_energy(on_curve) <= std::max(old_energy, energy_bound);
      if (tag.on_curve) p = on_curve;
      break;
    }
    case EdgeKind::secondary:
      tag.kind = VertexKind::secondary;
      break;
    case EdgeKind::boundary:
      tag.kind = VertexKind::boundary;
      tag.side = f.source;
      break;
    case EdgeKind::interior:
      break;
  }
  if (!valid(p)) return -1;
  if (f.kind == EdgeKind::secondary &&
      !(c.envelope.contains(m.point(a), p, f.curve) && c.envelope.contains(p, m.point(b), f.curve)))
    return -1;

  const int mid = m.add_vertex(p, tag);
  if (t1 >= 0) {
    m.set_triangle(t1, {a, mid, cc});
    m.add_triangle(mid, b, cc);
  }
  if (t2 >= 0) {
    m.set_triangle(t2, {b, mid, d});
    m.add_triangle(mid, a, d);
  }
  if (found) {
    m.clear_feature(a, b);
    if (f.kind == EdgeKind::primary) {
      m.set_feature(a, mid, primary_edge(f, a, ta, mid, tm));
      m.set_feature(mid, b, primary_edge(f, mid, tm, b, tb));
    } else {
      m.set_feature(a, mid, f);
      m.set_feature(mid, b, f);
    }
  }
  return mid;
}

namespace {

// collapse_allowed_by_kind with the edge's tag looked up already (`edge`, null when untagged).
bool allowed_by_kind(const VertexTag& tag, const EdgeFeature* edge) {
  if (tag.kind == VertexKind::fixed || tag.isolated) return false;
  switch (tag.kind) {
    case VertexKind::primary:
      return edge && edge->kind == EdgeKind::primary && edge->source == tag.section;
    case VertexKind::boundary:
      return edge && edge->kind == EdgeKind::boundary && edge->source == tag.side;
    case VertexKind::secondary:
      return !edge || edge->kind == EdgeKind::secondary;
    default:
      return !edge;
  }
}

}  // namespace

bool collapse_allowed_by_kind(const TriMesh& m, int from, int to) {
  return allowed_by_kind(m.tag(from), m.feature(from, to));
}

namespace {

// Stars and tag lists are short: the lists a collapse builds live on the stack unless one is not
// (a malloc and a free each cost about as much as the tests on tags).
template <class T>
using StarList = boost::container::small_vector<T, 16>;

// What a collapse of `from` into `to` does to the tagged edges of `from`: those that move to `to`
// (a curve edge with its parameter at `to`), the secondary ones that merge into an edge `to` has
// already, and the secondary ones to check against the envelope at their new place.
struct CollapseTags {
  struct Moved {
    int x;
    EdgeFeature f;
  };
  StarList<Moved> moved;
  StarList<int> merged;
  StarList<std::pair<int, int>> in_envelope;  // (x, the curve its edge stands for)
};

// The rules of a collapse on tags and curves alone: which vertices may move along which edge, how
// far a curve edge would turn, which tagged edges may merge. Fills `out` when given; false as soon
// as a rule refuses.
bool collapse_tags(const TriMesh& m, const Constraints& c, int from, int to, CollapseTags* out) {
  const EdgeFeature* edge = m.feature(from, to);
  if (!allowed_by_kind(m.tag(from), edge)) return false;
  for (const TaggedEdge& e : m.tagged_edges(from)) {
    const int x = e.other;
    if (x == to) continue;
    const EdgeFeature& g = e.feature;
    EdgeFeature h = g;
    if (g.kind == EdgeKind::primary) {
      if (!edge || edge->kind != EdgeKind::primary || edge->source != g.source) return false;
      const double tx = param_at(g, from, x, x), tt = param_at(*edge, from, to, to);
      if (c.sections[g.source].turning(tx, tt) > turning_limit(c)) return false;
      h = primary_edge(g, x, tx, to, tt);
    }
    if (out && g.kind == EdgeKind::secondary) out->in_envelope.push_back({x, g.curve});
    // Two tagged edges merge into one. A secondary edge only asks to stay inside the envelope, so
    // it may merge into any edge, which keeps the stronger tag; a curve or box side never merges
    // into another.
    if (const EdgeFeature* existing = m.feature(to, x)) {
      if (g.kind != EdgeKind::secondary && existing->kind != EdgeKind::secondary) return false;
      if (g.kind == EdgeKind::secondary) {
        if (out) out->merged.push_back(x);  // (to, x) keeps its own tag
        continue;
      }
    }
    if (out) out->moved.push_back({x, h});
  }
  return true;
}

}  // namespace

bool collapse_allowed_by_tags(const TriMesh& m, const Constraints& c, int from, int to) {
  return collapse_tags(m, c, from, to, nullptr);
}

namespace {

bool collapse_checked(TriMesh& m, const Constraints& c, int from, int to, double energy_bound, const CollapseTest* also) {
  // The tests on tags and curves refuse most collapses and are the cheapest: they come first, then
  // the caller's own, the energies, the exact orientations, the link condition and the envelope.
  CollapseTags tags;
  if (!collapse_tags(m, c, from, to, &tags)) return false;
  if (also && !(*also)(from, to)) return false;

  const std::vector<int>& star = m.triangles_of(from);  // read before the mesh changes
  StarList<int> removed, kept, opposite;
  for (int t : star) {
    const auto& tri = m.triangle(t);
    if (tri[0] == to || tri[1] == to || tri[2] == to) {
      removed.push_back(t);
      opposite.push_back(tri[0] != from && tri[0] != to ? tri[0] : tri[1] != from && tri[1] != to ? tri[1] : tri[2]);
    } else {
      kept.push_back(t);
    }
  }
  if (removed.empty()) return false;
  // Energy and orientation (exact) of the triangles that stay, with `from` replaced by `to`, the
  // energy before the exact test.
  double before = max_amips_of(m, star), after = 0;
  StarList<Triangle> replaced;
  for (int t : kept) {
    Triangle tri = m.triangle(t);
    for (int& v : tri)
      if (v == from) v = to;
    after = std::max(after, geometry::amips(m.point(tri[0]), m.point(tri[1]), m.point(tri[2])));
    replaced.push_back(tri);
  }
  if (after > std::max(before, energy_bound)) return false;
  for (const Triangle& tri : replaced)
    if (m.orientation(tri[0], tri[1], tri[2]) <= 0) return false;

  // Link condition: the common neighbours of the edge's ends are exactly the opposite corners
  // (which are common neighbours): no other neighbour of `from` is one of `to`.
  for (int t : star)
    for (int w : m.triangle(t)) {
      if (w == from || w == to || std::find(opposite.begin(), opposite.end(), w) != opposite.end()) continue;
      for (int u : m.triangles_of(to)) {
        const auto& tri = m.triangle(u);
        if (tri[0] == w || tri[1] == w || tri[2] == w) return false;
      }
    }
  for (const auto& [x, curve] : tags.in_envelope)
    if (!c.envelope.contains(m.point(to), m.point(x), curve)) return false;

  const bool had_edge = m.feature(from, to) != nullptr;
  for (int t : removed) m.remove_triangle(t);
  for (std::size_t i = 0; i < kept.size(); ++i) m.set_triangle(kept[i], replaced[i]);
  if (had_edge) m.clear_feature(from, to);
  for (int x : tags.merged) m.clear_feature(from, x);
  bool gained_secondary = false;
  for (const CollapseTags::Moved& mv : tags.moved) {
    m.clear_feature(from, mv.x);
    m.set_feature(to, mv.x, mv.f);
    gained_secondary |= mv.f.kind == EdgeKind::secondary;
  }
  if (gained_secondary && m.tag(to).kind == VertexKind::free) {
    VertexTag t = m.tag(to);
    t.kind = VertexKind::secondary;
    m.set_tag(to, t);
  }
  return true;
}

}  // namespace

bool collapse_edge(TriMesh& m, const Constraints& c, int from, int to, double energy_bound) {
  return collapse_checked(m, c, from, to, energy_bound, nullptr);
}

bool collapse_edge(TriMesh& m, const Constraints& c, int from, int to, double energy_bound, const CollapseTest& also) {
  return collapse_checked(m, c, from, to, energy_bound, &also);
}

bool swap_edge(TriMesh& m, int a, int b, double energy_bound, int left_hint, std::array<int, 2>* rewritten) {
  if (m.feature(a, b)) return false;
  const auto has_directed = [&](const Triangle& tri) {
    return (tri[0] == a && tri[1] == b) || (tri[1] == a && tri[2] == b) || (tri[2] == a && tri[0] == b);
  };
  const bool hinted = left_hint >= 0 && left_hint < m.triangle_slots() && has_directed(m.triangle(left_hint));
  // A valid mesh has one triangle with a given directed edge: the hint is the one the walk finds.
  const auto [t1, cc] = hinted ? std::pair{left_hint, prev_corner(m.triangle(left_hint), a)} : triangle_left_of(m, a, b);
  const auto [t2, d] = triangle_left_of(m, b, a);
  if (t1 < 0 || t2 < 0 || cc == d) return false;
  // Quad a, d, b, c counter-clockwise; the new diagonal is c–d. The energies first: most swaps
  // are refused there, before the exact tests.
  const Triangle n1{a, d, cc}, n2{d, b, cc};
  const double before = max_amips_of(m, std::array{t1, t2});
  const double after = std::max(geometry::amips(m.point(a), m.point(d), m.point(cc)),
                                geometry::amips(m.point(d), m.point(b), m.point(cc)));
  if (!(after < before) && !(after <= energy_bound)) return false;
  for (int t : m.triangles_of(cc)) {
    const auto& tri = m.triangle(t);
    if (tri[0] == d || tri[1] == d || tri[2] == d) return false;  // edge (c, d) exists already
  }
  if (m.orientation(n1[0], n1[1], n1[2]) <= 0 || m.orientation(n2[0], n2[1], n2[2]) <= 0) return false;
  m.set_triangle(t1, n1);
  m.set_triangle(t2, n2);
  if (rewritten) *rewritten = {t1, t2};
  return true;
}

namespace {

// What the smoothing of one vertex knows before it moves it: its star's energy at x0 and the
// derivatives there (none when that energy is infinite: a triangle too flat for doubles).
struct SmoothingStart {
  TriMesh& m;
  const Constraints& c;
  int v;
  Vec2 x0;
  double e0, max0;
  bool finite;
  geometry::AmipsDerivatives d;

  // A move is better when the summed energy decreases and the worst triangle gets no worse.
  bool better(const Vec2& p) const { return star_improves(m, v, p, e0, max0); }

  // The search along a step: halved until the energy decreases and every invariant holds.
  template <class Clamp>
  bool search(Vec2 step, int tries, const Clamp& clamp) const {
    for (int k = 0; k < tries; ++k, step *= 0.5) {
      const Vec2 p = clamp(x0 + step);
      if (p == x0) return false;
      if (!better(p) || !star_valid_at(m, v, p) || !secondary_edges_inside(m, c, v, p)) continue;
      m.set_position(v, p);
      return true;
    }
    return false;
  }
};

// A primary vertex moves along its curve, between its two curve neighbours: Newton's step on the
// curve's parameter, then towards the middle of its two curve edges.
bool smooth_on_curve(const SmoothingStart& s, const VertexTag& tag) {
  if (!tag.on_curve) return false;  // projection moves it first
  CurveNeighbours n;
  if (!curve_neighbours(s.m, s.v, n)) return false;
  const SectionCurve& curve = s.c.sections[tag.section];
  const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
  const auto search = [&](double dt) {
    for (int k = 0; k < 10; ++k, dt *= 0.5) {
      const double t = std::clamp(tag.t + dt, lo + margin, hi - margin);
      if (t == tag.t) return false;
      if (!s.better(curve.eval(t))) continue;
      if (try_curve_move(s.m, s.c, s.v, n, t)) return true;
    }
    return false;
  };
  if (s.finite) {
    const auto g = geometry::along_curve(s.d, curve.derivative(tag.t), curve.second_derivative(tag.t));
    if (search(g.second > 0 ? -g.first / g.second : (g.first > 0 ? -0.25 : 0.25) * (hi - lo))) return true;
  }
  return search(0.5 * (lo + hi) - tag.t);
}

// A vertex on a side of the box moves along it, between its two neighbours there.
bool smooth_on_side(const SmoothingStart& s, const VertexTag& tag) {
  const TriMesh& m = s.m;
  int x = -1, y = -1;
  if (!side_neighbours(m, s.v, x, y)) return false;
  const int axis = (tag.side == 0 || tag.side == 2) ? 0 : 1;
  const double reach = std::abs(m.point(x)[axis] - m.point(y)[axis]);
  const double lo = std::min(m.point(x)[axis], m.point(y)[axis]), hi = std::max(m.point(x)[axis], m.point(y)[axis]);
  const auto clamp = [&](Vec2 p) {
    p[1 - axis] = s.x0[1 - axis];
    p[axis] = std::clamp(p[axis], lo + 1e-3 * reach, hi - 1e-3 * reach);
    return p;
  };
  if (s.finite) {
    const double h = s.d.hessian(axis, axis), gr = s.d.gradient[axis];
    Vec2 step = Vec2::Zero();
    step[axis] = h > 0 ? -gr / h : (gr > 0 ? -0.25 : 0.25) * reach;
    if (step.allFinite() && s.search(step, 10, clamp)) return true;
  }
  Vec2 step = Vec2::Zero();
  step[axis] = 0.5 * (lo + hi) - s.x0[axis];
  return s.search(step, 10, clamp);
}

// Free and secondary vertices: Newton in the plane; a Hessian that is not positive definite is
// shifted until it is. If that fails, towards the centre of the star (Laplacian smoothing).
bool smooth_in_plane(const SmoothingStart& s) {
  const auto same = [](const Vec2& p) { return p; };
  if (s.finite) {
    Eigen::Matrix2d h = s.d.hessian;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(h);
    const double smallest = eig.eigenvalues()[0], largest = eig.eigenvalues()[1];
    if (!(smallest > 1e-12 * std::max(1.0, std::abs(largest))))
      h += Eigen::Matrix2d::Identity() * (std::abs(smallest) + 1e-6 * std::max(1.0, std::abs(largest)));
    const Vec2 step = -h.ldlt().solve(s.d.gradient);
    if (step.allFinite() && s.search(step, 12, same)) return true;
  }
  Vec2 centre = Vec2::Zero();
  const auto ring = s.m.neighbours(s.v);
  for (int w : ring) centre += s.m.point(w);
  centre /= static_cast<double>(ring.size());
  return s.search(Vec2(centre - s.x0), 8, same);
}

}  // namespace

bool smooth_vertex(TriMesh& m, const Constraints& c, int v) {
  const VertexTag tag = m.tag(v);
  if (tag.kind == VertexKind::fixed || m.has_exact(v) || m.triangles_of(v).empty()) return false;
  const Vec2 x0 = m.point(v);
  // A star with a triangle too flat for doubles has infinite energy: then there is no Newton step,
  // but any valid position of finite energy is better, and the fallback looks for one.
  const StarEnergy start = star_energy(m, v, x0);
  const bool finite = std::isfinite(start.sum);
  const SmoothingStart s{m, c, v, x0, start.sum, start.max, finite,
                         finite ? star_derivatives(m, v, x0) : geometry::AmipsDerivatives{}};
  if (tag.kind == VertexKind::primary) return smooth_on_curve(s, tag);
  if (tag.kind == VertexKind::boundary) return smooth_on_side(s, tag);
  return smooth_in_plane(s);
}

bool project_vertex(TriMesh& m, const Constraints& c, int v, double energy_bound) {
  const VertexTag tag = m.tag(v);
  if (tag.kind != VertexKind::primary || tag.on_curve || m.has_exact(v)) return false;
  CurveNeighbours n;
  if (!curve_neighbours(m, v, n)) return false;
  const SectionCurve& curve = c.sections[tag.section];
  const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
  const geometry::ClosestPoint cp = geometry::closest_point(curve.piece, m.point(v));
  const double t = std::clamp(curve.t0 + cp.t * (curve.t1 - curve.t0), lo + margin, hi - margin);
  // No worse than the star is now, or than the bound: projecting must not undo the optimization.
  const Vec2 x0 = m.point(v), target = curve.eval(t);
  const double allowed = std::max(star_energy(m, v, x0).max, energy_bound);
  if (star_energy(m, v, target).max <= allowed && try_curve_move(m, c, v, n, t)) return true;
  // Fig. 8: get as close as the neighbourhood allows now; smoothing of the others makes room.
  for (double lambda : {0.5, 0.25, 0.125}) {
    const Vec2 p = x0 + lambda * (target - x0);
    if (p == x0) break;
    if (star_energy(m, v, p).max <= allowed && star_valid_at(m, v, p) && secondary_edges_inside(m, c, v, p)) {
      m.set_position(v, p);
      return true;
    }
  }
  return false;
}

bool round_vertex(TriMesh& m, const Constraints& c, int v) {
  if (!m.has_exact(v)) return true;
  const Vec2 nearest = geometry::nearest_double(m.exact(v));
  Vec2 centre = Vec2::Zero();
  const auto ring = m.neighbours(v);
  for (int w : ring) centre += m.point(w);
  if (!ring.empty()) centre /= static_cast<double>(ring.size());
  // The nearest double first, then points ever further towards the centre of the star (a tiny
  // move: 2^-40 of the way first).
  for (int k = 0; k <= 30; k += 2) {
    const Vec2 p = k == 0 ? nearest : Vec2(nearest + std::ldexp(1.0, k - 42) * (centre - nearest));
    if (star_valid_at(m, v, p) && secondary_edges_inside(m, c, v, p)) {
      m.set_position(v, p);
      return true;
    }
  }
  return false;
}

bool release_secondary_edge(TriMesh& m, const Constraints& c, int a, int b) {
  const EdgeFeature* f = m.feature(a, b);
  if (!f || f->kind != EdgeKind::secondary) return false;
  bool shadowed = false;
  for (int t : m.edge_triangles(a, b)) {
    const auto& tri = m.triangle(t);
    const int x = tri[0] != a && tri[0] != b ? tri[0] : tri[1] != a && tri[1] != b ? tri[1] : tri[2];
    shadowed |= m.feature(a, x) != nullptr && m.feature(x, b) != nullptr &&
                c.envelope.contains(m.point(a), m.point(x), f->curve) &&
                c.envelope.contains(m.point(x), m.point(b), f->curve);
  }
  if (!shadowed) {
    // A vertex x that is no feature's (or only secondary features') and lies on the chord to
    // round-off (a flat triangle a–b–x, three fixed vertices in a row, say, which no cubic map
    // with rounded nodes can represent): the secondary edge moves onto the path a–x–b, which
    // stands for the input as well when it is inside the ε-envelope, and a swap of a–b can then
    // remove the flat triangle. Only flat ones: moving tags beside every bad triangle within ε
    // churned (100,000 moves on one drawing) without making meshes better.
    const EdgeFeature moved = *f;
    for (int t : m.edge_triangles(a, b)) {
      const auto& tri = m.triangle(t);
      const int x = tri[0] != a && tri[0] != b ? tri[0] : tri[1] != a && tri[1] != b ? tri[1] : tri[2];
      const VertexKind k = m.tag(x).kind;
      // A primary x (a curve lying along the chord) becomes a crossing of the curve and the
      // secondary input, fixed like every crossing; one still off its curve is left alone.
      if (k == VertexKind::boundary || (k == VertexKind::primary && !m.tag(x).on_curve)) continue;
      if (m.has_exact(x) || m.has_exact(a) || m.has_exact(b)) continue;
      // Path edges tagged already (a curve along the chord, say) keep their tag: as in the rule
      // above, any tagged edge inside the envelope stands for the input there.
      const EdgeFeature* ax = m.feature(a, x);
      const EdgeFeature* xb = m.feature(x, b);
      // Only a chord that is the triangle's longest edge moves (else the tag would go round the
      // sliver and come back).
      const double chord = (m.point(a) - m.point(b)).squaredNorm();
      if (!(chord > (m.point(a) - m.point(x)).squaredNorm() && chord > (m.point(x) - m.point(b)).squaredNorm())) continue;
      const Vec2 ab = m.point(b) - m.point(a), to_x = m.point(x) - m.point(a);
      const double height = std::abs(geometry::cross(ab, to_x)) / std::sqrt(chord);
      if (!(height <= 1e-9 * std::sqrt(chord))) continue;
      if (!c.envelope.contains(m.point(a), m.point(x), moved.curve) ||
          !c.envelope.contains(m.point(x), m.point(b), moved.curve))
        continue;
      m.clear_feature(a, b);
      if (!ax) m.set_feature(a, x, moved);
      if (!xb) m.set_feature(x, b, moved);
      if (k == VertexKind::free || k == VertexKind::primary) {
        VertexTag tag = m.tag(x);
        tag.kind = k == VertexKind::free ? VertexKind::secondary : VertexKind::fixed;
        m.set_tag(x, tag);
      }
      return true;
    }
    return false;
  }
  m.clear_feature(a, b);
  for (int v : {a, b}) {
    if (m.tag(v).kind != VertexKind::secondary) continue;
    bool still = false;
    for (const TaggedEdge& e : m.tagged_edges(v))
      if (e.feature.kind == EdgeKind::secondary) still = true;
    if (!still) {
      VertexTag tag = m.tag(v);
      tag.kind = VertexKind::free;
      m.set_tag(v, tag);
    }
  }
  return true;
}

}  // namespace curvemesh::mesh
