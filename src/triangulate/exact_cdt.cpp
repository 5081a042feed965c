// The arrangement by CGAL's constrained triangulation with exact constructions (`Epeck`), which
// computes every crossing as it inserts the constraints. It always succeeds.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <type_traits>
#include <unordered_map>

#include "triangulate/arrangement.hpp"

namespace curvemesh::triangulate::detail {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = K::Point_2;

struct VertexInfo {
  int index = -1;
  bool fixed = false, isolated = false, input = false;
};

using Vb = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_intersections_tag>;
using Cdtp = CGAL::Constrained_triangulation_plus_2<Cdt>;
using VertexHandle = Cdtp::Vertex_handle;

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

// A double when the exact value is one, else the rational and its nearest double.
void set_position(ArrangementVertex& v, const Point& p) {
  const auto ix = CGAL::to_interval(p.x()), iy = CGAL::to_interval(p.y());
  if (ix.first == ix.second && iy.first == iy.second) {  // the interval is a point: it is the value
    v.approx = {ix.first, iy.first};
    return;
  }
  v.set_exact(geometry::ExactPoint(to_mpq(p.x()), to_mpq(p.y())));
}

}  // namespace

Triangulation triangulate_exact(const Input& input) {
  Cdtp cdt;
  // Every input point once, in Hilbert order so that each insertion starts near the last one.
  std::vector<Point> points;
  points.reserve(input.points.size());
  for (const InputPoint& p : input.points) points.emplace_back(p.p.x(), p.p.y());
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  using Traits = CGAL::Spatial_sort_traits_adapter_2<K, CGAL::Pointer_property_map<Point>::type>;
  CGAL::hilbert_sort(order.begin(), order.end(), Traits(CGAL::make_property_map(points)));
  std::vector<VertexHandle> handles(points.size());
  Cdtp::Face_handle hint;
  for (std::size_t i : order) {
    VertexHandle v = cdt.insert(points[i], hint);
    if (input.points[i].fixed) v->info().fixed = true;
    if (input.points[i].isolated) v->info().isolated = true;
    v->info().input = true;
    handles[i] = v;
    hint = v->face();
  }

  std::unordered_map<const void*, int> constraint_of;
  std::vector<std::array<VertexHandle, 2>> ends(input.constraints.size());
  for (std::size_t c = 0; c < input.constraints.size(); ++c) {
    const VertexHandle va = handles[input.constraints[c].a], vb = handles[input.constraints[c].b];
    if (va == vb) continue;  // a zero-length input: its point is in already
    const auto id = cdt.insert_constraint(va, vb);
    constraint_of.emplace(id.vl_ptr(), static_cast<int>(c));
    ends[c] = {va, vb};
  }

  Triangulation out;
  out.method = Method::exact_constructions;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    v->info().index = static_cast<int>(out.vertices.size());
    ArrangementVertex& a = out.vertices.emplace_back();
    set_position(a, v->point());
    a.fixed = v->info().fixed;
    a.isolated = v->info().isolated;
    a.input = v->info().input;
  }
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    out.triangles.push_back({f->vertex(0)->info().index, f->vertex(1)->info().index, f->vertex(2)->info().index});
  for (auto sc = cdt.subconstraints_begin(); sc != cdt.subconstraints_end(); ++sc) {
    Piece piece{sc->first.first->info().index, sc->first.second->info().index,
                static_cast<int>(out.piece_constraints.size()), 0};
    for (auto ctx = sc->second->begin(); ctx != sc->second->end(); ++ctx) {
      const auto it = constraint_of.find(ctx->id().vl_ptr());
      if (it != constraint_of.end()) out.piece_constraints.push_back(it->second);
    }
    piece.last = static_cast<int>(out.piece_constraints.size());
    if (piece.last > piece.first) out.pieces.push_back(piece);
  }
  out.constraint_ends.resize(input.constraints.size(), {-1, -1});
  for (std::size_t c = 0; c < ends.size(); ++c)
    if (ends[c][0] != VertexHandle()) out.constraint_ends[c] = {ends[c][0]->info().index, ends[c][1]->info().index};
  return out;
}

}  // namespace curvemesh::triangulate::detail
