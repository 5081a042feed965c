#pragma once
// A drawing of the feature soup: every curve as an SVG cubic in its stroke colour (black when it
// has none), isolated points as dots. For looking at what the reader produced.
#include <string>

#include "svg/feature_soup.hpp"

namespace curvemesh::io {

std::string soup_to_svg(const svg::FeatureSoup& soup);

}  // namespace curvemesh::io
