#include "pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "base/limits.hpp"
#include "base/parallel.hpp"
#include "features/poly_input.hpp"
#include "io/curved_mesh.hpp"
#include "pipeline/domain.hpp"
#include "pipeline/output.hpp"
#include "svg/drawing_size.hpp"
#include "svg/error.hpp"
#include "svg/reader.hpp"
#include "triangulate/invariant_inputs.hpp"

namespace curvemesh::pipeline {

namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Json quality_json(const optimize::Quality& q) {
  return {{"vertices", q.vertices},   {"triangles", q.triangles},   {"min_angle_deg", q.min_angle_deg},
          {"max_amips", q.max_amips}, {"mean_amips", q.mean_amips}, {"mean_edge_length", q.mean_edge_length}};
}

Json optimize_json(const optimize::Stats& s) {
  return {{"iterations", s.iterations},
          {"stop_reason", s.stop_reason},
          {"splits", s.splits},
          {"collapses", s.collapses},
          {"coarsening_collapses", s.coarsening_collapses},
          {"coarsening_rounds", s.coarsening_rounds},
          {"triangles_before_coarsening", s.before_coarsening},
          {"swaps", s.swaps},
          {"smooths", s.smooths},
          {"projections", s.projections},
          {"released_secondary_edges", s.released},
          {"unprojected_vertices", s.unprojected},
          {"exact_vertices_left", s.exact_left}};
}

Json curve_json(const curve::Stats& s, const curve::Options& o, double d) {
  Json out = {{"split_triangles", s.split_triangles},
              {"primary_edges", s.primary_edges},
              {"curved_edges", s.curved_edges},
              {"fitted_edges", s.fitted_edges},
              {"straight_primary_edges", s.straight_primary_edges},
              {"curved_triangles", s.curved_triangles},
              {"alternative_centres", s.alternative_centres},
              {"invalid_triangles", s.invalid_triangles},
              {"min_scaled_jacobian", s.min_scaled_jacobian},
              {"max_amips_before_smoothing", s.max_amips_before_smoothing},
              {"smoothing_moves", s.smoothing_moves},
              {"curved_splits", s.curved_splits},
              {"curved_collapses", s.curved_collapses},
              {"coarsening_collapses", s.coarsening_collapses},
              {"curved_swaps", s.curved_swaps},
              {"late_projections", s.late_projections},
              {"projections_elsewhere", s.projections_elsewhere},
              {"cleared_projections", s.cleared_projections},
              {"repaired_moves", s.repaired_moves},
              {"refused_moves", s.refused_moves},
              {"max_amips", s.max_amips},
              {"mean_amips", s.mean_amips},
              {"smallest_wedge_deg", s.wedges.smallest_wedge * 180 / std::numbers::pi},
              {"wedge_amips_bound", s.wedges.smallest_wedge_bound},
              {"sharp_triangles", s.wedges.sharp_triangles},
              {"max_amips_elsewhere", s.wedges.max_amips_elsewhere},
              {"max_distance", s.max_distance},
              {"max_distance_rel", s.max_distance / d},
              {"mean_fit_distance_rel", s.mean_fit_distance / d}};
  if (o.order == 2) {
    out["tolerance"] = o.tolerance;
    out["tolerance_rel"] = o.tolerance / d;
    out["tolerance_splits"] = s.tolerance_splits;
    out["beyond_tolerance"] = s.beyond_tolerance;
  }
  return out;
}

// The largest distance from a primary edge to its curve (curve::max_edge_distance), absolute and
// relative to d.
void edge_distance_json(Json& mesh, double distance, double d) {
  mesh["max_edge_distance"] = distance;
  mesh["max_edge_distance_rel"] = distance / d;
}

Error invalid(const std::string& message) {
  return Error(Error::Kind::invalid_input, message);
}
Error internal(const std::string& message) {
  return Error(Error::Kind::internal, message);
}

// A soup made by the caller, refused when a coordinate is NaN or infinite (the reader refuses
// those in a file; here nothing else would).
const svg::FeatureSoup& finite_soup(const svg::FeatureSoup& soup, const std::string& name) {
  const auto finite = [](const geometry::Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); };
  const auto refuse = [&](const std::string& what, std::size_t i, const geometry::Vec2& p) {
    std::ostringstream s;
    s << name << ": " << what << " " << i << " has a coordinate that is not a finite number (" << p.x()
      << ", " << p.y() << ")";
    throw invalid(s.str());
  };
  for (std::size_t i = 0; i < soup.curves.size(); ++i)
    for (const geometry::Vec2& p : soup.curves[i].bezier.p)
      if (!finite(p)) refuse("curve", i, p);
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (!finite(soup.points[i].p)) refuse("point", i, soup.points[i].p);
  return soup;
}

// A drawing too small or too large for doubles (svg/drawing_size.hpp), or small beside its
// distance from the origin, which leaves too few bits of its coordinates to mesh (doubles near
// 1e15 are 0.125 apart: a drawing 1 wide there has three bits). The doubles where it lies must be
// at most 2^-30 of its size apart (as resolve() takes it).
double finite_diagonal(const geometry::Box2& box, const std::string& name) {
  if (const std::string problem = svg::drawing_size_problem(box); !problem.empty())
    throw invalid(name + ": " + problem);
  const double d = box.diagonal();  // within the range checked: no overflow or underflow
  if (!box.empty()) {
    const double far = std::max(
        {std::abs(box.min.x()), std::abs(box.min.y()), std::abs(box.max.x()), std::abs(box.max.y())});
    const double spacing = std::nextafter(far, std::numeric_limits<double>::infinity()) - far;
    const double size = d > 0 ? d : 1.0;
    if (spacing > std::ldexp(size, -30)) {
      std::ostringstream s;
      s << name << ": the drawing is too small for how far it lies from the origin: its size is " << size
        << ", and at coordinates of " << far << " doubles are " << spacing
        << " apart, more than 2^-30 of that size; move it nearer the origin";
      throw invalid(s.str());
    }
  }
  return d;
}

Stage stage_of(StopAfter s) {
  switch (s) {
    case StopAfter::triangulate:
      return Stage::triangulate;
    case StopAfter::optimize:
      return Stage::optimize;
    case StopAfter::curve:
      break;
  }
  return Stage::curve;
}

std::vector<double> stroke_widths(const std::vector<svg::FillLayer>& fills) {
  std::vector<double> widths;
  for (const svg::FillLayer& layer : fills)
    if (layer.stroke) widths.push_back(layer.width);
  return widths;
}

bool reads_paint(const Parameters& p) {
  return p.regions || p.domain == Domain::filled || p.domain == Domain::painted;
}

// Strokes narrower than --min-stroke-width paint nothing the mesh shows (regions::ClassifyOptions):
// said once, with the narrowest.
void warn_narrow_strokes(const Result& r, const regions::ClassifyOptions& c,
                         const std::function<void(const std::string&)>& warn) {
  int count = 0;
  double narrowest = std::numeric_limits<double>::infinity();
  for (const svg::FillLayer& layer : r.soup.fills)
    if (regions::too_narrow(layer, c)) ++count, narrowest = std::min(narrowest, layer.width);
  if (count == 0) return;
  std::ostringstream s;
  s << count << " stroke" << (count == 1 ? " is" : "s are") << " narrower than --min-stroke-width ("
    << r.parameters.min_stroke_width_rel << " of the drawing's diagonal), down to "
    << narrowest / r.resolved.d
    << " of it: they paint nothing in the mesh; a --min-stroke-width below that would keep them, with a mesh "
       "fine enough to hold their width";
  warn(s.str());
}

// The faces of the finished mesh, the fills over them and the part given out (Parameters'
// regions and domain).
void paint(Result& r, const std::function<void(const std::string&)>& warn) {
  const Parameters& o = r.parameters;
  if (!o.regions && o.domain == Domain::box) return;
  const auto t = Clock::now();
  const io::HighOrderMesh whole = r.curved ? io::curved_mesh(*r.curved) : io::linear_mesh(r.linear);
  if (reads_paint(o)) {
    if (r.soup.fills.empty())
      warn("no element is filled (fill none, or strokes only): every face is background");
    if (r.soup.clipped_elements > 0)
      warn(std::to_string(r.soup.clipped_elements) + " element" +
           (r.soup.clipped_elements == 1 ? " has" : "s have") +
           " a mask, or a clip path the regions cannot apply (objectBoundingBox units, text in it): their "
           "fills count unmasked, unclipped");
    regions::ClassifyOptions c;
    c.clearance = r.resolved.features.epsilon;
    c.resolution = 1e-10 * r.resolved.d;
    c.min_stroke_width = r.resolved.min_stroke_width;
    warn_narrow_strokes(r, c, warn);
    try {
      r.classification = regions::classify(whole, r.soup.fills, c, r.soup.clips);
    } catch (const regions::Undecided& e) {
      const svg::SourceElement& s = r.soup.sources.at(r.soup.fills.at(e.layer).source);
      throw internal(r.name + ": cannot decide on which side of the outline of <" + s.tag +
                     (s.id.empty() ? "" : " id=\"" + s.id + "\"") + "> (line " + std::to_string(s.line) +
                     ") face " + std::to_string(e.face) + " of the mesh lies");
    }
  } else {
    r.classification.faces = regions::find_faces(whole);
  }
  r.painted = regions::paint(whole, r.classification, r.soup, o.domain, o.regions);
  const regions::Painted& p = *r.painted;
  if (p.mesh.triangle_count() == 0) {
    throw invalid(r.name + ": the domain '" + regions::domain_name(o.domain) + "' is empty (" +
                  empty_domain_reason(o.domain, r.soup.has_fills(), r.soup.has_stroke_areas()) + ")");
  }
  Json& stats = r.stats;
  stats["domain"] = {{"name", regions::domain_name(o.domain)},
                     {"faces", r.classification.faces.count()},
                     {"triangles", p.mesh.triangle_count()}};
  if (o.regions) {
    Json list = Json::array();
    for (const regions::Region& region : p.regions)
      list.push_back({{"physical", region.physical},
                      {"name", region.name},
                      {"fill", region.fill.to_string()},
                      {"triangles", region.triangles},
                      {"area", region.area}});
    stats["regions"] = std::move(list);
  }
  stats["seconds"]["regions"] = seconds_since(t);
}

}  // namespace

const char* stage_name(Stage stage) {
  switch (stage) {
    case Stage::read:
      return "read";
    case Stage::features:
      return "features";
    case Stage::triangulate:
      return "triangulate";
    case Stage::optimize:
      return "optimize";
    case Stage::curve:
      return "curve";
  }
  return "?";
}

std::optional<Stage> stage_named(const std::string& name) {
  for (Stage s : {Stage::read, Stage::features, Stage::triangulate, Stage::optimize, Stage::curve})
    if (name == stage_name(s)) return s;
  return std::nullopt;
}

Source Source::file(std::string path) {
  Source s;
  s.kind = Kind::file;
  s.name = path;
  s.path = std::move(path);
  return s;
}

Source Source::svg(std::string text, std::string name) {
  Source s;
  s.kind = Kind::svg_text;
  s.text = std::move(text);
  s.name = std::move(name);
  return s;
}

Source Source::curves(svg::FeatureSoup soup, std::string name) {
  Source s;
  s.kind = Kind::soup;
  s.soup = std::move(soup);
  s.name = std::move(name);
  return s;
}

Source Source::beziers(const std::vector<std::array<geometry::Vec2, 4>>& curves, std::string name) {
  svg::FeatureSoup soup;
  // Numbered as the reader numbers the one <path> of a document that draws them (the root is
  // element 0): the same file, the same group name "path#1".
  soup.sources.push_back({"path", "", 1, 1});
  soup.curves.reserve(curves.size());
  for (const auto& p : curves)
    soup.curves.push_back({geometry::CubicBezier(p[0], p[1], p[2], p[3]), 0, {}, {}, {}, {}});
  return Source::curves(std::move(soup), std::move(name));
}

namespace {

// §4.2: the linear mesh curved (r.linear moves into r.curved), its statistics. Throws Error
// (internal) if a triangle could not be certified.
void curve_stage(Result& r, const std::string& name, const RunOptions& options,
                 const std::function<void(const std::string&)>& warn) {
  const auto t = Clock::now();
  curve::Stats& s = r.curve_stats;
  const auto report = [&](int pass, int triangles, double max_amips) {
    if (options.progress) options.progress({Stage::curve, pass, triangles, max_amips});
  };
  report(0, r.quality.triangles, r.quality.max_amips);
  curve::Options c = r.resolved.curve;
  int pass = 0;
  if (options.progress) c.on_pass = [&](int above, double max_amips) { report(++pass, above, max_amips); };
  r.curved = curve::curve(std::move(r.linear), r.constraints, c, &s);
  r.linear = mesh::TriMesh();
  Json& stats = r.stats;
  stats["seconds"]["curve"] = seconds_since(t);
  stats["curve"] = curve_json(s, c, r.resolved.d);
  stats["mesh"]["triangles"] = r.curved->triangles.size();
  edge_distance_json(stats["mesh"], curve::max_edge_distance(*r.curved, r.constraints), r.resolved.d);
  r.last = Stage::curve;
  if (s.invalid_triangles > 0)
    throw internal("internal error: " + name + ": " + std::to_string(s.invalid_triangles) +
                   " curved triangles could not be certified valid");
  if (s.beyond_tolerance > 0)
    warn(std::to_string(s.beyond_tolerance) + " primary edge" + (s.beyond_tolerance == 1 ? " is" : "s are") +
         " farther than --curve-tolerance from their curve (too short to split, or no split of it is valid)");
}

using Warn = std::function<void(const std::string&)>;

void report(const RunOptions& options, Stage stage, int pass = 0, int triangles = 0, double max_amips = 0) {
  if (options.progress) options.progress({stage, pass, triangles, max_amips});
}

// §3: the drawing read (a .poly file gives its features directly) and the lengths resolved
// against its bounding-box diagonal; then, unless `last` is the read, the features found.
void read_stage(Result& r, const Source& source, const Parameters& parameters, const RunOptions& options,
                Stage last, const Warn& warn) {
  Json& stats = r.stats;
  auto t = Clock::now();
  try {
    if (source.kind == Source::Kind::file && ends_with(source.path, ".poly")) {
      r.features = features::read_poly(source.path, parameters.limits);
      r.resolved = resolve(parameters, finite_diagonal(r.features.box, source.name));
      r.features.lengths = r.resolved.features;
      stats["seconds"]["read"] = seconds_since(t);
      stats["seconds"]["features"] = 0.0;
      r.last = Stage::features;
      return;
    }
    svg::ReadOptions read;
    // Every length, ε_m with the others, made absolute once, against the drawing's box as read.
    bool resolved = false;
    read.degenerate_tolerance = [&](const geometry::Box2& bounds, const geometry::Box2& canvas,
                                    const std::vector<svg::FillLayer>& fills) {
      r.resolved = resolve(parameters, finite_diagonal(features::drawing_box(bounds, canvas), source.name),
                           stroke_widths(fills));
      resolved = true;
      return r.resolved.features.eps_m;
    };
    read.close_filled_subpaths = reads_paint(parameters);
    read.strokes_as_areas = strokes_as_areas(parameters);
    read.max_curves = parameters.limits.max_curves;
    read.max_elements = parameters.limits.max_elements;
    read.max_input_bytes = static_cast<std::uint64_t>(parameters.limits.max_input_mb * 1048576.0);
    if (source.kind == Source::Kind::file)
      r.soup = svg::read_svg_file(source.path, read);
    else if (source.kind == Source::Kind::svg_text)
      r.soup = svg::read_svg(source.text, read, source.name);
    else
      r.soup = finite_soup(source.soup, source.name);
    for (const std::string& w : r.soup.warnings) warn(w);
    stats["seconds"]["read"] = seconds_since(t);
    if (!resolved)
      r.resolved = resolve(parameters, finite_diagonal(features::drawing_box(r.soup), source.name),
                           stroke_widths(r.soup.fills));
    if (last == Stage::read) return;
    report(options, Stage::features);
    t = Clock::now();
    r.features = features::process(r.soup, r.resolved.features);
    stats["seconds"]["features"] = seconds_since(t);
    r.last = Stage::features;
  } catch (const svg::InputError& e) {
    throw invalid(e.what());
  }
}

void features_json(Result& r) {
  const features::Features& f = r.features;
  int primary = 0;
  for (const auto& s : f.sections) primary += s.kind == features::Kind::primary;
  // μ and ε as the stages took them: smaller than the parameters' when strokes read as areas need it.
  const features::Lengths& l = r.resolved.features;
  r.stats["features"] = {{"primary_sections", primary},
                         {"secondary_segments", f.segments.size()},
                         {"points", f.points.size()},
                         {"mu_rel", l.mu / l.d},
                         {"epsilon_rel", l.epsilon / l.d}};
}

// §4.1, first half: the exact constrained triangulation of the features in their box.
void triangulate_stage(Result& r, const std::string& name, const Warn& warn) {
  const features::Features& f = r.features;
  if (f.box.empty()) throw invalid(name + ": nothing to mesh (no curves, segments or points)");
  if (f.sections.empty() && f.segments.empty() && f.points.empty())
    warn("nothing is drawn; meshing the canvas alone");
  const auto t = Clock::now();
  triangulate::Result tri = triangulate::triangulate(f, r.resolved.triangulate);
  r.stats["seconds"]["triangulate"] = seconds_since(t);
  r.stats["triangulate"] = {{"vertices", tri.stats.vertices},
                            {"triangles", tri.stats.triangles},
                            {"exact_vertices", tri.stats.exact_vertices},
                            {"method", triangulate::method_name(tri.stats.method)}};
  r.box = tri.box;
  r.triangulate_stats = tri.stats;
  r.shared = std::move(tri.shared);
  r.linear = std::move(tri.mesh);
  r.constraints = triangulate::invariant_inputs(f, r.box);
  r.last = Stage::triangulate;
}

// §4.1, second half: the linear mesh optimized.
void optimize_stage(Result& r, const RunOptions& options) {
  const auto t = Clock::now();
  report(options, Stage::optimize, 0, r.triangulate_stats.triangles);
  optimize::Options o = r.resolved.optimize;
  o.log = options.log;
  if (options.progress)
    o.on_iteration = [&](int iteration, int triangles, double max_amips) {
      report(options, Stage::optimize, iteration, triangles, max_amips);
    };
  r.optimize_stats = optimize::optimize(r.linear, r.constraints, o);
  r.stats["seconds"]["optimize"] = seconds_since(t);
  r.stats["optimize"] = optimize_json(r.optimize_stats);
  r.last = Stage::optimize;
}

// The linear mesh measured and checked before it is given out or curved.
void check_linear(Result& r, const std::string& name) {
  r.quality = optimize::measure(r.linear);
  Json& stats = r.stats;
  stats["mesh"] = quality_json(r.quality);
  stats["mesh"]["target_edge_length"] = r.resolved.features.edge;
  // How far the mesh's edges are from the curves they stand for, whatever its order: here the
  // chords'; the curved mesh's in curve_stage.
  edge_distance_json(stats["mesh"], curve::max_edge_distance(r.linear, r.constraints), r.resolved.d);
  if (const auto error = r.linear.structure_error())
    // Every operation checks its result exactly, so this is a bug; refuse rather than give it out.
    throw internal("internal error: " + name + ": the mesh is broken (" + *error + ")");
  if (r.linear.exact_vertex_count() > 0)
    // Rounded coordinates could invert a triangle: refuse instead.
    throw internal(name + ": " + std::to_string(r.linear.exact_vertex_count()) +
                   " vertices still have exact coordinates that do not round to doubles without inverting a "
                   "triangle");
}

// The stages in their order, up to the earlier of what the caller needs and what the parameters
// ask for (a linear mesh ends at `optimize`); then the paint over the finished mesh.
Result run_stages(const Source& source, const Parameters& parameters, const RunOptions& options) {
  parameters.validate();
  Result r;
  r.name = source.name;
  r.parameters = parameters;
  const Stage asked = std::min(options.stop_after, stage_of(parameters.stop_after));
  const Stage last = parameters.order == 1 && asked == Stage::curve ? Stage::optimize : asked;
  const Warn warn = [&](const std::string& w) {
    r.warnings.push_back(w);
    if (options.warn) options.warn(w);
  };
  r.stats["input"] = source.name;
  report(options, Stage::read);
  read_stage(r, source, parameters, options, last, warn);
  if (last == Stage::read) return r;
  features_json(r);
  if (last == Stage::features) return r;
  report(options, Stage::triangulate);
  triangulate_stage(r, source.name, warn);
  if (last != Stage::triangulate) optimize_stage(r, options);
  check_linear(r, source.name);
  if (last == Stage::curve) curve_stage(r, source.name, options, warn);
  paint(r, warn);
  return r;
}

// The stages, then the mesh as every writer and the API give it out.
Result run_and_group(const Source& source, const Parameters& parameters, const RunOptions& options) {
  Result r = run_stages(source, parameters, options);
  if (r.last >= Stage::triangulate) {
    // The mesh every writer and the API give out, with the groups a solver selects by
    // (regions/groups.hpp), listed as the .msh holds them.
    const auto t = Clock::now();
    r.output = std::make_shared<const io::HighOrderMesh>(make_output_mesh(r));
    r.stats["groups"] = groups_json(*r.output);
    r.stats["seconds"]["groups"] = seconds_since(t);
  }
  return r;
}

}  // namespace

// The whole run on the threads Parameters::threads allows (base/parallel.hpp).
Result run(const Source& source, const Parameters& parameters, const RunOptions& options) {
  try {
    return base::with_threads(parameters.threads, [&] { return run_and_group(source, parameters, options); });
  } catch (const base::LimitExceeded& e) {
    throw invalid(source.name + ": " + e.what());
  }
}

}  // namespace curvemesh::pipeline
