// §4 "Removal of degenerate curves" to "Curve resampling": every input curve becomes one or
// more curve sections (split at inflections and where the turning would reach 180°), each
// sampled into pieces short, flat and straight enough to become one mesh edge.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "base/parallel.hpp"
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

// One input curve cut as §4 cuts it, on its own: its sections (parameter intervals) and their
// pieces, whose `section` and `along` are given when the curves are joined, in order.
struct CurveCut {
  enum class Kind { degenerate, straight, curved } kind = Kind::curved;
  Vec2 centre = Vec2::Zero();                       // degenerate: the point it becomes
  Vec2 line_a = Vec2::Zero(), line_b = Vec2::Zero();  // straight: its chord
  std::vector<std::array<double, 2>> sections;      // curved: the sections' intervals
  std::vector<int> piece_counts;                    // per section (one section when straight)
  std::vector<Piece> pieces;
};

class Cutter {
 public:
  explicit Cutter(const Lengths& lengths) : len_(lengths) {}

  CurveCut cut(const CubicBezier& c) const {
    CurveCut out;
    if (geometry::is_degenerate(c, len_.eps_m)) {
      out.kind = CurveCut::Kind::degenerate;
      out.centre = (c.p[0] + c.p[1] + c.p[2] + c.p[3]) / 4.0;
      return out;
    }
    if (geometry::is_straight(c, len_.eps_m)) {
      cut_straight(c, out);
      return out;
    }
    const std::vector<double> kept = section_ends(c);
    for (std::size_t k = 0; k + 1 < kept.size(); ++k) {
      const std::size_t first = out.pieces.size();
      refine(c, kept[k], kept[k + 1], c.eval(kept[k]), c.eval(kept[k + 1]), 0, out.pieces);
      out.sections.push_back({kept[k], kept[k + 1]});
      out.piece_counts.push_back(static_cast<int>(out.pieces.size() - first));
    }
    return out;
  }

 private:
  // Split at inflections (eq. 1), then each constant-sign part where it would turn ≥ 180°.
  std::vector<double> section_ends(const CubicBezier& c) const {
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
    return kept;
  }

  void cut_straight(const CubicBezier& c, CurveCut& out) const {
    out.kind = CurveCut::Kind::straight;
    // §4: replaced by its chord; when the ends coincide, by the two farthest control points.
    Vec2 a = c.p[0], b = c.p[3];
    if ((b - a).norm() <= len_.eps_m) {
      double best = -1;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          if ((c.p[i] - c.p[j]).norm() > best) best = (c.p[i] - c.p[j]).norm(), a = c.p[i], b = c.p[j];
    }
    out.line_a = a;
    out.line_b = b;
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / len_.edge - 1e-12)));
    for (int k = 0; k < n; ++k) {
      Piece p;
      p.t0 = double(k) / n;
      p.t1 = double(k + 1) / n;
      p.a = k == 0 ? a : a + p.t0 * (b - a);
      p.b = k + 1 == n ? b : a + p.t1 * (b - a);
      p.leave_a = b - a, p.leave_b = a - b;
      p.unfit = (p.b - p.a).norm() < len_.min_edge;  // shorter than the minimal edge length
      out.pieces.push_back(p);
    }
    out.piece_counts.push_back(n);
  }

  // §4 "Curve resampling": halve until the piece is at most l long, within μ of its chord and
  // turns at most α (what Theorem 3.4 needs to bend the edge later). Pieces that cannot get
  // there (cusps, curvature above α / l_m) are kept, but marked for the secondary set.
  void refine(const CubicBezier& c, double t0, double t1, const Vec2& a, const Vec2& b, int depth,
              std::vector<Piece>& out) const {
    const CubicBezier sub = c.subcurve(t0, t1);
    const double chord = (b - a).norm();
    const bool short_enough = chord <= len_.edge;
    const bool flat_enough = chord_deviation(sub) <= len_.mu;
    const bool straight_enough = geometry::turning_angle(sub) <= len_.alpha_rad;
    if (short_enough && flat_enough && straight_enough) return emit(sub, t0, t1, a, b, false, out);
    // Too small to split further (the control polygon bounds the arc length, unlike the chord of
    // a loop): this part cannot be a primary edge.
    const double polygon = (sub.p[1] - sub.p[0]).norm() + (sub.p[2] - sub.p[1]).norm() + (sub.p[3] - sub.p[2]).norm();
    if (depth >= kMaxDepth || polygon < 0.5 * len_.min_edge) return emit(sub, t0, t1, a, b, true, out);
    const double tm = 0.5 * (t0 + t1);
    const Vec2 m = c.eval(tm);
    refine(c, t0, tm, a, m, depth + 1, out);
    refine(c, tm, t1, m, b, depth + 1, out);
  }

  void emit(const CubicBezier& sub, double t0, double t1, const Vec2& a, const Vec2& b, bool unresolved,
            std::vector<Piece>& out) const {
    Piece p;
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
    out.push_back(p);
  }

  const Lengths& len_;
};

// The curves are cut side by side, a block at a time, and joined in order: chains, sections and the
// pieces' lengths along their chains.
class Discretizer {
 public:
  Discretizer(const svg::FeatureSoup& soup, const Lengths& lengths) : soup_(soup), len_(lengths) {}

  Discretized run() {
    const Cutter cutter(len_);
    constexpr std::size_t kBlock = 512;  // curves cut at once: their pieces wait to be joined
    const std::size_t n = soup_.curves.size();
    std::vector<CurveCut> cuts;
    for (std::size_t first = 0; first < n; first += kBlock) {
      cuts.assign(std::min(kBlock, n - first), CurveCut{});
      base::for_each_part(cuts.size(), [&](std::size_t i) { cuts[i] = cutter.cut(soup_.curves[first + i].bezier); }, 16);
      for (std::size_t i = 0; i < cuts.size(); ++i) join(static_cast<int>(first + i), std::move(cuts[i]));
    }
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

  void join(int index, CurveCut cut) {
    enter_chain(index);
    if (cut.kind == CurveCut::Kind::degenerate) {
      out_.points.push_back({cut.centre, soup_.curves[index].source});
      ++out_.degenerate_curves;
      return;
    }
    out_.straight_curves += cut.kind == CurveCut::Kind::straight;
    std::size_t next = 0;
    for (std::size_t k = 0; k < cut.piece_counts.size(); ++k) {
      CurveSection s;
      s.curve = index;
      if (cut.kind == CurveCut::Kind::straight) {
        s.straight = true;
        s.line_a = cut.line_a;
        s.line_b = cut.line_b;
      } else {
        s.t0 = cut.sections[k][0];
        s.t1 = cut.sections[k][1];
      }
      s.first_piece = static_cast<int>(out_.pieces.size());
      for (int i = 0; i < cut.piece_counts[k]; ++i, ++next) {
        cut.pieces[next].section = static_cast<int>(out_.sections.size());
        out_.pieces.push_back(cut.pieces[next]);
      }
      finish_section(s);
    }
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
