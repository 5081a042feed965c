#include "svg/reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <pugixml.hpp>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "base/files.hpp"
#include "base/gzip.hpp"
#include "base/text.hpp"
#include "svg/drawing_size.hpp"
#include "svg/entities.hpp"
#include "svg/error.hpp"
#include "svg/fonts.hpp"
#include "svg/numbers.hpp"
#include "svg/paint.hpp"
#include "svg/path_data.hpp"
#include "svg/shapes.hpp"
#include "svg/stroke.hpp"
#include "svg/stroke_union.hpp"
#include "svg/style.hpp"
#include "svg/text.hpp"
#include "svg/transform.hpp"

namespace curvemesh::svg {

namespace {

constexpr std::string_view kSvgNamespace = "http://www.w3.org/2000/svg";

// Inherited state while walking the tree.
struct Context {
  Affine ctm;                           // element coordinates -> root user space
  Paint fill = Paint::rgb(0, 0, 0);     // SVG initial values
  Paint stroke;
  Paint color = Paint::rgb(0, 0, 0);
  Paint left, right;                    // data-color-left / data-color-right (none: not given)
  FillRule fill_rule = FillRule::nonzero;
  StrokeStyle stroke_style;
  bool visible = true;
  double viewport_width = 100, viewport_height = 100;  // for percentage lengths
  int depth = 0;
  TextStyle text;                       // font properties, text-anchor, xml:space
  double parent_font_size = TextStyle{}.size;  // what em and % in this element's font-size refer to
  FillRule clip_rule = FillRule::nonzero;
  std::string clip_path;                // this element's clip-path (not inherited), as declared
  std::vector<int> clips;               // FeatureSoup::clips it and its ancestors are drawn through
};

// Bytes of malformed UTF-8 replaced so far, and the line of the first.
struct TextRepairs {
  std::size_t bytes = 0;
  int first_line = 0;
};

// The lines of a text, found from offsets: the newlines counted before every block of 1 KiB (a
// line start for each newline would take 8 bytes for every byte of a file of empty lines).
class LineIndex {
 public:
  explicit LineIndex(std::string_view text) : text_(text) {
    std::size_t count = 0;
    for (std::size_t b = 0; b < text.size(); b += kBlock) {
      before_.push_back(count);
      count += std::count(text.begin() + b, text.begin() + std::min(b + kBlock, text.size()), '\n');
    }
    before_.push_back(count);
  }
  // The 1-based line of the byte at `offset` (the last line past the end).
  int line_of(std::size_t offset) const {
    offset = std::min(offset, text_.size());
    const std::size_t block = offset / kBlock;
    const auto from = text_.begin() + block * kBlock;
    return static_cast<int>(1 + before_[block] + std::count(from, text_.begin() + offset, '\n'));
  }

 private:
  static constexpr std::size_t kBlock = 1024;
  std::string_view text_;
  std::vector<std::size_t> before_;  // newlines before each block, and in all
};

// The element after `node` in document order below `root` (its descendants first), `depth`
// following it; nothing after the last. Walks the tree in place: a document of many elements,
// or of deep ones, takes no memory to go through.
pugi::xml_node next_element(pugi::xml_node node, pugi::xml_node root, int& depth) {
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling())
    if (child.type() == pugi::node_element) {
      ++depth;
      return child;
    }
  for (; node != root; node = node.parent(), --depth)
    for (pugi::xml_node sibling = node.next_sibling(); sibling; sibling = sibling.next_sibling())
      if (sibling.type() == pugi::node_element) return sibling;
  return {};
}

// Which axis a length is measured along (for percentages, SVG 1.1 §7.10).
enum class Axis { x, y, other };

// Geometry collected before the degenerate-path pass (which needs the whole drawing's size).
struct PendingSubpath {
  std::vector<CubicBezier> segments;
  Vec2 start;
  int source;
  Paint stroke, fill, left, right;
  bool filled = false;  // drawn with a fill (its FillLayer is made already)
  bool closed = false;  // ended by Z
  std::vector<char> continues;  // Subpath::continues
};

// A closed subpath whose last curve came back to its start only to within `tolerance` (relative
// path data that does not sum back exactly, an editor's rounding): Z then added a straight line of
// that length back to the start, or the data has one. Such a line is degenerate — the features
// stage makes it an isolated point — and leaves the last curve ending beside the first instead of
// at it, so that the two look like curves crossing within μ and one of them loses its primary
// piece there to a straight secondary one. The degenerate closing pieces are dropped instead, and
// the last curve is moved onto the start (its end and last control point together, by at most
// `tolerance`, keeping its end tangent): the outline closes exactly, one smooth curve.
void close_exactly(PendingSubpath& sp, double tolerance) {
  if (!sp.closed) return;
  auto at_start = [&](const CubicBezier& c) {
    for (const Vec2& q : c.p)
      if ((q - sp.start).norm() > tolerance) return false;
    return true;
  };
  std::size_t kept = sp.segments.size();
  while (kept > 1 && at_start(sp.segments[kept - 1])) --kept;
  if (kept == sp.segments.size()) return;
  sp.segments.resize(kept);
  if (sp.continues.size() > kept) sp.continues.resize(kept);
  CubicBezier& last = sp.segments.back();
  last.p[2] += sp.start - last.p[3];
  last.p[3] = sp.start;
}

class Reader {
 public:
  Reader(std::string_view text, const ReadOptions& options) : text_(text), options_(options), lines_(text) {}

  FeatureSoup read();

 private:
  // --- document structure ---
  void parse_document();
  void prepare_tree();
  void prepare_node(pugi::xml_node node, TextRepairs& repairs);
  std::optional<std::string> repaired(std::string_view s, pugi::xml_node node, TextRepairs& repairs);
  void index_document(pugi::xml_node root);
  void number_sources(pugi::xml_node root);
  std::string_view local_name(pugi::xml_node node) const;  // "" for elements of other namespaces
  std::string_view text_of(pugi::xml_node node, const char* name) const;
  void count_read(pugi::xml_node node, std::size_t characters) const;  // against max_attribute_text
  std::string attr(pugi::xml_node node, const char* name) const { return std::string(text_of(node, name)); }
  bool has_attr(pugi::xml_node node, const char* name) const { return !node.attribute(name).empty(); }
  std::string href(pugi::xml_node node) const;
  int line_of(pugi::xml_node node) const;
  std::string where(pugi::xml_node node) const;
  [[noreturn]] void fail(pugi::xml_node node, const std::string& message) const;
  [[noreturn]] void too_many_curves(pugi::xml_node node) const;

  // --- walking ---
  void walk(pugi::xml_node node, Context ctx);
  void walk_children(pugi::xml_node node, const Context& ctx);
  bool apply_style(pugi::xml_node node, std::string_view tag, Context& ctx);  // false: display:none
  bool apply_declaration(pugi::xml_node node, std::string_view name, std::string_view value, Context& ctx);
  std::optional<Paint> paint(pugi::xml_node node, std::string_view value, const Context& ctx) const;
  void apply_side_colors(pugi::xml_node node, Context& ctx);
  void apply_transform(pugi::xml_node node, Context& ctx);
  void walk_use(pugi::xml_node node, Context ctx);
  void walk_viewport(pugi::xml_node node, pugi::xml_node content, Context ctx, double x, double y, double width,
                     double height);
  bool switch_child_passes(pugi::xml_node child) const;
  // The element's viewBox; nothing (and a warning) when it is missing or malformed.
  std::optional<ViewBox> view_box_of(pugi::xml_node node);

  // --- geometry ---
  double length(pugi::xml_node node, const char* name, Axis axis, const Context& ctx, double fallback) const;
  void draw_shape(pugi::xml_node node, std::string_view tag, const Context& ctx);
  std::vector<Subpath> shape_subpaths(pugi::xml_node node, std::string_view tag, const Context& ctx);
  // emit, with the element's clip paths on the fill layers it adds.
  void emit_clipped(pugi::xml_node node, std::string_view tag, const std::vector<Subpath>& subpaths,
                    const Context& ctx);
  // --- clip paths ---
  void apply_clip_path(pugi::xml_node node, Context& ctx);
  int clip_path_of(pugi::xml_node clip, const Context& ctx);  // -1: not applied
  bool add_clip_child(pugi::xml_node child, std::string_view tag, const Context& base, ClipPath& path);
  void emit(pugi::xml_node node, std::string_view tag, const std::vector<Subpath>& subpaths, const Context& ctx);
  // ReadOptions::strokes_as_areas: the outline of the element's stroke, a fill layer of its own.
  void emit_stroke_area(pugi::xml_node node, int source, const std::vector<Subpath>& subpaths, const Context& ctx);
  // <text>: its glyphs' outlines, emitted as each tspan's shapes (svg/text.hpp).
  void draw_text(pugi::xml_node node, const Context& ctx);
  void collect_text(pugi::xml_node node, const Context& ctx, TextContent& content, std::vector<Context>& contexts);
  // Once the drawing's size is known: a subpath to an isolated point when all of it lies within
  // `tolerance` (ε_m·d) of one point (paper §4), else to the soup's curves.
  void add_to_soup(PendingSubpath& sp, double tolerance);
  int source_of(pugi::xml_node node, std::string_view tag);
  void warn_once(const std::string& key, const std::string& message);

  std::string_view text_;
  const ReadOptions& options_;

  pugi::xml_document doc_;
  EntityTable entities_;
  LineIndex lines_;
  // Views of the id attributes' values, which stay in place once prepare_tree has run.
  std::unordered_map<std::string_view, pugi::xml_node> ids_;
  std::unordered_map<const void*, int> source_index_;
  std::unordered_map<const void*, int> renamed_lines_;  // elements whose name was repaired
  mutable std::size_t attribute_text_ = 0;              // characters read by text_of so far
  std::unordered_set<std::string> svg_prefixes_;  // namespace prefixes bound to SVG ("svg" usually)
  bool default_namespace_is_svg_ = true;
  StyleSheet stylesheet_;
  std::vector<pugi::xml_node> use_stack_;
  std::size_t instantiated_ = 0;
  std::size_t curve_count_ = 0;
  std::map<std::string, std::size_t> skipped_kinds_;
  std::unordered_set<std::string> warned_;

  std::vector<PendingSubpath> pending_;
  // Clip paths made so far, by clipPath element and the map to root user space they were made
  // under; whether one is being made (its children's own clip-paths are not applied).
  std::map<std::pair<const void*, std::array<double, 6>>, int> clip_index_;
  bool making_clip_ = false;
  int arcs_ = 0;  // arcs numbered in the soup so far (SoupCurve::arc)
  Fonts fonts_;   // set up when the first text is drawn
  FeatureSoup soup_;
};

// ---------------------------------------------------------------------------------------------
// Document structure

void Reader::parse_document() {
  entities_ = EntityTable::from_document(text_, options_.max_entity_expansion);
  for (const auto& name : entities_.external())
    warn_once("external-entity:" + name, "external entity '" + name + "' is not loaded");

  // White space between the tspans of a text is text (pugixml drops white-space-only character
  // data unless asked to keep it): "<tspan>0</tspan> <tspan>1</tspan>" draws "0 1".
  const pugi::xml_parse_result result = doc_.load_buffer(text_.data(), text_.size(),
                                                         pugi::parse_default | pugi::parse_ws_pcdata, pugi::encoding_auto);
  if (!result) {
    const std::size_t offset = result.offset < 0 ? 0 : static_cast<std::size_t>(result.offset);
    throw InputError(std::string("not well-formed XML: ") + result.description(),
                     "line " + std::to_string(lines_.line_of(offset)));
  }
}

std::string_view Reader::local_name(pugi::xml_node node) const {
  const std::string_view name = node.name();
  const auto colon = name.find(':');
  if (colon == std::string_view::npos) return default_namespace_is_svg_ ? name : std::string_view{};
  if (svg_prefixes_.count(std::string(name.substr(0, colon)))) return name.substr(colon + 1);
  return {};
}

// The value of an attribute that is read (parsed or matched), counted against
// options_.max_attribute_text: an element drawn through many <use> is read as many times, and a
// long attribute so multiplied would keep the reader busy for hours.
std::string_view Reader::text_of(pugi::xml_node node, const char* name) const {
  const std::string_view value = node.attribute(name).value();
  count_read(node, value.size());
  return value;
}

void Reader::count_read(pugi::xml_node node, std::size_t characters) const {
  attribute_text_ += characters;
  if (attribute_text_ > options_.max_attribute_text)
    fail(node, "the attributes read amount to more than " + std::to_string(options_.max_attribute_text) +
                   " characters, each <use> instance reading its element's again (a limit of the reader)");
}

std::string Reader::href(pugi::xml_node node) const {
  for (const pugi::xml_attribute a : node.attributes()) {
    const std::string_view n = a.name();
    if (n == "href" || (n.size() > 5 && n.substr(n.size() - 5) == ":href")) return attr(node, a.name());
  }
  return {};
}

int Reader::line_of(pugi::xml_node node) const {
  const std::ptrdiff_t offset = node.offset_debug();
  if (offset < 0) {
    const auto renamed = renamed_lines_.find(node.internal_object());
    return renamed == renamed_lines_.end() ? 0 : renamed->second;
  }
  return lines_.line_of(static_cast<std::size_t>(offset));
}

std::string Reader::where(pugi::xml_node node) const {
  // Repaired: a message may name an element before prepare_tree has reached it.
  std::string w = "line " + std::to_string(line_of(node)) + ", <" + base::repair_utf8(node.name());
  if (const char* id = node.attribute("id").value(); *id) w += " id=\"" + base::repair_utf8(id) + "\"";
  return w + ">";
}

void Reader::fail(pugi::xml_node node, const std::string& message) const { throw InputError(message, where(node)); }

// The text is read as pugixml decoded it (it converts UTF-16 and Latin-1 to UTF-8, but passes
// malformed UTF-8 through): entity references are expanded where the reader reads text
// (attribute values, <style> sheets), then every name and value is made well-formed UTF-8, as a
// browser decodes a malformed document. Nothing the reader passes on (ids, paints, warnings,
// messages) can then break a JSON library. Iterative: a document of any depth is safe here.
void Reader::prepare_tree() {
  TextRepairs repairs;
  pugi::xml_node node = doc_.first_child();
  while (node) {
    prepare_node(node, repairs);
    if (const pugi::xml_node child = node.first_child()) {
      node = child;
      continue;
    }
    while (node && !node.next_sibling()) {
      node = node.parent();
      if (node.type() == pugi::node_document) node = pugi::xml_node();
    }
    if (node) node = node.next_sibling();
  }
  if (repairs.bytes > 0)
    soup_.warnings.push_back("invalid UTF-8 replaced by U+FFFD (" + std::to_string(repairs.bytes) + " byte" +
                             (repairs.bytes == 1 ? "" : "s") + ", the first at line " +
                             std::to_string(repairs.first_line) + ")");
}

// `s` made well-formed UTF-8, counted in `repairs` at the line of `node`; nothing when it is
// well-formed already (the common case, which costs one scan).
std::optional<std::string> Reader::repaired(std::string_view s, pugi::xml_node node, TextRepairs& repairs) {
  if (base::valid_utf8(s)) return std::nullopt;
  std::size_t replaced = 0;
  std::string out = base::repair_utf8(s, &replaced);
  if (repairs.bytes == 0) repairs.first_line = line_of(node);
  repairs.bytes += replaced;
  return out;
}

void Reader::prepare_node(pugi::xml_node node, TextRepairs& repairs) {
  if (auto name = repaired(node.name(), node, repairs)) {
    renamed_lines_[node.internal_object()] = line_of(node);  // pugixml loses the offset of a renamed node
    node.set_name(name->c_str());
  }
  const auto expanded = [&](std::string_view value) -> std::optional<std::string> {
    if (entities_.empty() || value.find('&') == std::string_view::npos) return std::nullopt;
    try {
      return entities_.expand(value);
    } catch (const InputError& e) {
      fail(node.type() == pugi::node_element ? node : node.parent(), e.message());
    }
  };
  if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata) {
    // Of all text, the reader reads style sheets only (any prefix: the namespaces are not known yet).
    const std::string_view parent = node.parent().name();
    const bool sheet = parent == "style" || parent.ends_with(":style");
    // ... and the characters of text (SVG 1.1 §10.3: the character data of text and tspan).
    const auto drawn = [&](std::string_view tag) {
      return parent == tag || (parent.ends_with(tag) && parent[parent.size() - tag.size() - 1] == ':');
    };
    const bool characters = drawn("text") || drawn("tspan") || drawn("a");
    std::optional<std::string> text = sheet || characters ? expanded(node.value()) : std::nullopt;
    if (auto fixed = repaired(text ? *text : std::string_view(node.value()), node, repairs))
      text = std::move(fixed);
    if (text) node.set_value(text->c_str());
  }
  for (pugi::xml_attribute a : node.attributes()) {
    if (auto name = repaired(a.name(), node, repairs)) a.set_name(name->c_str());
    std::optional<std::string> value = expanded(a.value());
    if (auto fixed = repaired(value ? *value : std::string_view(a.value()), node, repairs))
      value = std::move(fixed);
    if (value) a.set_value(value->c_str());
  }
}

void Reader::warn_once(const std::string& key, const std::string& message) {
  if (warned_.insert(key).second) soup_.warnings.push_back(message);
}

// One pass over the whole document (iterative, so any depth is safe here): ids, <style> sheets,
// namespace prefixes and the nesting depth.
void Reader::index_document(pugi::xml_node root) {
  for (const pugi::xml_attribute a : root.attributes()) {
    const std::string_view n = a.name();
    // Illustrator writes xmlns="&ns_svg;": the value counts after entity expansion.
    if (n == "xmlns") {
      const std::string uri = attr(root, a.name());
      default_namespace_is_svg_ = uri == kSvgNamespace || uri.empty();
    }
    if (n.substr(0, 6) == "xmlns:" && attr(root, a.name()) == kSvgNamespace)
      svg_prefixes_.insert(std::string(n.substr(6)));
  }
  // A prefixed root (<svg:svg xmlns:svg="...">) is SVG even when the default namespace is not.
  int depth = 1;
  for (pugi::xml_node node = root; node; node = next_element(node, root, depth)) {
    if (depth > options_.max_depth)
      fail(node, "elements nested deeper than " + std::to_string(options_.max_depth) + " levels");
    if (const char* id = node.attribute("id").value(); *id) ids_.emplace(id, node);  // first id wins
    if (local_name(node) == "style") {
      std::string css;
      for (const pugi::xml_node child : node.children())
        if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) css += child.value();
      try {
        stylesheet_.add(css);
      } catch (const InputError& e) {
        fail(node, e.message());
      }
    }
  }
}

// Each source's position in document order, counting every element: found once the drawing is
// walked, for the few elements that draw, rather than kept for all.
void Reader::number_sources(pugi::xml_node root) {
  int index = 0, depth = 1;
  for (pugi::xml_node node = root; node; node = next_element(node, root, depth), ++index)
    if (const auto it = source_index_.find(node.internal_object()); it != source_index_.end())
      soup_.sources[it->second].index = index;
}

// ---------------------------------------------------------------------------------------------
// Styles and transforms

bool Reader::apply_style(pugi::xml_node node, std::string_view tag, Context& ctx) {
  // Cascade, lowest precedence first: presentation attributes, style sheet, style attribute.
  // Visited in place, never gathered: a style attribute may be as large as the file.
  std::vector<const Declarations*> sheet;
  ctx.stroke_style.non_scaling = false;  // vector-effect is not inherited
  if (!stylesheet_.empty()) {
    try {
      stylesheet_.match(tag, text_of(node, "id"), text_of(node, "class"), sheet);
    } catch (const InputError& e) {
      fail(node, e.message());
    }
  }
  const auto visit = [&](const std::function<bool(std::string_view, std::string_view)>& f) {
    for (const char* p : kStyleProperties)
      if (has_attr(node, p) && !f(p, text_of(node, p))) return false;
    for (const Declarations* block : sheet)
      for (const auto& [name, value] : *block)
        if (!f(name, value)) return false;
    return for_each_declaration(text_of(node, "style"), f);
  };
  ctx.parent_font_size = ctx.text.size;
  ctx.clip_path.clear();
  // `color` first: currentColor in fill/stroke refers to this element's computed colour.
  visit([&](std::string_view name, std::string_view value) {
    if (name == "color")
      if (auto c = parse_color(value)) ctx.color = *c;
    return true;
  });
  if (!visit([&](std::string_view name, std::string_view value) { return apply_declaration(node, name, value, ctx); }))
    return false;
  if (!ctx.clip_path.empty() && ctx.clip_path != "none") {
    if (making_clip_)
      ++soup_.clipped_elements;  // a clip of a clip's part: not applied
    else
      apply_clip_path(node, ctx);
  }
  return true;
}

// One declaration of the cascade; false when it hides the element (display: none).
bool Reader::apply_declaration(pugi::xml_node node, std::string_view name, std::string_view value,
                               Context& ctx) {
  if (name == "fill") {
    if (auto p = paint(node, value, ctx)) {
      ctx.fill = *p;
    } else if (trim_svg_whitespace(value) != "inherit") {
      // Not a paint we can read: leave the element unfilled rather than guess its colour.
      ctx.fill = Paint{};
      warn_once("bad-fill:" + std::string(value),
                where(node) + ": fill=\"" + std::string(value) +
                    "\" is not a paint this reader understands: left unfilled");
    }
  } else if (name == "fill-rule") {
    const std::string_view v = trim_svg_whitespace(value);
    if (v == "evenodd") ctx.fill_rule = FillRule::evenodd;
    if (v == "nonzero") ctx.fill_rule = FillRule::nonzero;
  } else if (name == "clip-path") {
    ctx.clip_path = trim_svg_whitespace(value);  // the cascade's last one is applied (apply_style)
  } else if (name == "clip-rule") {
    const std::string_view v = trim_svg_whitespace(value);
    if (v == "evenodd") ctx.clip_rule = FillRule::evenodd;
    if (v == "nonzero") ctx.clip_rule = FillRule::nonzero;
  } else if (name == "mask") {
    // A mask multiplies the paint by a luminance: no geometric cut to apply.
    if (trim_svg_whitespace(value) != "none") ++soup_.clipped_elements;
  } else if (name == "stroke") {
    if (auto p = paint(node, value, ctx)) ctx.stroke = *p;
  } else if (name == "display") {
    if (trim_svg_whitespace(value) == "none") return false;
  } else if (name == "visibility") {
    const std::string_view v = trim_svg_whitespace(value);
    if (v == "hidden" || v == "collapse") ctx.visible = false;
    if (v == "visible") ctx.visible = true;
  } else {
    const double w = ctx.viewport_width, h = ctx.viewport_height;  // SVG 1.1 §7.10: percentages
    apply_stroke_declaration(name, value, std::sqrt((w * w + h * h) / 2), ctx.stroke_style);
    apply_text_declaration(name, value, ctx.parent_font_size, ctx.text);
  }
  return true;
}

// parse_paint, refusing a reference too long to be copied onto every curve the element draws.
std::optional<Paint> Reader::paint(pugi::xml_node node, std::string_view value, const Context& ctx) const {
  std::optional<Paint> p = parse_paint(value, ctx.color);
  if (p && p->kind == Paint::Kind::url && p->url.size() > kMaxPaintReference)
    fail(node, "a paint refers to an id of more than " + std::to_string(kMaxPaintReference) +
                   " characters (a limit of the reader)");
  return p;
}

// The two colours of a diffusion curve are data attributes, not CSS properties: no style sheet or
// style attribute sets them, but like presentation attributes they pass from a group to what it
// draws. A value that is not a colour is ignored (the inherited one stays), with a warning: unlike
// a misspelt fill, nothing else in the document would show it.
void Reader::apply_side_colors(pugi::xml_node node, Context& ctx) {
  for (const auto& [name, slot] :
       {std::pair{"data-color-left", &ctx.left}, std::pair{"data-color-right", &ctx.right}}) {
    if (!has_attr(node, name)) continue;
    const std::string value = attr(node, name);
    if (const std::optional<Paint> c = parse_color(value))
      *slot = *c;
    else
      warn_once(std::string("bad-side-color:") + name + where(node),
                where(node) + ": ignored " + name + "=\"" + value + "\" (not a colour)");
  }
}

void Reader::apply_transform(pugi::xml_node node, Context& ctx) {
  if (!has_attr(node, "transform")) return;
  const std::string text = attr(node, "transform");
  try {
    ctx.ctm = ctx.ctm * parse_transform(text);
  } catch (const SyntaxError& e) {
    // Browsers ignore a malformed transform attribute (CSS: an invalid value is dropped), but a
    // number that is not finite has no drawing to fall back to.
    if (e.non_finite()) fail(node, std::string("bad transform: ") + e.what() + " at offset " + std::to_string(e.offset()));
    warn_once("bad-transform:" + where(node), where(node) + ": ignored a malformed transform (" + e.what() + ")");
  }
  if (!ctx.ctm.is_finite()) fail(node, "transforms overflow a double");
}

// ---------------------------------------------------------------------------------------------
// Lengths

double Reader::length(pugi::xml_node node, const char* name, Axis axis, const Context& ctx,
                      double fallback) const {
  if (!has_attr(node, name)) return fallback;
  const std::string value = attr(node, name);
  std::string_view unit;
  std::optional<double> number;
  try {
    number = parse_number_with_unit(value, &unit);
  } catch (const SyntaxError& e) {
    fail(node, std::string("attribute ") + name + ": " + e.what());
  }
  if (!number) return fallback;  // an invalid length is ignored, as browsers do
  double scale = 1.0;
  if (unit.empty() || unit == "px") {
    scale = 1.0;
  } else if (unit == "%") {
    const double w = ctx.viewport_width, h = ctx.viewport_height;
    scale = (axis == Axis::x ? w : axis == Axis::y ? h : std::sqrt((w * w + h * h) / 2.0)) / 100.0;
  } else if (unit == "pt") {
    scale = 96.0 / 72.0;
  } else if (unit == "pc") {
    scale = 16.0;
  } else if (unit == "mm") {
    scale = 96.0 / 25.4;
  } else if (unit == "cm") {
    scale = 96.0 / 2.54;
  } else if (unit == "in") {
    scale = 96.0;
  } else if (unit == "em") {
    scale = 16.0;  // the CSS default font size: drawings rarely set another on shapes
  } else if (unit == "ex") {
    scale = 8.0;
  } else {
    return fallback;
  }
  const double result = *number * scale;
  if (!std::isfinite(result)) fail(node, std::string("attribute ") + name + " overflows a double");
  return result;
}

// ---------------------------------------------------------------------------------------------
// Walking the tree

void Reader::walk_children(pugi::xml_node node, const Context& ctx) {
  for (const pugi::xml_node child : node.children())
    if (child.type() == pugi::node_element) walk(child, ctx);
}

bool Reader::switch_child_passes(pugi::xml_node child) const {
  // SVG 1.1 §5.8.2: conditional processing. We support no extensions; SVG 2 dropped features.
  if (has_attr(child, "requiredExtensions")) return false;
  if (has_attr(child, "systemLanguage")) {
    const std::string langs = attr(child, "systemLanguage");
    return langs.find("en") != std::string::npos;
  }
  return true;
}

void Reader::walk(pugi::xml_node node, Context ctx) {
  const std::string_view tag = local_name(node);
  if (tag.empty()) return;  // elements of other namespaces (sodipodi:, inkscape:, ...) draw nothing
  if (++ctx.depth > options_.max_depth)
    fail(node, "elements nested deeper than " + std::to_string(options_.max_depth) + " levels (through <use>)");
  if (++instantiated_ > options_.max_elements)
    fail(node, "the document has more than " + std::to_string(options_.max_elements) +
                   " elements, each <use> instance counted (--max-elements raises the limit)");
  if (!apply_style(node, tag, ctx)) return;
  apply_side_colors(node, ctx);

  if (tag == "g" || tag == "a") {
    apply_transform(node, ctx);
    walk_children(node, ctx);
  } else if (tag == "switch") {
    apply_transform(node, ctx);
    for (const pugi::xml_node child : node.children()) {
      if (child.type() != pugi::node_element || local_name(child).empty() || !switch_child_passes(child)) continue;
      walk(child, ctx);
      break;
    }
  } else if (tag == "svg") {
    // A nested viewport (the root is handled in read()).
    const double x = length(node, "x", Axis::x, ctx, 0), y = length(node, "y", Axis::y, ctx, 0);
    const double w = length(node, "width", Axis::x, ctx, ctx.viewport_width);
    const double h = length(node, "height", Axis::y, ctx, ctx.viewport_height);
    apply_transform(node, ctx);
    walk_viewport(node, node, ctx, x, y, w, h);
  } else if (tag == "use") {
    walk_use(node, ctx);
  } else if (tag == "path" || tag == "rect" || tag == "circle" || tag == "ellipse" || tag == "line" ||
             tag == "polyline" || tag == "polygon") {
    if (!ctx.visible) return;
    apply_transform(node, ctx);
    draw_shape(node, tag, ctx);
  } else if (tag == "text") {
    apply_transform(node, ctx);
    draw_text(node, ctx);
  } else if (tag == "image" || tag == "foreignObject") {
    ++skipped_kinds_[std::string(tag)];
  }
  // Everything else draws nothing by itself: defs, symbol, clipPath, mask, pattern, marker,
  // gradients, filters, style, metadata, title, desc, ... (SVG 1.1 §5.3: never rendered directly).
}

std::optional<ViewBox> Reader::view_box_of(pugi::xml_node node) {
  if (!has_attr(node, "viewBox")) return std::nullopt;
  const std::string text = attr(node, "viewBox");  // the scanner only views it
  NumberScanner in(text);
  ViewBox vb;
  try {
    vb.x = in.number();
    in.skip_separator();
    vb.y = in.number();
    in.skip_separator();
    vb.width = in.number();
    in.skip_separator();
    vb.height = in.number();
  } catch (const SyntaxError& e) {
    warn_once("viewBox", "ignored a malformed viewBox (" + std::string(e.what()) + ")");
    return std::nullopt;
  }
  if (vb.width < 0 || vb.height < 0) {  // SVG 1.1 §7.7: an error; browsers ignore the attribute
    warn_once("viewBox", "ignored a viewBox with a negative size");
    return std::nullopt;
  }
  return vb;
}

void Reader::walk_viewport(pugi::xml_node node, pugi::xml_node content, Context ctx, double x, double y,
                           double width, double height) {
  if (!(width > 0 && height > 0)) return;  // SVG 1.1 §5.1.2: a zero-sized viewport disables rendering
  const std::optional<ViewBox> view_box = view_box_of(node);
  if (view_box && (view_box->width == 0 || view_box->height == 0)) return;  // rendering disabled
  const bool has_view_box = view_box.has_value();
  const ViewBox vb = view_box.value_or(ViewBox{});
  if (has_view_box) {
    ctx.ctm = ctx.ctm * viewbox_transform(vb, attr(node, "preserveAspectRatio"), x, y, width, height);
    ctx.viewport_width = vb.width;
    ctx.viewport_height = vb.height;
  } else {
    ctx.ctm = ctx.ctm * Affine::translate(x, y);
    ctx.viewport_width = width;
    ctx.viewport_height = height;
  }
  if (!ctx.ctm.is_finite()) fail(node, "viewport transform overflows a double");
  walk_children(content, ctx);
}

void Reader::walk_use(pugi::xml_node node, Context ctx) {
  const std::string ref = href(node);
  if (ref.empty()) return;
  if (ref[0] != '#') {
    warn_once("external-use", "<use> of another file ('" + ref + "') is not followed");
    return;
  }
  const auto it = ids_.find(std::string_view(ref).substr(1));
  if (it == ids_.end()) {
    warn_once("missing-use:" + ref, "<use> refers to a missing element '" + ref + "'");
    return;
  }
  const pugi::xml_node target = it->second;
  // A reference to an element that is being instantiated, or to an ancestor of this <use>,
  // would expand forever (SVG 1.1 §5.6: such references are an error).
  if (std::find(use_stack_.begin(), use_stack_.end(), target) != use_stack_.end())
    fail(node, "<use> cycle through '" + ref + "'");
  for (pugi::xml_node p = node; p; p = p.parent())
    if (p == target) fail(node, "<use> refers to its own ancestor '" + ref + "'");

  apply_transform(node, ctx);
  const double x = length(node, "x", Axis::x, ctx, 0), y = length(node, "y", Axis::y, ctx, 0);
  use_stack_.push_back(target);
  const std::string_view target_tag = local_name(target);
  if (target_tag == "symbol" || target_tag == "svg") {
    // The <use> width/height override the referenced viewport's (SVG 1.1 §5.6).
    const double w = has_attr(node, "width") ? length(node, "width", Axis::x, ctx, 0)
                                              : length(target, "width", Axis::x, ctx, ctx.viewport_width);
    const double h = has_attr(node, "height") ? length(node, "height", Axis::y, ctx, 0)
                                               : length(target, "height", Axis::y, ctx, ctx.viewport_height);
    Context inner = ctx;
    if (!apply_style(target, target_tag, inner)) {
      use_stack_.pop_back();
      return;
    }
    apply_side_colors(target, inner);
    if (target_tag == "svg") {
      inner.ctm = inner.ctm * Affine::translate(x, y);
      apply_transform(target, inner);
      walk_viewport(target, target, inner, length(target, "x", Axis::x, ctx, 0),
                    length(target, "y", Axis::y, ctx, 0), w, h);
    } else {
      apply_transform(target, inner);
      walk_viewport(target, target, inner, x, y, w, h);
    }
  } else {
    ctx.ctm = ctx.ctm * Affine::translate(x, y);
    walk(target, ctx);
  }
  use_stack_.pop_back();
}

// ---------------------------------------------------------------------------------------------
// Geometry

int Reader::source_of(pugi::xml_node node, std::string_view tag) {
  const auto [it, inserted] = source_index_.emplace(node.internal_object(), static_cast<int>(soup_.sources.size()));
  if (inserted) {
    SourceElement s;
    s.tag = std::string(tag);
    s.id = node.attribute("id").value();
    s.index = -1;  // number_sources sets it
    s.line = line_of(node);
    soup_.sources.push_back(std::move(s));
  }
  return it->second;
}

void Reader::too_many_curves(pugi::xml_node node) const {
  fail(node, "the document has more than " + std::to_string(options_.max_curves) +
                 " curves (--max-curves raises the limit)");
}

void Reader::draw_shape(pugi::xml_node node, std::string_view tag, const Context& ctx) {
  emit_clipped(node, tag, shape_subpaths(node, tag, ctx), ctx);
}

void Reader::emit_clipped(pugi::xml_node node, std::string_view tag, const std::vector<Subpath>& subpaths,
                          const Context& ctx) {
  const std::size_t before = soup_.fills.size();
  emit(node, tag, subpaths, ctx);
  for (std::size_t i = before; i < soup_.fills.size(); ++i) soup_.fills[i].clips = ctx.clips;
}

std::vector<Subpath> Reader::shape_subpaths(pugi::xml_node node, std::string_view tag, const Context& ctx) {
  std::vector<Subpath> subpaths;
  // What is left of the curves allowed, so that parsing stops there, before taking the memory.
  const std::size_t allowed = options_.max_curves - curve_count_;
  if (tag == "path") {
    try {
      bool truncated = false;
      subpaths = parse_path_data(attr(node, "d"), &truncated, allowed);
      if (truncated)
        warn_once("truncated-path", where(node) + ": path data ends inside a command; drawn up to there");
    } catch (const SyntaxError& e) {
      fail(node, std::string("bad path data: ") + e.what() + " at offset " + std::to_string(e.offset()));
    } catch (const TooManyPieces&) {
      too_many_curves(node);
    }
  } else if (tag == "rect") {
    const double w = length(node, "width", Axis::x, ctx, 0), h = length(node, "height", Axis::y, ctx, 0);
    double rx = length(node, "rx", Axis::x, ctx, -1), ry = length(node, "ry", Axis::y, ctx, -1);
    if (rx < 0 && ry < 0) rx = ry = 0;
    if (rx < 0) rx = ry;  // SVG 1.1 §9.2: a missing radius takes the other's value
    if (ry < 0) ry = rx;
    subpaths = rect_subpaths(length(node, "x", Axis::x, ctx, 0), length(node, "y", Axis::y, ctx, 0), w, h, rx, ry);
  } else if (tag == "circle") {
    const double r = length(node, "r", Axis::other, ctx, 0);
    subpaths = ellipse_subpaths(length(node, "cx", Axis::x, ctx, 0), length(node, "cy", Axis::y, ctx, 0), r, r);
  } else if (tag == "ellipse") {
    double rx = length(node, "rx", Axis::x, ctx, -1), ry = length(node, "ry", Axis::y, ctx, -1);
    if (rx < 0) rx = ry;  // SVG 2: "auto" (or missing) takes the other radius
    if (ry < 0) ry = rx;
    subpaths =
        ellipse_subpaths(length(node, "cx", Axis::x, ctx, 0), length(node, "cy", Axis::y, ctx, 0), rx, ry);
  } else if (tag == "line") {
    const Vec2 a(length(node, "x1", Axis::x, ctx, 0), length(node, "y1", Axis::y, ctx, 0));
    const Vec2 b(length(node, "x2", Axis::x, ctx, 0), length(node, "y2", Axis::y, ctx, 0));
    subpaths.push_back({a, {CubicBezier::line(a, b)}, false, {}});
  } else {  // polyline, polygon
    try {
      bool odd = false;
      subpaths = polyline_subpaths(attr(node, "points"), tag == "polygon", &odd, allowed);
      if (odd) warn_once("odd-points", "a points list with an odd number of coordinates: the last was dropped");
    } catch (const SyntaxError& e) {
      fail(node, std::string("bad points: ") + e.what() + " at offset " + std::to_string(e.offset()));
    } catch (const TooManyPieces&) {
      too_many_curves(node);
    }
  }
  return subpaths;
}

void Reader::emit(pugi::xml_node node, std::string_view tag, const std::vector<Subpath>& subpaths,
                  const Context& ctx) {
  if (subpaths.empty()) return;
  const int source = source_of(node, tag);
  Paint fill = ctx.fill;
  // A paint server that is not in the document paints nothing (there is no fallback colour here).
  if (fill.kind == Paint::Kind::url && !ids_.count(std::string_view(fill.url))) fill = Paint{};
  const bool stroke_area = options_.strokes_as_areas && ctx.stroke.kind != Paint::Kind::none &&
                           (ctx.stroke.kind != Paint::Kind::url || ids_.count(std::string_view(ctx.stroke.url))) &&
                           ctx.stroke_style.width > 0 && (ctx.stroke_style.non_scaling || ctx.ctm.determinant() != 0);
  FillLayer* layer = nullptr;
  if (fill.kind != Paint::Kind::none) {
    soup_.fills.push_back({source, fill, ctx.fill_rule, {}, {}});
    layer = &soup_.fills.back();
  }
  for (const Subpath& sp : subpaths) {
    PendingSubpath out;
    out.start = ctx.ctm.apply(sp.start);
    out.closed = sp.closed;
    out.continues = sp.continues;
    out.source = source;
    out.stroke = ctx.stroke;
    out.fill = ctx.fill;
    // Left and right are the sides on screen: a mirroring map exchanges them.
    const bool mirrored = ctx.ctm.determinant() < 0;
    out.left = mirrored ? ctx.right : ctx.left;
    out.right = mirrored ? ctx.left : ctx.right;
    out.segments.reserve(sp.segments.size());
    for (const CubicBezier& c : sp.segments) {
      // An affine map of a Bézier curve is the Bézier curve of the mapped control points.
      CubicBezier m(ctx.ctm.apply(c.p[0]), ctx.ctm.apply(c.p[1]), ctx.ctm.apply(c.p[2]), ctx.ctm.apply(c.p[3]));
      for (const Vec2& q : m.p)
        if (!std::isfinite(q.x()) || !std::isfinite(q.y())) fail(node, "coordinates overflow a double");
      out.segments.push_back(m);
    }
    if (!std::isfinite(out.start.x()) || !std::isfinite(out.start.y())) fail(node, "coordinates overflow a double");
    if (layer && !out.segments.empty()) {
      // Filled as a closed loop: an open subpath by the line from its end back to its start.
      std::vector<CubicBezier> loop = out.segments;
      const Vec2 end = loop.back().p[3];
      if (end != out.start) loop.push_back(CubicBezier::line(end, out.start));
      for (const CubicBezier& c : loop) layer->bounds.add(c.control_bounds());
      layer->subpaths.push_back(std::move(loop));
      out.filled = true;
    }
    // The stroke's outline stands for the centre line, which stays the edge of the fill only (seen
    // between dashes).
    if (stroke_area && !out.filled) continue;
    if (stroke_area) out.stroke = Paint{};
    // A subpath without a segment becomes an isolated point, which costs as much as a curve.
    curve_count_ += std::max<std::size_t>(1, out.segments.size());
    if (curve_count_ > options_.max_curves) too_many_curves(node);
    pending_.push_back(std::move(out));
  }
  if (stroke_area) emit_stroke_area(node, source, subpaths, ctx);
}

// The stroke painted over the element's fill (SVG 2 §13.5: the stroke shape, filled nonzero). A
// non-scaling stroke's width is in the root's user space (what this reader's output is in, for
// the screen): the path is offset after its transform; any other is offset in the element's user
// space and transformed with it, as a non-uniform transform draws it.
void Reader::emit_stroke_area(pugi::xml_node node, int source, const std::vector<Subpath>& subpaths,
                              const Context& ctx) {
  const auto mapped = [&](std::vector<Subpath> paths) {
    for (Subpath& sp : paths) {
      sp.start = ctx.ctm.apply(sp.start);
      for (CubicBezier& c : sp.segments)
        for (Vec2& q : c.p) q = ctx.ctm.apply(q);
    }
    return paths;
  };
  const std::vector<Subpath> outline = ctx.stroke_style.non_scaling
                                           ? stroke_outline(mapped(subpaths), ctx.stroke_style)
                                           : mapped(stroke_outline(subpaths, ctx.stroke_style));
  FillLayer layer{source, ctx.stroke, FillRule::nonzero, {}, {}, true};
  // A transform draws the width narrowest along the direction it shrinks most.
  layer.width = ctx.stroke_style.width * (ctx.stroke_style.non_scaling ? 1.0 : ctx.ctm.smallest_scale());
  for (const Subpath& sp : outline) {
    for (const CubicBezier& c : sp.segments) {
      for (const Vec2& q : c.p)
        if (!std::isfinite(q.x()) || !std::isfinite(q.y())) fail(node, "coordinates overflow a double");
      layer.bounds.add(c.control_bounds());
    }
    layer.subpaths.push_back(sp.segments);
    curve_count_ += sp.segments.size();
    if (curve_count_ > options_.max_curves) too_many_curves(node);
  }
  // The regions count windings with the whole outline; the features need only the edge of what
  // it paints, where that can be found.
  const std::optional<std::vector<Subpath>> edge =
      painted_edge(outline, kStrokeTolerance * layer.width, options_.max_curves);
  for (const Subpath& sp : edge ? *edge : outline)
    pending_.push_back({sp.segments, sp.start, source, Paint{}, ctx.stroke, {}, {}, true, true, sp.continues});
  if (!layer.subpaths.empty()) soup_.fills.push_back(std::move(layer));
}

// ---------------------------------------------------------------------------------------------
// Clip paths (SVG 1.1 §14.3.5; CSS Masking 1 §6.1)

// The element's clip-path="url(#id)": the clip path made in the element's user space (its own
// transform included: clipPathUnits="userSpaceOnUse") is added to the clips of its fills and of
// its descendants'. A reference to no clipPath is ignored, as CSS Masking says, with a warning;
// objectBoundingBox units are not read (counted with the masks, the pipeline warns).
void Reader::apply_clip_path(pugi::xml_node node, Context& ctx) {
  const std::string value = std::exchange(ctx.clip_path, {});
  const std::optional<Paint> ref = paint(node, value, ctx);  // url(#id), read as a paint's reference
  const auto it = ref && ref->kind == Paint::Kind::url ? ids_.find(ref->url) : ids_.end();
  if (it == ids_.end() || local_name(it->second) != "clipPath") {
    warn_once("bad-clip:" + value, where(node) + ": ignored clip-path=\"" + value + "\" (no such clipPath)");
    return;
  }
  const pugi::xml_node clip = it->second;
  if (trim_svg_whitespace(text_of(clip, "clipPathUnits")) == "objectBoundingBox") {
    ++soup_.clipped_elements;
    return;
  }
  Context own = ctx;
  apply_transform(node, own);  // done again when the element is walked; a warning is given once
  if (const int index = clip_path_of(clip, own); index >= 0)
    ctx.clips.push_back(index);
  else
    ++soup_.clipped_elements;
}

// The clip path `clip` as seen through `ctx` (the referencing element's user space, and what
// percentages refer to): each child shape's outline, with the clipPath's and its own transform,
// closed as a fill closes it and decided by its clip-rule; its curves are features too, so that
// the mesh follows the clip's edge. Made once per clipPath and user space.
int Reader::clip_path_of(pugi::xml_node clip, const Context& ctx) {
  Context base = ctx;
  base.fill = Paint::rgb(0, 0, 0);  // a clip's shapes are filled whatever their paint (§14.3.5)
  base.stroke = Paint{};
  base.clips.clear();
  apply_transform(clip, base);  // SVG 2 lets a clipPath have its own transform; librsvg applies it
  const Affine& m = base.ctm;
  const auto key = std::make_pair(clip.internal_object(), std::array<double, 6>{m.a, m.b, m.c, m.d, m.e, m.f});
  if (const auto found = clip_index_.find(key); found != clip_index_.end()) return found->second;
  making_clip_ = true;
  ClipPath path;
  bool applied = true;
  // Properties inherit into the clipPath from its own ancestors (§14.3.5); here from defaults and
  // the clipPath's own style, which is what drawings rely on.
  if (apply_style(clip, "clipPath", base)) {
    for (const pugi::xml_node child : clip.children()) {
      const std::string_view tag = local_name(child);
      if (child.type() != pugi::node_element || tag.empty()) continue;
      if (!add_clip_child(child, tag, base, path)) {
        // Clipping by the rest alone would hide what this child lets through: not applied at all.
        warn_once("clip-child:" + std::string(tag), "a clipPath holding a <" + std::string(tag) +
                                                         "> is not applied (only shapes and <use> of shapes are)");
        applied = false;
      }
    }
  }
  making_clip_ = false;
  const int index = applied ? static_cast<int>(soup_.clips.size()) : -1;
  if (applied) soup_.clips.push_back(std::move(path));
  clip_index_.emplace(key, index);
  return index;
}

// One child of a clipPath: a shape, or a <use> of one, drawn as a filled shape (its curves become
// features) whose fill layer is then taken for the clip. False for any other element.
bool Reader::add_clip_child(pugi::xml_node child, std::string_view tag, const Context& base, ClipPath& path) {
  const auto is_shape = [](std::string_view t) {
    return t == "path" || t == "rect" || t == "circle" || t == "ellipse" || t == "line" || t == "polyline" ||
           t == "polygon";
  };
  if (++instantiated_ > options_.max_elements)
    fail(child, "the document has more than " + std::to_string(options_.max_elements) +
                    " elements, each <use> instance counted (--max-elements raises the limit)");
  Context c = base;
  if (!apply_style(child, tag, c)) return true;  // display:none: no part of the clip
  pugi::xml_node shape = child;
  std::string_view shape_tag = tag;
  if (tag == "use") {
    // SVG 1.1 §14.3.5: a <use> may refer to a shape directly, placed by its transform and x, y.
    const std::string ref = href(child);
    const auto it = ref.size() > 1 && ref[0] == '#' ? ids_.find(std::string_view(ref).substr(1)) : ids_.end();
    if (it == ids_.end()) return true;  // refers to nothing: draws nothing
    shape = it->second;
    shape_tag = local_name(shape);
    if (!is_shape(shape_tag)) return false;
    apply_transform(child, c);
    c.ctm = c.ctm * Affine::translate(length(child, "x", Axis::x, c, 0), length(child, "y", Axis::y, c, 0));
    if (!apply_style(shape, shape_tag, c)) return true;
  } else if (!is_shape(tag)) {
    return false;
  }
  if (!c.visible) return true;
  apply_transform(shape, c);
  c.fill = Paint::rgb(0, 0, 0);
  c.stroke = Paint{};
  const std::size_t before = soup_.fills.size();
  emit(shape, shape_tag, shape_subpaths(shape, shape_tag, c), c);
  for (std::size_t i = before; i < soup_.fills.size(); ++i) {
    path.shapes.push_back(std::move(soup_.fills[i]));
    path.shapes.back().rule = c.clip_rule;
  }
  soup_.fills.resize(before);
  return true;
}

// The element's characters and those of its tspans (and <a>s), each with its style; textPath and
// the deprecated tref are skipped. Recursion as deep as the document, which index_document bounds.
void Reader::collect_text(pugi::xml_node node, const Context& ctx, TextContent& content,
                          std::vector<Context>& contexts) {
  const int index = static_cast<int>(content.elements.size());
  TextElement element{ctx.text, {}, {}, {}, {}, content.pieces.size(), 0, ctx.visible};
  if (const std::string_view space = node.attribute("xml:space").value(); space == "preserve" || space == "default")
    element.style.preserve_space = space == "preserve";
  const auto list = [&](const char* name, double percent_of) {
    return has_attr(node, name) ? parse_length_list(text_of(node, name), percent_of, ctx.text.size)
                                : std::vector<double>{};
  };
  element.x = list("x", ctx.viewport_width);
  element.y = list("y", ctx.viewport_height);
  element.dx = list("dx", ctx.viewport_width);
  element.dy = list("dy", ctx.viewport_height);
  Context own = ctx;  // what its children inherit, xml:space too
  own.text.preserve_space = element.style.preserve_space;
  content.elements.push_back(std::move(element));
  contexts.push_back(own);
  // Whether an element is among the siblings before and after each piece of character data.
  pugi::xml_node last_element;
  for (const pugi::xml_node child : node.children())
    if (child.type() == pugi::node_element) last_element = child;
  bool element_before = false, element_after = bool(last_element);
  for (const pugi::xml_node child : node.children()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
      // Counted with the attributes: a <use> of a long text reads it again.
      const std::string_view data = child.value();
      count_read(node, data.size());
      content.pieces.push_back({data, index, element_before, element_after});
      continue;
    }
    if (child.type() != pugi::node_element) continue;
    element_before = true;
    if (child == last_element) element_after = false;
    const std::string_view tag = local_name(child);
    if (tag.empty()) continue;
    if (tag == "textPath" || tag == "tref") {
      ++skipped_kinds_[std::string(tag)];
      continue;
    }
    if (tag != "tspan" && tag != "a") continue;  // title, desc, metadata: not text
    if (++instantiated_ > options_.max_elements)
      fail(child, "the document has more than " + std::to_string(options_.max_elements) +
                      " elements, each <use> instance counted (--max-elements raises the limit)");
    Context inner = own;
    if (!apply_style(child, tag, inner)) continue;  // display:none: neither drawn nor laid out
    apply_side_colors(child, inner);
    collect_text(child, inner, content, contexts);
  }
  content.elements[index].end_piece = content.pieces.size();
}

void Reader::draw_text(pugi::xml_node node, const Context& ctx) {
  TextContent content;
  std::vector<Context> contexts;
  collect_text(node, ctx, content, contexts);
  std::vector<std::string> warnings;
  std::vector<GlyphRun> runs;
  try {
    runs = layout_text(fonts_, content, options_.max_curves - curve_count_, warnings);
  } catch (const TooManyPieces&) {
    too_many_curves(node);
  }
  for (const std::string& w : warnings) warn_once("text:" + w, w);
  // The text is one source element; each tspan's glyphs are drawn with the tspan's paint.
  for (const GlyphRun& run : runs) emit_clipped(node, "text", run.subpaths, contexts[run.element]);
}

// ---------------------------------------------------------------------------------------------

FeatureSoup Reader::read() {
  parse_document();
  prepare_tree();
  const pugi::xml_node root = doc_.document_element();
  if (!root) throw InputError("no root element");
  const std::string_view root_name = root.name();
  const auto colon = root_name.find(':');
  const std::string_view root_local = colon == std::string_view::npos ? root_name : root_name.substr(colon + 1);
  if (root_local != "svg")
    throw InputError("the root element is <" + std::string(root_name) + ">, not <svg>", where(root));
  if (colon != std::string_view::npos) svg_prefixes_.insert(std::string(root_name.substr(0, colon)));
  index_document(root);

  // The root's user space is our coordinate system: its viewBox (if any) only sets the size that
  // percentages refer to; its width/height scale nothing.
  Context ctx;
  if (!apply_style(root, "svg", ctx)) {
    warn_once("root-hidden", "the root element has display:none: nothing is drawn");
  } else {
    apply_side_colors(root, ctx);
    const std::optional<ViewBox> vb = view_box_of(root);
    const bool sized = vb && vb->width > 0 && vb->height > 0;
    if (sized) ctx.viewport_width = vb->width, ctx.viewport_height = vb->height;
    if (!sized) {
      ctx.viewport_width = length(root, "width", Axis::x, ctx, 100);
      ctx.viewport_height = length(root, "height", Axis::y, ctx, 100);
      if (!(ctx.viewport_width > 0)) ctx.viewport_width = 100;
      if (!(ctx.viewport_height > 0)) ctx.viewport_height = 100;
    }
    const Vec2 origin = sized ? Vec2(vb->x, vb->y) : Vec2::Zero();
    soup_.canvas.add(origin);
    soup_.canvas.add(origin + Vec2(ctx.viewport_width, ctx.viewport_height));
    ctx.depth = 1;
    walk_children(root, ctx);
  }
  number_sources(root);

  for (const auto& [kind, count] : skipped_kinds_)
    soup_.warnings.push_back("skipped " + std::to_string(count) + " <" + kind + "> element" +
                             (count == 1 ? "" : "s") + ": not converted to curves");

  // Paths too small to draw at any mesh resolution become isolated points (paper §4).
  Box2 extent;
  for (const PendingSubpath& sp : pending_) {
    extent.add(sp.start);
    for (const CubicBezier& c : sp.segments) extent.add(c.control_bounds());
  }
  // Outside this range lengths relative to the drawing's size overflow or underflow, here first.
  if (const std::string problem = drawing_size_problem(extent); !problem.empty()) throw InputError(problem);
  Box2 bounds;  // what FeatureSoup::bounds() would be if no path became a point
  for (const PendingSubpath& sp : pending_) {
    bounds.add(sp.start);
    for (const CubicBezier& c : sp.segments) bounds.add(c.bounds());
  }
  const double tolerance =
      options_.degenerate_tolerance ? options_.degenerate_tolerance(bounds, soup_.canvas, soup_.fills) : 0.0;
  soup_.curves.reserve(curve_count_);
  for (PendingSubpath& sp : pending_) add_to_soup(sp, tolerance);
  pending_.clear();
  return std::move(soup_);
}

void Reader::add_to_soup(PendingSubpath& sp, double tolerance) {
  Vec2 sum = sp.start;
  std::size_t n = 1;
  for (const CubicBezier& c : sp.segments)
    for (const Vec2& q : c.p) sum += q, ++n;
  const Vec2 centre = sum / double(n);
  bool degenerate = (sp.start - centre).norm() <= tolerance;
  for (const CubicBezier& c : sp.segments)
    for (const Vec2& q : c.p) degenerate = degenerate && (q - centre).norm() <= tolerance;
  if (degenerate) {
    soup_.points.push_back({centre, sp.source});
    return;
  }
  close_exactly(sp, tolerance);
  // The pieces of one arc share its number (SoupCurve::arc); a curve not cut from an arc has none.
  int arc = -1;
  for (std::size_t i = 0; i < sp.segments.size(); ++i) {
    auto continues = [&](std::size_t k) { return k < sp.continues.size() && sp.continues[k]; };
    if (!continues(i)) arc = continues(i + 1) ? arcs_++ : -1;
    soup_.curves.push_back({sp.segments[i], sp.source, sp.stroke, sp.fill, sp.left, sp.right, arc});
  }
  // The edge of the filled shape where the outline leaves it open (not drawn, but filled to).
  if (options_.close_filled_subpaths && sp.filled && !sp.segments.empty()) {
    const Vec2 end = sp.segments.back().p[3];
    if ((end - sp.start).norm() > tolerance)
      soup_.curves.push_back({CubicBezier::line(end, sp.start), sp.source, Paint{}, sp.fill, sp.left, sp.right});
  }
}

}  // namespace

bool FeatureSoup::has_stroke_areas() const {
  return std::any_of(fills.begin(), fills.end(), [](const FillLayer& layer) { return layer.stroke; });
}

bool FeatureSoup::has_fills() const {
  return std::any_of(fills.begin(), fills.end(),
                     [](const FillLayer& layer) { return !layer.stroke && !layer.subpaths.empty(); });
}

Box2 FeatureSoup::bounds() const {
  Box2 b;
  for (const SoupCurve& c : curves) b.add(c.bezier.bounds());
  for (const SoupPoint& p : points) b.add(p.p);
  return b;
}

FeatureSoup read_svg(std::string_view text, const ReadOptions& options, const std::string& filename) {
  try {
    return Reader(text, options).read();
  } catch (const InputError& e) {
    // Prefix the file name once, here, so every message names it (shown as it may be printed:
    // a file's name can hold any byte).
    const std::string name = base::printable(filename);
    throw InputError(e.message(), e.where().empty() ? name : name + ": " + e.where());
  }
}

FeatureSoup read_svg_file(const std::string& path, const ReadOptions& options) {
  std::string text;
  try {
    text = base::read_input_file(path, options.max_input_bytes, "--max-input-mb");
    // A compressed drawing (.svgz) is told by its gzip header, whatever its name, as librsvg
    // tells it; the limit holds for the drawing decompressed.
    if (base::is_gzip(text)) text = base::gunzip(text, options.max_input_bytes, path, "--max-input-mb");
  } catch (const base::InputFileError& e) {
    throw input_error(e, path);
  }
  return read_svg(text, options, path);
}

}  // namespace curvemesh::svg
