// The features stage as one function: discretize, tag, simplify (paper §4, first half).
#include "features/features.hpp"
#include "features/pieces.hpp"

namespace curvemesh::features {

namespace {

// Maximal runs of same-kind pieces along each curve section become the output's sections.
std::vector<Section> runs_of(const detail::Discretized& d, const svg::FeatureSoup& soup) {
  std::vector<Section> out;
  for (const detail::CurveSection& cs : d.sections) {
    const int end = cs.first_piece + cs.piece_count;
    for (int i = cs.first_piece; i < end;) {
      int j = i;
      while (j + 1 < end && d.pieces[j + 1].kind == d.pieces[i].kind) ++j;
      Section s;
      s.curve = cs.curve;
      s.kind = d.pieces[i].kind;
      s.straight = cs.straight;
      s.t0 = d.pieces[i].t0;
      s.t1 = d.pieces[j].t1;
      const CubicBezier whole =
          cs.straight ? CubicBezier::line(cs.line_a, cs.line_b) : soup.curves[cs.curve].bezier;
      s.piece = whole.subcurve(s.t0, s.t1);
      for (int k = i; k <= j; ++k) {
        s.ts.push_back(d.pieces[k].t0);
        s.polyline.push_back(d.pieces[k].a);
      }
      s.ts.push_back(d.pieces[j].t1);
      s.polyline.push_back(d.pieces[j].b);
      out.push_back(std::move(s));
      i = j + 1;
    }
  }
  return out;
}

}  // namespace

double fraction_along(const Segment& s, const Vec2& p) {
  const Vec2 ab = s.b - s.a;
  const double len2 = ab.squaredNorm();
  return len2 > 0 ? (p - s.a).dot(ab) / len2 : 0.0;
}

Box2 drawing_box(const Box2& bounds, const Box2& canvas) {
  // Nothing drawn (a file of gradient or pattern definitions): the canvas alone is meshed.
  if (bounds.empty() && !canvas.empty() && canvas.diagonal() > 0) return canvas;
  return bounds;
}

Box2 drawing_box(const svg::FeatureSoup& soup) {
  return drawing_box(soup.bounds(), soup.canvas);
}

Features process(const svg::FeatureSoup& soup, const Lengths& lengths) {
  Features f;
  f.box = drawing_box(soup);
  f.lengths = lengths;
  detail::Discretized d = detail::discretize(soup, f.lengths);
  detail::tag_primary_secondary(d, f.lengths);
  f.segments = detail::simplify_secondary(d, f.lengths);
  f.sections = runs_of(d, soup);
  f.points = std::move(d.points);
  f.degenerate_curves = d.degenerate_curves;
  f.straight_curves = d.straight_curves;
  return f;
}

}  // namespace curvemesh::features
