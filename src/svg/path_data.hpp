#pragma once
// SVG path data (the `d` attribute) to cubic Béziers, in the element's own coordinates.
// Every command M L H V C S Q T A Z, absolute and relative, with implicit repeats.
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "svg/feature_soup.hpp"

namespace curvemesh::svg {

struct Subpath {
  Vec2 start = Vec2::Zero();           // the moveto point
  std::vector<CubicBezier> segments;   // lines, quadratics and arc pieces all as cubics
  bool closed = false;                 // ended by Z (a closing segment was added if needed)
  // Per segment, whether it continues the segment before it as a piece of the same arc: an arc is
  // cut into several cubics only to stay within kArcTolerance (svg/arc.hpp), and the features
  // stage takes the pieces for one curve. Shorter than `segments` (empty) where none does.
  std::vector<char> continues;

  bool continues_at(std::size_t i) const { return i < continues.size() && continues[i]; }
  // Appends the pieces of one arc; with `joins_previous`, its first piece continues the segment
  // before it too (two arcs of one ellipse meeting without a side between them).
  void add_arc(const std::vector<CubicBezier>& pieces, bool joins_previous = false) {
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      continues.resize(segments.size(), 0);
      continues.push_back(k > 0 || (joins_previous && !segments.empty()));
      segments.push_back(pieces[k]);
    }
  }
};

// Parses path data. Throws SyntaxError (with the offset into `d`) on an unknown command, a
// malformed number, or a number that overflows a double. Like browsers, an empty string gives no
// subpaths; a moveto followed by nothing gives a subpath without segments.
//
// Data that simply ends in the middle of a command's arguments ("M 0 0 L 5") is what some
// editors write; browsers draw it up to the incomplete command (SVG 2 §9.5.4). With `truncated`
// given, so do we and set *truncated; without it, that is a SyntaxError too.
//
// `max_pieces` bounds what is parsed, counting each segment and each subpath without one (a
// moveto alone): past it, throws TooManyPieces, before more memory is taken.
std::vector<Subpath> parse_path_data(std::string_view d, bool* truncated = nullptr,
                                     std::size_t max_pieces = std::numeric_limits<std::size_t>::max());

// Path data or a points list holding more pieces than the caller allows.
class TooManyPieces : public std::runtime_error {
 public:
  TooManyPieces() : std::runtime_error("more pieces than allowed") {}
};

}  // namespace curvemesh::svg
