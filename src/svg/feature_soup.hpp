#pragma once
// The reader's output and the pipeline's input (paper §3.1): a soup of isolated points and cubic
// Bézier curves in the root element's user space (viewBox units, y pointing down, as in SVG),
// each with the colours and the element it came from.
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/bezier.hpp"

namespace curvemesh::svg {

using geometry::Box2;
using geometry::CubicBezier;
using geometry::Vec2;

// A resolved `fill` or `stroke`: no paint, a colour, or a reference to a paint server.
struct Paint {
  enum class Kind : std::uint8_t { none, color, url };
  Kind kind = Kind::none;
  std::uint8_t r = 0, g = 0, b = 0;
  std::string url;  // the id for Kind::url, without '#'

  static Paint rgb(std::uint8_t r, std::uint8_t g, std::uint8_t b) { return {Kind::color, r, g, b, {}}; }
  // "#rrggbb", "none" or "url(#id)".
  std::string to_string() const;
  bool operator==(const Paint&) const = default;
};

// The drawn element a curve or point came from.
struct SourceElement {
  std::string tag;   // "path", "rect", ...
  std::string id;    // the element's id attribute, empty if it has none
  int index = 0;     // position of the element in document order (0-based, all elements counted)
  int line = 0;      // 1-based line of the element in the file
};

struct SoupCurve {
  CubicBezier bezier;
  int source = -1;  // index into FeatureSoup::sources
  Paint stroke;
  Paint fill;
  // Diffusion-curve colours (Orzan et al. 2008) from the data-color-left and data-color-right
  // attributes: the colour on each side of the curve, Kind::none where not given. Left is the
  // left on screen (y down) walking along the curve as its parameter grows: for a curve drawn
  // rightwards, the side above it. Under a mirroring transform the picture mirrors with the
  // drawing, so the reader has already swapped the two for such elements.
  Paint left;
  Paint right;
  // The arc this curve is a piece of (an SVG arc command, a circle, an ellipse, a rounded rect's
  // corner: cut into cubics only to stay within kArcTolerance of the conic), numbered in the soup,
  // its pieces consecutive in `curves`; -1 for every other curve. The features stage takes the
  // pieces of one arc for one curve.
  int arc = -1;
};

// How a shape's inside is decided from the winding number of its outline (SVG `fill-rule`).
enum class FillRule : std::uint8_t { nonzero, evenodd };

// One shape as the drawing fills it: an element drawn with a `fill` other than none (once per
// <use> that draws it), with its outline as the renderer fills it: every subpath closed, an open
// one by the straight line from its end back to its start. In paint order: a later layer is
// painted over an earlier one. With strokes read as areas (svg::ReadOptions::strokes_as_areas),
// an element's stroke is a layer too, just after its fill: the outline of the stroke, filled
// nonzero with the stroke's paint.
struct FillLayer {
  int source = -1;  // index into FeatureSoup::sources
  Paint fill;       // the stroke's paint for a stroke
  FillRule rule = FillRule::nonzero;
  std::vector<std::vector<CubicBezier>> subpaths;  // each a closed loop
  Box2 bounds;                                     // of the control points of every subpath
  bool stroke = false;                             // the area of the element's stroke
  double width = 0;  // a stroke's: its width where narrowest, in the root's user space
  // The clip paths the element is drawn through (indices into FeatureSoup::clips, its own and its
  // ancestors'): the painted set is the shape's inside that is inside every one of them.
  std::vector<int> clips = {};
};

// A <clipPath> as one element uses it (SVG 1.1 §14.3.5): the union of its children's insides,
// each child's outline closed as a fill closes it and decided by its own clip-rule, in the root's
// user space (through the referencing element's transform and the clipPath's own).
struct ClipPath {
  std::vector<FillLayer> shapes;  // `fill` unused; `rule` the child's clip-rule
};

struct SoupPoint {
  Vec2 p = Vec2::Zero();
  int source = -1;
};

struct FeatureSoup {
  std::vector<SoupCurve> curves;
  std::vector<SoupPoint> points;
  std::vector<SourceElement> sources;
  std::vector<std::string> warnings;
  // The filled shapes in paint order (what regions/ classifies the mesh's faces by), the clip
  // paths they refer to, and how many drawn elements have a mask or a clip path that the fills do
  // not apply (a mask is not a geometric cut; clipPathUnits="objectBoundingBox" is not read, nor
  // a clipPath holding anything but shapes and <use>s of shapes).
  std::vector<FillLayer> fills;
  std::vector<ClipPath> clips;
  int clipped_elements = 0;

  // The root's canvas in user units: its viewBox, else (0, 0) to its width and height (100 when
  // missing). What a drawing with nothing drawn is meshed on.
  Box2 canvas;

  // Tight bounding box of every curve and point (empty for an empty soup).
  Box2 bounds() const;
  // Whether some stroke was read as an area (a FillLayer::stroke).
  bool has_stroke_areas() const;
  // Whether some element is filled with some outline (a FillLayer that is not a stroke's, and has a
  // subpath: a filled moveto alone has none).
  bool has_fills() const;
};

}  // namespace curvemesh::svg
