#pragma once
// The part of CSS that drawings use for geometry and colours: `style` attributes and simple
// <style> sheets with type, class and id selectors (and lists of them). Other selectors are
// ignored; the properties that matter here (fill, stroke, color, display, visibility) are plain.
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace curvemesh::svg {

// Property name (lower case) and value, in the order they were written.
using Declarations = std::vector<std::pair<std::string, std::string>>;

// Parses "fill: red; stroke:#00f" (comments and !important allowed).
Declarations parse_declarations(std::string_view text);

class StyleSheet {
 public:
  // Adds the rules of one <style> element's text. @-rules are skipped.
  void add(std::string_view css);
  bool empty() const { return rules_.empty(); }

  // Appends the declarations of the matching rules to `out`, from lowest to highest precedence
  // (specificity, then order in the document), so later entries override earlier ones.
  void match(std::string_view tag, std::string_view id, std::string_view class_list, Declarations& out) const;

 private:
  struct Rule {
    std::string tag;                   // empty or "*" matches any
    std::string id;
    std::vector<std::string> classes;
    int specificity = 0;
    int order = 0;
    Declarations declarations;
  };
  void add_rule(std::string_view selector, const Declarations& declarations);

  std::vector<Rule> rules_;
  // Rules by their most selective key, so matching looks at few rules per element.
  std::map<std::string, std::vector<int>, std::less<>> by_id_, by_class_, by_tag_;
  std::vector<int> universal_;
};

}  // namespace curvemesh::svg
