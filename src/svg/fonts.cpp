#include "svg/fonts.hpp"

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include <hb-ft.h>
#include <hb.h>

#include <algorithm>
#include <cctype>
#include <utility>

namespace curvemesh::svg {

namespace {

// CSS generic families (CSS Fonts 4 §2.1.3) and the "sans" Inkscape writes: fontconfig has a
// configured family for each, so naming one never lacks a font.
bool generic_family(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* g : {"serif", "sans-serif", "sans", "monospace", "cursive", "fantasy", "system-ui"})
    if (name == g) return true;
  return false;
}

int fontconfig_slant(FontSlant slant) {
  switch (slant) {
    case FontSlant::italic:
      return FC_SLANT_ITALIC;
    case FontSlant::oblique:
      return FC_SLANT_OBLIQUE;
    default:
      return FC_SLANT_ROMAN;
  }
}

// The outline being decomposed, in font units.
struct OutlineBuilder {
  std::vector<Subpath> contours;
  Vec2 at = Vec2::Zero();
};

Vec2 point(const FT_Vector* v) {
  return Vec2(double(v->x), double(v->y));
}

int move_to(const FT_Vector* to, void* user) {
  auto& b = *static_cast<OutlineBuilder*>(user);
  b.at = point(to);
  b.contours.push_back({b.at, {}, true, {}});
  return 0;
}

int line_to(const FT_Vector* to, void* user) {
  auto& b = *static_cast<OutlineBuilder*>(user);
  const Vec2 p = point(to);
  // FreeType closes every contour with a line back to its start, of length zero when the contour
  // ends there already: such a line would only be a degenerate curve.
  if (p != b.at && !b.contours.empty()) b.contours.back().segments.push_back(CubicBezier::line(b.at, p));
  b.at = p;
  return 0;
}

int conic_to(const FT_Vector* control, const FT_Vector* to, void* user) {
  auto& b = *static_cast<OutlineBuilder*>(user);
  const Vec2 c = point(control), p = point(to);
  // Degree elevation: the quadratic (a, c, p) is exactly the cubic (a, a + 2/3 (c − a),
  // p + 2/3 (c − p), p).
  if (!b.contours.empty())
    b.contours.back().segments.emplace_back(b.at, b.at + (c - b.at) * (2.0 / 3.0), p + (c - p) * (2.0 / 3.0),
                                            p);
  b.at = p;
  return 0;
}

int cubic_to(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
  auto& b = *static_cast<OutlineBuilder*>(user);
  const Vec2 p = point(to);
  if (!b.contours.empty()) b.contours.back().segments.emplace_back(b.at, point(c1), point(c2), p);
  b.at = p;
  return 0;
}

}  // namespace

struct Fonts::Impl {
  struct Face {
    FT_Face ft = nullptr;
    hb_font_t* hb = nullptr;
  };
  FT_Library library = nullptr;
  FcConfig* config = nullptr;
  bool set_up = false;
  std::string setup_problem;
  std::vector<Face> faces;
  std::map<std::pair<std::string, int>, int> face_of_file;  // (file, index in it) -> faces
  std::map<FontRequest, FontMatch> matches;
  std::map<std::pair<int, std::uint32_t>, std::vector<Subpath>> outlines;

  ~Impl() {
    for (Face& f : faces) {
      hb_font_destroy(f.hb);
      FT_Done_Face(f.ft);
    }
    if (library) FT_Done_FreeType(library);
    if (config) FcConfigDestroy(config);
  }

  void set_up_once() {
    if (set_up) return;
    set_up = true;
    if (FT_Init_FreeType(&library) != 0) {
      library = nullptr;
      setup_problem = "FreeType could not be started";
      return;
    }
    // A configuration of our own (fontconfig's default one is process-wide state).
    config = FcInitLoadConfigAndFonts();
    if (!config) setup_problem = "fontconfig could not load its configuration";
  }

  int open_face(const std::string& file, int index);
  FontMatch find(const FontRequest& request);
};

// Faces are opened once per (file, index) for the whole reading.
int Fonts::Impl::open_face(const std::string& file, int index) {
  const auto key = std::make_pair(file, index);
  if (const auto it = face_of_file.find(key); it != face_of_file.end()) return it->second;
  int id = -1;
  FT_Face ft = nullptr;
  if (FT_New_Face(library, file.c_str(), index, &ft) == 0) {
    if (FT_IS_SCALABLE(ft) && ft->units_per_EM > 0 &&
        // One pixel per font unit: HarfBuzz's positions (26.6 fixed point) are in font units.
        FT_Set_Char_Size(ft, 0, FT_F26Dot6(ft->units_per_EM) * 64, 72, 72) == 0) {
      hb_font_t* hb = hb_ft_font_create_referenced(ft);
      // Unhinted advances and outlines, as a renderer that scales freely (librsvg) uses them.
      hb_ft_font_set_load_flags(hb, FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP);
      id = static_cast<int>(faces.size());
      faces.push_back({ft, hb});
    } else {
      FT_Done_Face(ft);
    }
  }
  face_of_file.emplace(key, id);
  return id;
}

FontMatch Fonts::Impl::find(const FontRequest& request) {
  FontMatch result;
  FcPattern* pattern = FcPatternCreate();
  bool named_any = false;
  for (const std::string& family : request.families) {
    FcPatternAddString(pattern, FC_FAMILY, reinterpret_cast<const FcChar8*>(family.c_str()));
    named_any = named_any || !generic_family(family);
  }
  FcPatternAddDouble(pattern, FC_WEIGHT, FcWeightFromOpenTypeDouble(request.weight));
  FcPatternAddInteger(pattern, FC_SLANT, fontconfig_slant(request.slant));
  FcPatternAddBool(pattern, FC_OUTLINE, FcTrue);
  FcConfigSubstitute(config, pattern, FcMatchPattern);
  FcDefaultSubstitute(pattern);
  FcResult status = FcResultNoMatch;
  FcPattern* found = FcFontMatch(config, pattern, &status);
  FcPatternDestroy(pattern);
  if (!found) return result;
  FcChar8* file = nullptr;
  int index = 0;
  if (FcPatternGetString(found, FC_FILE, 0, &file) == FcResultMatch) {
    FcPatternGetInteger(found, FC_INDEX, 0, &index);
    result.face = open_face(reinterpret_cast<const char*>(file), index);
  }
  // The face is a requested family when one of its names (a face may have several, in several
  // languages) is one asked for; fontconfig compares family names without case.
  result.named = !named_any;
  FcChar8* name = nullptr;
  for (int k = 0; FcPatternGetString(found, FC_FAMILY, k, &name) == FcResultMatch; ++k) {
    if (k == 0) result.family = reinterpret_cast<const char*>(name);
    for (const std::string& family : request.families)
      if (!generic_family(family) &&
          FcStrCmpIgnoreCase(name, reinterpret_cast<const FcChar8*>(family.c_str())) == 0)
        result.named = true;
  }
  FcPatternDestroy(found);
  return result;
}

Fonts::Fonts() : impl_(std::make_unique<Impl>()) {}
Fonts::~Fonts() = default;

FontMatch Fonts::match(const FontRequest& request, std::string& problem) {
  impl_->set_up_once();
  problem = impl_->setup_problem;
  if (!problem.empty()) return {};
  if (const auto it = impl_->matches.find(request); it != impl_->matches.end()) return it->second;
  FontMatch m = impl_->find(request);
  if (m.face < 0) problem = "no font could be loaded for the family '" + m.family + "'";
  impl_->matches.emplace(request, m);
  return m;
}

double Fonts::units_per_em(int face) const {
  return impl_->faces.at(face).ft->units_per_EM;
}

std::vector<ShapedGlyph> Fonts::shape(int face, const std::u32string& text) {
  hb_font_t* font = impl_->faces.at(face).hb;
  hb_buffer_t* buffer = hb_buffer_create();
  hb_buffer_add_utf32(buffer, reinterpret_cast<const std::uint32_t*>(text.data()),
                      static_cast<int>(text.size()), 0, static_cast<int>(text.size()));
  hb_buffer_guess_segment_properties(buffer);
  hb_shape(font, buffer, nullptr, 0);
  unsigned count = 0;
  const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
  const hb_glyph_position_t* pos = hb_buffer_get_glyph_positions(buffer, &count);
  // The font's scale is 64 per font unit (26.6 fixed point at one pixel per unit).
  int x_scale = 0, y_scale = 0;
  hb_font_get_scale(font, &x_scale, &y_scale);
  const double upem = units_per_em(face);
  const double to_units_x = x_scale ? upem / x_scale : 0, to_units_y = y_scale ? upem / y_scale : 0;
  std::vector<ShapedGlyph> glyphs;
  glyphs.reserve(count);
  for (unsigned i = 0; i < count; ++i)
    glyphs.push_back({info[i].codepoint, info[i].cluster, pos[i].x_advance * to_units_x,
                      pos[i].x_offset * to_units_x, pos[i].y_offset * to_units_y});
  hb_buffer_destroy(buffer);
  return glyphs;
}

const std::vector<Subpath>& Fonts::outline(int face, std::uint32_t glyph) {
  const auto key = std::make_pair(face, glyph);
  if (const auto it = impl_->outlines.find(key); it != impl_->outlines.end()) return it->second;
  OutlineBuilder b;
  FT_Face ft = impl_->faces.at(face).ft;
  // Unscaled and unhinted: the designer's outline in font units, scaled by the caller exactly.
  if (FT_Load_Glyph(ft, glyph, FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING | FT_LOAD_NO_BITMAP) == 0 &&
      ft->glyph->format == FT_GLYPH_FORMAT_OUTLINE) {
    const FT_Outline_Funcs funcs{move_to, line_to, conic_to, cubic_to, 0, 0};
    if (FT_Outline_Decompose(&ft->glyph->outline, &funcs, &b) != 0) b.contours.clear();
  }
  std::erase_if(b.contours, [](const Subpath& s) { return s.segments.empty(); });
  return impl_->outlines.emplace(key, std::move(b.contours)).first->second;
}

}  // namespace curvemesh::svg
