#include "svg/text.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

// A length in user units: `percent_of` for 100 %, `font_size` for 1em (CSS Values 3 §6).
std::optional<double> length_value(std::string_view text, double percent_of, double font_size) {
  std::string_view unit;
  std::optional<double> n;
  try {
    n = parse_number_with_unit(text, &unit);
  } catch (const SyntaxError&) {
    return std::nullopt;
  }
  if (!n) return std::nullopt;
  const std::string u = lower(unit);
  double scale = 0;
  if (u.empty() || u == "px")
    scale = 1;
  else if (u == "%")
    scale = percent_of / 100;
  else if (u == "em")
    scale = font_size;
  else if (u == "ex")
    scale = font_size / 2;  // CSS: 0.5em where the font's x-height is not used
  else if (u == "pt")
    scale = 96.0 / 72.0;
  else if (u == "pc")
    scale = 16;
  else if (u == "mm")
    scale = 96.0 / 25.4;
  else if (u == "cm")
    scale = 96.0 / 2.54;
  else if (u == "in")
    scale = 96;
  else
    return std::nullopt;
  const double v = *n * scale;
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

// CSS Fonts 3 §3.5: the absolute font sizes, scaled from medium = 16px.
constexpr std::pair<const char*, double> kAbsoluteSizes[] = {
    {"xx-small", 3.0 / 5}, {"x-small", 3.0 / 4}, {"small", 8.0 / 9}, {"medium", 1},
    {"large", 6.0 / 5},    {"x-large", 3.0 / 2}, {"xx-large", 2}};

// font-size: a keyword (absolute, or larger/smaller by 1.2) or a non-negative length.
std::optional<double> font_size_value(std::string_view value, double parent_size) {
  const std::string v = lower(trim_svg_whitespace(value));
  for (const auto& [name, factor] : kAbsoluteSizes)
    if (v == name) return 16 * factor;
  if (v == "larger") return parent_size * 1.2;
  if (v == "smaller") return parent_size / 1.2;
  const std::optional<double> size = length_value(v, parent_size, parent_size);
  if (size && *size >= 0) return size;
  return std::nullopt;
}

// CSS Fonts 4 §2.2: a keyword, a number from 1 to 1000, or bolder/lighter than the inherited
// weight (the table of §2.2.1).
std::optional<int> font_weight_value(std::string_view value, int parent) {
  const std::string v = lower(trim_svg_whitespace(value));
  if (v == "normal") return 400;
  if (v == "bold") return 700;
  if (v == "bolder") return parent < 350 ? 400 : parent < 550 ? 700 : 900;
  if (v == "lighter") return parent < 550 ? 100 : parent < 750 ? 400 : 700;
  std::string_view unit;
  try {
    const std::optional<double> n = parse_number_with_unit(v, &unit);
    if (n && unit.empty() && *n >= 1 && *n <= 1000) return static_cast<int>(std::lround(*n));
  } catch (const SyntaxError&) {
  }
  return std::nullopt;
}

std::optional<FontSlant> font_style_value(std::string_view value) {
  const std::string v = lower(trim_svg_whitespace(value));
  if (v == "normal") return FontSlant::normal;
  if (v == "italic") return FontSlant::italic;
  if (v.starts_with("oblique")) return FontSlant::oblique;  // "oblique 10deg": the angle is not used
  return std::nullopt;
}

// CSS Fonts 4 §2.1: a comma-separated list of family names, quoted or as words (several words of
// one name joined by single spaces).
std::vector<std::string> font_families(std::string_view value) {
  std::vector<std::string> families;
  std::size_t start = 0;
  while (start <= value.size()) {
    std::size_t end = value.find(',', start);
    if (end == std::string_view::npos) end = value.size();
    std::string_view item = trim_svg_whitespace(value.substr(start, end - start));
    if (item.size() >= 2 && (item.front() == '"' || item.front() == '\'') && item.back() == item.front()) {
      item = item.substr(1, item.size() - 2);
    }
    std::string name;
    for (std::size_t i = 0; i < item.size(); ++i) {
      if (is_svg_whitespace(item[i])) {
        if (!name.empty() && name.back() != ' ') name += ' ';
      } else {
        name += item[i];
      }
    }
    if (!name.empty() && name.back() == ' ') name.pop_back();
    if (!name.empty()) families.push_back(name);
    start = end + 1;
  }
  return families;
}

// CSS Fonts 4 §2.8, the `font` shorthand: [style] [variant] [weight] [stretch] size[/line-height]
// family-list, every longhand reset first. Values it cannot read leave the style unchanged.
bool apply_font_shorthand(std::string_view value, double parent_size, TextStyle& style) {
  TextStyle out = style;
  out.font = TextStyle{}.font;
  out.size = TextStyle{}.size;
  std::size_t pos = 0;
  const auto next_word = [&]() {
    while (pos < value.size() && is_svg_whitespace(value[pos])) ++pos;
    const std::size_t start = pos;
    while (pos < value.size() && !is_svg_whitespace(value[pos])) ++pos;
    return value.substr(start, pos - start);
  };
  for (std::string_view word = next_word(); !word.empty(); word = next_word()) {
    const std::string_view size_part = word.substr(0, word.find('/'));
    if (const auto slant = font_style_value(word); slant && lower(word) != "normal") {
      out.font.slant = *slant;
    } else if (const auto weight = font_weight_value(word, style.font.weight);
               weight && lower(word) != "normal") {
      out.font.weight = *weight;
    } else if (const auto size = font_size_value(size_part, parent_size)) {
      out.size = *size;
      std::vector<std::string> families = font_families(value.substr(pos));
      if (families.empty()) return true;  // no family: not a valid shorthand
      out.font.families = std::move(families);
      style = out;
      return true;
    }
    // Anything else (normal, small-caps, a stretch keyword, a line height after '/') sets nothing
    // used here.
  }
  return true;
}

// CSS Text 3 §8.2: letter-spacing, "normal" (0) or a length (em of the element's font-size).
void apply_letter_spacing(std::string_view value, TextStyle& style) {
  const std::string v = lower(trim_svg_whitespace(value));
  std::string_view unit;
  std::optional<double> n;
  try {
    n = parse_number_with_unit(v, &unit);
  } catch (const SyntaxError&) {
  }
  if (v == "normal") {
    style.letter_spacing = style.letter_spacing_em = 0;
  } else if (n && (unit == "em" || unit == "ex")) {
    style.letter_spacing = 0;
    style.letter_spacing_em = unit == "em" ? *n : *n / 2;
  } else if (const auto px = unit == "%" ? std::nullopt : length_value(v, 0, 0)) {
    style.letter_spacing = *px;
    style.letter_spacing_em = 0;
  }
}

// The code point of UTF-8 (well-formed: the reader has repaired it) at `i`, which it moves on.
char32_t next_code_point(std::string_view s, std::size_t& i) {
  const unsigned char b = static_cast<unsigned char>(s[i]);
  const int n = b < 0x80 ? 1 : b < 0xE0 ? 2 : b < 0xF0 ? 3 : 4;
  char32_t c = n == 1 ? b : n == 2 ? (b & 0x1F) : n == 3 ? (b & 0x0F) : (b & 0x07);
  for (int k = 1; k < n && i + k < s.size(); ++k)
    c = (c << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
  i += n;
  return c;
}

}  // namespace

bool apply_text_declaration(std::string_view name, std::string_view value, double parent_size,
                            TextStyle& style) {
  if (name == "font-family") {
    std::vector<std::string> families = font_families(value);
    if (!families.empty() && lower(families.front()) != "inherit") style.font.families = std::move(families);
  } else if (name == "font-size") {
    if (const auto size = font_size_value(value, parent_size)) style.size = *size;
  } else if (name == "font-weight") {
    if (const auto weight = font_weight_value(value, style.font.weight)) style.font.weight = *weight;
  } else if (name == "font-style") {
    if (const auto slant = font_style_value(value)) style.font.slant = *slant;
  } else if (name == "text-anchor") {
    const std::string v = lower(trim_svg_whitespace(value));
    if (v == "start") style.anchor = TextAnchor::start;
    if (v == "middle") style.anchor = TextAnchor::middle;
    if (v == "end") style.anchor = TextAnchor::end;
  } else if (name == "letter-spacing") {
    apply_letter_spacing(value, style);
  } else if (name == "font") {
    apply_font_shorthand(value, parent_size, style);
  } else {
    return false;
  }
  return true;
}

std::vector<double> parse_length_list(std::string_view text, double percent_of, double font_size) {
  std::vector<double> values;
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && (is_svg_whitespace(text[pos]) || text[pos] == ',')) ++pos;
    const std::size_t start = pos;
    while (pos < text.size() && !is_svg_whitespace(text[pos]) && text[pos] != ',') ++pos;
    if (start == pos) break;
    const std::optional<double> v = length_value(text.substr(start, pos - start), percent_of, font_size);
    if (!v) return {};
    values.push_back(*v);
  }
  return values;
}

namespace {

// The text's characters once white space is handled (§10.15), each with the element it is in,
// and where each piece's characters begin (one entry more than pieces: the end).
struct Characters {
  std::u32string text;
  std::vector<int> element;
  std::vector<std::size_t> piece_start;
};

// Past `max_characters` (kept after white space is handled), throws TooManyPieces: the memory
// taken per character (about 100 bytes through shaping) stays bounded whatever the input.
Characters collect_characters(const TextContent& content, std::size_t max_characters) {
  Characters c;
  const auto preserved = [&](int element) { return content.elements[element].style.preserve_space; };
  std::u32string kept;
  for (const TextPiece& piece : content.pieces) {
    c.piece_start.push_back(c.text.size());
    kept.clear();
    const bool preserve = preserved(piece.element);
    for (std::size_t i = 0; i < piece.data.size();) {
      char32_t ch = next_code_point(piece.data, i);
      if (c.text.size() + kept.size() >= max_characters) throw TooManyPieces();
      // xml:space="preserve": newlines and tabs become spaces, and every space is kept.
      // "default": newlines removed, tabs become spaces, and runs of spaces one space.
      if ((ch == '\n' || ch == '\r') && !preserve) continue;
      if (ch == '\n' || ch == '\r' || ch == '\t') ch = ' ';
      if (ch == ' ' && !preserve && !kept.empty() && kept.back() == ' ') continue;
      kept.push_back(ch);
    }
    // Leading and trailing spaces are stripped per piece of character data, not across the text,
    // where no element is beside it (librsvg 2.54: "a<tspan> b</tspan>" draws "ab", and
    // "a <tspan/> b" keeps both spaces).
    std::size_t from = 0, to = kept.size();
    if (!preserve && !piece.element_before)
      while (from < to && kept[from] == ' ') ++from;
    if (!preserve && !piece.element_after)
      while (to > from && kept[to - 1] == ' ') --to;
    c.text.append(kept, from, to - from);
    c.element.insert(c.element.end(), to - from, piece.element);
  }
  c.piece_start.push_back(c.text.size());
  return c;
}

// Each character's absolute position (when given) and shift (§10.4): an element's lists give
// its characters' values from its first on, a descendant's own lists overriding its ancestors'.
struct CharacterPositions {
  std::vector<std::optional<double>> x, y;
  std::vector<double> dx, dy;
  bool positioned(std::size_t i) const { return x[i] || y[i] || dx[i] != 0 || dy[i] != 0; }
};

CharacterPositions positions_of(const TextContent& content, const Characters& chars) {
  const std::size_t n = chars.text.size();
  CharacterPositions at{std::vector<std::optional<double>>(n), std::vector<std::optional<double>>(n),
                        std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  // Elements come parents first: a later assignment is a descendant's.
  for (const TextElement& e : content.elements) {
    const std::size_t begin = chars.piece_start[e.first_piece], end = chars.piece_start[e.end_piece];
    const auto assign = [&](const std::vector<double>& list, auto& slots) {
      for (std::size_t k = 0; k < list.size() && begin + k < end; ++k) slots[begin + k] = list[k];
    };
    assign(e.x, at.x);
    assign(e.y, at.y);
    assign(e.dx, at.dx);
    assign(e.dy, at.dy);
  }
  return at;
}

// A glyph placed on its baseline, before its chunk is anchored.
struct PlacedGlyph {
  int face = -1;
  std::uint32_t glyph = 0;
  Vec2 origin;
  double scale = 1;  // user units per font unit
  int element = 0;
  std::size_t chunk = 0;
};

// A text chunk (§10.9.1): from one absolute position to the next, anchored as a whole.
struct Chunk {
  double start = 0, end = 0;  // the current text position where it starts and ends
  TextAnchor anchor = TextAnchor::start;
};

class Warnings {
 public:
  explicit Warnings(std::vector<std::string>& out) : out_(out) {}
  void add(const std::string& message) {
    if (seen_.insert(message).second) out_.push_back(message);
  }

 private:
  std::vector<std::string>& out_;
  std::set<std::string> seen_;
};

std::string family_list(const std::vector<std::string>& families) {
  std::string s;
  for (const std::string& f : families) s += (s.empty() ? "" : ", ") + f;
  return s;
}

// Shapes one run (characters of one element, no position given after its first) and places its
// glyphs from `pen`, which it advances; returns the letter spacing added after its last character
// (librsvg spaces letters apart, not a chunk's end from what follows: an end-anchored chunk ends
// at its last glyph's advance).
double place_run(Fonts& fonts, const TextStyle& style, int element, const std::u32string& run,
                 std::size_t chunk, Vec2& pen, std::vector<PlacedGlyph>& placed, Warnings& warnings) {
  if (!(style.size > 0)) return 0;  // CSS: a font-size of 0 draws nothing
  std::string problem;
  FontRequest request = style.font;
  if (request.families.empty()) request.families = {kDefaultFontFamily};
  const FontMatch font = fonts.match(request, problem);
  if (!problem.empty()) {
    warnings.add("text not drawn: " + problem);
    return 0;
  }
  if (!font.named && !style.font.families.empty())
    warnings.add("font-family '" + family_list(style.font.families) + "' is not installed: drawn in " +
                 font.family + ", fontconfig's substitute");
  const double scale = style.size / fonts.units_per_em(font.face);
  const double spacing = style.letter_spacing + style.letter_spacing_em * style.size;
  bool missing = false;
  const std::vector<ShapedGlyph> glyphs = fonts.shape(font.face, run);
  for (std::size_t i = 0; i < glyphs.size(); ++i) {
    const ShapedGlyph& g = glyphs[i];
    // Glyph offsets and the font's y axis point up; SVG's y points down.
    if (g.glyph != 0)
      placed.push_back({font.face, g.glyph, Vec2(pen.x() + g.x_offset * scale, pen.y() - g.y_offset * scale),
                        scale, element, chunk});
    missing = missing || g.glyph == 0;
    pen.x() += g.x_advance * scale;
    if (i + 1 == glyphs.size() || glyphs[i + 1].cluster != g.cluster)
      pen.x() += spacing;  // after a character
  }
  if (missing) warnings.add("characters that " + font.family + " has no glyph for are not drawn");
  return glyphs.empty() ? 0 : spacing;
}

// The placed glyphs' outlines, each chunk moved by its anchor, in runs of one element.
std::vector<GlyphRun> outlines_of(Fonts& fonts, const std::vector<PlacedGlyph>& placed,
                                  const std::vector<Chunk>& chunks, const std::vector<char>& drawn,
                                  std::size_t max_curves) {
  std::vector<GlyphRun> runs;
  std::size_t curves = 0;
  for (const PlacedGlyph& g : placed) {
    if (!drawn[g.element]) continue;  // hidden: neither read nor counted
    const std::vector<Subpath>& outline = fonts.outline(g.face, g.glyph);
    for (const Subpath& s : outline) curves += s.segments.size();
    if (curves > max_curves) throw TooManyPieces();
    const Chunk& chunk = chunks[g.chunk];
    const double advance = chunk.end - chunk.start;
    const double shift = chunk.anchor == TextAnchor::middle ? -advance / 2
                         : chunk.anchor == TextAnchor::end  ? -advance
                                                            : 0.0;
    const Vec2 origin = g.origin + Vec2(shift, 0);
    const auto map = [&](const Vec2& p) {
      return Vec2(origin.x() + p.x() * g.scale, origin.y() - p.y() * g.scale);
    };
    if (runs.empty() || runs.back().element != g.element) runs.push_back({g.element, {}});
    for (const Subpath& s : outline) {
      Subpath out;
      out.start = map(s.start);
      out.closed = true;
      out.segments.reserve(s.segments.size());
      for (const CubicBezier& c : s.segments)
        out.segments.emplace_back(map(c.p[0]), map(c.p[1]), map(c.p[2]), map(c.p[3]));
      runs.back().subpaths.push_back(std::move(out));
    }
  }
  return runs;
}

}  // namespace

std::vector<GlyphRun> layout_text(Fonts& fonts, const TextContent& content, std::size_t max_curves,
                                  std::vector<std::string>& warning_list) {
  // A character drawn is a curve at least (white space aside, which costs no more): the text is
  // refused at as many characters as curves are left.
  const Characters chars = collect_characters(content, max_curves);
  const CharacterPositions at = positions_of(content, chars);
  Warnings warnings(warning_list);
  std::vector<PlacedGlyph> placed;
  std::vector<Chunk> chunks;
  Vec2 pen = Vec2::Zero();  // the current text position (§10.4: x and y default to 0)
  const std::size_t n = chars.text.size();
  for (std::size_t i = 0, j = 0; i < n; i = j) {
    // A run: the characters of one element up to the next that is given a position.
    for (j = i + 1; j < n && chars.element[j] == chars.element[i] && !at.positioned(j);) ++j;
    const TextStyle& style = content.elements[chars.element[i]].style;
    if (at.x[i]) pen.x() = *at.x[i];
    if (at.y[i]) pen.y() = *at.y[i];
    // An absolute position starts a new chunk, anchored by its first character's text-anchor.
    if (chunks.empty() || at.x[i] || at.y[i]) chunks.push_back({pen.x(), pen.x(), style.anchor});
    pen += Vec2(at.dx[i], at.dy[i]);
    const double trailing = place_run(fonts, style, chars.element[i], chars.text.substr(i, j - i),
                                      chunks.size() - 1, pen, placed, warnings);
    chunks.back().end = pen.x() - trailing;
  }
  std::vector<char> drawn;
  for (const TextElement& e : content.elements) drawn.push_back(e.drawn);
  return outlines_of(fonts, placed, chunks, drawn, max_curves);
}

}  // namespace curvemesh::svg
