// SVG path data (SVG 1.1 §8.3, with SVG 2's clarifications) to cubic Béziers.
#include "svg/path_data.hpp"

#include <string>

#include "svg/arc.hpp"
#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

bool is_command(char c) {
  switch (c) {
    case 'M': case 'm': case 'L': case 'l': case 'H': case 'h': case 'V': case 'v': case 'C': case 'c':
    case 'S': case 's': case 'Q': case 'q': case 'T': case 't': case 'A': case 'a': case 'Z': case 'z':
      return true;
    default:
      return false;
  }
}

class PathParser {
 public:
  PathParser(std::string_view d, std::size_t max_pieces) : in_(d), max_pieces_(max_pieces) {}

  // After a failed parse: whether the data ran out (rather than holding something malformed),
  // and what was complete before that.
  bool at_end() {
    in_.skip_whitespace();
    return in_.at_end();
  }
  std::vector<Subpath> take_result() { return std::move(out_); }

  std::vector<Subpath> parse() {
    in_.skip_whitespace();
    if (in_.at_end()) return {};
    if (in_.peek() != 'M' && in_.peek() != 'm')
      throw SyntaxError("path data must begin with a moveto (M or m)", in_.position());
    char command = 0;
    while (true) {
      in_.skip_whitespace();
      if (in_.at_end()) break;
      const char c = in_.peek();
      if (is_command(c)) {
        command = c;
        in_.advance();
      } else if (!in_.number_follows() || command == 'Z' || command == 'z') {
        const std::string shown = in_.shown_next();
        throw SyntaxError(is_command_like(c) ? "unknown path command '" + shown + "'"
                                              : "unexpected '" + shown + "' in path data",
                          in_.position());
      }
      // A command's arguments repeat while numbers follow (§8.3.2); after a moveto, the
      // repeated pairs are linetos.
      run(command);
      if (command == 'M') command = 'L';
      if (command == 'm') command = 'l';
    }
    return std::move(out_);
  }

 private:
  static bool is_command_like(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

  double number() {
    in_.skip_separator();
    return in_.number();
  }
  Vec2 pair(bool relative) {
    const double x = number();
    const double y = number();
    return relative ? current_ + Vec2(x, y) : Vec2(x, y);
  }

  // A drawing command after Z (without M) starts a new subpath at the old start (§8.3.3).
  Subpath& open_subpath() {
    if (out_.empty() || out_.back().closed) {
      Subpath sp;
      sp.start = start_;
      new_subpath(sp);
    }
    return out_.back();
  }
  // `continues`: c is a piece of the arc the segment before it is a piece of (Subpath::continues).
  void add(const CubicBezier& c, bool continues = false) {
    Subpath& sp = open_subpath();
    if (!sp.segments.empty()) count_piece();  // a subpath's first segment takes its place
    if (continues) {
      sp.continues.resize(sp.segments.size(), 0);
      sp.continues.push_back(1);
    }
    sp.segments.push_back(c);
    current_ = c.p[3];
  }
  void new_subpath(const Subpath& sp) {
    count_piece();
    out_.push_back(sp);
  }
  void count_piece() {
    if (++pieces_ > max_pieces_) throw TooManyPieces();
  }

  // One command with one set of arguments; returns after the arguments of one repetition.
  void run(char command) {
    const bool rel = command >= 'a' && command <= 'z';
    const char upper = rel ? char(command - 'a' + 'A') : command;
    char kind_for_reflection = 0;  // 'C' after cubic commands, 'Q' after quadratic ones
    switch (upper) {
      case 'M': {
        current_ = pair(rel);
        start_ = current_;
        Subpath sp;
        sp.start = current_;
        new_subpath(sp);
        break;
      }
      case 'Z': {
        if (!out_.empty() && !out_.back().closed) {
          if (current_ != start_) add(CubicBezier::line(current_, start_));
          out_.back().closed = true;
        }
        current_ = start_;
        break;
      }
      case 'L':
        add(CubicBezier::line(current_, pair(rel)));
        break;
      case 'H': {
        const double x = number();
        add(CubicBezier::line(current_, Vec2(rel ? current_.x() + x : x, current_.y())));
        break;
      }
      case 'V': {
        const double y = number();
        add(CubicBezier::line(current_, Vec2(current_.x(), rel ? current_.y() + y : y)));
        break;
      }
      case 'C': {
        const Vec2 c1 = pair(rel), c2 = pair(rel), end = pair(rel);
        add({current_, c1, c2, end});
        last_control_ = c2;
        kind_for_reflection = 'C';
        break;
      }
      case 'S': {
        const Vec2 c1 = last_kind_ == 'C' ? 2.0 * current_ - last_control_ : current_;
        const Vec2 c2 = pair(rel), end = pair(rel);
        add({current_, c1, c2, end});
        last_control_ = c2;
        kind_for_reflection = 'C';
        break;
      }
      case 'Q': {
        const Vec2 c = pair(rel), end = pair(rel);
        add(CubicBezier::from_quadratic(current_, c, end));
        last_control_ = c;
        kind_for_reflection = 'Q';
        break;
      }
      case 'T': {
        const Vec2 c = last_kind_ == 'Q' ? 2.0 * current_ - last_control_ : current_;
        add(CubicBezier::from_quadratic(current_, c, pair(rel)));
        last_control_ = c;
        kind_for_reflection = 'Q';
        break;
      }
      case 'A': {
        const double rx = number(), ry = number(), rotation = number();
        in_.skip_separator();
        const bool large = in_.flag();
        in_.skip_separator();
        const bool sweep = in_.flag();
        const Vec2 end = pair(rel);
        const Vec2 from = current_;
        const std::vector<CubicBezier> pieces = arc_to_cubics(from, rx, ry, rotation, large, sweep, end);
        for (std::size_t k = 0; k < pieces.size(); ++k) add(pieces[k], k > 0);
        current_ = end;
        break;
      }
    }
    last_kind_ = kind_for_reflection;
    in_.skip_separator();
  }

  NumberScanner in_;
  std::size_t max_pieces_;
  std::size_t pieces_ = 0;  // segments, and subpaths without one
  std::vector<Subpath> out_;
  Vec2 current_ = Vec2::Zero();
  Vec2 start_ = Vec2::Zero();
  Vec2 last_control_ = Vec2::Zero();
  char last_kind_ = 0;
};

}  // namespace

std::vector<Subpath> parse_path_data(std::string_view d, bool* truncated, std::size_t max_pieces) {
  PathParser parser(d, max_pieces);
  if (truncated) *truncated = false;
  try {
    return parser.parse();
  } catch (const SyntaxError&) {
    // Only the end of the data inside a command's arguments is drawn up to (see the header).
    if (!truncated || !parser.at_end()) throw;
    *truncated = true;
    return parser.take_result();
  }
}

}  // namespace curvemesh::svg
