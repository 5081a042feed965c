#include "features/poly_input.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>
#include <string_view>
#include <utility>

#include "base/files.hpp"
#include "base/text.hpp"
#include "svg/error.hpp"

namespace curvemesh::features {

namespace {

// The file as records: one per non-blank line, '#' to the end of the line ignored. Split into
// words one at a time, as they are read: a file of many short lines would take many times its
// size as strings.
class Records {
 public:
  Records(const std::string& path, std::string text) : path_(path), text_(std::move(text)) {
    int n = 1;
    for (std::size_t at = 0; at < text_.size(); ++n) {
      const std::string_view line = line_at(at);
      if (std::any_of(line.begin(), line.end(), [](unsigned char c) { return !std::isspace(c); }))
        ++total_, last_line_ = n;
    }
  }

  bool done() const { return next_ >= total_; }
  std::size_t remaining() const { return total_ - next_; }

  // The next record, which must have at least `min_tokens` tokens.
  const std::vector<std::string>& next(std::size_t min_tokens, const char* what) {
    if (done()) fail(last_line_, std::string("file ends before ") + what);
    do {
      ++line_number_;
      tokens_.clear();
      for (const std::string_view w : words_of(line_at(at_))) tokens_.emplace_back(w);
    } while (tokens_.empty());
    ++next_;
    line_ = line_number_;
    if (tokens_.size() < min_tokens) fail(line_, std::string("too few numbers for ") + what);
    return tokens_;
  }

  long integer(const std::string& token, const char* what) const {
    long v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec != std::errc() || r.ptr != token.data() + token.size())
      fail(line_, std::string("expected an integer ") + what + ", found \"" + base::printable(token) + "\"");
    return v;
  }

  double real(const std::string& token, const char* what) const {
    double v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec == std::errc::result_out_of_range || (r.ec == std::errc() && !std::isfinite(v)))
      fail(line_, std::string("the ") + what + " \"" + base::printable(token) + "\" is not a finite number");
    if (r.ec != std::errc() || r.ptr != token.data() + token.size())
      fail(line_,
           std::string("expected a number for the ") + what + ", found \"" + base::printable(token) + "\"");
    return v;
  }

  [[noreturn]] void fail(const std::string& message) const { fail(line_, message); }
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw svg::InputError(message, base::printable(path_) + ":" + std::to_string(line));
  }

 private:
  // The line starting at `at` without its comment; `at` moves past it.
  std::string_view line_at(std::size_t& at) const {
    const std::size_t end = std::min(text_.find('\n', at), text_.size());
    std::string_view line = std::string_view(text_).substr(at, end - at);
    at = end + 1;
    return line.substr(0, line.find('#'));
  }
  static std::vector<std::string_view> words_of(std::string_view line) {
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (j > i) words.push_back(line.substr(i, j - i));
      i = j;
    }
    return words;
  }

  std::string path_;
  std::string text_;
  std::size_t at_ = 0;  // where the next line starts
  std::size_t total_ = 0, next_ = 0;
  std::vector<std::string> tokens_;
  int line_number_ = 0;  // of the line read last
  int line_ = 1, last_line_ = 1;
};

}  // namespace

Features read_poly(const std::string& path, const Limits& limits) {
  std::string text;
  try {
    text = base::read_input_file(path, static_cast<std::uint64_t>(limits.max_input_mb * 1048576.0),
                                 "--max-input-mb");
  } catch (const base::InputFileError& e) {
    throw svg::input_error(e, path);
  }
  Records r(path, std::move(text));

  const auto& header = r.next(2, "the vertex count");
  const long nv = r.integer(header[0], "vertex count");
  const long dim = r.integer(header[1], "dimension");
  const long attributes = header.size() > 2 ? r.integer(header[2], "attribute count") : 0;
  const long markers = header.size() > 3 ? r.integer(header[3], "boundary marker count") : 0;
  if (dim != 2) r.fail("dimension " + std::to_string(dim) + ": only 2 is supported");
  if (nv == 0) r.fail("vertices in a separate .node file are not supported");
  if (nv < 0 || attributes < 0 || markers < 0 || markers > 1) r.fail("invalid vertex header");
  if (std::size_t(nv) > r.remaining()) r.fail("the file has fewer lines than the " + std::to_string(nv) + " vertices announced");

  std::vector<Vec2> vertices(nv);
  long first_index = 0;
  for (long i = 0; i < nv; ++i) {
    const auto& v = r.next(3, "a vertex");
    const long index = r.integer(v[0], "vertex number");
    if (i == 0) {
      if (index != 0 && index != 1) r.fail("vertices must be numbered from 0 or 1");
      first_index = index;
    }
    if (index != first_index + i) r.fail("vertex number " + std::to_string(index) + " out of sequence");
    vertices[i] = {r.real(v[1], "x coordinate"), r.real(v[2], "y coordinate")};
  }

  const auto& sh = r.next(1, "the segment count");
  const long ns = r.integer(sh[0], "segment count");
  if (ns < 0) r.fail("negative segment count");
  // Each segment is a curve of the drawing, as an SVG path's are.
  if (static_cast<unsigned long>(ns) > limits.max_curves)
    r.fail("the file has more than " + std::to_string(limits.max_curves) +
           " segments (--max-curves raises the limit)");
  if (std::size_t(ns) > r.remaining()) r.fail("the file has fewer lines than the " + std::to_string(ns) + " segments announced");
  Features f;
  std::set<std::pair<long, long>> seen;
  std::vector<char> used(nv, 0);
  for (long k = 0; k < ns; ++k) {
    const auto& s = r.next(3, "a segment");
    r.integer(s[0], "segment number");
    const long a = r.integer(s[1], "segment endpoint") - first_index, b = r.integer(s[2], "segment endpoint") - first_index;
    if (a < 0 || a >= nv || b < 0 || b >= nv) r.fail("segment endpoint out of range 0.." + std::to_string(nv - 1 + first_index) + " (numbering from " + std::to_string(first_index) + ")");
    if (vertices[a] == vertices[b]) continue;  // zero length: its vertex stays a point if nothing else uses it
    if (!seen.insert(std::minmax(a, b)).second) continue;
    used[a] = used[b] = 1;
    f.segments.push_back({vertices[a], vertices[b], -1, 0, 1, {}});
  }
  if (!r.done()) {
    const auto& hh = r.next(1, "the hole count");
    const long nh = r.integer(hh[0], "hole count");
    if (nh < 0 || std::size_t(nh) > r.remaining()) r.fail("invalid hole count");
    for (long h = 0; h < nh; ++h) {
      const auto& hole = r.next(3, "a hole");
      r.real(hole[1], "hole x");
      r.real(hole[2], "hole y");
    }
  }
  // Regional attributes, if any, are not used.

  for (long i = 0; i < nv; ++i) {
    f.box.add(vertices[i]);
    if (!used[i]) f.points.push_back({vertices[i], int(i)});
  }
  return f;
}

}  // namespace curvemesh::features
