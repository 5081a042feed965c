#pragma once
// CSS colours and SVG paint values for `fill`, `stroke` and `color`.
#include <cstddef>
#include <optional>
#include <string_view>

#include "svg/feature_soup.hpp"

namespace curvemesh::svg {

// A colour: "#rgb", "#rrggbb", "rgb(r, g, b)" (integers or percentages), "rgba(...)" (alpha
// dropped), or one of the 147 CSS named colours (case-insensitive). Nothing when invalid.
std::optional<Paint> parse_color(std::string_view text);

// A paint value: "none", "currentColor" (resolved to `current_color`), "url(#id) [fallback]", or a
// colour. "inherit" and invalid values give nothing: the caller keeps the inherited paint, as the
// SVG spec says an invalid presentation value is ignored.
std::optional<Paint> parse_paint(std::string_view text, const Paint& current_color);

// The longest id a paint may refer to, a fixed limit of the reader: a paint is copied onto every
// curve its element draws (up to the limit on curves), and ids are rarely more than a few dozen
// characters.
inline constexpr std::size_t kMaxPaintReference = 256;

}  // namespace curvemesh::svg
