#include "svg/shapes.hpp"

#include <algorithm>
#include <numbers>

#include "svg/arc.hpp"

#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

// The quarter q of the ellipse centred at c (its parameter from q·π/2 to (q + 1)·π/2: 0 from +x
// to +y, 1 to −x, 2 to −y, 3 back to +x; clockwise on screen, where y points down) from `from`
// to `to`, its ends as the caller puts them: arc_piece_count(π/2) = 9 cubics.
std::vector<CubicBezier> quarter(const Vec2& c, double rx, double ry, int q, const Vec2& from, const Vec2& to) {
  constexpr double kHalfPi = std::numbers::pi / 2;
  return elliptic_arc_cubics({c, rx, ry, 1, 0, q * kHalfPi, (q + 1) * kHalfPi}, from, to);
}

// A rounded rect's side shorter than this fraction of its width (or height) is the round-off of
// rx = w/2 (ry = h/2): x + w − rx need not be x + rx in doubles, and a side of that length would
// be a degenerate curve between two corners that meet.
constexpr double kSideRoundOff = 1e-12;

}  // namespace

std::vector<Subpath> rect_subpaths(double x, double y, double w, double h, double rx, double ry) {
  if (!(w > 0 && h > 0)) return {};
  rx = std::clamp(rx, 0.0, w / 2);
  ry = std::clamp(ry, 0.0, h / 2);
  Subpath sp;
  sp.closed = true;
  if (rx == 0 || ry == 0) {
    const Vec2 c[4] = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
    sp.start = c[0];
    for (int i = 0; i < 4; ++i) sp.segments.push_back(CubicBezier::line(c[i], c[(i + 1) % 4]));
    return {sp};
  }
  // SVG 2 §10.2: from (x + rx, y) clockwise, each side (where it has a length) then the corner's
  // quarter ellipse to the next side's start; the last corner ends exactly at the start.
  const Vec2 centres[4] = {{x + w - rx, y + ry}, {x + w - rx, y + h - ry}, {x + rx, y + h - ry}, {x + rx, y + ry}};
  const Vec2 sides[4][2] = {{{x + rx, y}, {x + w - rx, y}},
                            {{x + w, y + ry}, {x + w, y + h - ry}},
                            {{x + w - rx, y + h}, {x + rx, y + h}},
                            {{x, y + h - ry}, {x, y + ry}}};
  const bool across = w - 2 * rx > kSideRoundOff * w, down = h - 2 * ry > kSideRoundOff * h;
  const bool has_side[4] = {across, down, across, down};
  sp.start = sides[0][0];
  Vec2 current = sp.start;
  for (int i = 0; i < 4; ++i) {
    if (has_side[i]) {
      sp.segments.push_back(CubicBezier::line(current, sides[i][1]));
      current = sides[i][1];
    }
    const Vec2 next = sides[(i + 1) % 4][0];
    // Without a side between them, two corners are one arc of the ellipse of radii rx, ry.
    sp.add_arc(quarter(centres[i], rx, ry, (i + 3) % 4, current, next), !has_side[i]);
    current = next;
  }
  return {sp};
}

std::vector<Subpath> ellipse_subpaths(double cx, double cy, double rx, double ry) {
  if (!(rx > 0 && ry > 0)) return {};
  Subpath sp;
  sp.closed = true;
  const Vec2 c(cx, cy);
  // SVG 2 §10.4: from (cx + rx, cy) through the other three extreme points, each exactly.
  const Vec2 extremes[4] = {{cx + rx, cy}, {cx, cy + ry}, {cx - rx, cy}, {cx, cy - ry}};
  for (int q = 0; q < 4; ++q) sp.add_arc(quarter(c, rx, ry, q, extremes[q], extremes[(q + 1) % 4]), q > 0);
  sp.start = extremes[0];
  return {sp};
}

std::vector<Subpath> polyline_subpaths(std::string_view points, bool closed, bool* odd_count,
                                       std::size_t max_pieces) {
  NumberScanner in(points);
  std::vector<Vec2> pts;
  *odd_count = false;
  while (in.number_follows()) {
    const double x = in.number();
    in.skip_separator();
    if (!in.number_follows()) {
      *odd_count = true;
      break;
    }
    const double y = in.number();
    in.skip_separator();
    // n points make n - 1 segments (and a closing one): the first is free.
    if (pts.size() > max_pieces) throw TooManyPieces();
    pts.emplace_back(x, y);
  }
  in.skip_whitespace();
  if (!in.at_end() && !*odd_count)
    throw SyntaxError("unexpected '" + in.shown_next() + "' in points", in.position());
  if (pts.empty()) return {};
  Subpath sp;
  sp.start = pts.front();
  sp.closed = closed;
  for (std::size_t i = 1; i < pts.size(); ++i) sp.segments.push_back(CubicBezier::line(pts[i - 1], pts[i]));
  if (closed && pts.size() > 1 && pts.back() != pts.front())
    sp.segments.push_back(CubicBezier::line(pts.back(), pts.front()));
  return {sp};
}

}  // namespace curvemesh::svg
