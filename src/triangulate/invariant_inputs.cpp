#include "triangulate/invariant_inputs.hpp"

#include "geometry/bezier_analysis.hpp"

namespace curvemesh::triangulate {

mesh::Constraints invariant_inputs(const features::Features& features, const geometry::Box2& box) {
  mesh::Constraints c;
  c.sections.reserve(features.sections.size());
  for (const features::Section& s : features.sections)
    c.sections.push_back({s.piece, s.t0, s.t1, s.kind == features::Kind::primary && geometry::turns_monotonically(s.piece)});
  // Each segment in the group of its curve: a secondary edge stays within ε of its own curve.
  std::vector<std::array<geometry::Vec2, 2>> segments;
  std::vector<int> curves;
  segments.reserve(features.segments.size());
  curves.reserve(features.segments.size());
  for (const features::Segment& s : features.segments) segments.push_back({s.a, s.b}), curves.push_back(s.curve);
  c.envelope = geometry::SegmentEnvelope(std::move(segments), features.lengths.epsilon, std::move(curves));
  c.box = box;
  c.max_turning = features.lengths.alpha_rad;
  return c;
}

}  // namespace curvemesh::triangulate
