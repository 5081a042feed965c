// Steps 2 and 3 of curve(): the placed nodes certified (order 3 choosing each curved triangle's
// centre), the edges that fail straightened, then every triangle's nodes.
#include "base/parallel.hpp"
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
  p.fill(Vec2::Zero());
  const int count = form.quadratic() ? 6 : 9;
  for (int i = 0; i < count; ++i) p[i] = form.node(ids[i]);
  p[9] = (p[0] + p[1] + p[2]) / 3;
  return p;
}

// A curved triangle's certificate as its nodes are placed (order 3: with the first certified
// centre candidate, `centre` and `choice` set).
struct Placed {
  geometry::P3Nodes element;
  bool certified = false;
  int choice = -1;
  double scaled = 1.0;
  Vec2 centre = Vec2::Zero();
};

Placed certify_placed(const CurvedForm& form, const mesh::Triangle& tri, int depth) {
  Placed out;
  out.element = placed_element(form, tri);
  if (form.quadratic()) {  // no centre to choose: the element is its edges'
    const auto& p = out.element;
    geometry::JacobianCheckOptions check;
    check.max_depth = depth;
    const auto cert =
        geometry::certify_jacobian(geometry::P2Nodes{p[0], p[1], p[2], p[3], p[4], p[5]}, check);
    out.certified = cert.verdict == geometry::JacobianVerdict::positive;
    if (out.certified) out.scaled = cert.scaled_jacobian;
    return out;
  }
  geometry::P3Nodes p = out.element;
  out.certified = choose_centre(p, depth, out.choice, out.scaled);
  if (out.certified) out.centre = p[9];
  return out;
}

// The scaled Jacobian of a straight triangle, whose nodes are rounded to doubles too (order 3
// with the certificate's default depth), or −1.
double certify_straight(const Curving& cv, int t) {
  if (cv.form.quadratic()) return cv.certify(t).value_or(-1.0);
  const auto cert = geometry::certify_jacobian(cv.form.p3(t));
  return cert.verdict == geometry::JacobianVerdict::positive ? cert.scaled_jacobian : -1.0;
}

}  // namespace

// The triangles with a curved edge are certified in parallel (each certificate reads the
// triangle's own nodes alone); then, in the triangles' order, an edge whose triangle fails is
// straightened. A triangle has at most one curved edge, and straightening an edge changes no other
// edge: the centre certified stays valid unless the triangle's own curved edge is lost. (Where
// step 1 left a triangle with two, one straightened before its turn changes its element: it is
// certified again then, as in a serial sweep.) Then every triangle's nodes, and the certificates
// of the straight ones, again in parallel.
void certify_placed_nodes(Curving& cv) {
  const TriMesh& m = cv.mesh;
  CurvedForm& form = cv.form;
  const int depth = cv.options.certificate_depth;
  const int count = m.triangle_slots();  // the mesh is compacted: every slot is alive
  std::vector<Placed> placed(count);
  base::for_each_part(count, [&](std::size_t t) {
    if (form.curved_edge_of(m.triangle(static_cast<int>(t))) >= 0)
      placed[t] = certify_placed(form, m.triangle(static_cast<int>(t)), depth);
  });
  for (int t = 0; t < count; ++t) {
    const auto& tri = m.triangle(t);
    const int curved = form.curved_edge_of(tri);
    if (curved < 0) continue;
    if (placed_element(form, tri) != placed[t].element) placed[t] = certify_placed(form, tri, depth);
    if (!placed[t].certified) form.straighten(tri[curved], tri[(curved + 1) % 3]);
  }
  std::vector<int> straight;
  for (int t = 0; t < count; ++t) {
    const auto& tri = m.triangle(t);
    const bool curved = form.curved_edge_of(tri) >= 0;
    if (curved)
      cv.stats.alternative_centres += placed[t].choice > 0;
    else
      straight.push_back(t);
    form.push_triangle(tri,
                       curved ? placed[t].centre : (m.point(tri[0]) + m.point(tri[1]) + m.point(tri[2])) / 3,
                       curved ? placed[t].scaled : 1.0);
  }
  std::vector<double> scaled(straight.size());
  base::for_each_part(straight.size(), [&](std::size_t k) { scaled[k] = certify_straight(cv, straight[k]); });
  for (std::size_t k = 0; k < straight.size(); ++k) form.set_scaled(straight[k], scaled[k]);
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
