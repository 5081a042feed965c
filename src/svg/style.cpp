#include "svg/style.hpp"

#include <algorithm>
#include <cctype>

#include "svg/error.hpp"
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

// The loop of for_each_declaration, on text without comments.
bool each_declaration_no_comments(std::string_view text,
                                  const std::function<bool(std::string_view, std::string_view)>& visit) {
  std::string name;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(';', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view decl = text.substr(start, end - start);
    const auto colon = decl.find(':');
    if (colon != std::string_view::npos) {
      name = trim_svg_whitespace(decl.substr(0, colon));
      std::string_view value = trim_svg_whitespace(decl.substr(colon + 1));
      if (const auto bang = value.find("!important"); bang != std::string_view::npos)
        value = trim_svg_whitespace(value.substr(0, bang));
      std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::tolower(c)); });
      if (!name.empty() && !visit(name, value)) return false;
    }
    start = end + 1;
  }
  return true;
}

bool is_style_property(std::string_view name) {
  return std::find(kStyleProperties.begin(), kStyleProperties.end(), name) != kStyleProperties.end();
}

InputError limit_error(const char* what, std::size_t limit) {
  return InputError(std::string(what) + " " + std::to_string(limit) + " (a limit of the reader)");
}

}  // namespace

bool for_each_declaration(std::string_view text,
                          const std::function<bool(std::string_view, std::string_view)>& visit) {
  if (text.find("/*") == std::string_view::npos) return each_declaration_no_comments(text, visit);
  return each_declaration_no_comments(strip_comments(text), visit);
}

Declarations parse_declarations(std::string_view text) {
  Declarations out;
  for_each_declaration(text, [&](std::string_view name, std::string_view value) {
    out.emplace_back(name, value);
    return true;
  });
  return out;
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
      Block block;
      each_declaration_no_comments(
          s.substr(open + 1, close - open - 1), [&](std::string_view n, std::string_view v) {
            if (++declarations_ > kMaxStyleDeclarations)
              throw limit_error("the style sheets have more declarations than", kMaxStyleDeclarations);
            if (!is_style_property(n)) return true;
            block.declarations.emplace_back(n, v);
            block.cost += 1 + v.size() / 8;
            return true;
          });
      blocks_.push_back(std::move(block));
      std::size_t start = 0;
      while (start <= prelude.size()) {
        std::size_t comma = prelude.find(',', start);
        if (comma == std::string_view::npos) comma = prelude.size();
        if (++selectors_ > kMaxStyleSelectors)
          throw limit_error("the style sheets have more selectors than", kMaxStyleSelectors);
        add_rule(trim_svg_whitespace(prelude.substr(start, comma - start)),
                 static_cast<int>(blocks_.size() - 1));
        start = comma + 1;
      }
    }
    i = close + 1;
  }
}

void StyleSheet::add_rule(std::string_view selector, int block) {
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
  rule.block = block;
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

void StyleSheet::count_matching(std::size_t work) {
  matching_ += work;
  if (matching_ > kMaxStyleMatching)
    throw limit_error("matching the style sheets takes more steps (rules tried, declarations taken) than",
                      kMaxStyleMatching);
}

void StyleSheet::match(std::string_view tag, std::string_view id, std::string_view class_list,
                       std::vector<const Declarations*>& out) {
  if (rules_.empty()) return;
  std::vector<std::string_view> classes;
  for (std::size_t i = 0; i < class_list.size();) {
    while (i < class_list.size() && is_svg_whitespace(class_list[i])) ++i;
    std::size_t j = i;
    while (j < class_list.size() && !is_svg_whitespace(class_list[j])) ++j;
    if (j > i) classes.push_back(class_list.substr(i, j - i));
    i = j;
  }
  // A set: a class named twice collects its rules once, and a rule's classes are looked up fast.
  std::sort(classes.begin(), classes.end());
  classes.erase(std::unique(classes.begin(), classes.end()), classes.end());
  count_matching(classes.size());
  std::vector<int> candidates = universal_;
  auto collect = [&](const auto& index, std::string_view key) {
    if (const auto it = index.find(key); it != index.end())
      candidates.insert(candidates.end(), it->second.begin(), it->second.end());
  };
  if (!id.empty()) collect(by_id_, id);
  for (const auto c : classes) collect(by_class_, c);
  collect(by_tag_, tag);
  count_matching(candidates.size());

  std::vector<const Rule*> matched;
  for (const int index : candidates) {
    const Rule& r = rules_[index];
    if (!r.tag.empty() && r.tag != tag) continue;
    if (!r.id.empty() && r.id != id) continue;
    count_matching(r.classes.size());
    const bool all_classes = std::all_of(r.classes.begin(), r.classes.end(), [&](const std::string& c) {
      return std::binary_search(classes.begin(), classes.end(), std::string_view(c));
    });
    if (all_classes) matched.push_back(&r);
  }
  std::sort(matched.begin(), matched.end(), [](const Rule* a, const Rule* b) {
    return a->specificity != b->specificity ? a->specificity < b->specificity : a->order < b->order;
  });
  for (const Rule* r : matched) {
    count_matching(blocks_[r->block].cost);
    out.push_back(&blocks_[r->block].declarations);
  }
}

}  // namespace curvemesh::svg
