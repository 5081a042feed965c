#pragma once
// A small writer of SVG drawings of our data (soups, features, meshes): a viewBox around the
// data with a margin, lines a thousandth of the data's diagonal wide (about one pixel of the
// 1000-pixel-wide picture) in the drawing's own units, so that every renderer draws them alike.
#include <string>
#include <string_view>
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::io {

class SvgWriter {
 public:
  explicit SvgWriter(const geometry::Box2& extent);
  void cubic(const geometry::CubicBezier& c, std::string_view colour);
  void segment(const geometry::Vec2& a, const geometry::Vec2& b, std::string_view colour);
  void dot(const geometry::Vec2& p, std::string_view colour);
  // A region bounded by cubic pieces end to end (the last ends where the first starts), filled
  // and not stroked.
  void filled(const std::vector<geometry::CubicBezier>& boundary, std::string_view fill);
  std::string finish();

 private:
  void number(double v);
  void path_start(std::string_view colour);  // "<path ... stroke=colour d="M"
  std::string out_;
  double dot_radius_ = 1.0;
};

}  // namespace curvemesh::io
