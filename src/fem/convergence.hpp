#pragma once
// The check that curved geometry pays: a Poisson problem with a known smooth solution on a disk
// made from an SVG circle, meshed at shrinking edge lengths, solved with P2 on the cubic map
// and with P2 on the straight map of the same meshes.
//
//   −Δu = f in the unit disk, u = 0 on its circle, u = (1 − x² − y²) eˣ cos y.
//
// The circle is drawn as 32 arcs, which the reader turns into cubics within 1e-9 of it (two each):
// the curved meshes then carry no geometric error the finest level could see, and the straight
// ones carry O(h²). The cubics' ends, every 5.6°, are vertices the mesh keeps: at the coarsest
// levels its boundary edges are no longer than its inner ones. (A <circle>'s cubics end every 10°:
// there its boundary edges would be longer than h, and the straight map's error would fall faster
// than h² from the coarsest level to the next, 2.3 over the five levels.)
#include <string>
#include <vector>

#include "pipeline/parameters.hpp"

namespace curvemesh::fem {

struct ConvergenceOptions {
  std::vector<double> edge_lengths_rel = {0.04, 0.028, 0.02, 0.014, 0.01};  // -l of each level
  pipeline::Parameters parameters;  // of the meshes; the edge length is each level's
};

struct ConvergenceLevel {
  double edge_length_rel = 0;
  double h = 0;          // mean edge length of the disk's triangles (corners), in units of the radius
  int triangles = 0;     // in the disk
  int unknowns = 0;      // P2 unknowns in the disk
  double l2 = 0, h1 = 0;  // ‖u_h − u‖ and |u_h − u|
  double seconds = 0;    // assembly and solve
};

struct ConvergenceSeries {
  std::vector<ConvergenceLevel> levels;
  double rate_l2 = 0, rate_h1 = 0;  // least-squares slopes of log error against log h
};

struct ConvergenceResult {
  ConvergenceSeries p3_geometry, p1_geometry;
  double mesh_seconds = 0;
};

// The SVG of the disk.
std::string disk_svg();

ConvergenceResult poisson_convergence(const ConvergenceOptions& options = {});

// Least-squares slope of log y against log x.
double convergence_rate(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace curvemesh::fem
