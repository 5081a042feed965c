// §4 "Removal of degenerate curves" to "Curve resampling": every input curve becomes one or
// more curve sections (split at inflections and where the turning would reach 180°), each
// sampled into pieces short, flat and straight enough to become one mesh edge.
#include <algorithm>
#include <cmath>

#include "features/pieces.hpp"
#include "geometry/bezier_analysis.hpp"
#include "geometry/vec2.hpp"

namespace curvemesh::features::detail {

namespace {

constexpr int kMaxDepth = 40;

// Upper bound of the distance between a Bézier piece and its chord (convex hull property).
double chord_deviation(const CubicBezier& c) {
  const Vec2 a = c.p[0], b = c.p[3];
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  double worst = 0;
  for (int i = 1; i <= 2; ++i) {
    const Vec2 ap = c.p[i] - a;
    double dist;
    if (len2 == 0) {
      dist = ap.norm();
    } else {
      const double s = std::clamp(ap.dot(ab) / len2, 0.0, 1.0);
      dist = (ap - s * ab).norm();
    }
    worst = std::max(worst, dist);
  }
  return worst;
}

// Largest curvature at a few parameters of the piece: |det(c', c'')| / |c'|^3. A vanishing
// derivative (a cusp) counts as infinite curvature.
double sampled_curvature(const CubicBezier& c) {
  double worst = 0;
  for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const Vec2 d1 = c.derivative(t), d2 = c.second_derivative(t);
    const double speed = d1.norm();
    const double cross = std::abs(geometry::cross(d1, d2));
    if (speed <= 1e-300) return INFINITY;
    worst = std::max(worst, cross / (speed * speed * speed));
  }
  return worst;
}

class Discretizer {
 public:
  Discretizer(const svg::FeatureSoup& soup, const Lengths& lengths) : soup_(soup), len_(lengths) {}

  Discretized run() {
    for (int i = 0; i < static_cast<int>(soup_.curves.size()); ++i) add_curve(i);
    for (const svg::SoupPoint& p : soup_.points) out_.points.push_back({p.p, p.source});
    return std::move(out_);
  }

 private:
  // The chain input curve `index` lies on: the previous curve's when both are pieces of one arc.
  void enter_chain(int index) {
    const svg::SoupCurve& curve = soup_.curves[index];
    const bool continues = index > 0 && curve.arc >= 0 && soup_.curves[index - 1].arc == curve.arc;
    if (!continues) {
      out_.chains.push_back({});
      chain_first_ = index;
      curve_along_ = 0;
    }
    // Closed once its last piece ends where its first starts: an arc's pieces only (a single
    // input curve that closes on itself keeps the rule of every input curve).
    out_.chains.back().closed = continues && curve.bezier.p[3] == soup_.curves[chain_first_].bezier.p[0];
  }

  void add_curve(int index) {
    const CubicBezier& c = soup_.curves[index].bezier;
    enter_chain(index);
    if (geometry::is_degenerate(c, len_.eps_m)) {
      const Vec2 centre = (c.p[0] + c.p[1] + c.p[2] + c.p[3]) / 4.0;
      out_.points.push_back({centre, soup_.curves[index].source});
      ++out_.degenerate_curves;
      return;
    }
    if (geometry::is_straight(c, len_.eps_m)) {
      ++out_.straight_curves;
      add_straight(index, c);
      return;
    }
    // Split at inflections (eq. 1), then each constant-sign part where it would turn ≥ 180°.
    std::vector<double> cuts{0.0};
    std::vector<double> inflections = geometry::inflection_parameters(c);
    inflections.push_back(1.0);
    double start = 0.0;
    for (const double end : inflections) {
      if (end <= start) continue;
      const CubicBezier part = c.subcurve(start, end);
      for (const double s : geometry::split_for_turning(part, M_PI)) cuts.push_back(start + s * (end - start));
      cuts.push_back(end);
      start = end;
    }
    std::sort(cuts.begin(), cuts.end());
    // A section shorter than the minimal edge length l_m (an inflection next to another cut or to
    // the curve's end) would pin two mesh vertices closer than any edge may be: its cut is dropped.
    std::vector<double> kept{0.0};
    for (std::size_t k = 1; k < cuts.size(); ++k) {
      if ((c.eval(cuts[k]) - c.eval(kept.back())).norm() > len_.min_edge) {
        kept.push_back(cuts[k]);
      } else if (k + 1 == cuts.size() && kept.size() > 1) {
        kept.back() = cuts[k];  // the curve's end stays; the cut before it goes
      }
    }
    if (kept.size() == 1) kept.push_back(1.0);
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) add_section(index, c, kept[k], kept[k + 1]);
  }

  void add_straight(int index, const CubicBezier& c) {
    // §4: replaced by its chord; when the ends coincide, by the two farthest control points.
    Vec2 a = c.p[0], b = c.p[3];
    if ((b - a).norm() <= len_.eps_m) {
      double best = -1;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          if ((c.p[i] - c.p[j]).norm() > best) best = (c.p[i] - c.p[j]).norm(), a = c.p[i], b = c.p[j];
    }
    CurveSection s;
    s.curve = index;
    s.straight = true;
    s.line_a = a;
    s.line_b = b;
    s.first_piece = static_cast<int>(out_.pieces.size());
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / len_.edge - 1e-12)));
    for (int k = 0; k < n; ++k) {
      Piece p;
      p.section = static_cast<int>(out_.sections.size());
      p.t0 = double(k) / n;
      p.t1 = double(k + 1) / n;
      p.a = k == 0 ? a : a + p.t0 * (b - a);
      p.b = k + 1 == n ? b : a + p.t1 * (b - a);
      p.leave_a = b - a, p.leave_b = a - b;
      p.unfit = (p.b - p.a).norm() < len_.min_edge;  // shorter than the minimal edge length
      out_.pieces.push_back(p);
    }
    finish_section(s);
  }

  void add_section(int index, const CubicBezier& c, double t0, double t1) {
    CurveSection s;
    s.curve = index;
    s.t0 = t0;
    s.t1 = t1;
    s.first_piece = static_cast<int>(out_.pieces.size());
    refine(c, t0, t1, c.eval(t0), c.eval(t1), 0);
    finish_section(s);
  }

  void finish_section(CurveSection& s) {
    s.chain = static_cast<int>(out_.chains.size()) - 1;
    s.piece_count = static_cast<int>(out_.pieces.size()) - s.first_piece;
    for (int k = s.first_piece; k < s.first_piece + s.piece_count; ++k) {
      out_.pieces[k].along = curve_along_ + s.length;
      s.length += (out_.pieces[k].b - out_.pieces[k].a).norm();
    }
    curve_along_ += s.length;
    out_.chains.back().length += s.length;
    out_.sections.push_back(s);
  }

  // §4 "Curve resampling": halve until the piece is at most l long, within μ of its chord and
  // turns at most α (what Theorem 3.4 needs to bend the edge later). Pieces that cannot get
  // there (cusps, curvature above α / l_m) are kept, but marked for the secondary set.
  void refine(const CubicBezier& c, double t0, double t1, const Vec2& a, const Vec2& b, int depth) {
    const CubicBezier sub = c.subcurve(t0, t1);
    const double chord = (b - a).norm();
    const bool short_enough = chord <= len_.edge;
    const bool flat_enough = chord_deviation(sub) <= len_.mu;
    const bool straight_enough = geometry::turning_angle(sub) <= len_.alpha_rad;
    if (short_enough && flat_enough && straight_enough) return emit(sub, t0, t1, a, b, false);
    // Too small to split further (the control polygon bounds the arc length, unlike the chord of
    // a loop): this part cannot be a primary edge.
    const double polygon = (sub.p[1] - sub.p[0]).norm() + (sub.p[2] - sub.p[1]).norm() + (sub.p[3] - sub.p[2]).norm();
    if (depth >= kMaxDepth || polygon < 0.5 * len_.min_edge) return emit(sub, t0, t1, a, b, true);
    const double tm = 0.5 * (t0 + t1);
    const Vec2 m = c.eval(tm);
    refine(c, t0, tm, a, m, depth + 1);
    refine(c, tm, t1, m, b, depth + 1);
  }

  void emit(const CubicBezier& sub, double t0, double t1, const Vec2& a, const Vec2& b,
            bool unresolved) {
    Piece p;
    p.section = static_cast<int>(out_.sections.size());
    p.t0 = t0;
    p.t1 = t1;
    p.a = a;
    p.b = b;
    // The end tangents (their limits from inside where the derivative vanishes).
    p.leave_a = geometry::unit_tangent(sub, 0.0);
    p.leave_b = -geometry::unit_tangent(sub, 1.0);
    // A primary edge is at least l_m long (the minimal edge length of the mesh) and turns at most
    // α, so a shorter piece — a whole curve shorter than l_m — or one where the curvature exceeds
    // α / l_m cannot be followed by primary edges (§3.1, bounded curvature).
    p.unfit = unresolved || (b - a).norm() < len_.min_edge || sampled_curvature(sub) > len_.alpha_rad / len_.min_edge;
    out_.pieces.push_back(p);
  }

  const svg::FeatureSoup& soup_;
  const Lengths& len_;
  Discretized out_;
  double curve_along_ = 0;  // polyline length of the current chain so far
  int chain_first_ = 0;     // the first input curve of the current chain
};

}  // namespace

Discretized discretize(const svg::FeatureSoup& soup, const Lengths& lengths) {
  return Discretizer(soup, lengths).run();
}

}  // namespace curvemesh::features::detail
