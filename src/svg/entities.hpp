#pragma once
// Internal DTD entities. Illustrator writes `<!ENTITY st0 "fill:#FFFFFF;">` and uses `&st0;`
// in attributes; browsers expand them, so we do too — with a budget, so that "billion laughs"
// documents are refused instead of eating the machine. External entities are never loaded.
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace curvemesh::svg {

class EntityTable {
 public:
  // Reads the declarations of the DOCTYPE's internal subset (if any) and expands them fully.
  // Throws InputError when the declarations refer to themselves or expand past `max_expansion`
  // characters in total.
  static EntityTable from_document(std::string_view text, std::size_t max_expansion);

  bool empty() const { return values_.empty(); }
  // Replaces references to declared entities in `value`; other references stay as written.
  // Throws InputError when the result would exceed the budget.
  std::string expand(std::string_view value) const;
  // Names of external (SYSTEM/PUBLIC) entities that were declared and will not be loaded.
  const std::vector<std::string>& external() const { return external_; }

 private:
  std::map<std::string, std::string, std::less<>> values_;  // fully expanded replacement text
  std::vector<std::string> external_;
  std::size_t max_expansion_ = 0;
};

}  // namespace curvemesh::svg
