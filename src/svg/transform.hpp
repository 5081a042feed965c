#pragma once
// SVG transforms: the `transform` attribute grammar and viewBox/preserveAspectRatio mapping.
#include <string_view>

#include "geometry/vec2.hpp"

namespace curvemesh::svg {

// x' = a x + c y + e,  y' = b x + d y + f  (SVG's matrix(a b c d e f)).
struct Affine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;

  static Affine translate(double tx, double ty) { return {1, 0, 0, 1, tx, ty}; }
  static Affine scale(double sx, double sy) { return {sx, 0, 0, sy, 0, 0}; }
  static Affine rotate_deg(double angle_deg);

  geometry::Vec2 apply(const geometry::Vec2& p) const { return {a * p.x() + c * p.y() + e, b * p.x() + d * p.y() + f}; }
  // (*this) * other: apply `other` first, then this.
  Affine operator*(const Affine& o) const {
    return {a * o.a + c * o.b, b * o.a + d * o.b, a * o.c + c * o.d, b * o.c + d * o.d, a * o.e + c * o.f + e,
            b * o.e + d * o.f + f};
  }
  double determinant() const { return a * d - b * c; }
  // How much the linear part shrinks a vector at most: its smaller singular value, |det| / σ_max.
  double smallest_scale() const;
  bool is_finite() const;
};

// Parses a transform list ("translate(10) rotate(45 5 5), scale(2)"). Throws SyntaxError on a
// malformed list or a non-finite result. An empty list is the identity.
Affine parse_transform(std::string_view text);

struct ViewBox {
  double x = 0, y = 0, width = 0, height = 0;
};

// The transform from viewBox coordinates to a viewport at (x, y) of size width × height, under a
// preserveAspectRatio value ("xMidYMid meet" when empty; "none" stretches). SVG 1.1 §7.8.
Affine viewbox_transform(const ViewBox& view_box, std::string_view preserve_aspect_ratio, double x, double y,
                         double width, double height);

}  // namespace curvemesh::svg
