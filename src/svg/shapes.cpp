#include "svg/shapes.hpp"

#include <algorithm>

#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

// The quarter of the ellipse centred at c with radii (rx, ry), from angle index k to k + 1
// (0 = +x, 1 = +y, 2 = -x, 3 = -y: clockwise on screen, where y points down).
CubicBezier quarter(const Vec2& c, double rx, double ry, int k) {
  static const Vec2 dirs[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  const Vec2 u = dirs[k % 4], v = dirs[(k + 1) % 4];
  const Vec2 a = c + Vec2(u.x() * rx, u.y() * ry), b = c + Vec2(v.x() * rx, v.y() * ry);
  return {a, a + kQuarterArcKappa * Vec2(v.x() * rx, v.y() * ry), b + kQuarterArcKappa * Vec2(u.x() * rx, u.y() * ry),
          b};
}

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
  // Corner centres, clockwise from the top right; straight sides only where they have length.
  const Vec2 centres[4] = {{x + w - rx, y + ry}, {x + w - rx, y + h - ry}, {x + rx, y + h - ry}, {x + rx, y + ry}};
  sp.start = Vec2(x + rx, y);
  Vec2 current = sp.start;
  for (int i = 0; i < 4; ++i) {
    const CubicBezier arc = quarter(centres[i], rx, ry, (i + 3) % 4);
    if (arc.p[0] != current) sp.segments.push_back(CubicBezier::line(current, arc.p[0]));
    sp.segments.push_back(arc);
    current = arc.p[3];
  }
  if (current != sp.start) sp.segments.push_back(CubicBezier::line(current, sp.start));
  return {sp};
}

std::vector<Subpath> ellipse_subpaths(double cx, double cy, double rx, double ry) {
  if (!(rx > 0 && ry > 0)) return {};
  Subpath sp;
  sp.closed = true;
  const Vec2 c(cx, cy);
  for (int k = 0; k < 4; ++k) sp.segments.push_back(quarter(c, rx, ry, k));
  sp.start = sp.segments.front().p[0];
  sp.segments.back().p[3] = sp.start;  // closed exactly
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
