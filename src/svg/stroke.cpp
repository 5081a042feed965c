// Strokes as areas (SVG 2 §13.5). Each loop of an outline is the sum of the bands of its segments
// and the wedges of its joins and caps, every one of them turning the same way: filled by the
// nonzero rule, the loops paint their union, however they overlap.
#include "svg/stroke.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "geometry/bezier_analysis.hpp"
#include "geometry/offset.hpp"
#include "svg/arc.hpp"
#include "svg/numbers.hpp"

namespace curvemesh::svg {

namespace {

using geometry::cross;

// A length of a stroke property: a number with a CSS unit, nothing when it is not one.
std::optional<double> stroke_length(std::string_view value, double percent_base) {
  try {
    std::string_view unit;
    const std::optional<double> number = parse_number_with_unit(value, &unit);
    if (!number) return std::nullopt;
    const std::optional<double> scale = css_unit_scale(unit, percent_base);
    if (!scale) return std::nullopt;
    const double v = *number * *scale;
    return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
  } catch (const SyntaxError&) {
    return std::nullopt;  // not finite: dropped as any invalid value
  }
}

// stroke-dasharray: "none", or lengths separated by commas and/or whitespace.
std::optional<std::vector<double>> dash_list(std::string_view value, double percent_base) {
  value = trim_svg_whitespace(value);
  if (value == "none") return std::vector<double>{};
  std::vector<double> out;
  std::size_t i = 0;
  while (i < value.size()) {
    while (i < value.size() && (is_svg_whitespace(value[i]) || value[i] == ',')) ++i;
    std::size_t j = i;
    while (j < value.size() && !is_svg_whitespace(value[j]) && value[j] != ',') ++j;
    if (j == i) break;
    const std::optional<double> v = stroke_length(value.substr(i, j - i), percent_base);
    if (!v) return std::nullopt;
    out.push_back(*v);
    i = j;
  }
  return out;
}

}  // namespace

bool apply_stroke_declaration(std::string_view name, std::string_view value, double percent_base,
                              StrokeStyle& style) {
  const std::string_view v = trim_svg_whitespace(value);
  if (name == "stroke-width") {
    if (const auto w = stroke_length(v, percent_base); w && *w >= 0) style.width = *w;
  } else if (name == "stroke-linejoin") {
    // SVG 2's miter-clip and arcs are drawn as miter, as renderers without them do.
    if (v == "miter" || v == "miter-clip" || v == "arcs") style.join = LineJoin::miter;
    if (v == "round") style.join = LineJoin::round;
    if (v == "bevel") style.join = LineJoin::bevel;
  } else if (name == "stroke-linecap") {
    if (v == "butt") style.cap = LineCap::butt;
    if (v == "round") style.cap = LineCap::round;
    if (v == "square") style.cap = LineCap::square;
  } else if (name == "stroke-miterlimit") {
    if (const auto m = stroke_length(v, percent_base); m && *m >= 1) style.miter_limit = *m;
  } else if (name == "stroke-dasharray") {
    if (auto d = dash_list(v, percent_base)) style.dashes = std::move(*d);
  } else if (name == "stroke-dashoffset") {
    if (const auto o = stroke_length(v, percent_base)) style.dash_offset = *o;
  } else if (name == "vector-effect") {
    if (v == "non-scaling-stroke") style.non_scaling = true;
    if (v == "none") style.non_scaling = false;
  } else {
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Dashes

namespace {

// The parameter of c at arc length `s` from its start (bisection on the length of the piece
// before it: monotone, and as exact as CubicBezier::length).
double parameter_at_length(const CubicBezier& c, double s, double total) {
  if (s <= 0) return 0;
  if (s >= total) return 1;
  double lo = 0, hi = 1;
  for (int k = 0; k < 50 && hi - lo > 1e-14; ++k) {
    const double m = (lo + hi) / 2;
    (c.subcurve(0, m).length() < s ? lo : hi) = m;
  }
  return (lo + hi) / 2;
}

// The piece of a subpath between arc lengths a and b (0 ≤ a ≤ b ≤ its length), as an open
// subpath; without a segment when a = b.
Subpath piece_between(const Subpath& sp, const std::vector<double>& lengths, double a, double b) {
  Subpath out;
  double from = 0;
  bool started = false;
  for (std::size_t i = 0; i < sp.segments.size(); from += lengths[i], ++i) {
    const double to = from + lengths[i];
    if (b == a) {
      if (a > to && i + 1 < sp.segments.size()) continue;
      out.start = sp.segments[i].eval(parameter_at_length(sp.segments[i], a - from, lengths[i]));
      return out;
    }
    if (!(from < b && to > a)) continue;
    const double t0 = parameter_at_length(sp.segments[i], a - from, lengths[i]);
    const double t1 = parameter_at_length(sp.segments[i], b - from, lengths[i]);
    const CubicBezier piece = sp.segments[i].subcurve(t0, t1);
    if (!started) out.start = piece.p[0];
    out.add_arc({piece}, started && sp.continues_at(i));
    started = true;
  }
  if (!started) out.start = sp.segments.empty() ? sp.start : sp.segments.back().p[3];
  return out;
}

// The "on" intervals of the pattern along a subpath of length `total`.
std::vector<std::pair<double, double>> dash_intervals(const std::vector<double>& pattern, double offset,
                                                      double total) {
  double period = 0;
  for (double x : pattern) period += x;
  std::vector<std::pair<double, double>> out;
  // Where the pattern stands at the subpath's start: `offset` into it, modulo its period.
  double phase = std::fmod(offset, period);
  if (phase < 0) phase += period;
  std::size_t k = 0;
  while (phase >= pattern[k]) phase -= pattern[k], k = (k + 1) % pattern.size();
  double s = -phase;
  for (std::size_t steps = 0; s <= total && steps < 10'000'000; ++steps) {
    const double e = s + pattern[k];
    if (k % 2 == 0 && e >= 0) out.emplace_back(std::max(s, 0.0), std::min(e, total));
    s = e;
    k = (k + 1) % pattern.size();
  }
  return out;
}

}  // namespace

std::vector<Subpath> dash_subpaths(const std::vector<Subpath>& subpaths, const std::vector<double>& dashes,
                                   double offset) {
  std::vector<double> pattern = dashes;
  double period = 0;
  for (double x : pattern) {
    if (!(x >= 0)) return subpaths;  // SVG 2 §13.5.6: a negative value makes the pattern invalid
    period += x;
  }
  if (!(period > 0)) return subpaths;
  if (pattern.size() % 2 == 1) pattern.insert(pattern.end(), dashes.begin(), dashes.end());
  std::vector<Subpath> out;
  for (const Subpath& sp : subpaths) {
    std::vector<double> lengths;
    double total = 0;
    for (const CubicBezier& c : sp.segments) total += lengths.emplace_back(c.length());
    const auto on = dash_intervals(pattern, offset, total);
    const std::size_t first = out.size();
    for (const auto& [a, b] : on) out.push_back(piece_between(sp, lengths, a, b));
    // A closed subpath's last dash reaching its end continues into the first from its start.
    if (sp.closed && on.size() > 1 && on.front().first == 0 && on.back().second == total && total > 0) {
      Subpath& last = out.back();
      const Subpath& head = out[first];
      for (std::size_t i = 0; i < head.segments.size(); ++i) {
        last.continues.resize(last.segments.size(), 0);
        last.continues.push_back(head.continues_at(i));
        last.segments.push_back(head.segments[i]);
      }
      out.erase(out.begin() + static_cast<std::ptrdiff_t>(first));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Outlines

namespace {

// Cubics joined end to start, with Subpath's continues flags.
struct Chain {
  std::vector<CubicBezier> curves;
  std::vector<char> continues;

  void add(const CubicBezier& c, bool continues_previous) {
    curves.push_back(c);
    continues.push_back(continues_previous);
  }
  const Vec2& end() const { return curves.back().p[3]; }
  void line_to(const Vec2& p) { add(CubicBezier::line(end(), p), false); }
};

class Outliner {
 public:
  explicit Outliner(const StrokeStyle& style)
      : style_(style), d_(style.width / 2), tolerance_(kStrokeTolerance * style.width) {}

  void outline(const Subpath& sp, std::vector<Subpath>& out) const;

 private:
  Chain side(const std::vector<CubicBezier>& segments, const std::vector<char>& continues, bool closed) const;
  void append(Chain& chain, const geometry::OffsetRun& run, const Vec2& p, const Vec2& in, const Vec2& out,
              double room, bool continues) const;
  void corner(Chain& chain, const Vec2& p, const Vec2& in, const Vec2& out, const Vec2& to,
              double room) const;
  bool meet_inside(CubicBezier& last, CubicBezier& next, const Vec2& in, const Vec2& out) const;
  bool meet_at_miter(CubicBezier& last, CubicBezier& next, const Vec2& p, const Vec2& in, const Vec2& out) const;
  std::optional<Vec2> miter_point(const Vec2& p, const Vec2& in, const Vec2& out, const Vec2& from,
                                  const Vec2& to) const;
  void cap(Chain& chain, const Vec2& p, const Vec2& direction, const Vec2& to) const;
  void arc(Chain& chain, const Vec2& centre, const Vec2& to, double sweep) const;
  void dot(const Vec2& p, std::vector<Subpath>& out) const;

  const StrokeStyle& style_;
  double d_;          // half the width: the offsets' distance
  double tolerance_;  // of each offset cubic
};

// Whether the left offset of a closed path at distance d folds all the way round: the path bends
// tighter than d towards its left everywhere (d·κ > 1, no offset cusp) and turns smoothly at every
// joint. Then it is convex, and every point inside it is within d of it (the disc of radius ρ
// about an inner point touching the path at its nearest point fits in the path's osculating
// circle there, so ρ is at most the radius of curvature, below d): the stroke is all of the inside
// of its other side, and this side's loop, winding the other way over the fold, would only cut a
// hole into it.
bool folds_all_round(const std::vector<CubicBezier>& segments, double d) {
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const CubicBezier& c = segments[i];
    if (!geometry::cusp_parameters(c).empty() || !geometry::offset_cusp_parameters(c, d).empty())
      return false;
    const Vec2 v = c.derivative(0.5);
    if (!(d * cross(v, c.second_derivative(0.5)) > std::pow(v.norm(), 3))) return false;
    const Vec2 in = geometry::unit_tangent(segments[(i + segments.size() - 1) % segments.size()], 1.0);
    const Vec2 out = geometry::unit_tangent(c, 0.0);
    if (!(in.dot(out) > 0) || std::abs(cross(in, out)) > 1e-9) return false;
  }
  return true;
}

Subpath loop_of(Chain&& chain) {
  Subpath sp;
  sp.start = chain.curves.front().p[0];
  sp.segments = std::move(chain.curves);
  sp.continues = std::move(chain.continues);
  sp.closed = true;
  return sp;
}

// The circular arc about `centre` from the chain's end to `to` (both at distance d from it),
// turning by `sweep` radians, in pieces as the reader's circles are.
void Outliner::arc(Chain& chain, const Vec2& centre, const Vec2& to, double sweep) const {
  const Vec2 from = chain.end();
  const double start = std::atan2(from.y() - centre.y(), from.x() - centre.x());
  const std::vector<CubicBezier> pieces =
      elliptic_arc_cubics({centre, d_, d_, 1, 0, start, start + sweep}, from, to);
  for (std::size_t k = 0; k < pieces.size(); ++k) chain.add(pieces[k], k > 0);
}

// The join at corner p, the path arriving in direction `in` and leaving in direction `out`, from
// the chain's end (the left offset of the segment before) to `to` (that of the one after). The left
// side is the outer one where the path turns right (in × out < 0, n being `in` turned by +90°).
// `room`: the shorter of the two segments' chords.
void Outliner::corner(Chain& chain, const Vec2& p, const Vec2& in, const Vec2& out, const Vec2& to,
                      double room) const {
  if (cross(in, out) > 0) {
    // The inner side. Through the corner, the loop is the sum of the two segments' bands (their
    // ends across the path) and the outer wedge. Straight across instead, it differs from that by
    // the triangle (end, corner, start), inside both bands when the turn is below 90° and the
    // segments reach d·sin(turn) past the corner: winding 2 there, 1 or 3 after, painted all the
    // same — one short line where a slight turn would otherwise put two nearly on one another.
    if (in.dot(out) > 0 && d_ * cross(in, out) <= room / 2) {
      chain.line_to(to);
      return;
    }
    chain.line_to(p);
    chain.line_to(to);
    return;
  }
  const Vec2 a = (chain.end() - p) / d_, b = (to - p) / d_;  // the unit normals on the outer side
  switch (style_.join) {
    case LineJoin::round: {
      double sweep = std::atan2(cross(a, b), a.dot(b));
      if (sweep > 0) sweep -= 2 * std::numbers::pi;  // the outer way round: a turn back is −π
      arc(chain, p, to, sweep);
      return;
    }
    case LineJoin::miter:
      if (const std::optional<Vec2> tip = miter_point(p, in, out, chain.end(), to)) chain.line_to(*tip);
      chain.line_to(to);  // beyond the limit: a bevel
      return;
    case LineJoin::bevel:
      chain.line_to(to);
      return;
  }
}

// The cap at an end p of an open subpath, `direction` pointing out of the path, from the chain's
// end (the left offset arriving there) to `to` (the right one, leaving).
void Outliner::cap(Chain& chain, const Vec2& p, const Vec2& direction, const Vec2& to) const {
  switch (style_.cap) {
    case LineCap::butt:
      chain.line_to(to);
      return;
    case LineCap::square: {
      const Vec2 reach = d_ * direction;
      chain.line_to(chain.end() + reach);
      chain.line_to(to + reach);
      chain.line_to(to);
      return;
    }
    case LineCap::round:
      arc(chain, p, to, -std::numbers::pi);  // through p + d·direction
      return;
  }
}

// At a corner turning towards this side (in × out > 0), two straight offset pieces cross inside
// the band: `last` ends and `next` starts past the point q where their lines meet. Cut back to q,
// the loop no longer runs on to the corner and back (that notch lies inside both segments' bands:
// the triangles (q, end, corner) and (q, corner, start) each between its segment and its offset),
// and the outline's inner corner is the painted area's own, q, instead of a notch of half the
// width that feature processing would see as a cluster of short pieces. False, and nothing
// changed, unless both are straight and q lies strictly inside both.
bool Outliner::meet_inside(CubicBezier& last, CubicBezier& next, const Vec2& in, const Vec2& out) const {
  if (!(cross(in, out) > 0) || !geometry::is_straight(last, tolerance_) || !geometry::is_straight(next, tolerance_))
    return false;
  const Vec2 u = last.p[3] - last.p[0], v = next.p[3] - next.p[0];
  const double det = cross(u, v);
  if (!(std::abs(det) > 1e-9 * u.norm() * v.norm())) return false;
  const double s = cross(next.p[0] - last.p[0], v) / det;  // q = last.p0 + s·u
  const double r = cross(next.p[0] - last.p[0], u) / det;  // q = next.p0 + r·v
  if (!(s > 0 && s < 1 && r > 0 && r < 1)) return false;
  const Vec2 q = last.p[0] + s * u;
  last = CubicBezier::line(last.p[0], q);
  next = CubicBezier::line(q, next.p[3]);
  return true;
}

// At a corner turning away from this side with a miter join inside its limit, the miter's tip is
// where the two straight offset pieces' lines meet: extended to it, they are the outline the join
// would draw (the same area), without the two short lines from their ends to the tip, which
// feature processing would leave unfit, the two sides ending a fraction of the width apart with
// nothing between them. False, and nothing changed, unless both are straight and the join is a
// miter within its limit.
bool Outliner::meet_at_miter(CubicBezier& last, CubicBezier& next, const Vec2& p, const Vec2& in,
                             const Vec2& out) const {
  if (!(cross(in, out) < 0) || style_.join != LineJoin::miter || !geometry::is_straight(last, tolerance_) ||
      !geometry::is_straight(next, tolerance_))
    return false;
  const std::optional<Vec2> tip = miter_point(p, in, out, last.p[3], next.p[0]);
  if (!tip) return false;
  last = CubicBezier::line(last.p[0], *tip);
  next = CubicBezier::line(*tip, next.p[3]);
  return true;
}

// The tip of a miter join at corner p, between the outer offsets' ends `from` and `to` (at d from
// p), or nothing beyond the limit. SVG 2 §13.5.3: the miter's length over the width is
// 1/sin(θ/2), θ the angle between the segments; cos(φ/2) here, φ = π − θ the angle turned.
std::optional<Vec2> Outliner::miter_point(const Vec2& p, const Vec2& in, const Vec2& out, const Vec2& from,
                                          const Vec2& to) const {
  const double cos_half = std::sqrt(std::max(0.0, (1 + in.dot(out)) / 2));
  if (!(cos_half > 0 && 1 / cos_half <= style_.miter_limit)) return std::nullopt;
  const Vec2 a = (from - p) / d_, b = (to - p) / d_;  // the unit normals on the outer side
  return p + d_ * (a + b) / (1 + a.dot(b));
}

// Appends one offset run after a corner at p (or at a cusp of the curve): the pieces continue the
// chain directly when its end is within the tolerance of their start (a smooth joint).
void Outliner::append(Chain& chain, const geometry::OffsetRun& run, const Vec2& p, const Vec2& in,
                      const Vec2& out, double room, bool continues) const {
  std::vector<CubicBezier> pieces = run.pieces;
  bool first_continues = false;
  if (!chain.curves.empty()) {
    const Vec2 from = chain.end();
    if ((pieces.front().p[0] - from).norm() <= tolerance_) {
      pieces.front().p[1] += from - pieces.front().p[0];
      pieces.front().p[0] = from;
      first_continues = continues;
    } else if (!meet_inside(chain.curves.back(), pieces.front(), in, out) &&
               !meet_at_miter(chain.curves.back(), pieces.front(), p, in, out)) {
      corner(chain, p, in, out, pieces.front().p[0], room);
    }
  }
  for (std::size_t k = 0; k < pieces.size(); ++k)
    chain.add(pieces[k], k == 0 ? first_continues : run.smooth[k]);
}

// The left offset of a path of segments with its corners (closed: the one at its start too).
Chain Outliner::side(const std::vector<CubicBezier>& segments, const std::vector<char>& continues,
                     bool closed) const {
  Chain chain;
  Vec2 in = Vec2::UnitX(), first_out = Vec2::UnitX();
  const auto chord = [&](std::size_t i) { return (segments[i].p[3] - segments[i].p[0]).norm(); };
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const CubicBezier& c = segments[i];
    const std::vector<geometry::OffsetRun> runs = geometry::offset_cubic(c, d_, tolerance_);
    // Between segments, the shorter chord; at a cusp of a curve, none (the corner point it is).
    const double room = i > 0 ? std::min(chord(i - 1), chord(i)) : 0.0;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const Vec2 out = geometry::unit_tangent(c, runs[r].t0, runs[r].t0, runs[r].t1);
      if (i == 0 && r == 0) first_out = out;
      append(chain, runs[r], r == 0 ? c.p[0] : c.eval(runs[r].t0), in, out, r == 0 ? room : 0.0,
             r == 0 && i > 0 && continues[i]);
      in = geometry::unit_tangent(c, runs[r].t1, runs[r].t0, runs[r].t1);
    }
  }
  if (closed && !chain.curves.empty()) {
    const Vec2 start = chain.curves.front().p[0];
    if ((chain.end() - start).norm() <= tolerance_) {
      CubicBezier& last = chain.curves.back();
      last.p[2] += start - last.p[3];
      last.p[3] = start;
    } else if (meet_inside(chain.curves.back(), chain.curves.front(), in, first_out) ||
               meet_at_miter(chain.curves.back(), chain.curves.front(), segments.front().p[0], in, first_out)) {
      chain.continues.front() = false;
    } else {
      corner(chain, segments.front().p[0], in, first_out, start,
             std::min(chord(0), chord(segments.size() - 1)));
    }
  }
  return chain;
}

// A subpath of no length: SVG 2 §13.5.4 paints a round cap as a disc, a square one as a square.
void Outliner::dot(const Vec2& p, std::vector<Subpath>& out) const {
  if (style_.cap == LineCap::butt) return;
  Chain chain;
  const Vec2 east = p + Vec2(d_, 0), west = p - Vec2(d_, 0);
  // Clockwise as (x, y) go, as every band of outline() is (its left side first): loops overlapping
  // add up.
  if (style_.cap == LineCap::round) {
    const std::vector<CubicBezier> half =
        elliptic_arc_cubics({p, d_, d_, 1, 0, 0, -std::numbers::pi}, east, west);
    for (std::size_t k = 0; k < half.size(); ++k) chain.add(half[k], k > 0);
    arc(chain, p, east, -std::numbers::pi);
  } else {
    chain.add(CubicBezier::line(p + Vec2(d_, d_), p + Vec2(d_, -d_)), false);
    chain.line_to(p + Vec2(-d_, -d_));
    chain.line_to(p + Vec2(-d_, d_));
    chain.line_to(p + Vec2(d_, d_));
  }
  out.push_back(loop_of(std::move(chain)));
}

void Outliner::outline(const Subpath& sp, std::vector<Subpath>& out) const {
  // Segments shorter than the tolerance draw nothing of their own.
  std::vector<CubicBezier> segments;
  std::vector<char> continues;
  for (std::size_t i = 0; i < sp.segments.size(); ++i) {
    const CubicBezier& c = sp.segments[i];
    double reach = 0;
    for (const Vec2& q : c.p) reach = std::max(reach, (q - c.p[0]).norm());
    if (reach <= tolerance_) continue;
    segments.push_back(c);
    continues.push_back(sp.continues_at(i));
  }
  if (segments.empty()) return dot(sp.segments.empty() ? sp.start : sp.segments.front().p[0], out);
  // The same path backwards: its left side is the right side of the path.
  const std::size_t n = segments.size();
  std::vector<CubicBezier> reversed(n);
  std::vector<char> reversed_continues(n, 0);
  for (std::size_t j = 0; j < n; ++j) {
    const CubicBezier& c = segments[n - 1 - j];
    reversed[j] = CubicBezier(c.p[3], c.p[2], c.p[1], c.p[0]);
    if (j + 1 < n) reversed_continues[j + 1] = continues[n - 1 - j];
  }
  const bool closed = sp.closed && (segments.back().p[3] - segments.front().p[0]).norm() <= tolerance_;
  Chain left = side(segments, continues, closed), right = side(reversed, reversed_continues, closed);
  if (left.curves.empty() || right.curves.empty()) return;
  if (closed) {
    if (!folds_all_round(segments, d_)) out.push_back(loop_of(std::move(left)));
    if (!folds_all_round(reversed, d_)) out.push_back(loop_of(std::move(right)));
    return;
  }
  const Vec2 start = left.curves.front().p[0];
  cap(left, segments.back().p[3], geometry::unit_tangent(segments.back(), 1.0), right.curves.front().p[0]);
  for (std::size_t k = 0; k < right.curves.size(); ++k)
    left.add(right.curves[k], k > 0 && right.continues[k]);
  cap(left, segments.front().p[0], -geometry::unit_tangent(segments.front(), 0.0), start);
  out.push_back(loop_of(std::move(left)));
}

}  // namespace

std::vector<Subpath> stroke_outline(const std::vector<Subpath>& subpaths, const StrokeStyle& style) {
  std::vector<Subpath> out;
  if (!(style.width > 0)) return out;
  const Outliner outliner(style);
  if (style.dashes.empty()) {
    for (const Subpath& sp : subpaths) outliner.outline(sp, out);
  } else {
    for (const Subpath& sp : dash_subpaths(subpaths, style.dashes, style.dash_offset))
      outliner.outline(sp, out);
  }
  return out;
}

}  // namespace curvemesh::svg
