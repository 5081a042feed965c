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
  // characters: the budget of the whole document, which expand() then draws on.
  static EntityTable from_document(std::string_view text, std::size_t max_expansion);

  bool empty() const { return values_.empty(); }
  // Replaces references to declared entities in `value`; other references stay as written. The
  // replacement text counts against the document's budget, so that many references to one large
  // entity cost no more than one enormous entity would. Throws InputError once the declarations
  // and every expansion so far exceed it.
  std::string expand(std::string_view value);
  // Names of external (SYSTEM/PUBLIC) entities that were declared and will not be loaded
  // (well-formed UTF-8: they are shown in warnings).
  const std::vector<std::string>& external() const { return external_; }

 private:
  std::map<std::string, std::string, std::less<>> values_;  // fully expanded replacement text
  std::vector<std::string> external_;
  std::size_t max_expansion_ = 0;
  std::size_t expanded_ = 0;  // characters of the declarations' and references' expansions so far
};

// The message for a document past its budget of `max_expansion` characters.
std::string entity_budget_message(std::size_t max_expansion);

}  // namespace curvemesh::svg
