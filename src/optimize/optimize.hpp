#pragma once
// §4.1 second half: quality improvement of the linear mesh by TetWild's loop in 2D — split long
// edges, collapse short ones, swap, smooth, project feature vertices onto their curves — under
// the invariants of mesh/operations.hpp, with adaptive sizing where quality stalls.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

#include "mesh/constraints.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::optimize {

// The first five come from pipeline::Parameters, lengths made absolute.
struct Options {
  double edge_length = 0;                // l: target edge length
  double min_edge_length = 0;            // l_m: adaptive sizing never asks for less
  int max_iterations = 0;                // §4.1: passes at most
  // Refuse (base::LimitExceeded) a pass whose splits would take the mesh past this many triangles.
  std::size_t max_triangles = SIZE_MAX;
  double stop_min_angle_deg = 0;         // α: stop once every angle is at least this ...
  double stop_max_amips = 0;             // ... or every AMIPS energy is at most this (TetWild)
  // Sizing: near two vertices that can never merge (a tight bend of a curve), the target is this
  // factor times their distance, and it grows away from there by `gradation` per unit length.
  double pinned_size_factor = 3.0;
  double gradation = 1.0;
  // Smoothing rounds, after each pass, on the vertices of the triangles still above stop_max_amips.
  int extra_smoothing_rounds = 10;
  // Coarsening after the loop: collapses against the target length alone, at most this many rounds.
  bool coarsen = true;
  int coarsening_rounds = 8;
  // The curved pipeline: coarsening also refuses a collapse or swap that leaves a triangle whose
  // curved form, as the curve stage first makes it (mesh::curved_element), is above
  // curved_stop_amips and above the worst it replaces.
  bool curved = false;
  double curved_stop_amips = 20;
  std::ostream* log = nullptr;           // one line per iteration when set (--verbose)
  // Called after each iteration with its number (from 1), the triangles and the worst AMIPS energy.
  std::function<void(int iteration, int triangles, double max_amips)> on_iteration;
};

struct Quality {
  int vertices = 0, triangles = 0;
  double min_angle_deg = 0, max_amips = 0, mean_amips = 0, mean_edge_length = 0;
};

struct Stats {
  int iterations = 0;
  long splits = 0, collapses = 0, swaps = 0, smooths = 0, projections = 0;
  long coarsening_collapses = 0;  // collapses in coarsening (not in `collapses`)
  int coarsening_rounds = 0;
  int before_coarsening = 0;  // triangles
  long released = 0;    // secondary edges whose tag was dropped (mesh::release_secondary_edge)
  int unprojected = 0;  // primary vertices still off their curve at the end
  int exact_left = 0;   // vertices that could not be rounded to doubles (0 in a writable mesh)
  Quality initial, final;
  std::string stop_reason;
  double seconds = 0;
};

// Measures the mesh as stored (doubles).
Quality measure(const mesh::TriMesh& mesh);
// The same without the mean edge length (which needs every edge): what each iteration looks at.
Quality measure(const mesh::TriMesh& mesh, bool mean_edge_length);

// Coarsening, the last step of optimize (when options.coarsen): rounds of collapses of the edges
// shorter than edge_length, shortest first, judged against the target length alone (no new edge
// longer than 5/3 of it) rather than the sizing field the loop refined, each kept only under every
// invariant and with no new triangle above max(stop_max_amips, the worst it replaces) (nor, with
// `curved`, beside a curve above curved_stop_amips once curved); then a swap pass, and smoothing where
// the collapses and swaps changed the mesh. Adds to stats.
void coarsen(mesh::TriMesh& mesh, const mesh::Constraints& constraints, const Options& options, Stats& stats);

// Improves `mesh` in place.
Stats optimize(mesh::TriMesh& mesh, const mesh::Constraints& constraints, const Options& options);

}  // namespace curvemesh::optimize
