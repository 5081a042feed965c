#include "svg/transform.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "svg/numbers.hpp"

namespace curvemesh::svg {

Affine Affine::rotate_deg(double angle_deg) {
  // Exact values for the right angles that drawings use all the time.
  double s, c;
  const double r = std::fmod(angle_deg, 360.0);
  if (r == 0) {
    s = 0, c = 1;
  } else if (r == 90 || r == -270) {
    s = 1, c = 0;
  } else if (r == 180 || r == -180) {
    s = 0, c = -1;
  } else if (r == 270 || r == -90) {
    s = -1, c = 0;
  } else {
    const double rad = angle_deg * std::numbers::pi / 180.0;
    s = std::sin(rad), c = std::cos(rad);
  }
  return {c, s, -s, c, 0, 0};
}

double Affine::smallest_scale() const {
  const double sum = a * a + b * b + c * c + d * d, det = std::abs(determinant());
  const double largest = std::sqrt((sum + std::sqrt(std::max(0.0, sum * sum - 4 * det * det))) / 2);
  return largest > 0 ? det / largest : 0.0;
}

bool Affine::is_finite() const {
  return std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d) && std::isfinite(e) &&
         std::isfinite(f);
}

namespace {
bool is_name_char(char ch) { return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z'); }
}  // namespace

Affine parse_transform(std::string_view text) {
  NumberScanner in(text);
  Affine result;
  in.skip_whitespace();
  while (!in.at_end()) {
    const std::size_t name_start = in.position();
    while (!in.at_end() && is_name_char(in.peek())) in.advance();
    const std::string name(text.substr(name_start, in.position() - name_start));
    in.skip_whitespace();
    if (name.empty() || in.peek() != '(')
      throw SyntaxError(name.empty() ? "expected a transform function" : "expected '(' after '" + name + "'",
                        in.position());
    in.advance();
    std::array<double, 6> v{};
    int n = 0;
    in.skip_whitespace();
    while (in.peek() != ')') {
      if (n == 6) throw SyntaxError("too many arguments to " + name + "()", in.position());
      v[n++] = in.number();
      in.skip_separator();
      if (in.at_end()) throw SyntaxError("missing ')' after " + name + "(", in.position());
    }
    in.advance();  // ')'

    auto bad_count = [&] { return SyntaxError("wrong number of arguments to " + name + "()", name_start); };
    Affine t;
    if (name == "matrix") {
      if (n != 6) throw bad_count();
      t = {v[0], v[1], v[2], v[3], v[4], v[5]};
    } else if (name == "translate") {
      if (n != 1 && n != 2) throw bad_count();
      t = Affine::translate(v[0], n == 2 ? v[1] : 0.0);
    } else if (name == "scale") {
      if (n != 1 && n != 2) throw bad_count();
      t = Affine::scale(v[0], n == 2 ? v[1] : v[0]);
    } else if (name == "rotate") {
      if (n != 1 && n != 3) throw bad_count();
      t = Affine::rotate_deg(v[0]);
      if (n == 3) t = Affine::translate(v[1], v[2]) * t * Affine::translate(-v[1], -v[2]);
    } else if (name == "skewX") {
      if (n != 1) throw bad_count();
      t = {1, 0, std::tan(v[0] * std::numbers::pi / 180.0), 1, 0, 0};
    } else if (name == "skewY") {
      if (n != 1) throw bad_count();
      t = {1, std::tan(v[0] * std::numbers::pi / 180.0), 0, 1, 0, 0};
    } else {
      throw SyntaxError("unknown transform function '" + name + "'", name_start);
    }
    result = result * t;  // the list applies right to left: the last function acts first
    in.skip_separator();
  }
  if (!result.is_finite()) throw SyntaxError("transform overflows a double", 0, true);
  return result;
}

Affine viewbox_transform(const ViewBox& vb, std::string_view par, double x, double y, double width,
                         double height) {
  if (!(vb.width > 0 && vb.height > 0)) return Affine::translate(x, y);
  double sx = width / vb.width, sy = height / vb.height;
  // Parse "[defer] <align> [meet|slice]".
  std::string align = "xMidYMid";
  bool slice = false;
  {
    NumberScanner in(par);
    std::string words[3];
    int count = 0;
    in.skip_whitespace();
    while (!in.at_end() && count < 3) {
      const std::size_t s = in.position();
      while (!in.at_end() && !is_svg_whitespace(in.peek())) in.advance();
      words[count++] = std::string(par.substr(s, in.position() - s));
      in.skip_whitespace();
    }
    int i = 0;
    if (i < count && words[i] == "defer") ++i;
    if (i < count) align = words[i++];
    if (i < count) slice = words[i] == "slice";
  }
  if (align == "none") return Affine::translate(x - vb.x * sx, y - vb.y * sy) * Affine::scale(sx, sy);
  const double s = slice ? std::max(sx, sy) : std::min(sx, sy);
  double tx = x - vb.x * s, ty = y - vb.y * s;
  const double extra_x = width - vb.width * s, extra_y = height - vb.height * s;
  if (align.size() == 8) {
    const std::string ax = align.substr(1, 3), ay = align.substr(5, 3);
    if (ax == "Mid") tx += extra_x / 2;
    if (ax == "Max") tx += extra_x;
    if (ay == "Mid") ty += extra_y / 2;
    if (ay == "Max") ty += extra_y;
  } else {
    tx += extra_x / 2, ty += extra_y / 2;
  }
  return Affine::translate(tx, ty) * Affine::scale(s, s);
}

}  // namespace curvemesh::svg
