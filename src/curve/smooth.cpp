// Step 4 of curve(), smoothing: corners and centre nodes move where the worst energy around them
// is lowest (free and secondary corners in the plane, corners on curves along them), each move
// certified; primary vertices still off their curve are projected onto it.
#include "base/parallel.hpp"
#include "curve/steps.hpp"
#include "geometry/closest_point.hpp"

namespace curvemesh::curve::detail {

namespace {

// The two neighbours of primary vertex v along its section, and their parameters.
struct CurveNeighbours {
  int x = -1, y = -1;
  double tx = 0, ty = 0;
};

bool curve_neighbours(const Curving& cv, int v, CurveNeighbours& n) {
  const TriMesh& m = cv.mesh;
  const mesh::VertexTag& tag = m.tag(v);
  int found = 0;
  for (int t : m.triangles_of(v))
    for (int w : m.triangle(t)) {
      const mesh::EdgeFeature* f = w == v ? nullptr : m.feature(v, w);
      if (!f || f->kind != EdgeKind::primary || f->source != tag.section || w == n.x || w == n.y) continue;
      const double tw = w < v ? f->t_lo : f->t_hi;
      if (found == 0)
        n.x = w, n.tx = tw;
      else if (found == 1)
        n.y = w, n.ty = tw;
      ++found;
    }
  return found == 2;
}

// A primary corner at parameter t of its curve: its tag and the parameters of its two edges
// along the curve follow.
void place_on_curve_at(Curving& cv, int v, const CurveNeighbours& n, double t) {
  TriMesh& m = cv.mesh;
  mesh::VertexTag tag = m.tag(v);
  tag.t = t;
  m.set_tag(v, tag);
  for (int w : {n.x, n.y}) {
    mesh::EdgeFeature f = *m.feature(v, w);
    (v < w ? f.t_lo : f.t_hi) = t;
    m.set_feature(v, w, f);
  }
  cv.form.place_corner(v, cv.constraints.sections[tag.section].eval(t));
}

// A free or secondary corner moves in the plane (secondary edges inside the ε-envelope) to where
// its star is best, kept when that is better and certified.
int smooth_corner(Curving& cv, int v) {
  TriMesh& m = cv.mesh;
  const auto& star = m.triangles_of(v);
  const auto energy_of = [&](int t, double bound) { return cv.energy(t, bound); };
  const CurvedForm::Snapshot saved = cv.form.snapshot(star);  // everything the move can change
  const Vec2 x0 = m.point(v);
  const double before = star_worst(cv, v, energy_of);
  const Vec2 x = search_corner(cv, v, energy_of);
  if (x == x0) return 0;
  cv.form.place_corner(v, x);
  if (!(star_worst(cv, v, energy_of, before) < before) || !certify_all(cv, star)) {
    cv.form.restore(saved);
    return 0;
  }
  m.set_position(v, x);
  return 1;
}

// A primary corner (on its curve, inside its section) slides along the curve between its two
// curve neighbours; the curve's turning per edge no longer matters once the edges are curved
// (§4.2), only the certificate does.
int smooth_curve_corner(Curving& cv, int v) {
  TriMesh& m = cv.mesh;
  const mesh::VertexTag tag0 = m.tag(v);
  CurveNeighbours n;
  if (!curve_neighbours(cv, v, n)) return 0;
  const auto& star = m.triangles_of(v);
  const auto energy_of = [&](int t, double bound) { return cv.energy(t, bound); };
  const CurvedForm::Snapshot saved = cv.form.snapshot(star);
  const mesh::EdgeFeature fx = *m.feature(v, n.x), fy = *m.feature(v, n.y);
  const auto undo = [&] {
    cv.form.restore(saved);
    m.set_tag(v, tag0);
    m.set_feature(v, n.x, fx);
    m.set_feature(v, n.y, fy);
  };
  const mesh::SectionCurve& curve = cv.constraints.sections[tag0.section];
  const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
  // Order 2: its two edges along the curve stay within the tolerance (or within what they were,
  // if more).
  const auto deviation_at = [&](double t) {
    return std::max(quadratic_deviation(curve, t, n.tx), quadratic_deviation(curve, t, n.ty));
  };
  const bool bounded = cv.form.quadratic() && cv.options.tolerance > 0;
  const double allowed = bounded ? std::max(cv.options.tolerance, deviation_at(tag0.t)) : 0;
  const auto objective = [&](double t, double bound) {
    if (!(t > lo + margin && t < hi - margin) || !mesh::star_valid_at(m, v, curve.eval(t)) ||
        (bounded && deviation_at(t) > allowed))
      return std::numeric_limits<double>::infinity();
    place_on_curve_at(cv, v, n, t);
    const double e = star_worst(cv, v, energy_of, bound);
    undo();
    return e;
  };
  const double before = star_worst(cv, v, energy_of);
  double t = tag0.t, best = before, h = 0.25 * std::min(t - lo, hi - t);
  for (int halvings = 0; halvings < 12;) {
    bool improved = false;
    for (const double step : {h, -h})
      if (const double e = objective(t + step, best); e < best) best = e, t += step, improved = true;
    if (!improved) h *= 0.5, ++halvings;
  }
  if (t == tag0.t || !(best < before)) return 0;
  place_on_curve_at(cv, v, n, t);
  if (!certify_all(cv, star)) {
    undo();
    return 0;
  }
  m.set_position(v, cv.form.at(v));
  return 1;
}

// Primary vertex v (still off its curve) at parameter t, its edges along the curve curved where
// they can follow it, under a journal level the caller closes.
void put_on_curve(Curving& cv, int v, const CurveNeighbours& n, double t) {
  TriMesh& m = cv.mesh;
  m.open_journal();
  mesh::VertexTag tag = m.tag(v);
  tag.on_curve = true;
  m.set_tag(v, tag);
  for (int w : {n.x, n.y}) cv.form.set_follows(v, w, followable(m, v, w));
  place_on_curve_at(cv, v, n, t);
}

// Another place on the curve for v: of 63 evenly spaced in parameter over [lo, hi] less the
// margins, where the star stays counter-clockwise, the one whose curved triangles are best
// (badness: the worst energy where all are valid on the lattice, else how far from valid).
std::optional<double> best_place_on_curve(Curving& cv, int v, const CurveNeighbours& n, double lo,
                                          double hi) {
  TriMesh& m = cv.mesh;
  const mesh::SectionCurve& curve = cv.constraints.sections[m.tag(v).section];
  const double margin = 1e-3 * (hi - lo);
  double best = std::numeric_limits<double>::infinity();
  std::optional<double> place;
  for (int k = 1; k < 64; ++k) {
    const double t = lo + margin + (hi - lo - 2 * margin) * k / 64.0;
    if (!mesh::star_valid_at(m, v, curve.eval(t))) continue;
    put_on_curve(cv, v, n, t);
    const double b = worst_over(m.triangles_of(v), [&](int u, double) { return cv.form.badness(u); });
    m.rollback();
    if (b < best) best = b, place = t;
  }
  return place;
}

// How far from turned over v's star is with v at p and w at q: the smallest signed area of its
// triangles over their squared longest side (negative: turned over).
double star_margin(const TriMesh& m, int v, const Vec2& p, int w, const Vec2& q) {
  const auto at = [&](int u) { return u == v ? p : u == w ? q : m.point(u); };
  double margin = std::numeric_limits<double>::infinity();
  for (int t : m.triangles_of(v)) {
    const mesh::Triangle& tri = m.triangle(t);
    const Vec2 a = at(tri[0]), b = at(tri[1]), c = at(tri[2]);
    const double area = geometry::cross(b - a, c - a);
    const double side = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    margin = std::min(margin, side > 0 ? area / side : -1.0);
  }
  return margin;
}

// Where no place on v's curve keeps v's star counter-clockwise (a neighbour lies between v and the
// curve), the free and secondary neighbours that are not on v's curve move out of the way of p,
// v's place on the curve: each, by compass search from where it is, to where v's star with v at p
// is farthest from turned over (star_margin), as its own star and the ε-envelope allow; its nodes
// follow and its triangles are certified again. Returns whether v's star is then valid at p.
bool clear_the_way(Curving& cv, int v, const CurveNeighbours& n, const Vec2& p) {
  TriMesh& m = cv.mesh;
  for (int w : m.neighbours(v)) {
    const mesh::VertexKind kind = m.tag(w).kind;
    if (w == n.x || w == n.y || cv.form.on_fitted_edge(w) ||
        (kind != mesh::VertexKind::free && kind != mesh::VertexKind::secondary))
      continue;
    const Vec2 x = search_in_plane(cv, w, m.point(w),
                                   [&](const Vec2& q, double) { return -star_margin(m, v, p, w, q); });
    if (x == m.point(w)) continue;
    cv.form.place_corner(w, x);
    m.set_position(w, x);
    for (int t : m.triangles_of(w)) cv.form.set_scaled(t, cv.certify(t).value_or(-1.0));
  }
  return mesh::star_valid_at(m, v, p);
}

// Moves primary vertex v, still off its curve, onto the curve between its two curve neighbours:
// to its closest point there, or, where that would turn one of its triangles over (a neighbour
// lies between v and the curve) or is not kept, to the place on the curve where its curved
// triangles are best (best_place_on_curve). Its edges along the curve become curved where their
// other end is on the curve too. Where v's triangles are certified but end above max(stop
// energy, the worst around v before), v's neighbours and the centres around them are smoothed
// towards the new place (twice at most). Kept only if nothing around ends worse or uncertified,
// if need be after step 4's operations (keep_unless_worse); otherwise v waits off its curve for
// a later attempt.
int project(Curving& cv, int v) {
  TriMesh& m = cv.mesh;
  CurveNeighbours n;
  if (!curve_neighbours(cv, v, n)) return 0;
  const mesh::SectionCurve& curve = cv.constraints.sections[m.tag(v).section];
  const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
  const geometry::ClosestPoint cp = geometry::closest_point(curve.piece, m.point(v));
  const double closest = std::clamp(curve.t0 + cp.t * (curve.t1 - curve.t0), lo + margin, hi - margin);
  const std::vector<int> neighbours = m.neighbours(v);
  const std::vector<int> region = triangles_at(m, vertices_near(m, {v}, 1));  // what the move changes
  const double allowed = std::max(cv.options.stop_amips, worst_of(cv, region));
  const int moves_before = cv.stats.smoothing_moves;
  const auto undo = [&] {
    m.rollback();  // v and its curve edges, the neighbours and every node moved, the certificates
    cv.stats.smoothing_moves = moves_before;
  };
  const auto move_to = [&](double t) {
    return [&, t] {
      put_on_curve(cv, v, n, t);
      m.set_position(v, curve.eval(t));  // the neighbours' searches see v where it is now
      if (!certify_all(cv, m.triangles_of(v))) {
        // A curved edge that bulges into a triangle: left to the repair by the operations, which
        // keep any change that leaves fewer triangles uncertified.
        for (int u : m.triangles_of(v)) cv.form.set_scaled(u, cv.certify(u).value_or(-1.0));
        return true;
      }
      for (int round = 0; round < 2 && worst_of(cv, region) > allowed; ++round) {
        for (int w : neighbours) move_corner(cv, w);
        for (int u : region) smooth_centre(cv, u);
      }
      return true;
    };
  };
  if (mesh::star_valid_at(m, v, curve.eval(closest)) && keep_unless_worse(cv, {v}, move_to(closest), undo))
    return 1;
  // The move and its repair are undone: v and its star are as they were.
  const std::optional<double> alternative = best_place_on_curve(cv, v, n, lo, hi);
  if (alternative) {
    if (*alternative == closest || !keep_unless_worse(cv, {v}, move_to(*alternative), undo)) return 0;
    ++cv.stats.projections_elsewhere;
    return 1;
  }
  // Nowhere on the curve: the neighbours in the way move first, then v goes to its closest point,
  // the two as one move (one journal level) that the guard keeps or takes back.
  const auto clear_and_move = [&] {
    m.open_journal();
    if (!clear_the_way(cv, v, n, curve.eval(closest))) {
      m.rollback();
      return false;
    }
    move_to(closest)();
    m.commit();  // the placement's level into this one
    return true;
  };
  if (!keep_unless_worse(cv, {v}, clear_and_move, undo)) return 0;
  ++cv.stats.cleared_projections;
  return 1;
}

}  // namespace

// Up to max_smoothing_passes passes over the triangles above stop_amips: the free and
// secondary corners of each (they move in the plane, their edges stay straight, secondary
// ones inside the ε-envelope), its corners on curves (they slide along their curve, their curved
// edges follow) and its centre node move where the worst energy around them is lowest, by
// compass search; a move is kept only when every triangle it changes is certified and the worst
// energy among them went down.
void smooth(Curving& cv) {
  for (int pass = 0; pass < cv.options.max_smoothing_passes; ++pass)
    if (smooth_pass(cv) == 0) return;
}

std::vector<double> energies(const Curving& cv) {
  std::vector<double> e(cv.form.triangle_slots(), 0.0);
  base::for_each_part(e.size(), [&](std::size_t t) {
    if (cv.mesh.alive(static_cast<int>(t))) e[t] = cv.energy(static_cast<int>(t));
  });
  return e;
}

std::vector<int> bad_triangles(const Curving& cv) {
  const std::vector<double> energy = energies(cv);
  std::vector<std::pair<double, int>> bad;
  for (int t = 0; t < cv.form.triangle_slots(); ++t)
    if (cv.mesh.alive(t) && energy[t] > cv.options.stop_amips) bad.push_back({-energy[t], t});
  std::sort(bad.begin(), bad.end());
  std::vector<int> out;
  for (const auto& [e, t] : bad) out.push_back(t);
  return out;
}

// One smoothing pass; returns the number of moves kept.
int smooth_pass(Curving& cv) {
  const std::vector<int> bad = bad_triangles(cv);
  if (bad.empty()) return 0;
  if (cv.options.on_pass) cv.options.on_pass(static_cast<int>(bad.size()), cv.energy(bad.front()));
  std::vector<int> corners;
  for (int t : bad)
    for (int v : cv.mesh.triangle(t)) corners.push_back(v);
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  int moved = 0;
  for (int v : corners) moved += move_corner(cv, v);
  for (int t : bad) moved += smooth_centre(cv, t);
  cv.stats.smoothing_moves += moved;
  return moved;
}

// Corner v moves to where its star is best, as its kind allows: free vertices in the plane,
// secondary ones in the plane while their secondary edges stay in the ε-envelope, primary ones
// on their curve along it; others, and the ends of a fitted edge (its bend was fitted for where
// they are), stay. Returns 1 if it moved.
int move_corner(Curving& cv, int v) {
  const mesh::VertexTag& tag = cv.mesh.tag(v);
  if (cv.form.on_fitted_edge(v)) return 0;
  if (tag.kind == mesh::VertexKind::free || tag.kind == mesh::VertexKind::secondary)
    return smooth_corner(cv, v);
  if (tag.kind == mesh::VertexKind::primary && tag.on_curve) return smooth_curve_corner(cv, v);
  return 0;
}

int smooth_centre(Curving& cv, int t) {
  if (cv.form.quadratic()) return 0;  // no centre node: the map is its edges'
  const int id = cv.form.triangle_nodes(t)[9];
  const Vec2 x0 = cv.form.node(id);
  const double before = cv.energy(t);
  geometry::P3Nodes q = cv.form.p3(t);
  double size = 0;
  for (int i = 0; i < 3; ++i) size = std::max(size, (q[i] - q[(i + 1) % 3]).norm());
  const Vec2 x = compass_search(x0, 0.05 * size, [&](const Vec2& p, double bound) {
    q[9] = p;
    return geometry::p3_max_amips(q, bound);
  });
  q[9] = x;
  if (x == x0 || !(geometry::p3_max_amips(q) < before)) return 0;
  cv.form.set_node(id, x);
  const auto cert = cv.certify(t);
  if (!cert) {
    cv.form.set_node(id, x0);
    return 0;
  }
  cv.form.set_scaled(t, *cert);
  return 1;
}

int project_late(Curving& cv) {
  const TriMesh& m = cv.mesh;
  int projected = 0;
  for (int v = 0; v < m.vertex_count(); ++v)
    if (!m.triangles_of(v).empty() && m.tag(v).kind == mesh::VertexKind::primary && !m.tag(v).on_curve)
      projected += project(cv, v);
  return projected;
}

}  // namespace curvemesh::curve::detail
