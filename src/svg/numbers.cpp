#include "svg/numbers.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "base/text.hpp"

namespace curvemesh::svg {

bool is_svg_whitespace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f'; }

std::string_view trim_svg_whitespace(std::string_view s) {
  while (!s.empty() && is_svg_whitespace(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_svg_whitespace(s.back())) s.remove_suffix(1);
  return s;
}

std::string NumberScanner::shown_next() const {
  if (at_end()) return {};
  const auto lead = static_cast<unsigned char>(s_[pos_]);
  const std::size_t n = lead < 0xc0 ? 1 : lead < 0xe0 ? 2 : lead < 0xf0 ? 3 : 4;
  return base::printable(s_.substr(pos_, n));
}

void NumberScanner::skip_whitespace() {
  while (!at_end() && is_svg_whitespace(s_[pos_])) ++pos_;
}

void NumberScanner::skip_separator() {
  skip_whitespace();
  if (!at_end() && s_[pos_] == ',') {
    ++pos_;
    skip_whitespace();
  }
}

bool NumberScanner::number_follows() {
  skip_whitespace();
  if (at_end()) return false;
  const char c = s_[pos_];
  if (c == '+' || c == '-') {
    if (pos_ + 1 >= s_.size()) return false;
    const char d = s_[pos_ + 1];
    return (d >= '0' && d <= '9') || d == '.';
  }
  return (c >= '0' && c <= '9') || c == '.';
}

namespace {
bool is_digit(char c) { return c >= '0' && c <= '9'; }
// "nan", "inf", "infinity" in any case, with an optional sign: not SVG numbers, but worth naming.
bool names_non_finite(std::string_view s) {
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.remove_prefix(1);
  auto starts = [&](std::string_view word) {
    if (s.size() < word.size()) return false;
    for (std::size_t i = 0; i < word.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(s[i])) != word[i]) return false;
    return true;
  };
  return starts("nan") || starts("inf");
}


// Length of the number token starting at s[0], or 0 if none.
std::size_t scan_number(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t int_start = i;
  while (i < s.size() && is_digit(s[i])) ++i;
  bool digits = i > int_start;
  if (i < s.size() && s[i] == '.') {
    const std::size_t frac_start = i + 1;
    std::size_t j = frac_start;
    while (j < s.size() && is_digit(s[j])) ++j;
    if (j > frac_start || digits) {
      digits = true;
      i = j;
    }
  }
  if (!digits) return 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    const std::size_t exp_start = j;
    while (j < s.size() && is_digit(s[j])) ++j;
    if (j > exp_start) i = j;  // otherwise the 'e' belongs to what follows (e.g. a unit "em")
  }
  return i;
}

// Converts a token accepted by scan_number. Underflow gives zero (as browsers do); overflow is
// an error because no finite coordinate can stand for it.
double convert(std::string_view token, std::size_t offset) {
  std::string_view t = token;
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);  // from_chars does not accept '+'
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // Tell overflow from underflow by the exponent's sign.
    const auto e = t.find_first_of("eE");
    const bool negative_exponent = e != std::string_view::npos && e + 1 < t.size() && t[e + 1] == '-';
    if (negative_exponent) return 0.0;
    throw SyntaxError("number '" + std::string(token) + "' is too large for a double", offset, true);
  }
  if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(value))
    throw SyntaxError("bad number '" + std::string(token) + "'", offset);
  return value;
}
}  // namespace

std::optional<double> NumberScanner::try_number() {
  skip_whitespace();
  const std::size_t n = scan_number(s_.substr(pos_));
  if (n == 0) return std::nullopt;
  const double v = convert(s_.substr(pos_, n), pos_);
  pos_ += n;
  return v;
}


double NumberScanner::number() {
  if (auto v = try_number()) return *v;
  if (names_non_finite(s_.substr(pos_))) throw SyntaxError("not a finite number", pos_, true);
  if (at_end()) throw SyntaxError("expected a number, found the end", pos_);
  throw SyntaxError("expected a number, found '" + shown_next() + "'", pos_);
}

bool NumberScanner::flag() {
  skip_whitespace();
  if (!at_end() && (s_[pos_] == '0' || s_[pos_] == '1')) return s_[pos_++] == '1';
  throw SyntaxError("expected an arc flag (0 or 1)", pos_);
}

std::optional<double> parse_number_with_unit(std::string_view text, std::string_view* unit) {
  text = trim_svg_whitespace(text);
  const std::size_t n = scan_number(text);
  if (n == 0) {
    if (names_non_finite(text)) throw SyntaxError("not a finite number", 0, true);
    return std::nullopt;
  }
  const double v = convert(text.substr(0, n), 0);  // overflow throws: no finite value stands for it
  if (unit) *unit = text.substr(n);
  return v;
}

std::optional<double> css_unit_scale(std::string_view unit, double percent_base) {
  if (unit.empty() || unit == "px") return 1.0;
  if (unit == "%") return percent_base / 100.0;
  if (unit == "pt") return 96.0 / 72.0;
  if (unit == "pc") return 16.0;
  if (unit == "mm") return 96.0 / 25.4;
  if (unit == "cm") return 96.0 / 2.54;
  if (unit == "in") return 96.0;
  if (unit == "em") return 16.0;
  if (unit == "ex") return 8.0;
  return std::nullopt;
}

}  // namespace curvemesh::svg
