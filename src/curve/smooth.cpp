// Step 4 of curve(), smoothing: corners and centre nodes move where the worst energy around them
// is lowest (free and secondary corners in the plane, corners on curves along them), each move
// certified; primary vertices still off their curve are projected onto it.
#include "curve/builder.hpp"
#include "geometry/closest_point.hpp"

namespace curvemesh::curve::detail {

// Up to max_smoothing_passes passes over the triangles above stop_amips: the free and
// secondary corners of each (they move in the plane, their edges stay straight, secondary
// ones inside the ε-envelope), its corners on curves (they slide
// along their curve, their curved edges follow) and its centre node move where the worst
// energy around them is lowest, by compass search; a move is kept only when every
// triangle it changes is certified and the worst energy among them went down.
void Builder::smooth() {
  for (int pass = 0; pass < o_.max_smoothing_passes; ++pass)
    if (smooth_pass() == 0) return;
}

// The alive triangles above the stop energy, worst first.
std::vector<int> Builder::bad_triangles() const {
  std::vector<std::pair<double, int>> bad;
  for (std::size_t t = 0; t < triangle_nodes_.size(); ++t)
    if (out_.linear.alive(static_cast<int>(t)))
      if (const double e = energy(static_cast<int>(t)); e > o_.stop_amips) bad.push_back({-e, static_cast<int>(t)});
  std::sort(bad.begin(), bad.end());
  std::vector<int> out;
  for (const auto& [e, t] : bad) out.push_back(t);
  return out;
}

// One smoothing pass; returns the number of moves kept.
int Builder::smooth_pass() {
  const std::vector<int> bad = bad_triangles();
  if (bad.empty()) return 0;
  if (o_.on_pass) o_.on_pass(static_cast<int>(bad.size()), energy(bad.front()));
  std::vector<int> corners;
  for (int t : bad)
    for (int v : out_.linear.triangle(t)) corners.push_back(v);
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  int moved = 0;
  for (int v : corners) moved += move_corner(v);
  for (int t : bad) moved += smooth_centre(t);
  s_.smoothing_moves += moved;
  return moved;
}

// Corner v moves to where its star is best, as its kind allows: free vertices in the plane,
// secondary ones in the plane while their secondary edges stay in the ε-envelope, primary ones
// on their curve along it; others, and the ends of a fitted edge (its bend was fitted for where
// they are), stay. Returns 1 if it moved.
int Builder::move_corner(int v) {
  const mesh::VertexTag& tag = out_.linear.tag(v);
  if (on_fitted_edge(v)) return 0;
  if (tag.kind == mesh::VertexKind::free || tag.kind == mesh::VertexKind::secondary) return smooth_corner(v);
  if (tag.kind == mesh::VertexKind::primary && tag.on_curve) return smooth_curve_corner(v);
  return 0;
}

// Places the nodes that depend on corner v's position (and, on a curve, on its parameter): v,
// the inner nodes of its edges (curved ones on their curve, at thirds of their parameter
// interval; straight ones at thirds; order 2: at the middles), and the centres of its triangles
// (straight: the centroid; curved: the candidate of lowest badness, certified later; order 2 has
// none).
void Builder::place_corner(int v, const Vec2& p) {
  nodes_.set(vertex_node_[v], p);
  const TriMesh& m = out_.linear;
  for (int t : m.triangles_of(v)) {
    const auto& ids = triangle_nodes_[t];
    const auto& tri = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const int a = tri[i], b = tri[(i + 1) % 3];
      if (a != v && b != v) continue;
      if (curved_.at(mesh::edge_key(a, b))) {
        place_on_curve(std::min(a, b), std::max(a, b));
      } else if (quadratic()) {
        place_straight(std::min(a, b), std::max(a, b));
      } else {
        nodes_.set(ids[3 + 2 * i], (2 * at(a) + at(b)) / 3);
        nodes_.set(ids[4 + 2 * i], (at(a) + 2 * at(b)) / 3);
      }
    }
    if (quadratic()) continue;
    if (curved_edge_of(tri) < 0) {
      nodes_.set(ids[9], (at(tri[0]) + at(tri[1]) + at(tri[2])) / 3);
      continue;
    }
    choose_centre_of(t);
  }
}

// A primary corner at parameter t of its curve: its tag and the parameters of its two edges
// along the curve follow.
void Builder::place_on_curve_at(int v, const CurveNeighbours& n, double t) {
  TriMesh& m = out_.linear;
  mesh::VertexTag tag = m.tag(v);
  tag.t = t;
  m.set_tag(v, tag);
  for (int w : {n.x, n.y}) {
    mesh::EdgeFeature f = *m.feature(v, w);
    (v < w ? f.t_lo : f.t_hi) = t;
    m.set_feature(v, w, f);
  }
  place_corner(v, c_.sections[tag.section].eval(t));
}

bool Builder::curve_neighbours(int v, CurveNeighbours& n) const {
  const TriMesh& m = out_.linear;
  const mesh::VertexTag& tag = m.tag(v);
  int found = 0;
  for (int t : m.triangles_of(v))
    for (int w : m.triangle(t)) {
      const mesh::EdgeFeature* f = w == v ? nullptr : m.feature(v, w);
      if (!f || f->kind != EdgeKind::primary || f->source != tag.section || w == n.x || w == n.y) continue;
      const double tw = w < v ? f->t_lo : f->t_hi;
      if (found == 0) n.x = w, n.tx = tw;
      else if (found == 1) n.y = w, n.ty = tw;
      ++found;
    }
  return found == 2;
}

// A primary corner (on its curve, inside its section) slides along the curve between its two
// curve neighbours; the curve's turning per edge no longer matters once the edges are curved
// (§4.2), only the certificate does.
int Builder::smooth_curve_corner(int v) {
  TriMesh& m = out_.linear;
  const mesh::VertexTag tag0 = m.tag(v);
  CurveNeighbours n;
  if (!curve_neighbours(v, n)) return 0;
  const auto& star = m.triangles_of(v);
  const auto energy_of = [&](int t, double bound) { return energy(t, bound); };
  const Snapshot saved = snapshot(star);
  const mesh::EdgeFeature fx = *m.feature(v, n.x), fy = *m.feature(v, n.y);
  const auto undo = [&] {
    restore(saved);
    m.set_tag(v, tag0);
    m.set_feature(v, n.x, fx);
    m.set_feature(v, n.y, fy);
  };
  const mesh::SectionCurve& curve = c_.sections[tag0.section];
  const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
  // Order 2: its two edges along the curve stay within the tolerance (or within what they were,
  // if more).
  const auto deviation_at = [&](double t) {
    return std::max(quadratic_deviation(curve, t, n.tx), quadratic_deviation(curve, t, n.ty));
  };
  const bool bounded = quadratic() && o_.tolerance > 0;
  const double allowed = bounded ? std::max(o_.tolerance, deviation_at(tag0.t)) : 0;
  const auto objective = [&](double t, double bound) {
    if (!(t > lo + margin && t < hi - margin) || !mesh::star_valid_at(m, v, curve.eval(t)) ||
        (bounded && deviation_at(t) > allowed))
      return std::numeric_limits<double>::infinity();
    place_on_curve_at(v, n, t);
    const double e = star_worst(v, energy_of, bound);
    undo();
    return e;
  };
  const double before = star_worst(v, energy_of);
  double t = tag0.t, best = before, h = 0.25 * std::min(t - lo, hi - t);
  for (int halvings = 0; halvings < 12;) {
    bool improved = false;
    for (const double step : {h, -h})
      if (const double e = objective(t + step, best); e < best) best = e, t += step, improved = true;
    if (!improved) h *= 0.5, ++halvings;
  }
  if (t == tag0.t || !(best < before)) return 0;
  place_on_curve_at(v, n, t);
  if (!certify_all(star)) {
    undo();
    return 0;
  }
  m.set_position(v, at(v));
  return 1;
}

// Moves primary vertex v, still off its curve, onto the curve between its two curve neighbours:
// to its closest point there, or, where that would turn one of its triangles over (a neighbour
// lies between v and the curve) or is not kept, to the place on the curve where its curved
// triangles are best (of 63 evenly spaced in parameter). Its edges along the curve
// become curved where their other end is on the curve too. Where v's triangles are certified but
// end above max(stop energy, the worst around v before), v's neighbours and the centres around
// them are smoothed towards the new place (twice at most). Kept only if nothing around ends worse
// or uncertified, if need be after step 4's operations (keep_unless_worse); otherwise v waits
// off its curve for a later attempt.
int Builder::project(int v) {
  TriMesh& m = out_.linear;
  const mesh::VertexTag tag0 = m.tag(v);
  CurveNeighbours n;
  if (!curve_neighbours(v, n)) return 0;
  const mesh::SectionCurve& curve = c_.sections[tag0.section];
  const double lo = std::min(n.tx, n.ty), hi = std::max(n.tx, n.ty), margin = 1e-3 * (hi - lo);
  const geometry::ClosestPoint cp = geometry::closest_point(curve.piece, m.point(v));
  const double closest = std::clamp(curve.t0 + cp.t * (curve.t1 - curve.t0), lo + margin, hi - margin);
  const std::vector<int> neighbours = m.neighbours(v);
  const std::vector<int> region = triangles_at(vertices_near({v}, 1));  // what the move changes
  const double allowed = std::max(o_.stop_amips, worst_of(region));
  const int moves_before = s_.smoothing_moves;
  const auto undo = [&] {
    m.rollback();  // v and its curve edges, the neighbours and every node moved, the certificates
    s_.smoothing_moves = moves_before;
  };
  // v on the curve at t, its edges along the curve curved where they can follow it, under the
  // journal (undo takes it back).
  const auto put_on_curve = [&](double t) {
    m.open_journal();
    mesh::VertexTag tag = tag0;
    tag.on_curve = true;
    m.set_tag(v, tag);
    for (int w : {n.x, n.y}) curved_.set(mesh::edge_key(v, w), followable(m, v, w));
    place_on_curve_at(v, n, t);
  };
  const auto move_to = [&](double t) {
    return [&, t] {
      put_on_curve(t);
      m.set_position(v, curve.eval(t));  // the neighbours' searches see v where it is now
      if (!certify_all(m.triangles_of(v))) {
        // A curved edge that bulges into a triangle: left to the repair by the operations, which
        // keep any change that leaves fewer triangles uncertified.
        for (int u : m.triangles_of(v)) scaled_.set(u, certify(u).value_or(-1.0));
        return true;
      }
      for (int round = 0; round < 2 && worst_of(region) > allowed; ++round) {
        for (int w : neighbours) move_corner(w);
        for (int u : region) smooth_centre(u);
      }
      return true;
    };
  };
  // Another place on the curve: of 63 evenly spaced in parameter, where the star stays
  // counter-clockwise, the one whose curved triangles are best (badness: the worst energy where
  // all are valid on the lattice, else how far from valid).
  double alternative = closest, best = std::numeric_limits<double>::infinity();
  const auto find_alternative = [&] {
    for (int k = 1; k < 64; ++k) {
      const double t = lo + margin + (hi - lo - 2 * margin) * k / 64.0;
      if (!mesh::star_valid_at(m, v, curve.eval(t))) continue;
      put_on_curve(t);
      const double b = worst_over(m.triangles_of(v), [this](int u, double) { return badness(u); });
      undo();
      if (b < best) best = b, alternative = t;
    }
    return best < std::numeric_limits<double>::infinity();
  };
  if (mesh::star_valid_at(m, v, curve.eval(closest)) && keep_unless_worse({v}, move_to(closest), undo))
    return 1;
  // The move and its repair are undone: v and its star are as they were.
  if (!find_alternative() || alternative == closest || !keep_unless_worse({v}, move_to(alternative), undo))
    return 0;
  ++s_.projections_elsewhere;
  return 1;
}

int Builder::smooth_corner(int v) {
  TriMesh& m = out_.linear;
  const auto& star = m.triangles_of(v);
  const auto energy_of = [&](int t, double bound) { return energy(t, bound); };
  const Snapshot saved = snapshot(star);  // everything the move can change
  const Vec2 x0 = m.point(v);
  const double before = star_worst(v, energy_of);
  const Vec2 x = search_corner(v, energy_of);
  if (x == x0) return 0;
  place_corner(v, x);
  if (!(star_worst(v, energy_of, before) < before) || !certify_all(star)) {
    restore(saved);
    return 0;
  }
  m.set_position(v, x);
  return 1;
}

int Builder::smooth_centre(int t) {
  if (quadratic()) return 0;  // no centre node: the map is its edges'
  const int id = triangle_nodes_[t][9];
  const Vec2 x0 = nodes_[id];
  const double before = energy(t);
  geometry::P3Nodes q = nodes_of(t);
  double size = 0;
  for (int i = 0; i < 3; ++i) size = std::max(size, (q[i] - q[(i + 1) % 3]).norm());
  const Vec2 x = compass_search(x0, 0.05 * size, [&](const Vec2& p, double bound) {
    q[9] = p;
    return geometry::p3_max_amips(q, bound);
  });
  q[9] = x;
  if (x == x0 || !(geometry::p3_max_amips(q) < before)) return 0;
  nodes_.set(id, x);
  const auto cert = certify(t);
  if (!cert) {
    nodes_.set(id, x0);
    return 0;
  }
  scaled_.set(t, *cert);
  return 1;
}

}  // namespace curvemesh::curve::detail
