#pragma once
// The SVG number grammar, shared by path data, transforms, points and viewBox lists:
//   number ::= sign? (digits ('.' digits?)? | '.' digits) (('e'|'E') sign? digits)?
// separated by whitespace and at most one comma. "-1-2" is two numbers, ".5.5" is two numbers,
// "1e-5" is one. No "nan", "inf" or hex forms; values that overflow a double are errors.
#include <optional>
#include <string>
#include <string_view>

#include "svg/error.hpp"

namespace curvemesh::svg {

class NumberScanner {
 public:
  explicit NumberScanner(std::string_view text) : s_(text) {}

  bool at_end() const { return pos_ >= s_.size(); }
  std::size_t position() const { return pos_; }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }
  void advance() { ++pos_; }
  // The character at the position as a message may quote it: the whole UTF-8 sequence (a byte
  // alone would cut a character in two), escaped if it is a control character or malformed.
  std::string shown_next() const;

  void skip_whitespace();
  // Skips whitespace, then at most one comma and more whitespace.
  void skip_separator();
  // True when the next character (after whitespace) can start a number.
  bool number_follows();

  // Reads a number (after whitespace); throws SyntaxError when there is none or it is not finite.
  double number();
  // Like number(), but returns nothing (and consumes nothing) when no number starts here.
  std::optional<double> try_number();
  // An arc flag: a single '0' or '1', which needs no separator after it ("011 1").
  bool flag();

 private:
  std::string_view s_;
  std::size_t pos_ = 0;
};

bool is_svg_whitespace(char c);
// `s` without leading and trailing SVG whitespace.
std::string_view trim_svg_whitespace(std::string_view s);

// Parses a whole attribute as one number with an optional unit suffix left in `unit`.
// Returns nothing when the text is not a number; throws SyntaxError (non_finite) when it is NaN,
// infinite or overflows a double.
std::optional<double> parse_number_with_unit(std::string_view text, std::string_view* unit);

// User units per one of a CSS length unit ("" and "px" 1, "pt", "pc", "mm", "cm", "in", "em" and
// "ex" at the CSS default font size of 16); "%" is `percent_base` / 100. Nothing for another unit.
std::optional<double> css_unit_scale(std::string_view unit, double percent_base);

}  // namespace curvemesh::svg
