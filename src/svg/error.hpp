#pragma once
// Input errors: a drawing we refuse to read. Carries what a user needs to find the problem.
#include <stdexcept>
#include <string>

namespace curvemesh::svg {

class InputError : public std::runtime_error {
 public:
  // `where` names the line and element, e.g. "line 12, <path id=\"p3\">"; may be empty.
  InputError(const std::string& message, std::string where = {})
      : std::runtime_error(where.empty() ? message : where + ": " + message), message_(message), where_(std::move(where)) {}
  const std::string& message() const { return message_; }
  const std::string& where() const { return where_; }

 private:
  std::string message_;
  std::string where_;
};

// A syntax error inside an attribute value (path data, transform, points, ...), at `offset`
// characters into the value. The reader turns it into an InputError naming the element.
class SyntaxError : public std::runtime_error {
 public:
  SyntaxError(const std::string& message, std::size_t offset)
      : std::runtime_error(message), offset_(offset) {}
  std::size_t offset() const { return offset_; }

 private:
  std::size_t offset_;
};

}  // namespace curvemesh::svg
