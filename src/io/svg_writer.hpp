#pragma once
// A small writer of SVG drawings of our data (soups, features, meshes): a viewBox around the
// data with a margin, lines a thousandth of the data's diagonal wide (about one pixel of the
// 1000-pixel-wide picture) in the drawing's own units, so that every renderer draws them alike.
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::io {

// A Bézier piece of degree 1, 2 or 3 by its control points p[0..degree]: SVG's L, Q or C.
struct BezierPiece {
  int degree = 3;
  std::array<geometry::Vec2, 4> p;
};

class SvgWriter {
 public:
  explicit SvgWriter(const geometry::Box2& extent);
  void cubic(const geometry::CubicBezier& c, std::string_view colour);
  void piece(const BezierPiece& c, std::string_view colour);
  void segment(const geometry::Vec2& a, const geometry::Vec2& b, std::string_view colour);
  void dot(const geometry::Vec2& p, std::string_view colour);
  // A region bounded by pieces end to end (the last ends where the first starts), filled and not
  // stroked.
  void filled(const std::vector<BezierPiece>& boundary, std::string_view fill);
  std::string finish();

 private:
  void number(double v);
  void command(const BezierPiece& c);  // " L x y", " Q x y x y" or " C x y x y x y"
  void path_start(std::string_view colour);  // "<path ... stroke=colour d="M"
  std::string out_;
  double dot_radius_ = 1.0;
};

}  // namespace curvemesh::io
