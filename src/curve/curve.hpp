#pragma once
// §4.2: from the optimized linear mesh to cubic (10-node) triangles whose primary edges follow
// their curves.
//
//  1. Triangles with more than one primary edge are split (at the middle of a non-primary edge,
//     or at the mid-parameter of a primary one) until each has at most one.
//  2. Every primary edge whose two vertices lie on the curve gets the cubic Lagrange nodes at 1/3
//     and 2/3 of its parameter interval (App. C); all other edges are straight (nodes at thirds).
//     The centre node reproduces quadratic maps (finite elements keep their order on such maps);
//     where that map is not certified, the paper's (the average of the nine others), then the
//     corners' centroid.
//  3. Validity: the Jacobian determinant of every curved triangle is certified positive on the
//     whole triangle (Bernstein coefficients, subdivision; geometry/p3_triangle). A primary edge
//     is straightened when either of its triangles cannot be certified with it curved.
//  4. Primary vertices still off their curve are projected onto it. Where a triangle's AMIPS
//     energy exceeds Options::stop_amips, smoothing first: its free and secondary corners move in
//     the plane (secondary edges inside the ε-envelope), its corners on curves along them, its
//     centre node anywhere, each move certified again. Then, for triangles still above, the local
//     operations of §4.1 on the curved mesh: a swap of one of its edges, else a collapse, else a
//     split of one edge or of the two edges at one corner, the new vertices smoothed; the touched
//     triangles get their P3 nodes and are certified, and the operation is kept only if fewer
//     of them are uncertified than before, or all are and their worst energy went down (the
//     linear mesh's journal takes a refused one back). Passes stop at the stop energy or after
//     Options::max_smoothing_passes. These run after step 5's first attempt, which may leave a
//     poor triangle.
//  5. A straightened edge gets its free opposite corners moved out of the curve's way; failing
//     that, it is fitted: bent towards the curve as far as its triangles stay certified and within
//     the stop energy. The distance left from every fitted or straight edge to its curve is
//     recorded.
//  6. Coarsening along the curves: invariant 3 (α per primary edge) is no longer needed once the
//     triangles are curved and certified (§4.2, Curved Mesh Optimization), so primary edges
//     shorter than l are collapsed along their curve, the merged edge covering any interval of
//     its section, where every changed triangle is certified, every new primary edge follows
//     its curve, no new edge is longer than 5/3 l and the worst energy of what changed is at
//     most max(Options::coarsen_amips, the worst it replaces).
// High-order nodes are shared: one per edge position, one centre per triangle.
//
// Order 2 (Options::order) makes the same steps on quadratic (6-node) triangles: a primary edge on
// its curve has its one inner node at the curve's point at the middle of its parameter interval,
// every other edge its middle; there is no centre node to choose or smooth, and the certificate
// is that of the degree-2 Jacobian determinant (geometry/p2_triangle). Such an edge is within
// quadratic_deviation of its curve, not on it: where that is above Options::tolerance the edge is
// split, on the linear mesh after step 1 and, for edges that a later step left there, by step 4's
// split at the end; no step may make a primary edge on its curve beyond it otherwise.
#include <array>
#include <functional>
#include <numbers>
#include <vector>

#include "geometry/vec2.hpp"
#include "mesh/constraints.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::curve {

using geometry::Vec2;

struct Options {
  int certificate_depth = 10;  // subdivision levels of the Jacobian certificate
  // The elements' order, 3 or 2 (pipeline::Parameters::order).
  int order = 3;
  // Order 2: the largest distance allowed between a primary edge on its curve and the curve
  // (quadratic_deviation); a primary edge no longer than min_split_length is not split for it.
  // Both from pipeline::Parameters (the tolerance, l_m); a tolerance of 0 allows any distance.
  double tolerance = 0;
  double min_split_length = 0;
  // Step 4 (§4.2): smoothing and the local operations on the curved mesh stop once every
  // triangle's AMIPS energy is at most this, or after this many passes (of each); both from
  // pipeline::Parameters.
  double stop_amips = 0;
  int max_smoothing_passes = 0;
  // Step 6: primary edges shorter than coarsen_edge_length are collapsed along their curve where
  // the triangles they change stay certified and at most max(coarsen_amips, the worst they
  // replace); 0 leaves the mesh as step 5 made it. Both from pipeline::Parameters (l, and the
  // linear stop energy).
  double coarsen_edge_length = 0;
  double coarsen_amips = 0;
  // Called at the start of each smoothing pass of step 4 (also those between the operations)
  // with the number of triangles above stop_amips and the worst energy among them.
  std::function<void(int above, double max_amips)> on_pass;
};

struct WedgeStats {
  double smallest_wedge = 2 * std::numbers::pi;  // radians, over the fixed vertices' wedges
  double smallest_wedge_bound = 0;  // wedge_amips_bound(smallest_wedge); 0 when there is no wedge
  int sharp_triangles = 0;          // triangles in a wedge whose bound is above the stop energy
  double max_amips_elsewhere = 0;   // the largest AMIPS over all other triangles
};

struct Stats {
  int split_triangles = 0;      // splits made so that every triangle has at most one primary edge
  int primary_edges = 0;        // primary edges of the final mesh
  int curved_edges = 0;         // of those, followed by the cubic map exactly (nodes on the curve)
  int fitted_edges = 0;         // bent towards the curve as far as certified (step 5), not on it
  int straight_primary_edges = 0;  // left straight: off the curve, or no bend certified at all
  int curved_triangles = 0;     // triangles with a curved edge
  int alternative_centres = 0;  // curved triangles certified only with another centre than the first
  double min_scaled_jacobian = 1;  // over curved triangles (geometry::JacobianCertificate)
  int invalid_triangles = 0;    // triangles whose map is not certified (0 in a mesh that is written)
  // The largest distance from a primary edge to its curve (the edge's point and the curve's at
  // equal fractions of the edge): order 3, from a fitted or straight one (the others are the
  // curve); order 2, from any.
  double max_distance = 0;
  double mean_fit_distance = 0;  // mean distance from a fitted edge to its curve
  // Quality of the curved mesh: the conformal AMIPS energy of each triangle's map, its largest
  // value over the triangle (geometry::p3_max_amips); the largest and the mean over triangles.
  double max_amips = 0, mean_amips = 0;
  double max_amips_before_smoothing = 0;  // the same before step 4
  int smoothing_moves = 0;                // corner and centre moves step 4 kept
  int curved_splits = 0, curved_collapses = 0, curved_swaps = 0;  // operations step 4 kept
  int coarsening_collapses = 0;                                    // collapses step 6 kept
  int late_projections = 0;               // primary vertices brought onto their curve only now
  int projections_elsewhere = 0;          // of those, placed on the curve away from their closest point
  int cleared_projections = 0;            // of those, placed once neighbours in the way had moved
  // Late projections and step 5's placements on the curve kept after a repair by step 4's
  // operations, and those taken back because the triangles around them stayed worse.
  int repaired_moves = 0;
  int refused_moves = 0;
  WedgeStats wedges;                      // the sharp wedges at fixed vertices, and the rest
  // Order 2: primary edges split so that their quadratic form is within the tolerance of their
  // curve, and the primary edges left farther than it (0 unless an edge could not be split).
  int tolerance_splits = 0;
  int beyond_tolerance = 0;
  double seconds = 0;
};

// A feature edge of the curved mesh: its order + 1 nodes (ends first, then the inner ones in
// order; the rest −1).
struct FeatureLine {
  std::array<int, 4> nodes;
  mesh::EdgeKind kind;
};

struct CurvedMesh {
  int order = 3;                    // 3 (10-node triangles, 4-node lines) or 2 (6-node, 3-node)
  mesh::TriMesh linear;             // the corners, tags and features after step 1
  std::vector<Vec2> nodes;          // vertices first (same indices as `linear`), then the rest
  // Per triangle its (order + 1)(order + 2) / 2 nodes in Gmsh's order (the rest −1):
  // counter-clockwise corners, the inner nodes of edges 0→1, 1→2, 2→0, then order 3's centre.
  std::vector<std::array<int, 10>> triangles;
  std::vector<FeatureLine> lines;   // every tagged edge, deterministic order
};

// The largest distance between a section's curve over [ta, tb] and the quadratic that
// interpolates it at ta, tb and their middle (an order-2 edge on its curve), at equal parameters.
// The curve is a cubic in the edge's parameter s ∈ [0, 1] and the quadratic interpolates it at
// s = 0, ½, 1, so their difference is w s (s − ½)(s − 1) with w the cubic's third difference
// P3 − 3P2 + 3P1 − P0 over [ta, tb]: at most |w| √3 / 36, reached. The distance between the edge
// and the curve as sets is at most this.
double quadratic_deviation(const mesh::SectionCurve& curve, double ta, double tb);

// The distance from a primary edge to its curve, as --stats reports it for every order: the edge
// (the polynomial through `nodes`, its two ends then its inner nodes, at equal steps of its
// parameter) at 33 points, each to the nearest point of the curve that Newton's method finds from
// the curve's point at the same fraction of the edge's parameter interval [ta, tb] (any point of
// the curve bounds the distance from above); the largest.
double edge_distance(const std::vector<Vec2>& nodes, const mesh::SectionCurve& curve, double ta, double tb);
// Its largest value over the primary edges of a straight mesh, and of a curved one.
double max_edge_distance(const mesh::TriMesh& linear, const mesh::Constraints& constraints);
double max_edge_distance(const CurvedMesh& mesh, const mesh::Constraints& constraints);

// Where tagged lines (curves, secondary lines, the box) leave a fixed vertex at a small angle,
// the triangles between them cannot all be good: k triangles filling a wedge of angle w are at
// best isosceles with apex w / k, of AMIPS (2 + 4 sin²(θ/2)) / (√3 sin θ) at θ = w / k. This is
// that best value for the best k (6.75 at 10°, 13.3 at 5°, 20 at about 3.3°).
double wedge_amips_bound(double wedge);

// The wedges of a finished curved mesh (corner directions from its nodes), with `amips` each
// triangle's energy (geometry::p3_max_amips, p2_max_amips) and stop_amips the curved stop energy.
WedgeStats wedges(const CurvedMesh& mesh, const std::vector<double>& amips, double stop_amips);

// `diagonal` is the input's bounding-box diagonal d. The linear mesh must be valid (the output of
// optimize). Never fails: the worst outcome is a straight mesh.
CurvedMesh curve(mesh::TriMesh linear, const mesh::Constraints& constraints, const Options& options = {},
                 Stats* stats = nullptr);

}  // namespace curvemesh::curve
