#include "pipeline/check.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/parallel.hpp"
#include "geometry/closest_point.hpp"
#include "geometry/p2_triangle.hpp"
#include "geometry/p3_triangle.hpp"

namespace curvemesh::pipeline {

namespace {

using geometry::P3NodesT;
using geometry::PointT;
using geometry::Vec2;

PointT<mpq_class> exact(const Vec2& p) {
  return {mpq_class(p.x()), mpq_class(p.y())};
}

// A P1 or P3 element's map written as a P3 map, exactly: a P1 map is evaluated at the ten P3
// reference nodes (rational points), which gives the P3 nodes of the very same map.
P3NodesT<mpq_class> as_p3(const io::HighOrderMesh& m, std::size_t t) {
  const auto n = m.triangle(static_cast<int>(t));
  P3NodesT<mpq_class> out;
  if (m.order == 3) {
    for (int i = 0; i < 10; ++i) out[i] = exact(m.nodes[n[i]]);
    return out;
  }
  std::array<PointT<mpq_class>, 3> x;
  for (int i = 0; i < 3; ++i) x[i] = exact(m.nodes[n[i]]);
  for (int i = 0; i < 10; ++i) {
    const mpq_class u(geometry::kP3ReferenceNodesTimes3[i][0], 3),
        v(geometry::kP3ReferenceNodesTimes3[i][1], 3);
    const std::array<mpq_class, 3> w{1 - u - v, u, v};
    out[i] = {0, 0};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c) out[i][c] += w[k] * x[k][c];
  }
  return out;
}

geometry::P3Nodes to_double(const P3NodesT<mpq_class>& p) {
  geometry::P3Nodes out;
  for (int i = 0; i < 10; ++i) out[i] = Vec2(p[i][0].get_d(), p[i][1].get_d());
  return out;
}

template <std::size_t N>
std::array<Vec2, N> element_nodes(const io::HighOrderMesh& m, std::size_t t) {
  const auto n = m.triangle(static_cast<int>(t));
  std::array<Vec2, N> p;
  for (std::size_t i = 0; i < N; ++i) p[i] = m.nodes[n[i]];
  return p;
}

struct ElementCheck {
  geometry::JacobianVerdict verdict;
  double scaled_jacobian;
  bool exact;  // decided with rationals
};

// Element t's verdict and scaled Jacobian (always in doubles). A quadratic element is decided on
// its own degree-2 determinant, a linear or cubic one as a P3 map (degree 4), on the rationals of
// its nodes as read. The double certificate decides first unless `exact`: its verdict, when it
// has one, is the exact certificate's (bernstein_certificate.hpp, certify: a filter in the sense
// of CGAL's filtered predicates); only an undecided element is decided again in rationals. A
// linear element's sign is that of its corners' orientation (certify_jacobian_linear); its scaled
// Jacobian is measured on its map as a P3 map, the rational nodes rounded toward zero as mpq
// rounds them, which p3_straight_nodes_truncated gives without rationals.
ElementCheck check_element(const io::HighOrderMesh& m, std::size_t t, bool exact) {
  using geometry::JacobianVerdict;
  if (m.order == 3) {
    const auto p = element_nodes<10>(m, t);
    const geometry::JacobianCertificate c = geometry::certify_jacobian(p);
    if (!exact && c.verdict != JacobianVerdict::undecided) return {c.verdict, c.scaled_jacobian, false};
    return {geometry::certify_jacobian_exact(p), c.scaled_jacobian, true};
  }
  if (m.order == 2) {
    const auto p = element_nodes<6>(m, t);
    const geometry::JacobianCertificate c = geometry::certify_jacobian(p);
    if (!exact && c.verdict != JacobianVerdict::undecided) return {c.verdict, c.scaled_jacobian, false};
    return {geometry::certify_jacobian_exact(p), c.scaled_jacobian, true};
  }
  const auto x = element_nodes<3>(m, t);
  if (!exact) {
    const double scaled =
        geometry::certify_jacobian(geometry::p3_straight_nodes_truncated(x[0], x[1], x[2])).scaled_jacobian;
    const JacobianVerdict v = geometry::certify_jacobian_linear(x[0], x[1], x[2]);
    if (v != JacobianVerdict::undecided) return {v, scaled, false};
    return {geometry::certify_jacobian_exact(as_p3(m, t)), scaled, true};
  }
  const auto p = as_p3(m, t);
  return {geometry::certify_jacobian_exact(p), geometry::certify_jacobian(to_double(p)).scaled_jacobian,
          true};
}

// A point of line element `l` at s in [0, 1] (its nodes: the ends, then the inner ones in order).
Vec2 line_point(const io::HighOrderMesh& m, std::size_t l, double s) {
  const auto nodes = m.line(static_cast<int>(l));
  const int order = static_cast<int>(nodes.size()) - 1;
  std::vector<Vec2> p(order + 1);
  std::vector<double> at(order + 1);
  p[0] = m.nodes[nodes[0]];
  at[0] = 0;
  p[order] = m.nodes[nodes[1]];
  at[order] = 1;
  for (int i = 1; i < order; ++i) {
    p[i] = m.nodes[nodes[i + 1]];
    at[i] = double(i) / order;
  }
  Vec2 x = Vec2::Zero();
  for (int i = 0; i <= order; ++i) {
    double w = 1;
    for (int j = 0; j <= order; ++j)
      if (j != i) w *= (s - at[j]) / (at[i] - at[j]);
    x += w * p[i];
  }
  return x;
}

}  // namespace

// Every element decided on its own, in parallel (base/parallel.hpp), the counts made in order. A
// small mesh, or one thread, is decided in this thread: starting the threads costs about 0.7 ms,
// the time of some 4,000 cubic elements, which a second thread wins back only on twice as many.
MeshCheck check_mesh(const io::HighOrderMesh& m, const CheckOptions& options) {
  constexpr std::size_t kFewestForThreads = 8192;
  MeshCheck out;
  out.order = m.order;
  out.triangles = static_cast<std::size_t>(m.triangle_count());
  std::vector<ElementCheck> checks(out.triangles);
  const auto decide = [&](std::size_t t) { checks[t] = check_element(m, t, options.exact); };
  if (options.threads == 1 || out.triangles < kFewestForThreads)
    for (std::size_t t = 0; t < out.triangles; ++t) decide(t);
  else
    base::with_threads(options.threads, [&] { base::for_each_part(out.triangles, decide); });
  double min_scaled = INFINITY;
  for (const ElementCheck& e : checks) {
    out.invalid += e.verdict != geometry::JacobianVerdict::positive;
    out.undecided += e.verdict == geometry::JacobianVerdict::undecided;
    out.exact_fallbacks += e.exact;
    min_scaled = std::min(min_scaled, e.scaled_jacobian);
  }
  out.min_scaled_jacobian = out.triangles ? min_scaled : 0.0;
  return out;
}

FeatureDistance feature_distance(const io::HighOrderMesh& m, const svg::FeatureSoup& soup) {
  geometry::Box2 box;
  for (const auto& c : soup.curves)
    for (const Vec2& q : c.bezier.p) box.add(q);
  // Curves by bounding box, for a cheap lower bound before the exact closest point.
  std::vector<geometry::Box2> boxes;
  for (const auto& c : soup.curves) {
    geometry::Box2 b;
    for (const Vec2& q : c.bezier.p) b.add(q);
    boxes.push_back(b);
  }
  const auto box_distance = [](const geometry::Box2& b, const Vec2& q) {
    const double dx = std::max({b.min.x() - q.x(), 0.0, q.x() - b.max.x()});
    const double dy = std::max({b.min.y() - q.y(), 0.0, q.y() - b.max.y()});
    return std::hypot(dx, dy);
  };
  FeatureDistance out;
  for (std::size_t l = 0; l < static_cast<std::size_t>(m.line_count()); ++l) {
    const auto name = m.physical_names.find({1, m.line_physical[l]});
    if (name == m.physical_names.end() || name->second != "primary") continue;
    ++out.primary_lines;
    for (int i = 0; i <= 8; ++i) {
      const Vec2 q = line_point(m, l, i / 8.0);
      double best = INFINITY;
      for (std::size_t c = 0; c < soup.curves.size(); ++c)
        if (box_distance(boxes[c], q) < best)
          best = std::min(best, geometry::closest_point(soup.curves[c].bezier, q).distance);
      out.max = std::max(out.max, best);
    }
  }
  out.max_rel = box.diagonal() > 0 ? out.max / box.diagonal() : 0.0;
  return out;
}

}  // namespace curvemesh::pipeline
