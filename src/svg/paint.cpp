#include "svg/paint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "svg/numbers.hpp"

namespace curvemesh::svg {

std::string Paint::to_string() const {
  switch (kind) {
    case Kind::none:
      return "none";
    case Kind::url:
      return "url(#" + url + ")";
    case Kind::color: {
      char buf[8];
      std::snprintf(buf, sizeof buf, "#%02x%02x%02x", r, g, b);
      return buf;
    }
  }
  return "none";
}

namespace {

struct NamedColor {
  const char* name;
  std::uint32_t rgb;
};

// CSS Color Module Level 3, §4.3 extended colour keywords (sorted by name for binary search).
constexpr std::array<NamedColor, 147> kNamedColors = {{
    {"aliceblue", 0xf0f8ff}, {"antiquewhite", 0xfaebd7}, {"aqua", 0x00ffff}, {"aquamarine", 0x7fffd4},
    {"azure", 0xf0ffff}, {"beige", 0xf5f5dc}, {"bisque", 0xffe4c4}, {"black", 0x000000},
    {"blanchedalmond", 0xffebcd}, {"blue", 0x0000ff}, {"blueviolet", 0x8a2be2}, {"brown", 0xa52a2a},
    {"burlywood", 0xdeb887}, {"cadetblue", 0x5f9ea0}, {"chartreuse", 0x7fff00}, {"chocolate", 0xd2691e},
    {"coral", 0xff7f50}, {"cornflowerblue", 0x6495ed}, {"cornsilk", 0xfff8dc}, {"crimson", 0xdc143c},
    {"cyan", 0x00ffff}, {"darkblue", 0x00008b}, {"darkcyan", 0x008b8b}, {"darkgoldenrod", 0xb8860b},
    {"darkgray", 0xa9a9a9}, {"darkgreen", 0x006400}, {"darkgrey", 0xa9a9a9}, {"darkkhaki", 0xbdb76b},
    {"darkmagenta", 0x8b008b}, {"darkolivegreen", 0x556b2f}, {"darkorange", 0xff8c00}, {"darkorchid", 0x9932cc},
    {"darkred", 0x8b0000}, {"darksalmon", 0xe9967a}, {"darkseagreen", 0x8fbc8f}, {"darkslateblue", 0x483d8b},
    {"darkslategray", 0x2f4f4f}, {"darkslategrey", 0x2f4f4f}, {"darkturquoise", 0x00ced1},
    {"darkviolet", 0x9400d3}, {"deeppink", 0xff1493}, {"deepskyblue", 0x00bfff}, {"dimgray", 0x696969},
    {"dimgrey", 0x696969}, {"dodgerblue", 0x1e90ff}, {"firebrick", 0xb22222}, {"floralwhite", 0xfffaf0},
    {"forestgreen", 0x228b22}, {"fuchsia", 0xff00ff}, {"gainsboro", 0xdcdcdc}, {"ghostwhite", 0xf8f8ff},
    {"gold", 0xffd700}, {"goldenrod", 0xdaa520}, {"gray", 0x808080}, {"green", 0x008000},
    {"greenyellow", 0xadff2f}, {"grey", 0x808080}, {"honeydew", 0xf0fff0}, {"hotpink", 0xff69b4},
    {"indianred", 0xcd5c5c}, {"indigo", 0x4b0082}, {"ivory", 0xfffff0}, {"khaki", 0xf0e68c},
    {"lavender", 0xe6e6fa}, {"lavenderblush", 0xfff0f5}, {"lawngreen", 0x7cfc00}, {"lemonchiffon", 0xfffacd},
    {"lightblue", 0xadd8e6}, {"lightcoral", 0xf08080}, {"lightcyan", 0xe0ffff},
    {"lightgoldenrodyellow", 0xfafad2}, {"lightgray", 0xd3d3d3}, {"lightgreen", 0x90ee90},
    {"lightgrey", 0xd3d3d3}, {"lightpink", 0xffb6c1}, {"lightsalmon", 0xffa07a}, {"lightseagreen", 0x20b2aa},
    {"lightskyblue", 0x87cefa}, {"lightslategray", 0x778899}, {"lightslategrey", 0x778899},
    {"lightsteelblue", 0xb0c4de}, {"lightyellow", 0xffffe0}, {"lime", 0x00ff00}, {"limegreen", 0x32cd32},
    {"linen", 0xfaf0e6}, {"magenta", 0xff00ff}, {"maroon", 0x800000}, {"mediumaquamarine", 0x66cdaa},
    {"mediumblue", 0x0000cd}, {"mediumorchid", 0xba55d3}, {"mediumpurple", 0x9370db},
    {"mediumseagreen", 0x3cb371}, {"mediumslateblue", 0x7b68ee}, {"mediumspringgreen", 0x00fa9a},
    {"mediumturquoise", 0x48d1cc}, {"mediumvioletred", 0xc71585}, {"midnightblue", 0x191970},
    {"mintcream", 0xf5fffa}, {"mistyrose", 0xffe4e1}, {"moccasin", 0xffe4b5}, {"navajowhite", 0xffdead},
    {"navy", 0x000080}, {"oldlace", 0xfdf5e6}, {"olive", 0x808000}, {"olivedrab", 0x6b8e23},
    {"orange", 0xffa500}, {"orangered", 0xff4500}, {"orchid", 0xda70d6}, {"palegoldenrod", 0xeee8aa},
    {"palegreen", 0x98fb98}, {"paleturquoise", 0xafeeee}, {"palevioletred", 0xdb7093},
    {"papayawhip", 0xffefd5}, {"peachpuff", 0xffdab9}, {"peru", 0xcd853f}, {"pink", 0xffc0cb},
    {"plum", 0xdda0dd}, {"powderblue", 0xb0e0e6}, {"purple", 0x800080}, {"red", 0xff0000},
    {"rosybrown", 0xbc8f8f}, {"royalblue", 0x4169e1}, {"saddlebrown", 0x8b4513}, {"salmon", 0xfa8072},
    {"sandybrown", 0xf4a460}, {"seagreen", 0x2e8b57}, {"seashell", 0xfff5ee}, {"sienna", 0xa0522d},
    {"silver", 0xc0c0c0}, {"skyblue", 0x87ceeb}, {"slateblue", 0x6a5acd}, {"slategray", 0x708090},
    {"slategrey", 0x708090}, {"snow", 0xfffafa}, {"springgreen", 0x00ff7f}, {"steelblue", 0x4682b4},
    {"tan", 0xd2b48c}, {"teal", 0x008080}, {"thistle", 0xd8bfd8}, {"tomato", 0xff6347},
    {"turquoise", 0x40e0d0}, {"violet", 0xee82ee}, {"wheat", 0xf5deb3}, {"white", 0xffffff},
    {"whitesmoke", 0xf5f5f5}, {"yellow", 0xffff00}, {"yellowgreen", 0x9acd32},
}};

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::optional<Paint> parse_hex(std::string_view h) {
  int v[6];
  if (h.size() != 3 && h.size() != 6) return std::nullopt;
  for (std::size_t i = 0; i < h.size(); ++i)
    if ((v[i] = hex_digit(h[i])) < 0) return std::nullopt;
  if (h.size() == 3) return Paint::rgb(std::uint8_t(v[0] * 17), std::uint8_t(v[1] * 17), std::uint8_t(v[2] * 17));
  return Paint::rgb(std::uint8_t(v[0] * 16 + v[1]), std::uint8_t(v[2] * 16 + v[3]), std::uint8_t(v[4] * 16 + v[5]));
}

// "rgb(" already consumed from the lowered text; parses "r, g, b)" with optional alpha.
std::optional<Paint> parse_rgb_function(std::string_view args) {
  if (args.empty() || args.back() != ')') return std::nullopt;
  args.remove_suffix(1);
  NumberScanner in(args);
  std::array<std::uint8_t, 3> c{};
  try {
    for (int i = 0; i < 3; ++i) {
      double v = in.number();
      if (in.peek() == '%') {
        in.advance();
        v = v * 255.0 / 100.0;
      }
      c[i] = std::uint8_t(std::clamp(std::lround(v), 0L, 255L));
      in.skip_separator();
      if (in.peek() == '/') {  // CSS4 space-separated alpha
        in.advance();
        in.skip_whitespace();
      }
    }
  } catch (const SyntaxError&) {
    return std::nullopt;
  }
  return Paint::rgb(c[0], c[1], c[2]);
}

}  // namespace

std::optional<Paint> parse_color(std::string_view text) {
  text = trim_svg_whitespace(text);
  if (text.empty()) return std::nullopt;
  if (text[0] == '#') return parse_hex(text.substr(1));
  const std::string l = lower(text);
  if (l.rfind("rgb(", 0) == 0) return parse_rgb_function(std::string_view(l).substr(4));
  if (l.rfind("rgba(", 0) == 0) return parse_rgb_function(std::string_view(l).substr(5));
  const auto it = std::lower_bound(kNamedColors.begin(), kNamedColors.end(), l,
                                   [](const NamedColor& c, const std::string& n) { return c.name < n; });
  if (it != kNamedColors.end() && it->name == l)
    return Paint::rgb(std::uint8_t(it->rgb >> 16), std::uint8_t(it->rgb >> 8), std::uint8_t(it->rgb));
  return std::nullopt;
}

std::optional<Paint> parse_paint(std::string_view text, const Paint& current_color) {
  text = trim_svg_whitespace(text);
  const std::string l = lower(text);
  if (l == "none" || l == "transparent") return Paint{};
  if (l == "currentcolor") return current_color;
  if (l.rfind("url(", 0) == 0) {
    const auto close = text.find(')');
    if (close == std::string_view::npos) return std::nullopt;
    std::string_view ref = trim_svg_whitespace(text.substr(4, close - 4));
    if (ref.size() >= 2 && (ref.front() == '"' || ref.front() == '\'')) ref = ref.substr(1, ref.size() - 2);
    const auto hash = ref.find('#');
    Paint p;
    p.kind = Paint::Kind::url;
    p.url = std::string(hash == std::string_view::npos ? ref : ref.substr(hash + 1));
    return p;
  }
  return parse_color(text);
}

}  // namespace curvemesh::svg
