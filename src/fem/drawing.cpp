#include "fem/drawing.hpp"

#include <chrono>

#include "features/features.hpp"
#include "io/curved_mesh.hpp"
#include "triangulate/constraints.hpp"

namespace curvemesh::fem {

MeshedDrawing mesh_drawing(const svg::FeatureSoup& soup, DrawingOptions options) {
  const auto start = std::chrono::steady_clock::now();
  // One target length for the whole pipeline, as in `curvemesh mesh`.
  options.optimize.edge_length_rel = options.features.edge_length_rel;
  options.optimize.min_edge_length_rel = options.features.min_edge_length_rel;
  options.optimize.stop_min_angle_deg = options.features.alpha_deg;
  const features::Features f = features::process(soup, options.features);
  if (f.box.empty()) throw DrawingError("nothing to mesh (no curves, segments or points)");
  triangulate::Result tri = triangulate::triangulate(f, options.triangulate);
  const mesh::Constraints constraints = triangulate::constraints_of(f, tri.box);
  optimize::optimize(tri.mesh, constraints, f.lengths.d, options.optimize);
  if (tri.mesh.exact_vertex_count() > 0)
    throw DrawingError("vertices still have exact coordinates that do not round to doubles without inverting a triangle");
  curve::Stats stats;
  const curve::CurvedMesh curved = curve::curve(std::move(tri.mesh), constraints, options.curve, &stats);
  if (stats.invalid_triangles > 0) throw DrawingError("curved triangles could not be certified valid");

  MeshedDrawing out;
  out.mesh = io::curved_mesh(curved);
  out.diagonal = f.lengths.d;
  for (const curve::FeatureLine& line : curved.lines) {
    const int a = line.nodes[0], b = line.nodes[1];
    const auto feature = curved.linear.feature(a, b);
    out.line_curve.push_back(feature ? feature->curve : -1);
    // EdgeFeature's parameters are at the lower- and higher-numbered vertex. A secondary edge
    // has none (its vertices move within ε of the input): it follows its input segment, which runs
    // from the segment's t0 to its t1, when it points the same way.
    bool forward = true;
    if (feature && feature->kind == mesh::EdgeKind::primary) forward = (a < b) == (feature->t_lo < feature->t_hi);
    if (feature && feature->kind == mesh::EdgeKind::secondary && feature->source >= 0) {
      const features::Segment& s = f.segments[feature->source];
      const double along = (curved.linear.point(b) - curved.linear.point(a)).dot(s.b - s.a);
      forward = (along > 0) == (s.t0 <= s.t1);
    }
    out.line_forward.push_back(forward);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace curvemesh::fem
