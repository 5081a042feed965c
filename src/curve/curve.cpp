// curve(): the schedule of §4.2 (the steps are listed in curve.hpp, their code in the files that
// curve/steps.hpp names), and the statistics of the result.
#include "curve/curve.hpp"

#include <chrono>

#include "curve/steps.hpp"

namespace curvemesh::curve {

namespace detail {

namespace {

double worst_energy(const Curving& cv) {
  double worst = 0;
  for (const double e : energies(cv)) worst = std::max(worst, e);
  return worst;
}

// After compaction: the energies, validity and wedges of the triangles, the feature lines and the
// distances of the primary edges from their curves.
void record_statistics(const Curving& cv, CurvedMesh& out) {
  const TriMesh& m = cv.mesh;
  const CurvedForm& form = cv.form;
  Stats& s = cv.stats;
  const std::vector<double> amips = energies(cv);
  for (std::size_t k = 0; k < out.triangles.size(); ++k) {
    const int t = static_cast<int>(k);
    const double e = amips[k];
    s.max_amips = std::max(s.max_amips, e);
    s.mean_amips += e / static_cast<double>(out.triangles.size());
    if (form.scaled(t) <= 0) ++s.invalid_triangles;
    if (form.curved_edge_of(m.triangle(t)) >= 0 || form.fitted_edge_of(m.triangle(t)) >= 0) {
      ++s.curved_triangles;
      s.min_scaled_jacobian = std::min(s.min_scaled_jacobian, form.scaled(t));
    }
  }
  s.wedges = wedges(out, amips, cv.options.stop_amips);
  for (const auto& [edge, f] : m.sorted_features()) {
    const auto [first, second] = form.edge_nodes(edge[0], edge[1]);
    out.lines.push_back({{edge[0], edge[1], first, form.quadratic() ? -1 : second}, f.kind});
    if (f.kind != EdgeKind::primary) continue;
    ++s.primary_edges;
    if (form.quadratic() && cv.options.tolerance > 0 &&
        deviation(cv, edge[0], edge[1]) > cv.options.tolerance)
      ++s.beyond_tolerance;
    const double distance = distance_to_curve(cv, edge[0], edge[1], f);
    if (form.follows(edge[0], edge[1])) {
      ++s.curved_edges;
    } else if (form.fitted(edge[0], edge[1])) {
      ++s.fitted_edges;
      s.mean_fit_distance += distance;
    } else {
      ++s.straight_primary_edges;
    }
    s.max_distance = std::max(s.max_distance, distance);
  }
  if (s.fitted_edges > 0) s.mean_fit_distance /= s.fitted_edges;
}

}  // namespace

}  // namespace detail

CurvedMesh curve(mesh::TriMesh linear, const mesh::Constraints& constraints, const Options& options,
                 Stats* stats) {
  using namespace detail;
  const auto start = std::chrono::steady_clock::now();
  Stats s;
  CurvedMesh out;
  out.order = options.order;
  s.split_triangles = split_until_one_primary_edge(linear, constraints);  // step 1
  if (options.order == 2) s.tolerance_splits = split_beyond_tolerance(linear, constraints, options);
  linear.compact();
  out.linear = std::move(linear);
  {
    CurvedForm form(out.linear, constraints, options.order);  // step 2: every edge's nodes
    Curving cv{out.linear, form, constraints, options, s};
    certify_placed_nodes(cv);  // steps 2 and 3: centres, certificates, straightened edges
    s.max_amips_before_smoothing = worst_energy(cv);
    // Step 4: smoothing where the curved triangles are worse than the stop energy. A vertex the
    // linear optimization left off its curve (Fig. 8) may get there now that edges bend; one
    // refused is tried again once the smoothing, and then the operations, changed its star.
    s.late_projections += project_late(cv);
    smooth(cv);
    s.late_projections += project_late(cv);
    fit_straight_edges(cv);  // step 5
    improve(cv);             // step 4's local operations
    s.late_projections += project_late(cv);
    coarsen(cv);  // step 6
    // Order 2: the edges a late projection, a fit or a straightened edge left beyond the
    // tolerance are split, whatever the energy; step 4 then improves what the splits made worse.
    if (meet_tolerance(cv) > 0) improve(cv);
    form.compact();
    out.nodes = form.nodes();
    out.triangles = form.triangles();
    record_statistics(cv, out);
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = s;
  return out;
}

}  // namespace curvemesh::curve
