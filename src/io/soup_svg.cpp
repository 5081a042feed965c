#include "io/soup_svg.hpp"

#include <cstdio>

#include "io/svg_writer.hpp"

namespace curvemesh::io {

std::string soup_to_svg(const svg::FeatureSoup& soup) {
  SvgWriter w(soup.bounds());
  for (const svg::SoupCurve& c : soup.curves) {
    const std::string colour = c.stroke.kind == svg::Paint::Kind::color ? c.stroke.to_string() : "#000000";
    w.cubic(c.bezier, colour);
  }
  for (const svg::SoupPoint& p : soup.points) w.dot(p.p, "#000000");
  return w.finish();
}

}  // namespace curvemesh::io
