#include "svg/style.hpp"

#include <algorithm>
#include <cctype>

#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

std::string strip_comments(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const auto end = text.find("*/", i + 2);
      if (end == std::string_view::npos) break;
      i = end + 1;
      out += ' ';
      continue;
    }
    out += text[i];
  }
  return out;
}

Declarations parse_declarations_no_comments(std::string_view text) {
  Declarations out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(';', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view decl = text.substr(start, end - start);
    const auto colon = decl.find(':');
    if (colon != std::string_view::npos) {
      std::string name(trim_svg_whitespace(decl.substr(0, colon)));
      std::string_view value = trim_svg_whitespace(decl.substr(colon + 1));
      if (const auto bang = value.find("!important"); bang != std::string_view::npos)
        value = trim_svg_whitespace(value.substr(0, bang));
      std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
      if (!name.empty()) out.emplace_back(std::move(name), std::string(value));
    }
    start = end + 1;
  }
  return out;
}

}  // namespace

Declarations parse_declarations(std::string_view text) {
  if (text.find("/*") == std::string_view::npos) return parse_declarations_no_comments(text);
  return parse_declarations_no_comments(strip_comments(text));
}

void StyleSheet::add(std::string_view css_text) {
  const std::string css = strip_comments(css_text);
  std::string_view s(css);
  std::size_t i = 0;
  while (i < s.size()) {
    const auto open = s.find('{', i);
    if (open == std::string_view::npos) break;
    const std::string_view prelude = trim_svg_whitespace(s.substr(i, open - i));
    // Find the matching '}' (nested blocks occur in @media).
    int depth = 0;
    std::size_t close = open;
    for (; close < s.size(); ++close) {
      if (s[close] == '{') ++depth;
      if (s[close] == '}' && --depth == 0) break;
    }
    if (close >= s.size()) break;
    if (!prelude.empty() && prelude[0] != '@') {
      const Declarations decls = parse_declarations_no_comments(s.substr(open + 1, close - open - 1));
      std::size_t start = 0;
      while (start <= prelude.size()) {
        std::size_t comma = prelude.find(',', start);
        if (comma == std::string_view::npos) comma = prelude.size();
        add_rule(trim_svg_whitespace(prelude.substr(start, comma - start)), decls);
        start = comma + 1;
      }
    }
    i = close + 1;
  }
}

void StyleSheet::add_rule(std::string_view selector, const Declarations& declarations) {
  if (selector.empty()) return;
  Rule rule;
  // A compound selector: [tag|*] followed by .class and #id parts. Anything else (combinators,
  // attribute selectors, pseudo-classes) is beyond what we match: skip the rule.
  std::size_t i = 0;
  auto ident_end = [&](std::size_t from) {
    std::size_t j = from;
    while (j < selector.size() && (std::isalnum(static_cast<unsigned char>(selector[j])) || selector[j] == '-' ||
                                   selector[j] == '_' || static_cast<unsigned char>(selector[j]) >= 0x80))
      ++j;
    return j;
  };
  if (selector[0] == '*') {
    i = 1;
  } else if (selector[0] != '.' && selector[0] != '#') {
    i = ident_end(0);
    rule.tag = std::string(selector.substr(0, i));
    if (rule.tag.empty()) return;
    rule.specificity += 1;
  }
  while (i < selector.size()) {
    const char kind = selector[i];
    if (kind != '.' && kind != '#') return;
    const std::size_t end = ident_end(i + 1);
    if (end == i + 1) return;
    std::string name(selector.substr(i + 1, end - i - 1));
    if (kind == '.') {
      rule.classes.push_back(std::move(name));
      rule.specificity += 100;
    } else {
      rule.id = std::move(name);
      rule.specificity += 10000;
    }
    i = end;
  }
  rule.order = static_cast<int>(rules_.size());
  rule.declarations = declarations;
  const int index = rule.order;
  if (!rule.id.empty())
    by_id_[rule.id].push_back(index);
  else if (!rule.classes.empty())
    by_class_[rule.classes.front()].push_back(index);
  else if (!rule.tag.empty())
    by_tag_[rule.tag].push_back(index);
  else
    universal_.push_back(index);
  rules_.push_back(std::move(rule));
}

void StyleSheet::match(std::string_view tag, std::string_view id, std::string_view class_list,
                       Declarations& out) const {
  if (rules_.empty()) return;
  std::vector<std::string_view> classes;
  for (std::size_t i = 0; i < class_list.size();) {
    while (i < class_list.size() && is_svg_whitespace(class_list[i])) ++i;
    std::size_t j = i;
    while (j < class_list.size() && !is_svg_whitespace(class_list[j])) ++j;
    if (j > i) classes.push_back(class_list.substr(i, j - i));
    i = j;
  }
  std::vector<int> candidates = universal_;
  auto collect = [&](const auto& index, std::string_view key) {
    if (const auto it = index.find(key); it != index.end())
      candidates.insert(candidates.end(), it->second.begin(), it->second.end());
  };
  if (!id.empty()) collect(by_id_, id);
  for (const auto c : classes) collect(by_class_, c);
  collect(by_tag_, tag);

  std::vector<const Rule*> matched;
  for (const int index : candidates) {
    const Rule& r = rules_[index];
    if (!r.tag.empty() && r.tag != tag) continue;
    if (!r.id.empty() && r.id != id) continue;
    const bool all_classes = std::all_of(r.classes.begin(), r.classes.end(), [&](const std::string& c) {
      return std::find(classes.begin(), classes.end(), c) != classes.end();
    });
    if (all_classes) matched.push_back(&r);
  }
  std::sort(matched.begin(), matched.end(), [](const Rule* a, const Rule* b) {
    return a->specificity != b->specificity ? a->specificity < b->specificity : a->order < b->order;
  });
  matched.erase(std::unique(matched.begin(), matched.end()), matched.end());
  for (const Rule* r : matched) out.insert(out.end(), r->declarations.begin(), r->declarations.end());
}

}  // namespace curvemesh::svg
