#pragma once
// The feature soup as JSON (`curvemesh features`). Stable keys:
//   {"bbox": [xmin, ymin, xmax, ymax],
//    "curves": [{"p": [x0,y0,x1,y1,x2,y2,x3,y3], "source": i, "stroke": "#rrggbb"|"none"|"url(#id)",
//                "fill": ...}],
//    "points": [[x, y]], "point_sources": [i],
//    "sources": [{"tag": "path", "id": "...", "index": n, "line": n}],
//    "warnings": ["..."]}
// `source` indexes `sources`; `index` is the element's position in document order.
#include <nlohmann/json.hpp>

#include "svg/feature_soup.hpp"

namespace curvemesh::io {

nlohmann::ordered_json soup_to_json(const svg::FeatureSoup& soup);

}  // namespace curvemesh::io
