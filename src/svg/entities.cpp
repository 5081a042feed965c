#include "svg/entities.hpp"

#include <functional>
#include <optional>
#include <set>

#include "base/text.hpp"
#include "svg/error.hpp"
#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

// The internal subset: the text between '[' and the matching ']' of <!DOCTYPE ... [ ... ]>.
std::string_view internal_subset(std::string_view text) {
  const auto doctype = text.find("<!DOCTYPE");
  if (doctype == std::string_view::npos) return {};
  // The DOCTYPE must come before the first element; a later "<!DOCTYPE" is just text.
  for (std::size_t i = text.find('<'); i < doctype; i = text.find('<', i + 1)) {
    if (i + 1 < text.size() && text[i + 1] != '?' && text[i + 1] != '!') return {};
  }
  std::size_t i = doctype + 9;
  char quote = 0;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      return {};
    } else if (c == '[') {
      break;
    }
  }
  if (i >= text.size()) return {};
  const std::size_t start = i + 1;
  quote = 0;
  for (i = start; i < text.size(); ++i) {
    const char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '<' && text.substr(i, 4) == "<!--") {
      const auto end = text.find("-->", i + 4);
      if (end == std::string_view::npos) return {};
      i = end + 2;
    } else if (c == ']') {
      return text.substr(start, i - start);
    }
  }
  return {};
}

bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':' ||
         static_cast<unsigned char>(c) >= 0x80;
}

// The name in a reference "&name;" starting at value[k] (a '&'), or nothing. Declared names are
// made of name characters, so the search stops at the first other one: a value of many '&' and
// no ';' is read in linear time.
std::optional<std::string_view> reference_at(std::string_view value, std::size_t k) {
  std::size_t j = k + 1;
  while (j < value.size() && is_name_char(value[j])) ++j;
  if (j >= value.size() || value[j] != ';') return std::nullopt;
  return value.substr(k + 1, j - k - 1);
}

}  // namespace

EntityTable EntityTable::from_document(std::string_view text, std::size_t max_expansion) {
  EntityTable table;
  table.max_expansion_ = max_expansion;
  const std::string_view subset = internal_subset(text);
  if (subset.empty()) return table;

  std::map<std::string, std::string, std::less<>> raw;
  for (std::size_t i = subset.find("<!ENTITY"); i != std::string_view::npos; i = subset.find("<!ENTITY", i)) {
    i += 8;
    while (i < subset.size() && is_svg_whitespace(subset[i])) ++i;
    if (i < subset.size() && subset[i] == '%') continue;  // parameter entity: DTD-only, not used in content
    const std::size_t name_start = i;
    while (i < subset.size() && is_name_char(subset[i])) ++i;
    std::string name(subset.substr(name_start, i - name_start));
    while (i < subset.size() && is_svg_whitespace(subset[i])) ++i;
    if (name.empty() || i >= subset.size()) continue;
    if (subset[i] == '"' || subset[i] == '\'') {
      const auto end = subset.find(subset[i], i + 1);
      if (end == std::string_view::npos) break;
      // The first declaration of a name wins (XML 1.0 §4.2).
      raw.emplace(std::move(name), std::string(subset.substr(i + 1, end - i - 1)));
      i = end + 1;
    } else {
      table.external_.push_back(base::repair_utf8(name));
    }
  }

  // Expand every entity fully, once, refusing cycles and oversized results.
  std::size_t total = 0;
  std::set<std::string, std::less<>> active;
  std::function<const std::string&(const std::string&)> resolve = [&](const std::string& name) -> const std::string& {
    if (const auto done = table.values_.find(name); done != table.values_.end()) return done->second;
    if (!active.insert(name).second)
      throw InputError("entity '" + base::repair_utf8(name) + "' refers to itself", "DOCTYPE");
    if (active.size() > 64) throw InputError("entities nested more than 64 deep", "DOCTYPE");
    const std::string& value = raw.at(name);
    std::string out;
    for (std::size_t k = 0; k < value.size(); ++k) {
      if (value[k] == '&') {
        if (const auto ref = reference_at(value, k); ref && raw.count(*ref)) {
          out += resolve(std::string(*ref));
          k += ref->size() + 1;
          if (total + out.size() > max_expansion) break;
          continue;
        }
      }
      out += value[k];
    }
    total += out.size();
    if (total > max_expansion) throw InputError(entity_budget_message(max_expansion), "DOCTYPE");
    active.erase(name);
    return table.values_.emplace(name, std::move(out)).first->second;
  };
  for (const auto& [name, value] : raw) resolve(name);
  table.expanded_ = total;
  return table;
}

std::string entity_budget_message(std::size_t max_expansion) {
  return "entity references expand to more than " + std::to_string(max_expansion) +
         " characters in all (a limit of the reader)";
}

std::string EntityTable::expand(std::string_view value) {
  std::string out;
  out.reserve(value.size());
  for (std::size_t k = 0; k < value.size(); ++k) {
    if (value[k] == '&') {
      const auto ref = reference_at(value, k);
      if (const auto it = ref ? values_.find(*ref) : values_.end(); it != values_.end()) {
        expanded_ += it->second.size();
        if (expanded_ > max_expansion_) throw InputError(entity_budget_message(max_expansion_));
        out += it->second;
        k += ref->size() + 1;
        continue;
      }
    }
    out += value[k];
  }
  return out;
}

}  // namespace curvemesh::svg
