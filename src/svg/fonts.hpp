#pragma once
// Fonts for <text>, found and read as librsvg has Pango find and read them: fontconfig chooses a
// face for a family list, weight and slant (FcFontMatch); FreeType opens it and gives each glyph's
// outline; HarfBuzz shapes a run of characters into glyphs and their positions. One Fonts belongs
// to one reading of a drawing: it owns its FreeType library and fontconfig configuration (no
// process-wide state), made when the first text is drawn, and keeps each face (per file and index)
// and each glyph's outline once.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "svg/path_data.hpp"

namespace curvemesh::svg {

// CSS font-style, as fontconfig's slants.
enum class FontSlant : std::uint8_t { normal, italic, oblique };

// What a run of text asks for (CSS Fonts: font-family, font-weight, font-style).
struct FontRequest {
  std::vector<std::string> families;  // in order of preference; generic families allowed
  int weight = 400;                   // CSS 1..1000
  FontSlant slant = FontSlant::normal;
  auto operator<=>(const FontRequest&) const = default;
};

// The face fontconfig chose for a request.
struct FontMatch {
  int face = -1;       // for Fonts' other functions; -1: no font could be loaded
  std::string family;  // the chosen face's family name
  bool named = true;   // false: none of the request's families (other than generic ones) exists
};

// One glyph of a shaped run, in font units (the em is units_per_em), y up as in the font.
struct ShapedGlyph {
  std::uint32_t glyph = 0;    // 0 is .notdef: the font has no glyph for the character
  std::uint32_t cluster = 0;  // the index of the first character it draws
  double x_advance = 0, x_offset = 0, y_offset = 0;
};

class Fonts {
 public:
  Fonts();
  ~Fonts();
  Fonts(const Fonts&) = delete;
  Fonts& operator=(const Fonts&) = delete;

  // The face for a request; the first call sets fontconfig up (reading its caches). A family
  // that does not exist gives fontconfig's substitute for it (its default family at worst), as
  // Pango draws it, with `named` false. An empty string when everything worked, else why no font.
  FontMatch match(const FontRequest& request, std::string& problem);
  double units_per_em(int face) const;
  // HarfBuzz's glyphs for `text` (Unicode code points) in the face, with kerning and ligatures as
  // the font's default features give them, in visual order (left to right).
  std::vector<ShapedGlyph> shape(int face, const std::u32string& text);
  // The glyph's closed contours in font units, y up (exact: FreeType's conic pieces raised to
  // cubics of the same curve); empty for a glyph without an outline (a space, a bitmap).
  const std::vector<Subpath>& outline(int face, std::uint32_t glyph);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace curvemesh::svg
