#include "triangulate/triangulate.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <type_traits>
#include <unordered_map>

namespace curvemesh::triangulate {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = K::Point_2;
using Vec2 = geometry::Vec2;

// What we know of a vertex from the input alone.
struct VertexInfo {
  int mesh_index = -1;
  bool fixed = false;     // box corner, section end, isolated point
  bool isolated = false;  // an input point
  bool input = false;     // inserted as an input point (the others are crossings)
};

using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_intersections_tag>;
using Cdtp = CGAL::Constrained_triangulation_plus_2<Cdt>;
using VertexHandle = Cdtp::Vertex_handle;

// What an input constraint is: a primary polyline edge, a secondary segment or a box side.
struct ConstraintInfo {
  mesh::EdgeKind kind = mesh::EdgeKind::interior;
  int source = -1;      // section / segment / side
  int edge = -1;        // primary: the polyline edge (between polyline vertices edge, edge + 1)
  VertexHandle front, back;  // its two input ends
};

int priority(mesh::EdgeKind k) {
  switch (k) {
    case mesh::EdgeKind::primary: return 3;
    case mesh::EdgeKind::secondary: return 2;
    case mesh::EdgeKind::boundary: return 1;
    default: return 0;
  }
}

// The kernel's exact number type is mpq_class or CGAL::Gmpq, depending on how CGAL was built.
template <class Exact>
mpq_class exact_to_mpq(const Exact& e) {
  if constexpr (std::is_same_v<Exact, mpq_class>) {
    return e;
  } else {
    return mpq_class(e.mpq());
  }
}

mpq_class to_mpq(const K::FT& x) { return exact_to_mpq(CGAL::exact(x)); }

// The position of a CGAL vertex: a double when the exact value is one, else the rational.
struct Position {
  Vec2 approx;
  bool exact_needed = false;
  geometry::ExactPoint exact;
};

Position position_of(const Point& p) {
  Position pos;
  const auto ix = CGAL::to_interval(p.x()), iy = CGAL::to_interval(p.y());
  if (ix.first == ix.second && iy.first == iy.second) {  // the interval is a point: it is the value
    pos.approx = {ix.first, iy.first};
    return pos;
  }
  pos.exact = geometry::ExactPoint(to_mpq(p.x()), to_mpq(p.y()));
  pos.approx = geometry::nearest_double(pos.exact);
  pos.exact_needed = geometry::ExactPoint(pos.approx).x != pos.exact.x || geometry::ExactPoint(pos.approx).y != pos.exact.y;
  return pos;
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

class Builder {
 public:
  Builder(const features::Features& f, const Options& o) : f_(f), o_(o) {}

  Result run() {
    const auto start = std::chrono::steady_clock::now();
    make_box();
    insert_points();
    insert_constraints();
    extract();
    round_vertices();
    result_.stats.vertices = result_.mesh.vertex_count();
    result_.stats.triangles = result_.mesh.triangle_count();
    result_.stats.exact_vertices = result_.mesh.exact_vertex_count();
    result_.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(result_);
  }

 private:
  void make_box() {
    geometry::Box2 box = f_.box;
    if (box.empty()) box.add(Vec2::Zero());
    const double margin = o_.box_margin;
    // A drawing with no extent (one point) still gets a box of the working length scale.
    const double pad = margin > 0 ? margin : f_.lengths.d;
    box.min -= Vec2(pad, pad);
    box.max += Vec2(pad, pad);
    result_.box = box;
  }

  // Every input point once, in Hilbert order so that each insertion starts near the last one.
  void insert_points() {
    const geometry::Box2& b = result_.box;
    corners_ = {add_point({b.min.x(), b.min.y()}, true), add_point({b.max.x(), b.min.y()}, true),
                add_point({b.max.x(), b.max.y()}, true), add_point({b.min.x(), b.max.y()}, true)};
    section_points_.resize(f_.sections.size());
    for (std::size_t s = 0; s < f_.sections.size(); ++s) {
      // Secondary sections reach the mesh as their simplified segments, not as curves.
      if (f_.sections[s].kind != features::Kind::primary) continue;
      const auto& poly = f_.sections[s].polyline;
      for (std::size_t i = 0; i < poly.size(); ++i)
        section_points_[s].push_back(add_point(poly[i], i == 0 || i + 1 == poly.size()));
    }
    for (const features::Segment& seg : f_.segments) segment_points_.push_back({add_point(seg.a, false), add_point(seg.b, false)});
    for (const features::IsolatedPoint& p : f_.points) {
      const int i = add_point(p.p, true);
      isolated_input_[i] = true;
    }

    std::vector<std::size_t> order(points_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    using Traits = CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<Point>::type>;
    CGAL::hilbert_sort(order.begin(), order.end(), Traits(CGAL::make_property_map(points_)));
    handles_.resize(points_.size());
    Cdtp::Face_handle hint;
    for (std::size_t i : order) {
      VertexHandle v = cdt_.insert(points_[i], hint);
      if (fixed_input_[i]) v->info().fixed = true;
      if (isolated_input_[i]) v->info().isolated = true;
      v->info().input = true;
      handles_[i] = v;
      hint = v->face();
    }
  }

  int add_point(const Vec2& p, bool fixed) {
    points_.emplace_back(p.x(), p.y());
    fixed_input_.push_back(fixed);
    isolated_input_.push_back(false);
    return static_cast<int>(points_.size()) - 1;
  }

  // Highest priority first: a constraint identical to one already in is not inserted again,
  // so an overlap keeps the tag of the more important feature.
  void insert_constraints() {
    for (std::size_t s = 0; s < section_points_.size(); ++s)
      for (std::size_t i = 0; i + 1 < section_points_[s].size(); ++i)
        insert(section_points_[s][i], section_points_[s][i + 1], {mesh::EdgeKind::primary, int(s), int(i), {}, {}});
    for (std::size_t k = 0; k < segment_points_.size(); ++k)
      insert(segment_points_[k][0], segment_points_[k][1], {mesh::EdgeKind::secondary, int(k), -1, {}, {}});
    for (int side = 0; side < 4; ++side)
      insert(corners_[side], corners_[(side + 1) % 4], {mesh::EdgeKind::boundary, side, -1, {}, {}});
  }

  void insert(int a, int b, ConstraintInfo info) {
    const VertexHandle va = handles_[a], vb = handles_[b];
    if (va == vb) return;  // a zero-length input: its point is in already
    const auto id = cdt_.insert_constraint(va, vb);
    if (id.vl_ptr() == nullptr) return;  // the same constraint is already there
    info.front = va;
    info.back = vb;
    constraints_.emplace(id.vl_ptr(), info);
    ++result_.stats.input_constraints;
  }

  // The parameter of vertex `v` of a primary constraint: exact at the polyline vertices,
  // interpolated along the chord for a crossing inside the edge (not on the curve yet).
  double primary_parameter(const ConstraintInfo& c, VertexHandle v, bool& on_curve) const {
    const features::Section& s = f_.sections[c.source];
    const double ta = s.ts[c.edge], tb = s.ts[c.edge + 1];
    on_curve = true;
    if (v == c.front) return ta;
    if (v == c.back) return tb;
    on_curve = false;
    const Vec2& a = s.polyline[c.edge];
    const Vec2 ab = s.polyline[c.edge + 1] - a;
    const Vec2 p = positions_[v->info().mesh_index].approx;
    const double len2 = ab.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.5;
    return ta + u * (tb - ta);
  }

  void extract() {
    mesh::TriMesh& m = result_.mesh;
    for (auto v = cdt_.finite_vertices_begin(); v != cdt_.finite_vertices_end(); ++v) {
      v->info().mesh_index = static_cast<int>(positions_.size());
      positions_.push_back(position_of(v->point()));
      if (!v->info().input) ++result_.stats.crossing_vertices;
    }
    std::vector<Incidence> inc(positions_.size());

    for (auto sc = cdt_.subconstraints_begin(); sc != cdt_.subconstraints_end(); ++sc) {
      const VertexHandle u = sc->first.first, w = sc->first.second;
      const ConstraintInfo* best = nullptr;
      double best_tu = 0, best_tw = 0;
      for (auto ctx = sc->second->begin(); ctx != sc->second->end(); ++ctx) {
        const auto it = constraints_.find(ctx->id().vl_ptr());
        if (it == constraints_.end()) continue;
        const ConstraintInfo& c = it->second;
        double tu = 0, tw = 0;
        if (c.kind == mesh::EdgeKind::primary) {
          bool exact_u = false, exact_w = false;
          tu = primary_parameter(c, u, exact_u);
          tw = primary_parameter(c, w, exact_w);
          inc[u->info().mesh_index].add_section(c.source, tu, exact_u);
          inc[w->info().mesh_index].add_section(c.source, tw, exact_w);
        } else if (c.kind == mesh::EdgeKind::secondary) {
          inc[u->info().mesh_index].secondary = inc[w->info().mesh_index].secondary = true;
        } else {
          inc[u->info().mesh_index].sides |= 1u << c.source;
          inc[w->info().mesh_index].sides |= 1u << c.source;
        }
        if (!best || priority(c.kind) > priority(best->kind) ||
            (priority(c.kind) == priority(best->kind) && c.source < best->source)) {
          best = &c;
          best_tu = tu;
          best_tw = tw;
        }
      }
      if (!best) continue;
      mesh::EdgeFeature feature;
      feature.kind = best->kind;
      feature.source = best->source;
      if (best->kind == mesh::EdgeKind::primary) {
        feature.curve = f_.sections[best->source].curve;
        const bool u_low = u->info().mesh_index < w->info().mesh_index;
        feature.t_lo = u_low ? best_tu : best_tw;
        feature.t_hi = u_low ? best_tw : best_tu;
      } else if (best->kind == mesh::EdgeKind::secondary) {
        feature.curve = f_.segments[best->source].curve;
      }
      pending_features_.push_back({u->info().mesh_index, w->info().mesh_index, feature});
    }

    for (auto v = cdt_.finite_vertices_begin(); v != cdt_.finite_vertices_end(); ++v) {
      const int i = v->info().mesh_index;
      m.add_vertex(positions_[i].approx, tag_of(v->info(), inc[i]));
    }
    for (auto v = cdt_.finite_vertices_begin(); v != cdt_.finite_vertices_end(); ++v) {
      const int i = v->info().mesh_index;
      if (positions_[i].exact_needed) m.set_exact_position(i, positions_[i].exact);
    }
    for (auto fh = cdt_.finite_faces_begin(); fh != cdt_.finite_faces_end(); ++fh)
      m.add_triangle(fh->vertex(0)->info().mesh_index, fh->vertex(1)->info().mesh_index, fh->vertex(2)->info().mesh_index);
    for (const auto& [a, b, feature] : pending_features_) m.set_feature(a, b, feature);
  }

  static mesh::VertexTag tag_of(const VertexInfo& info, const Incidence& inc) {
    mesh::VertexTag tag;
    tag.isolated = info.isolated;
    // Secondary edges only ask to stay inside the ε-envelope, which every operation checks, so
    // they do not pin a vertex: where a secondary segment meets a curve or the box, the vertex
    // moves like a primary or boundary vertex. Only curves and box sides pin each other.
    const int families = (inc.section >= 0) + std::popcount(inc.sides);
    if (info.fixed || inc.several_sections || families > 1) {
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

  // Rounds each rational vertex to its nearest double when no incident triangle inverts or
  // degenerates; repeated because rounding one vertex can free a neighbour.
  void round_vertices() {
    mesh::TriMesh& m = result_.mesh;
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

  struct PendingFeature {
    int a, b;
    mesh::EdgeFeature feature;
  };

  const features::Features& f_;
  const Options& o_;
  Result result_;
  Cdtp cdt_;
  std::vector<Point> points_;
  std::vector<char> fixed_input_, isolated_input_;
  std::vector<VertexHandle> handles_;
  std::vector<int> corners_;
  std::vector<std::vector<int>> section_points_;
  std::vector<std::array<int, 2>> segment_points_;
  std::unordered_map<const void*, ConstraintInfo> constraints_;
  std::vector<Position> positions_;
  std::vector<PendingFeature> pending_features_;
};

}  // namespace

Result triangulate(const features::Features& features, const Options& options) {
  return Builder(features, options).run();
}

}  // namespace curvemesh::triangulate
