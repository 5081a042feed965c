#include "triangulate/triangulate.hpp"

#include <algorithm>
#include <bit>
#include <chrono>

#include "triangulate/arrangement.hpp"

namespace curvemesh::triangulate {

namespace {

using Vec2 = geometry::Vec2;
using detail::ArrangementVertex;
using detail::InputConstraint;

int priority(mesh::EdgeKind k) {
  switch (k) {
    case mesh::EdgeKind::primary: return 3;
    case mesh::EdgeKind::secondary: return 2;
    case mesh::EdgeKind::boundary: return 1;
    default: return 0;
  }
}

// Per mesh vertex: the features its tagged edges lie on, to decide how it may move.
struct Incidence {
  int section = -1;
  bool several_sections = false;
  bool secondary = false;
  unsigned sides = 0;
  double t = 0;
  bool t_known = false;
  bool on_curve = false;
  void add_section(int s, double t_here, bool exact_here) {
    if (section >= 0 && section != s) several_sections = true;
    section = s;
    if (!t_known || (exact_here && !on_curve)) {
      t = t_here;
      on_curve = exact_here;
      t_known = true;
    }
  }
};

mesh::VertexTag tag_of(const ArrangementVertex& v, const Incidence& inc) {
  mesh::VertexTag tag;
  tag.isolated = v.isolated;
  // Secondary edges only ask to stay inside the ε-envelope, which every operation checks, so
  // they do not pin a vertex: where a secondary segment meets a curve or the box, the vertex
  // moves like a primary or boundary vertex. Only curves and box sides pin each other.
  const int families = (inc.section >= 0) + std::popcount(inc.sides);
  if (v.fixed || inc.several_sections || families > 1) {
    tag.kind = mesh::VertexKind::fixed;
  } else if (inc.section >= 0) {
    tag.kind = mesh::VertexKind::primary;
    tag.section = inc.section;
    tag.t = inc.t;
    tag.on_curve = inc.on_curve;
  } else if (inc.secondary) {
    tag.kind = mesh::VertexKind::secondary;
  } else if (inc.sides) {
    tag.kind = mesh::VertexKind::boundary;
    tag.side = std::countr_zero(inc.sides);
  }
  return tag;
}

geometry::Box2 outer_box(const features::Features& f, const Options& o) {
  geometry::Box2 box = f.box;
  if (box.empty()) box.add(Vec2::Zero());
  // A drawing with no extent (one point) still gets a box of the working length scale.
  const double pad = o.box_margin > 0 ? o.box_margin : f.lengths.d;
  box.min -= Vec2(pad, pad);
  box.max += Vec2(pad, pad);
  return box;
}

// The box corners, the primary polyline vertices, the secondary segments' ends and the isolated
// points; then the constraints: primary polyline edges, secondary segments, box sides. Where
// constraints overlap, the piece takes the tag of the most important (`tag_piece`).
detail::Input make_input(const features::Features& f, const geometry::Box2& b) {
  detail::Input in;
  const auto add = [&](const Vec2& p, bool fixed) {
    in.points.push_back({p, fixed, false});
    return static_cast<int>(in.points.size()) - 1;
  };
  const int corners[4] = {add({b.min.x(), b.min.y()}, true), add({b.max.x(), b.min.y()}, true),
                          add({b.max.x(), b.max.y()}, true), add({b.min.x(), b.max.y()}, true)};
  std::vector<int> first_point(f.sections.size(), -1);
  for (std::size_t s = 0; s < f.sections.size(); ++s) {
    // Secondary sections reach the mesh as their simplified segments, not as curves.
    if (f.sections[s].kind != features::Kind::primary) continue;
    const auto& poly = f.sections[s].polyline;
    first_point[s] = static_cast<int>(in.points.size());
    for (std::size_t i = 0; i < poly.size(); ++i) add(poly[i], i == 0 || i + 1 == poly.size());
  }
  const int first_segment_point = static_cast<int>(in.points.size());
  for (const features::Segment& seg : f.segments) {
    add(seg.a, false);
    add(seg.b, false);
  }
  for (const features::IsolatedPoint& p : f.points) in.points[add(p.p, true)].isolated = true;

  for (std::size_t s = 0; s < f.sections.size(); ++s)
    if (first_point[s] >= 0)
      for (std::size_t i = 0; i + 1 < f.sections[s].polyline.size(); ++i)
        in.constraints.push_back({mesh::EdgeKind::primary, int(s), int(i), first_point[s] + int(i), first_point[s] + int(i) + 1});
  for (std::size_t k = 0; k < f.segments.size(); ++k) {
    const int a = first_segment_point + 2 * int(k);
    in.constraints.push_back({mesh::EdgeKind::secondary, int(k), -1, a, a + 1});
  }
  for (int side = 0; side < 4; ++side)
    in.constraints.push_back({mesh::EdgeKind::boundary, side, -1, corners[side], corners[(side + 1) % 4]});
  return in;
}

class Assembler {
 public:
  Assembler(const features::Features& f, const detail::Input& in, const detail::Triangulation& tri)
      : f_(f), in_(in), tri_(tri) {}

  mesh::TriMesh run(Stats& stats, std::vector<SharedPiece>& shared) {
    mesh::TriMesh m;
    std::vector<Incidence> inc(tri_.vertices.size());
    std::vector<std::pair<std::array<int, 2>, mesh::EdgeFeature>> features;
    features.reserve(tri_.pieces.size());
    for (const detail::Piece& piece : tri_.pieces) {
      features.push_back({{piece.u, piece.w}, tag_piece(piece, inc)});
      share(piece, features.back().second, shared);
    }

    for (std::size_t i = 0; i < tri_.vertices.size(); ++i) {
      const ArrangementVertex& v = tri_.vertices[i];
      m.add_vertex(v.approx, tag_of(v, inc[i]));
      if (!v.input) ++stats.crossing_vertices;
    }
    for (std::size_t i = 0; i < tri_.vertices.size(); ++i)
      if (tri_.vertices[i].exact_needed) m.set_exact_position(static_cast<int>(i), tri_.vertices[i].exact);
    for (const auto& t : tri_.triangles) m.add_triangle(t[0], t[1], t[2]);
    for (const auto& [e, feature] : features) m.set_feature(e[0], e[1], feature);
    for (const auto& ends : tri_.constraint_ends) stats.input_constraints += ends[0] >= 0;
    return m;
  }

 private:
  // The parameter of vertex `v` of a primary constraint: exact at the polyline vertices,
  // interpolated along the chord for a crossing inside the edge (not on the curve yet).
  double primary_parameter(int c, int v, bool& on_curve) const {
    const InputConstraint& ic = in_.constraints[c];
    const features::Section& s = f_.sections[ic.source];
    const double ta = s.ts[ic.edge], tb = s.ts[ic.edge + 1];
    on_curve = true;
    if (v == tri_.constraint_ends[c][0]) return ta;
    if (v == tri_.constraint_ends[c][1]) return tb;
    on_curve = false;
    const Vec2& a = s.polyline[ic.edge];
    const Vec2 ab = s.polyline[ic.edge + 1] - a;
    const Vec2 p = tri_.vertices[v].approx;
    const double len2 = ab.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.5;
    return ta + u * (tb - ta);
  }

  // What the piece's ends learn from every constraint on it, and the tag of the most important.
  mesh::EdgeFeature tag_piece(const detail::Piece& piece, std::vector<Incidence>& inc) const {
    const int u = piece.u, w = piece.w;
    int best = -1;
    double best_tu = 0, best_tw = 0;
    for (int k = piece.first; k < piece.last; ++k) {
      const int c = tri_.piece_constraints[k];
      const InputConstraint& ic = in_.constraints[c];
      double tu = 0, tw = 0;
      if (ic.kind == mesh::EdgeKind::primary) {
        bool exact_u = false, exact_w = false;
        tu = primary_parameter(c, u, exact_u);
        tw = primary_parameter(c, w, exact_w);
        inc[u].add_section(ic.source, tu, exact_u);
        inc[w].add_section(ic.source, tw, exact_w);
      } else if (ic.kind == mesh::EdgeKind::secondary) {
        inc[u].secondary = inc[w].secondary = true;
      } else {
        inc[u].sides |= 1u << ic.source;
        inc[w].sides |= 1u << ic.source;
      }
      const InputConstraint* b = best >= 0 ? &in_.constraints[best] : nullptr;
      if (!b || priority(ic.kind) > priority(b->kind) || (priority(ic.kind) == priority(b->kind) && ic.source < b->source)) {
        best = c;
        best_tu = tu;
        best_tw = tw;
      }
    }
    const InputConstraint& b = in_.constraints[best];
    mesh::EdgeFeature feature;
    feature.kind = b.kind;
    feature.source = b.source;
    if (b.kind == mesh::EdgeKind::primary) {
      feature.curve = f_.sections[b.source].curve;
      feature.t_lo = u < w ? best_tu : best_tw;
      feature.t_hi = u < w ? best_tw : best_tu;
    } else if (b.kind == mesh::EdgeKind::secondary) {
      feature.curve = f_.segments[b.source].curve;
    }
    return feature;
  }

  // The input curves of constraint c: a section's curve, a segment's and those it stands for too.
  void add_curves(int c, std::vector<int>& out) const {
    const InputConstraint& ic = in_.constraints[c];
    if (ic.kind == mesh::EdgeKind::primary) out.push_back(f_.sections[ic.source].curve);
    if (ic.kind != mesh::EdgeKind::secondary) return;
    const features::Segment& s = f_.segments[ic.source];
    out.push_back(s.curve);
    out.insert(out.end(), s.other_curves.begin(), s.other_curves.end());
  }

  // Records the piece when it lies on other curves than the one its tag names.
  void share(const detail::Piece& piece, const mesh::EdgeFeature& tag, std::vector<SharedPiece>& out) const {
    if (tag.kind != mesh::EdgeKind::primary && tag.kind != mesh::EdgeKind::secondary) return;
    std::vector<int> curves;
    for (int k = piece.first; k < piece.last; ++k) add_curves(tri_.piece_constraints[k], curves);
    std::sort(curves.begin(), curves.end());
    curves.erase(std::unique(curves.begin(), curves.end()), curves.end());
    std::erase_if(curves, [&](int c) { return c < 0 || c == tag.curve; });
    if (curves.empty()) return;
    SharedPiece p{tag.kind, tag.source, std::min(tag.t_lo, tag.t_hi), std::max(tag.t_lo, tag.t_hi), std::move(curves)};
    if (tag.kind == mesh::EdgeKind::secondary) {
      const features::Segment& s = f_.segments[tag.source];
      const double a = features::fraction_along(s, tri_.vertices[piece.u].approx),
                   b = features::fraction_along(s, tri_.vertices[piece.w].approx);
      p.from = std::min(a, b);
      p.to = std::max(a, b);
    }
    out.push_back(std::move(p));
  }

  const features::Features& f_;
  const detail::Input& in_;
  const detail::Triangulation& tri_;
};

// Rounds each rational vertex to its nearest double when no incident triangle inverts or
// degenerates; repeated because rounding one vertex can free a neighbour.
void round_vertices(mesh::TriMesh& m) {
  for (bool changed = true; changed;) {
    changed = false;
    for (int v = 0; v < m.vertex_count(); ++v) {
      if (!m.has_exact(v)) continue;
      const Vec2 p = geometry::nearest_double(m.exact(v));
      bool ok = true;
      for (int t : m.triangles_of(v)) {
        const mesh::Triangle& tri = m.triangle(t);
        if (m.orientation_with(tri[0], tri[1], tri[2], v, p) <= 0) {
          ok = false;
          break;
        }
      }
      if (ok) {
        m.set_position(v, p);
        changed = true;
      }
    }
  }
}

}  // namespace

const char* method_name(Method m) {
  switch (m) {
    case Method::rounded: return "rounded";
    case Method::exact_crossings: return "exact crossings";
    case Method::exact_constructions: return "exact constructions";
  }
  return "";
}

Result triangulate(const features::Features& features, const Options& options) {
  const auto start = std::chrono::steady_clock::now();
  Result result;
  result.box = outer_box(features, options);
  detail::Input input = make_input(features, result.box);
  input.max_triangles = options.max_triangles;
  std::optional<detail::Triangulation> tri = detail::triangulate_arrangement(input);
  if (!tri) tri = detail::triangulate_exact(input);
  result.stats.method = tri->method;
  result.mesh = Assembler(features, input, *tri).run(result.stats, result.shared);
  tri.reset();
  round_vertices(result.mesh);
  result.stats.vertices = result.mesh.vertex_count();
  result.stats.triangles = result.mesh.triangle_count();
  result.stats.exact_vertices = result.mesh.exact_vertex_count();
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace curvemesh::triangulate
