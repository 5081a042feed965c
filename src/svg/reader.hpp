#pragma once
// SVG document -> FeatureSoup. Coordinates are in the root element's user space: viewBox units
// when the root has a viewBox, otherwise the root's CSS pixels; every transform, nested <svg>
// viewport and <use> offset has been applied. The root's width/height do not scale anything.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <curvemesh/parameters.hpp>
#include <string>
#include <string_view>

#include "svg/feature_soup.hpp"

namespace curvemesh::svg {

struct ReadOptions {
  // ε_m (paper §4): paths whose control points all lie within it of their centre become isolated
  // points. It is a length relative to the drawing's size, asked for once the drawing is read: of
  // the tight box of its curves (before any path became a point) and its canvas. The pipeline
  // answers with pipeline::resolve's ε_m, made absolute against the diagonal every other length
  // is (with the fill layers read, whose strokes' widths are lengths of the drawing too). Unset:
  // 0, no path is a point unless all its control points coincide.
  std::function<double(const Box2& bounds, const Box2& canvas, const std::vector<FillLayer>& fills)>
      degenerate_tolerance;
  // Add the straight line that closes each open subpath of a filled element to the curves (not
  // degenerate ones): the edge of the filled shape becomes a feature, so the mesh's faces follow
  // the paint (regions/). Off, the curves are the drawn outlines alone.
  bool close_filled_subpaths = false;
  // Each stroked element (stroke not none, width above 0) draws the outline of its stroke instead
  // of its centre line (svg/stroke.hpp), and that area is a fill layer of the stroke's paint
  // (FillLayer::stroke) painted over the element's fill. Off, a stroke is its centre line alone.
  bool strokes_as_areas = false;
  // Refuse documents nested deeper than this (elements inside elements, <use> included).
  int max_depth = 512;
  // Refuse documents that expand (through <use>) to more curves or elements than this: a small
  // file can otherwise describe an exponentially large drawing (Limits, the public defaults). A
  // subpath without a segment (a moveto alone, read as an isolated point) counts as a curve; path
  // data and points lists are parsed no further than the curves left.
  std::size_t max_curves = Limits{}.max_curves;
  std::size_t max_elements = Limits{}.max_elements;
  // Refuse documents whose entity references expand to more characters than this in all: the
  // declarations' own expansion and every reference in every attribute and style sheet, summed.
  std::size_t max_entity_expansion = 1u << 24;
  // Refuse documents whose attributes, as read (parsed or matched against style sheets), amount
  // to more characters than this: an element drawn through <use> is read again for each instance,
  // and a long attribute multiplied so would keep the reader busy for hours. Drawings read at most
  // twice their file's size (openclipart's 114 files above 200 KB); 1 Gi characters take seconds.
  std::size_t max_attribute_text = std::size_t(1) << 30;
  // read_svg_file refuses larger files.
  std::uint64_t max_input_bytes = static_cast<std::uint64_t>(Limits{}.max_input_mb * 1048576.0);
};

// Reads SVG text. `filename` is only used in messages. Throws InputError when the document is
// refused (message names the line and element where it can). Malformed UTF-8 is replaced by
// U+FFFD, with a warning: every string of the soup, and every message, is well-formed UTF-8.
FeatureSoup read_svg(std::string_view text, const ReadOptions& options = {}, const std::string& filename = "<input>");

// Reads an SVG file; throws InputError when it cannot be opened, is not a regular file (a FIFO or
// a device is refused without waiting on it), is larger than options.max_input_bytes, or is
// refused.
FeatureSoup read_svg_file(const std::string& path, const ReadOptions& options = {});

}  // namespace curvemesh::svg
