#include "features/poly_input.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "svg/error.hpp"

namespace curvemesh::features {

namespace {

// The file as records: one per non-blank line, '#' to the end of the line ignored.
class Records {
 public:
  Records(const std::string& path, std::istream& in) : path_(path) {
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      line = line.substr(0, line.find('#'));
      std::istringstream words(line);
      std::vector<std::string> tokens;
      for (std::string w; words >> w;) tokens.push_back(w);
      if (!tokens.empty()) records_.push_back({n, std::move(tokens)});
    }
    last_line_ = records_.empty() ? 1 : records_.back().first;
  }

  bool done() const { return next_ >= records_.size(); }
  std::size_t remaining() const { return records_.size() - next_; }

  // The next record, which must have at least `min_tokens` tokens.
  const std::vector<std::string>& next(std::size_t min_tokens, const char* what) {
    if (done()) fail(last_line_, std::string("file ends before ") + what);
    line_ = records_[next_].first;
    const auto& r = records_[next_++].second;
    if (r.size() < min_tokens) fail(line_, std::string("too few numbers for ") + what);
    return r;
  }

  long integer(const std::string& token, const char* what) const {
    long v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec != std::errc() || r.ptr != token.data() + token.size()) fail(line_, std::string("expected an integer ") + what + ", found \"" + token + "\"");
    return v;
  }

  double real(const std::string& token, const char* what) const {
    double v = 0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (r.ec == std::errc::result_out_of_range || (r.ec == std::errc() && !std::isfinite(v)))
      fail(line_, std::string("the ") + what + " \"" + token + "\" is not a finite number");
    if (r.ec != std::errc() || r.ptr != token.data() + token.size())
      fail(line_, std::string("expected a number for the ") + what + ", found \"" + token + "\"");
    return v;
  }

  [[noreturn]] void fail(const std::string& message) const { fail(line_, message); }
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw svg::InputError(message, path_ + ":" + std::to_string(line));
  }

 private:
  std::string path_;
  std::vector<std::pair<int, std::vector<std::string>>> records_;
  std::size_t next_ = 0;
  int line_ = 1, last_line_ = 1;
};

}  // namespace

Features read_poly(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw svg::InputError("cannot open the file", path);
  Records r(path, in);

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
    f.segments.push_back({vertices[a], vertices[b], -1, 0, 1});
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
