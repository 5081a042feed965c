// Steps 2 and 3 of curve(): the placed nodes certified (order 3 choosing each curved triangle's
// centre), the edges that fail straightened, then every triangle's nodes.
#include "curve/steps.hpp"

namespace curvemesh::curve::detail {

namespace {

// Sets p[9] to the first certified centre candidate (geometry::p3_centre_candidates; its index in
// `choice`, its scaled Jacobian in `scaled`) and returns true, or returns false. The candidate that
// reproduces quadratic maps exactly comes first: finite elements on the mesh need it for their
// full order (with the paper's centre, P2 on a disk converges at L2 rate 2.35 instead of 3;
// fem/convergence.hpp).
bool choose_centre(geometry::P3Nodes& p, int depth, int& choice, double& scaled) {
  const std::array<Vec2, 3> centres = geometry::p3_centre_candidates(p);
  for (int k = 0; k < 3; ++k) {
    p[9] = centres[k];
    geometry::JacobianCheckOptions check;
    check.max_depth = depth;
    const auto result = geometry::certify_jacobian(p, check);
    if (result.verdict == geometry::JacobianVerdict::positive) {
      choice = k;
      scaled = result.scaled_jacobian;
      return true;
    }
  }
  return false;
}

// A triangle's element as its edges' nodes are placed (order 3 with the corners' centroid as
// centre; order 2's six nodes in the first six).
geometry::P3Nodes placed_element(const CurvedForm& form, const mesh::Triangle& tri) {
  const std::array<int, 10> ids = form.corner_and_edge_nodes(tri);
  geometry::P3Nodes p;
  const int count = form.quadratic() ? 6 : 9;
  for (int i = 0; i < count; ++i) p[i] = form.node(ids[i]);
  p[9] = (p[0] + p[1] + p[2]) / 3;
  return p;
}

}  // namespace

// A triangle has at most one curved edge, and straightening an edge changes no other edge: the
// centre certified here stays valid unless the triangle's own curved edge is lost.
void certify_placed_nodes(Curving& cv) {
  const TriMesh& m = cv.mesh;
  CurvedForm& form = cv.form;
  geometry::JacobianCheckOptions check;
  check.max_depth = cv.options.certificate_depth;
  const int count = m.triangle_slots();  // the mesh is compacted: every slot is alive
  std::vector<Vec2> centre(count);
  std::vector<int> choice(count, -1);
  std::vector<double> scaled(count, 1.0);
  for (int t = 0; t < count; ++t) {
    const auto& tri = m.triangle(t);
    const int curved = form.curved_edge_of(tri);
    if (curved < 0) continue;
    geometry::P3Nodes p = placed_element(form, tri);
    if (form.quadratic()) {  // no centre to choose: the element is its edges'
      const geometry::P2Nodes q{p[0], p[1], p[2], p[3], p[4], p[5]};
      const auto cert = geometry::certify_jacobian(q, check);
      if (cert.verdict == geometry::JacobianVerdict::positive)
        scaled[t] = cert.scaled_jacobian;
      else
        form.straighten(tri[curved], tri[(curved + 1) % 3]);
    } else if (choose_centre(p, cv.options.certificate_depth, choice[t], scaled[t])) {
      centre[t] = p[9];
    } else {
      form.straighten(tri[curved], tri[(curved + 1) % 3]);
    }
  }
  // Final nodes and centres (triangles that lost their curved edge become straight).
  for (int t = 0; t < count; ++t) {
    const auto& tri = m.triangle(t);
    const bool curved = form.curved_edge_of(tri) >= 0;
    if (curved) cv.stats.alternative_centres += choice[t] > 0;
    form.push_triangle(tri, curved ? centre[t] : (m.point(tri[0]) + m.point(tri[1]) + m.point(tri[2])) / 3,
                       scaled[t]);
    if (curved) continue;
    // A straight element's nodes are rounded to doubles too: certify it like the others (order 3
    // with the certificate's default depth).
    if (form.quadratic()) {
      form.set_scaled(t, cv.certify(t).value_or(-1.0));
    } else {
      const auto cert = geometry::certify_jacobian(form.p3(t));
      form.set_scaled(t, cert.verdict == geometry::JacobianVerdict::positive ? cert.scaled_jacobian : -1.0);
    }
  }
}

bool certify_all(Curving& cv, const std::vector<int>& triangles) {
  std::vector<double> scaled;
  for (int t : triangles) {
    const auto cert = cv.certify(t);
    if (!cert) return false;
    scaled.push_back(*cert);
  }
  for (std::size_t k = 0; k < triangles.size(); ++k) cv.form.set_scaled(triangles[k], scaled[k]);
  return true;
}

}  // namespace curvemesh::curve::detail
