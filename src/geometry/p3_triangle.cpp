#include "geometry/p3_triangle.hpp"

namespace curvemesh::geometry {

Vec2 p3_reference_node(int i) {
  return Vec2(kP3ReferenceNodesTimes3[i][0], kP3ReferenceNodesTimes3[i][1]) / 3.0;
}

P3Nodes p3_straight_nodes(const Vec2& a, const Vec2& b, const Vec2& c) {
  auto third = [](const Vec2& p, const Vec2& q) -> Vec2 { return (2 * p + q) / 3; };  // 1/3 from p
  return {a,           b,           c,           third(a, b), third(b, a),
          third(b, c), third(c, b), third(c, a), third(a, c), (a + b + c) / 3};
}

P3NodesT<mpq_class> to_exact(const P3Nodes& nodes) {
  P3NodesT<mpq_class> out;
  for (int i = 0; i < 10; ++i) out[i] = {mpq_class(nodes[i].x()), mpq_class(nodes[i].y())};
  return out;
}

P3NodesT<double> to_array(const P3Nodes& nodes) {
  P3NodesT<double> out;
  for (int i = 0; i < 10; ++i) out[i] = {nodes[i].x(), nodes[i].y()};
  return out;
}

Vec2 p3_map(const P3Nodes& nodes, double u, double v) {
  const auto x = p3_map(to_array(nodes), u, v);
  return {x[0], x[1]};
}

Eigen::Matrix2d p3_jacobian(const P3Nodes& nodes, double u, double v) {
  const auto d = p3_basis_gradients(u, v);
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  for (int i = 0; i < 10; ++i) J += nodes[i] * Eigen::RowVector2d(d[i][0], d[i][1]);
  return J;
}

}  // namespace curvemesh::geometry
