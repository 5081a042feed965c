// Step 5 of curve(): primary edges that could not follow their curve exactly (their triangles
// were not certified with it): the free opposite corners move out of the way, else the edge is
// bent towards the curve as far as certified; and the distance left from an edge to its curve.
#include "curve/steps.hpp"

namespace curvemesh::curve::detail {

namespace {

// The parameters of a primary edge at its ends, oriented from `from` to `to`.
std::pair<double, double> parameters(const mesh::EdgeFeature& f, int from, int to) {
  return from < to ? std::pair{f.t_lo, f.t_hi} : std::pair{f.t_hi, f.t_lo};
}

// The cubic through p0, p1, p2, p3 at s = 0, 1/3, 2/3, 1 (a P3 edge), at s.
Vec2 edge_point(const Vec2& p0, const Vec2& p1, const Vec2& p2, const Vec2& p3, double s) {
  const double a = 3 * s, l0 = -(a - 1) * (a - 2) * (a - 3) / 6, l1 = a * (a - 2) * (a - 3) / 2,
               l2 = -a * (a - 1) * (a - 3) / 2, l3 = a * (a - 1) * (a - 2) / 6;
  return l0 * p0 + l1 * p1 + l2 * p2 + l3 * p3;
}

// The quadratic through p0, m, p1 at s = 0, 1/2, 1 (a P2 edge), at s.
Vec2 edge_point(const Vec2& p0, const Vec2& m, const Vec2& p1, double s) {
  return (1 - s) * (1 - 2 * s) * p0 + 4 * s * (1 - s) * m + s * (2 * s - 1) * p1;
}

// The triangles of edge (a, b) and the free corners opposite it, whose moves a placement on the
// curve may need.
struct EdgeSurroundings {
  std::vector<int> triangles, movable, touched;  // touched: the triangles and the movable stars
};

EdgeSurroundings surroundings(const TriMesh& m, int a, int b) {
  EdgeSurroundings e;
  e.triangles = m.edge_triangles(a, b);
  e.touched = e.triangles;
  for (int t : e.triangles)
    for (int v : m.triangle(t))
      if (v != a && v != b && m.tag(v).kind == mesh::VertexKind::free) {
        e.movable.push_back(v);
        e.touched.insert(e.touched.end(), m.triangles_of(v).begin(), m.triangles_of(v).end());
      }
  std::sort(e.touched.begin(), e.touched.end());
  e.touched.erase(std::unique(e.touched.begin(), e.touched.end()), e.touched.end());
  return e;
}

// The edge on its curve, with the centres and the free corners moved (compass search on
// badness) until every touched triangle is certified, kept only if nothing around the edge ends
// worse than it was, if need be after step 4's operations (keep_unless_worse).
bool place_on_curve(Curving& cv, int a, int b, const EdgeSurroundings& e) {
  TriMesh& m = cv.mesh;
  const auto take_back = [&] { m.rollback(); };
  const auto on_curve = [&] {
    m.open_journal();
    cv.form.set_follows(a, b, true);
    cv.form.place_on_curve(std::min(a, b), std::max(a, b));
    for (int t : e.triangles) cv.form.choose_centre(t);
    for (int v : e.movable) {
      const Vec2 x = search_corner(cv, v, [&](int t, double) { return cv.form.badness(t); });
      cv.form.place_corner(v, x);
      m.set_position(v, x);  // the next corner's orientation checks see this one where it is now
    }
    for (int t : e.triangles) cv.form.choose_centre(t);
    if (certify_all(cv, e.touched)) return true;
    take_back();
    return false;
  };
  return keep_unless_worse(cv, {a, b}, on_curve, take_back);
}

// The fit: the largest blend s·(curve) + (1 − s)·(chord) of the edge's inner nodes with both
// triangles certified and no worse than the stop energy or the straight edge's (the bare validity
// limit would leave an element next to degenerate there), s by bisection: the least-squares fit
// to the curve along the one direction in which the straight edge is known to be valid.
void fit_towards_curve(Curving& cv, int a, int b, const EdgeSurroundings& e) {
  TriMesh& m = cv.mesh;
  CurvedForm& form = cv.form;
  const int lo = std::min(a, b), hi = std::max(a, b);
  const CurvedForm::Snapshot saved = form.snapshot(e.touched);
  std::vector<Vec2> positions;
  for (int v : e.movable) positions.push_back(m.point(v));
  double allowed = cv.options.stop_amips;
  for (int t : e.triangles) allowed = std::max(allowed, cv.energy(t));
  const auto acceptable = [&] {
    for (int t : e.triangles)
      if (!(cv.energy(t) <= allowed)) return false;
    return certify_all(cv, e.touched);
  };
  const auto [first, second] = form.edge_nodes(lo, hi);
  const Vec2 straight1 = form.node(first), straight2 = form.node(second);
  form.place_on_curve(lo, hi);
  const Vec2 curve1 = form.node(first), curve2 = form.node(second);
  const auto blend = [&, first = first, second = second](double w) {
    form.set_node(first, straight1 + w * (curve1 - straight1));
    form.set_node(second, straight2 + w * (curve2 - straight2));
    for (int t : e.triangles) form.choose_centre(t);
  };
  // certify_all records the scaled Jacobians of each accepted blend: the last one is `good`.
  double good = 0, bad = 1;
  for (int k = 0; k < 12; ++k) {
    const double w = 0.5 * (good + bad);
    blend(w);
    (acceptable() ? good : bad) = w;
  }
  if (good == 0) {
    form.restore(saved);
    for (std::size_t k = 0; k < e.movable.size(); ++k) m.set_position(e.movable[k], positions[k]);
    return;
  }
  blend(good);
  form.set_fitted(a, b);
}

}  // namespace

// §4.2 step 5 for each primary edge still straight that could follow its curve, in the order of
// the edges (an earlier edge's repair may have removed a later one): put on its curve where
// nothing around it ends worse, else fitted towards it. The remaining distance is recorded in the
// statistics.
void fit_straight_edges(Curving& cv) {
  const TriMesh& m = cv.mesh;
  for (const auto& [edge, f] : m.sorted_features()) {
    const int a = edge[0], b = edge[1];
    if (f.kind != EdgeKind::primary || !m.feature(a, b) || cv.form.follows(a, b) || !followable(m, a, b))
      continue;
    const EdgeSurroundings e = surroundings(m, a, b);
    if (!place_on_curve(cv, a, b, e)) fit_towards_curve(cv, a, b, e);
  }
}

// An upper bound of the distance from the edge to its curve: the edge's point and the curve's
// point at the same fraction s of the edge (17 samples).
double distance_to_curve(const Curving& cv, int a, int b, const mesh::EdgeFeature& f) {
  const mesh::SectionCurve& curve = cv.constraints.sections[f.source];
  const auto [ta, tb] = parameters(f, a, b);
  const auto [first, second] = cv.form.edge_nodes(a, b);
  const Vec2 &p0 = cv.form.at(a), &p1 = cv.form.node(first), &p2 = cv.form.node(second), &p3 = cv.form.at(b);
  double worst = 0;
  for (int i = 0; i <= 16; ++i) {
    const double s = i / 16.0;
    const Vec2 x = cv.form.quadratic() ? edge_point(p0, p1, p3, s) : edge_point(p0, p1, p2, p3, s);
    worst = std::max(worst, (x - curve.eval(ta + s * (tb - ta))).norm());
  }
  return worst;
}

}  // namespace curvemesh::curve::detail
