#include "features/options.hpp"

#include <numbers>

namespace curvemesh::features {

Lengths resolve(const Options& o, double diagonal) {
  Lengths l;
  l.d = diagonal > 0 ? diagonal : 1.0;  // a soup of a single point has no size: use unit lengths
  l.mu = o.mu_rel * l.d;
  l.epsilon = o.epsilon_rel * l.d;
  l.eps_m = o.eps_m_rel * l.d;
  l.edge = o.edge_length_rel * l.d;
  l.min_edge = o.min_edge_length_rel * l.d;
  l.alpha_rad = o.alpha_deg * std::numbers::pi / 180.0;
  l.junction_angle_rad = o.junction_angle_deg * std::numbers::pi / 180.0;
  return l;
}

}  // namespace curvemesh::features
