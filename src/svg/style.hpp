#pragma once
// The part of CSS that drawings use for geometry and colours: `style` attributes and simple
// <style> sheets with type, class and id selectors (and lists of them). Other selectors are
// ignored; the properties that matter here (fill, stroke, color, display, visibility, the font's) are
// plain.
#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace curvemesh::svg {

// Property name (lower case) and value, in the order they were written.
using Declarations = std::vector<std::pair<std::string, std::string>>;

// The properties the reader takes from presentation attributes and CSS; a style sheet keeps no
// other.
inline constexpr std::array<const char*, 23> kStyleProperties = {
    "fill",           "stroke",            "color",            "display",           "visibility",
    "fill-rule",      "clip-path",         "clip-rule",        "mask",              "stroke-width",
    "stroke-linejoin", "stroke-linecap",   "stroke-miterlimit", "stroke-dasharray", "stroke-dashoffset",
    "vector-effect",  "font",              "font-family",      "font-size",         "font-weight",
    "font-style",     "text-anchor",       "letter-spacing"};
// An entry left out of the list above would be a null name, read as a string.
static_assert([] {
  for (const char* name : kStyleProperties)
    if (!name) return false;
  return true;
}());

// Fixed limits of the reader on the style sheets of one document. Drawings have a few hundred
// rules (in openclipart at most 388 selectors and 749 declarations); a small hostile sheet could
// otherwise cost without bound: selectors listed before a long block, or rules that every element
// matches. Past a limit the document is refused (InputError naming it).
inline constexpr std::size_t kMaxStyleSelectors = 100'000;       // every selector of a list counted
inline constexpr std::size_t kMaxStyleDeclarations = 1'000'000;  // in the sheets' rule blocks
// Steps of matching, summed over every element drawn (each <use> instance again): a rule tried, a
// class compared, a declaration taken (and one more per 8 characters of its value). Drawings
// take about 5 per element; this allows 20 at the limit on elements, and a few seconds at most.
inline constexpr std::size_t kMaxStyleMatching = 20'000'000;

// Calls `visit(name, value)` for each declaration of "fill: red; stroke:#00f" (comments and
// !important allowed; names in lower case) until it returns false; returns false then. Nothing is
// stored: a style attribute may be as large as the file.
bool for_each_declaration(std::string_view text,
                          const std::function<bool(std::string_view name, std::string_view value)>& visit);

// Parses "fill: red; stroke:#00f" (comments and !important allowed).
Declarations parse_declarations(std::string_view text);

class StyleSheet {
 public:
  // Adds the rules of one <style> element's text. @-rules are skipped, and declarations of other
  // properties than kStyleProperties. Throws InputError past kMaxStyleSelectors or
  // kMaxStyleDeclarations (counted over every sheet added).
  void add(std::string_view css);
  bool empty() const { return rules_.empty(); }

  // Appends the declaration blocks of the matching rules to `out`, from lowest to highest
  // precedence (specificity, then order in the document), so later declarations override earlier
  // ones. Throws InputError once the matching done for the document passes kMaxStyleMatching.
  void match(std::string_view tag, std::string_view id, std::string_view class_list,
             std::vector<const Declarations*>& out);

 private:
  struct Rule {
    std::string tag;                   // empty or "*" matches any
    std::string id;
    std::vector<std::string> classes;
    int specificity = 0;
    int order = 0;
    int block = 0;  // index into blocks_: the selectors of a list share theirs
  };
  struct Block {
    Declarations declarations;
    std::size_t cost = 0;  // steps of matching to take them
  };
  void add_rule(std::string_view selector, int block);
  void count_matching(std::size_t work);

  std::vector<Rule> rules_;
  std::vector<Block> blocks_;
  std::size_t selectors_ = 0, declarations_ = 0, matching_ = 0;
  // Rules by their most selective key, so matching looks at few rules per element.
  std::map<std::string, std::vector<int>, std::less<>> by_id_, by_class_, by_tag_;
  std::vector<int> universal_;
};

}  // namespace curvemesh::svg
