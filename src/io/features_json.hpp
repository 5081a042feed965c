#pragma once
// Processed features as JSON, added to the soup's keys (`curvemesh features --processed`):
//   "sections": [{"curve": i, "t": [t0, t1], "p": [8 numbers], "kind": "primary"|"secondary",
//                 "straight": bool, "polyline": [[x, y], ...], "ts": [...]}],
//   "segments": [{"a": [x, y], "b": [x, y], "curve": i, "t": [t0, t1]}],   (secondary, simplified)
//   "feature_points": [[x, y]], "feature_point_sources": [i],   (i indexes "sources")
//   "parameters": {"d", "mu", "epsilon", "eps_m", "l", "l_m", "alpha_deg", "junction_angle_deg", "features"},
//   "counts": {...}
#include <nlohmann/json.hpp>

#include "features/features.hpp"

namespace curvemesh::io {

void add_features_json(const features::Features& f, nlohmann::ordered_json& j);

// A drawing of the features: primary sections red (as curves), secondary segments green, points
// black, as in the paper's figures.
std::string features_to_svg(const features::Features& f);

}  // namespace curvemesh::io
