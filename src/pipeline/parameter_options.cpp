// The one definition of every option of curvemesh::Parameters: its names on the command line and
// in Python, the paper's symbol, its range and its help (include/curvemesh/parameters.hpp,
// ParameterOption). The command line (app/mesh_options.cpp) and the Python module register what
// is here; Parameters::validate checks these ranges.
#include <cmath>
#include <limits>

#include "pipeline/parameters.hpp"

namespace curvemesh {

namespace {

using Kind = ParameterOption::Kind;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kIntMax = std::numeric_limits<int>::max();
constexpr double kCountMax = 9007199254740992.0;  // 2^53: every count up to it is a double exactly

// A field of Parameters as the table's number, and back.
#define CURVEMESH_FIELD(expr, type)                                  \
  [](const Parameters& p) { return static_cast<double>(p.expr); }, \
      [](Parameters& p, double v) { p.expr = static_cast<type>(v); }

std::vector<ParameterOption> feature_options() {
  return {
      {"--mu", "--mu", "mu", "μ", "features", Kind::number, 0, kInf, true, 0, {},
       "feature envelope mu, relative to d: min distance between primary features", CURVEMESH_FIELD(mu_rel, double)},
      {"--epsilon", "--epsilon", "epsilon", "ε", "features", Kind::number, 0, kInf, true, 0, {},
       "envelope epsilon of secondary features, relative to d; at least mu", CURVEMESH_FIELD(epsilon_rel, double)},
      {"--edge-length", "-l,--edge-length", "edge_length", "l", "features", Kind::number, 0, kInf, true, 0, {},
       "target edge length l, relative to d", CURVEMESH_FIELD(edge_length_rel, double)},
      {"--min-edge-length", "--min-edge-length", "min_edge_length", "l_m", "features", Kind::number, 0, kInf, true,
       0, {},
       "minimal edge length l_m, relative to d: pieces shorter than l_m, or curving more than alpha/l_m (a primary "
       "edge turning alpha would be shorter than l_m), are secondary",
       CURVEMESH_FIELD(min_edge_length_rel, double)},
      {"--min-angle", "--min-angle", "min_angle", "α", "features", Kind::number, 0.1, 60, false, 0, {},
       "alpha in degrees: max turning of the curve along one primary edge (target min angle)",
       CURVEMESH_FIELD(alpha_deg, double)},
      {"--junction-angle", "--junction-angle", "junction_angle", "", "features", Kind::number, 0, 180, false, 0, {},
       "primary pieces sharing an endpoint stay primary when they meet at least at this angle, both their chords "
       "and their curves' tangents there (deg)",
       CURVEMESH_FIELD(junction_angle_deg, double)},
      {"--no-features", "--no-features", "features", "", "features", Kind::flag, 0, 1, false, 0, {},
       "no feature curves: every curve is secondary, kept within epsilon by straight segments and followed by no "
       "edge, as TriWild meshes a drawing without a feature file (its linear mode, there with epsilon 0.001); the "
       "curved mesh then has straight edges only (Python: features=False)",
       CURVEMESH_FIELD(features, bool)},
      {"--eps-m", "--eps-m,--degenerate-tolerance", "eps_m", "ε_m", "features", Kind::number, 0, kInf, false, 0, {},
       "round-off tolerance epsilon_m, relative to d: paths whose control points all lie within it of each other "
       "become isolated points, curves within it of a line become straight",
       CURVEMESH_FIELD(eps_m_rel, double)},
      {"--strokes", "--strokes", "strokes", "", "features", Kind::choice, 0, 1, false, 0, {"lines", "areas"},
       "what a stroked element draws: lines (its centre line, a curve of no width) or areas (the outline of the "
       "area its stroke paints: offset curves at half the stroke-width, within 1e-8 of the width of the exact "
       "offset, with stroke-linejoin, stroke-miterlimit, stroke-linecap, stroke-dasharray, stroke-dashoffset and "
       "vector-effect: non-scaling-stroke; with --regions each stroke is a region of its own, named by its "
       "element and '.stroke', painted over the element's fill); --domain painted implies areas",
       CURVEMESH_FIELD(strokes, Strokes)},
      {"--min-stroke-width", "--min-stroke-width", "min_stroke_width", "", "features", Kind::number, 0, kInf, true, 0,
       {},
       "with strokes as areas, the narrowest stroke the mesh keeps, relative to d: mu and epsilon shrink together "
       "(below what --mu and --epsilon say) until the narrowest stroke at least this wide is 3 mu wide, so that its "
       "two sides and its fill's outline stay apart; narrower strokes paint nothing, with a warning",
       CURVEMESH_FIELD(min_stroke_width_rel, double)},
  };
}

std::vector<ParameterOption> limit_options() {
  return {
      {"--max-input-mb", "--max-input-mb", "max_input_mb", "", "limits", Kind::number, 0, kInf, true, 0, {},
       "refuse an input file larger than this many MiB (and any that is not a regular file)",
       CURVEMESH_FIELD(limits.max_input_mb, double)},
      {"--max-elements", "--max-elements", "max_elements", "", "limits", Kind::integer, 1, kCountMax, false, 0, {},
       "refuse a drawing with more SVG elements than this, each instance of a <use> counted",
       CURVEMESH_FIELD(limits.max_elements, std::size_t)},
      {"--max-curves", "--max-curves", "max_curves", "", "limits", Kind::integer, 1, kCountMax, false, 0, {},
       "refuse a drawing with more cubic curves than this, after <use> and path data",
       CURVEMESH_FIELD(limits.max_curves, std::size_t)},
      {"--max-triangles", "--max-triangles", "max_triangles", "", "limits", Kind::integer, 1, kCountMax, false, 0,
       {},
       "refuse a drawing whose mesh has more triangles than this at any stage (curves crossing everywhere, a tiny "
       "--edge-length, curves piled on one another); with the other limits' defaults, a run stays under about 2 GB "
       "of memory",
       CURVEMESH_FIELD(limits.max_triangles, std::size_t)},
      {"--threads", "--threads", "threads", "", "limits", Kind::integer, 0, 4096, false, 0, {},
       "threads one run may use (0: every hardware thread); what it writes is the same, byte for byte, whatever "
       "the number",
       CURVEMESH_FIELD(threads, int)},
  };
}

std::vector<ParameterOption> mesh_options() {
  return {
      {"--order", "--order", "order", "", "mesh", Kind::integer, 1, 3, false, 0, {},
       "the elements' order: 3 (curved, cubic 10-node triangles whose edges follow the primary curves), 2 (curved, "
       "quadratic 6-node triangles whose edges stay within --curve-tolerance of the primary curves) or 1 (straight "
       "3-node triangles)",
       CURVEMESH_FIELD(order, int)},
      {"--curve-tolerance", "--curve-tolerance", "curve_tolerance", "", "mesh", Kind::number, 0, kInf, false, 0, {},
       "with --order 2: the largest distance from an edge on a primary curve to the curve, relative to d; an edge "
       "farther is split (0: epsilon)",
       CURVEMESH_FIELD(curve_tolerance_rel, double)},
      {"--linear", "--linear", "linear", "", "mesh", Kind::flag, 0, 1, false, 1, {},
       "make a linear mesh (straight-sided 3-node triangles): --order 1",
       [](const Parameters& p) { return p.order == 1 ? 1.0 : 0.0; },
       [](Parameters& p, double v) {
         if (v != 0) p.order = 1;
       }},
      {"--max-iterations", "--max-iterations", "max_iterations", "", "mesh", Kind::integer, 0, kIntMax, false, 0, {},
       "optimization passes at most", CURVEMESH_FIELD(max_iterations, int)},
      {"--stop-amips", "--stop-amips", "stop_amips", "", "mesh", Kind::number, 2, 1e9, false, 0, {},
       "optimization stops once every triangle's AMIPS energy is at most this (2 = equilateral); coarsening, of the "
       "linear mesh and along the curves, keeps what it changes at most this or its worst before",
       CURVEMESH_FIELD(stop_amips, double)},
      {"--box-margin", "--box-margin", "box_margin", "", "mesh", Kind::number, 1e-3, 10, false, 0, {},
       "the meshed box extends the drawing's bounding box by this, relative to d, on every side",
       CURVEMESH_FIELD(box_margin_rel, double)},
      {"--curved-stop-amips", "--curved-stop-amips", "curved_stop_amips", "", "mesh", Kind::number, 2, 1e9, false, 0,
       {},
       "curving: smoothing and local operations stop once every curved triangle's AMIPS energy is at most this",
       CURVEMESH_FIELD(curved_stop_amips, double)},
      {"--max-curved-passes", "--max-curved-passes", "max_curved_passes", "", "mesh", Kind::integer, 0, kIntMax,
       false, 0, {}, "curving: smoothing and operation passes at most", CURVEMESH_FIELD(max_curved_passes, int)},
  };
}

std::vector<ParameterOption> run_options() {
  return {
      {"--regions", "--regions", "regions", "", "run", Kind::flag, 0, 1, false, 1, {},
       "tag the triangles by what the drawing paints on them, as a browser does (fill, fill-rule, transforms, "
       "<use>, CSS; the topmost filled element wins): one physical surface per visible element, named by its id "
       "(else TAG#INDEX, its index in the document), and 'background' where nothing is filled, with the same ids "
       "whatever --domain keeps; --stats lists them with fill, triangles and area; --svg fills each triangle with its element's colour. Text covers "
       "what its glyphs do. Opacity, gradients and "
       "patterns do not change what covers what; a clip path cuts its element's fill to its inside (its outline "
       "becomes a feature), while masks (not a geometric cut) and clip paths in objectBoundingBox units are ignored "
       "(with a warning). The line "
       "closing an open filled subpath becomes a feature",
       CURVEMESH_FIELD(regions, bool)},
      {"--domain", "--domain", "domain", "", "run", Kind::choice, 0, 4, false, 0,
       {"box", "filled", "evenodd", "painted", "outside"},
       "the part of the box to mesh: box (all of it), filled (what some filled element covers: the shape as it is "
       "seen, without the background), evenodd (the even-odd inside of all curves), painted (what some fill or "
       "stroke paints; implies --strokes areas) or outside (the box without evenodd); nodes no triangle uses are "
       "dropped, lines on the domain's border keep their tag",
       CURVEMESH_FIELD(domain, Domain)},
      {"--stop-after", "--stop-after", "stop_after", "", "run", Kind::choice, 0, 2, false, 0,
       {"triangulate", "optimize", "curve"},
       "last stage to run: triangulate (the exact triangulation, unoptimized), optimize (the linear mesh) or curve "
       "(optimize with --order 1)",
       CURVEMESH_FIELD(stop_after, StopAfter)},
  };
}

#undef CURVEMESH_FIELD

}  // namespace

std::vector<ParameterOption> parameter_options() {
  std::vector<ParameterOption> all;
  for (auto group : {mesh_options(), feature_options(), limit_options(), run_options()})
    all.insert(all.end(), group.begin(), group.end());
  return all;
}

}  // namespace curvemesh
