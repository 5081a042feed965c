#pragma once
// Input errors: a drawing we refuse to read. Carries what a user needs to find the problem.
#include <stdexcept>
#include <string>
#include <string_view>

#include "base/files.hpp"
#include "base/text.hpp"

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

// An input file that could not be read (base::read_input_file) as an InputError: where() is the
// path (as it may be printed), the message what follows it.
inline InputError input_error(const base::InputFileError& e, const std::string& path) {
  std::string_view message = e.what();
  if (message.starts_with(path + ": ")) message.remove_prefix(path.size() + 2);
  return InputError(std::string(message), base::printable(path));
}

// A syntax error inside an attribute value (path data, transform, points, ...), at `offset`
// characters into the value. The reader turns it into an InputError naming the element.
class SyntaxError : public std::runtime_error {
 public:
  // `non_finite`: the text holds a number that no double stands for (NaN, infinity, overflow),
  // as opposed to text that is merely malformed.
  SyntaxError(const std::string& message, std::size_t offset, bool non_finite = false)
      : std::runtime_error(message), offset_(offset), non_finite_(non_finite) {}
  std::size_t offset() const { return offset_; }
  bool non_finite() const { return non_finite_; }

 private:
  std::size_t offset_;
  bool non_finite_;
};

}  // namespace curvemesh::svg
