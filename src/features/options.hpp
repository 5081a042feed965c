#pragma once
// Parameters of feature processing (paper §4), relative to the bounding-box diagonal d of the
// input, with the paper's defaults. `resolve` turns them into absolute lengths once.
namespace curvemesh::features {

struct Options {
  double mu_rel = 1e-3;                // μ: feature envelope, min distance between primary features
  double epsilon_rel = 2e-3;           // ε: envelope of secondary features (2μ); at least μ
  double eps_m_rel = 1e-8;             // ε_m: round-off tolerance on control points
  double alpha_deg = 10.0;             // α: max turning per primary edge (and target min angle)
  double edge_length_rel = 1.0 / 20;   // l: target edge length
  double min_edge_length_rel = 1e-4;   // l_m: curvature above α / l_m is secondary
  // Junction rule: primary pieces that share an endpoint may meet there if the angle between
  // them is at least this (a triangle with min angle α fits between them).
  double junction_angle_deg = 10.0;
};

// The same parameters as absolute lengths for a drawing of diagonal `d`.
struct Lengths {
  double d = 1, mu = 0, epsilon = 0, eps_m = 0, edge = 0, min_edge = 0;
  double alpha_rad = 0, junction_angle_rad = 0;
};

Lengths resolve(const Options& options, double diagonal);

}  // namespace curvemesh::features
