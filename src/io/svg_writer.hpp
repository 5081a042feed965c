#pragma once
// A small writer of SVG drawings of our data (soups, features, meshes): a viewBox around the
// data with a margin, hairline strokes that keep their width when zoomed.
#include <string>
#include <string_view>

#include "geometry/bezier.hpp"

namespace curvemesh::io {

class SvgWriter {
 public:
  explicit SvgWriter(const geometry::Box2& extent);
  void cubic(const geometry::CubicBezier& c, std::string_view colour);
  void segment(const geometry::Vec2& a, const geometry::Vec2& b, std::string_view colour);
  void dot(const geometry::Vec2& p, std::string_view colour);
  std::string finish();

 private:
  void number(double v);
  void path_start(std::string_view colour);  // "<path ... stroke=colour d="M"
  std::string out_;
  double dot_radius_ = 1.0;
};

}  // namespace curvemesh::io
