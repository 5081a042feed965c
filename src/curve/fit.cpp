// Step 5 of curve(): primary edges that could not follow their curve exactly (their triangles
// were not certified with it): the free opposite corners move out of the way, else the edge is
// bent towards the curve as far as certified; and the distance left from an edge to its curve.
#include "curve/builder.hpp"

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

}  // namespace

// §4.2 step 5 for primary edge (a, b), whose triangles cannot be certified with the edge on its
// curve. First the edge is put on its curve and the centre nodes and the free opposite corners
// move (compass search on badness) until both triangles are certified, kept only if nothing
// around the edge ends worse than it was, if need be after step 4's operations
// (keep_unless_worse); failing that, the edge's two inner nodes are fitted: the largest blend
// s·(curve) + (1 − s)·(chord) with both triangles certified and within the stop energy (or the
// straight edge's), s by bisection (the least-squares fit to the curve along the one direction in
// which the straight edge is known to be valid). The remaining distance is recorded in the stats.
void Builder::fit(int a, int b) {
  TriMesh& m = out_.linear;
  const auto key = mesh::edge_key(a, b);
  const int lo = std::min(a, b), hi = std::max(a, b);
  const std::vector<int> triangles = m.edge_triangles(a, b);
  // Everything that can change: the triangles of the edge and the stars of their free corners.
  std::vector<int> touched = triangles, movable;
  for (int t : triangles)
    for (int v : m.triangle(t))
      if (v != a && v != b && m.tag(v).kind == mesh::VertexKind::free) {
        movable.push_back(v);
        touched.insert(touched.end(), m.triangles_of(v).begin(), m.triangles_of(v).end());
      }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  const Snapshot saved = snapshot(touched);
  std::vector<Vec2> positions;
  for (int v : movable) positions.push_back(m.point(v));
  const auto undo = [&] {
    restore(saved);
    for (std::size_t k = 0; k < movable.size(); ++k) m.set_position(movable[k], positions[k]);
  };

  // On the curve, with the centres and the free corners moved, under the journal.
  const auto take_back = [&] { m.rollback(); };
  const auto on_curve = [&] {
    m.open_journal();
    curved_.set(key, true);
    place_on_curve(lo, hi);
    for (int t : triangles) choose_centre_of(t);
    for (int v : movable) {
      const Vec2 x = search_corner(v, [&](int t, double) { return badness(t); });
      place_corner(v, x);
      m.set_position(v, x);  // the next corner's orientation checks see this one where it is now
    }
    for (int t : triangles) choose_centre_of(t);
    if (certify_all(touched)) return true;
    take_back();
    return false;
  };
  if (keep_unless_worse({a, b}, on_curve, take_back)) return;

  // The fit: the largest blend towards the curve with both triangles certified and no worse
  // than the stop energy or the straight edge's (the bare validity limit would leave an element
  // next to degenerate there).
  double allowed = o_.stop_amips;
  for (int t : triangles) allowed = std::max(allowed, energy(t));
  const auto acceptable = [&] {
    for (int t : triangles)
      if (!(energy(t) <= allowed)) return false;
    return certify_all(touched);
  };
  // (Not a structured binding: the lambda below uses them, which clang before 16 refuses.)
  const std::pair<int, int> inner = edge_nodes(lo, hi);
  const int first = inner.first, second = inner.second;
  const Vec2 straight1 = nodes_[first], straight2 = nodes_[second];
  place_on_curve(lo, hi);
  const Vec2 curve1 = nodes_[first], curve2 = nodes_[second];
  const auto blend = [&](double w) {
    nodes_.set(first, straight1 + w * (curve1 - straight1));
    nodes_.set(second, straight2 + w * (curve2 - straight2));
    for (int t : triangles) choose_centre_of(t);
  };
  // certify_all records the scaled Jacobians of each accepted blend: the last one is `good`.
  double good = 0, bad = 1;
  for (int k = 0; k < 12; ++k) {
    const double w = 0.5 * (good + bad);
    blend(w);
    (acceptable() ? good : bad) = w;
  }
  if (good == 0) {
    undo();
    return;
  }
  blend(good);
  fitted_.set(key, true);
}

bool Builder::on_fitted_edge(int v) const {
  if (fitted_.empty()) return false;
  for (int w : out_.linear.neighbours(v))
    if (fitted_.contains(mesh::edge_key(v, w))) return true;
  return false;
}

int Builder::fitted_edge_of(const mesh::Triangle& tri) const {
  for (int i = 0; i < 3; ++i)
    if (fitted_.contains(mesh::edge_key(tri[i], tri[(i + 1) % 3]))) return i;
  return -1;
}

// An upper bound of the distance from the edge to its curve: the edge's point and the curve's
// point at the same fraction s of the edge (17 samples). Order 2: `first` is the middle node.
double Builder::distance_to_curve(int a, int b, const mesh::EdgeFeature& f, int first, int second) const {
  const mesh::SectionCurve& curve = c_.sections[f.source];
  const auto [ta, tb] = parameters(f, a, b);
  const Vec2 &p0 = at(a), &p1 = nodes_[first], &p2 = nodes_[second], &p3 = at(b);
  double worst = 0;
  for (int i = 0; i <= 16; ++i) {
    const double s = i / 16.0;
    const Vec2 x = quadratic() ? edge_point(p0, p1, p3, s) : edge_point(p0, p1, p2, p3, s);
    worst = std::max(worst, (x - curve.eval(ta + s * (tb - ta))).norm());
  }
  return worst;
}

}  // namespace curvemesh::curve::detail
