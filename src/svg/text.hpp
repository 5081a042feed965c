#pragma once
// <text> and <tspan> as their glyphs' outlines (SVG 1.1 §10), laid out as librsvg lays them out:
// the font properties inherited through the cascade, the character data with white space
// collapsed (§10.15), absolute and relative positions per character (x, y, dx, dy, §10.4), text
// chunks anchored by text-anchor (§10.9.1), letter-spacing, each run of characters shaped by
// HarfBuzz in the face fontconfig chooses (svg/fonts.hpp). Horizontal text only; no textPath,
// rotate, textLength or word-spacing.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "svg/fonts.hpp"
#include "svg/path_data.hpp"

namespace curvemesh::svg {

enum class TextAnchor : std::uint8_t { start, middle, end };

// librsvg's initial font-family, for text that names none (fontconfig substitutes a serif face
// where it is not installed, without a warning: the drawing asked for no family).
inline constexpr const char* kDefaultFontFamily = "Times New Roman";

// The text properties an element inherits (CSS Fonts; SVG 1.1 §10.9 text-anchor; the XML
// attribute xml:space, §10.15).
struct TextStyle {
  FontRequest font;  // no family: kDefaultFontFamily
  // font-size in user units. librsvg's initial value is 12, not CSS's medium (16): rsvg-convert
  // draws text without a font-size as at font-size="12".
  double size = 12;
  TextAnchor anchor = TextAnchor::start;
  // letter-spacing (CSS Text 3 §8.2): letter_spacing + letter_spacing_em · size between characters.
  double letter_spacing = 0, letter_spacing_em = 0;
  bool preserve_space = false;  // xml:space="preserve"
};

// Applies one declaration of the cascade to `style`; false when `name` is not a text property.
// A value that cannot be read leaves the property as inherited (CSS: an invalid declaration is
// ignored). Lengths in em and percentages of font-size refer to the inherited size, given as
// `parent_size`.
bool apply_text_declaration(std::string_view name, std::string_view value, double parent_size,
                            TextStyle& style);

// A list of lengths (x, y, dx, dy on text and tspan): user units, with % of `percent_of` and em of
// `font_size`. Empty for an empty or malformed list (browsers ignore a malformed attribute).
std::vector<double> parse_length_list(std::string_view text, double percent_of, double font_size);

// What the reader gathers from one <text> element: its elements (the text element first, then
// its tspans in document order, each after its parent) and its character data in document order.
struct TextElement {
  TextStyle style;
  std::vector<double> x, y, dx, dy;            // per character, from the element's first (§10.4)
  std::size_t first_piece = 0, end_piece = 0;  // the pieces inside the element, its descendants' too
  bool drawn = true;  // false: visibility hidden; its characters advance but have no outlines
};
struct TextPiece {
  std::string_view data;  // character data, UTF-8
  int element = 0;        // the element it is directly in
  // Whether an element comes before it, or after it, among its siblings (librsvg strips leading
  // and trailing spaces of character data only where there is none).
  bool element_before = false, element_after = false;
};
struct TextContent {
  std::vector<TextElement> elements;
  std::vector<TextPiece> pieces;
};

// The outlines of consecutive glyphs drawn by one element, in the text element's user space.
struct GlyphRun {
  int element = 0;
  std::vector<Subpath> subpaths;
};

// Lays the text out and returns its glyphs' outlines. Stops with TooManyPieces once the outlines
// hold more than `max_curves` curves, before taking more memory; appends what the reader should
// warn about (a missing family, a missing glyph) to `warnings`, each once per distinct message.
std::vector<GlyphRun> layout_text(Fonts& fonts, const TextContent& content, std::size_t max_curves,
                                  std::vector<std::string>& warnings);

}  // namespace curvemesh::svg
