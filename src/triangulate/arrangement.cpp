// The arrangement's crossings found and ordered exactly, the triangulation built on their rounded
// positions with a double kernel and certified against the exact positions; where that fails, the
// same arrangement triangulated at the exact positions.
//
// 1. Candidate pairs of constraints (and loose points) come from CGAL's box intersection.
// 2. Each pair is classified with the exact orientation predicate on its (double) ends: disjoint,
//    crossing, one end on the other constraint, or collinear and overlapping.
// 3. The events on each constraint (crossings, input points inside it) are sorted by their
//    parameter along it, a rational compared with an interval first and exactly when the intervals
//    overlap; events at exactly the same parameter are the same point and become one vertex.
// 4. A crossing's position is its parameter's interval carried through the line's equation; the
//    mesh takes the interval's midpoint, which is the exact value when the interval is a point.
// 5. CGAL's constrained Delaunay triangulation with exact predicates on doubles triangulates the
//    rounded vertices with every piece as a constraint, refusing any constraint that crosses
//    another (No_constraint_intersection_tag).
// 6. Every piece must be an edge of the result, and every triangle with a rounded vertex must be
//    counter-clockwise at the exact positions too (interval test, then GMP). Then the triangulation
//    is one of the exact arrangement whose vertices round without inverting anything.
// 7. The crossings that share their rounded position with another vertex, or are corners of a
//    triangle that inverts at the exact positions, keep their exact (rational) positions; the
//    same vertices and pieces go into CGAL's triangulation with the exact-constructions kernel
//    (`Epeck`, used for its exact predicates on rationals: it constructs nothing), the other
//    crossings still at their rounded positions, and 6 is checked again (a few rounds).
// 8. If a piece is crossed or split in 5 or 7, or 7 does not settle, every crossing takes its exact
//    position. If even that finds a piece split or crossed (which would mean an event was missed),
//    the result is nullopt and the caller uses CGAL's constrained triangulation with exact
//    intersections.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/hilbert_sort.h>
#include <CGAL/mpq_class.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <numeric>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "base/limits.hpp"
#include "base/parallel.hpp"
#include "triangulate/arrangement.hpp"

namespace curvemesh::triangulate::detail {

namespace {

using geometry::ExactPoint;
using geometry::Vec2;
using Interval = CGAL::Interval_nt<true>;  // every operation rounds outwards by itself

using Ki = CGAL::Exact_predicates_inexact_constructions_kernel;
using Ke = CGAL::Exact_predicates_exact_constructions_kernel;

struct VertexIndex {
  int i = -1;
};

// A constrained Delaunay triangulation that refuses constraints crossing each other.
template <class K>
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    K,
    CGAL::Triangulation_data_structure_2<CGAL::Triangulation_vertex_base_with_info_2<VertexIndex, K>,
                                         CGAL::Constrained_triangulation_face_base_2<K>>,
    CGAL::No_constraint_intersection_tag>;

// A rational as the exact kernel's number (its exact type is mpq_class or CGAL::Gmpq).
Ke::FT exact_number(const mpq_class& q) {
  using ET = Ke::FT::ET;
  if constexpr (std::is_same_v<ET, mpq_class>) {
    return Ke::FT(q);
  } else {
    return Ke::FT(ET(q.get_mpq_t()));
  }
}

std::uint64_t bits(double x) {
  if (x == 0) x = 0;  // -0 and +0 are one point
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

struct PointHash {
  std::size_t operator()(const Vec2& p) const {
    const std::uint64_t h = bits(p.x()) * 0x9E3779B97F4A7C15ull ^ (bits(p.y()) + 0x632BE59BD9B4E019ull);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

struct PointEqual {
  bool operator()(const Vec2& a, const Vec2& b) const { return a.x() == b.x() && a.y() == b.y(); }
};

// A constraint between two distinct vertices (indices into the input points' unique positions).
struct Segment {
  int constraint;
  int a, b;
};

// A point of the arrangement strictly inside a segment: an input point or a crossing (`node`,
// a union-find node: unique input points first, then crossings), at parameter `t` in (0, 1).
struct Event {
  int segment;
  int node;
  Interval t;
};

class Builder {
 public:
  explicit Builder(const Input& in) : in_(in) {}

  std::optional<Triangulation> run() {
    unique_points();
    segments();
    classify_pairs();
    order_events();
    number_vertices();
    make_pieces();
    held_.assign(out_.vertices.size(), 0);
    std::vector<int> unrounded = sharing_rounded_positions();
    Outcome o = unrounded.empty() ? build_cdt<Ki>(unrounded) : Outcome::unrounded;
    // The crossings that cannot be rounded keep their exact positions, the others their rounded
    // ones; certifying the result can find more that cannot. Where rounded crossings still cross
    // or split a piece, every crossing on a segment through a held one is held too.
    for (int round = 0; round < 4 && o != Outcome::ok; ++round) {
      out_.method = Method::exact_crossings;
      if (o == Outcome::broken) {
        if (round == 0) break;  // nothing held yet to start from
        unrounded = on_segments_through_held();
      }
      hold_exact(unrounded);
      o = build_cdt<Ke>(unrounded);
    }
    if (o != Outcome::ok) {  // every crossing at its exact position
      out_.method = Method::exact_crossings;
      std::vector<int> all(out_.vertices.size());
      std::iota(all.begin(), all.end(), 0);
      hold_exact(all);
      o = build_cdt<Ke>(unrounded);
    }
    if (o != Outcome::ok) return std::nullopt;
    return std::move(out_);
  }

 private:
  // Input points with the same coordinates are one vertex (fixed or isolated if any of them is).
  void unique_points() {
    base::check_triangles(2 * in_.points.size(), in_.max_triangles,
                          "the curves are cut into " + std::to_string(in_.points.size()) + " points");
    std::unordered_map<Vec2, int, PointHash, PointEqual> seen;
    seen.reserve(in_.points.size());
    point_node_.resize(in_.points.size());
    for (std::size_t i = 0; i < in_.points.size(); ++i) {
      const InputPoint& p = in_.points[i];
      const auto [it, fresh] = seen.emplace(p.p, static_cast<int>(points_.size()));
      if (fresh) points_.push_back({p.p, false, {}, p.fixed, p.isolated, true});
      ArrangementVertex& v = points_[it->second];
      v.fixed = v.fixed || p.fixed;
      v.isolated = v.isolated || p.isolated;
      point_node_[i] = it->second;
    }
  }

  // The constraints as segments between unique points; zero-length ones are dropped.
  void segments() {
    out_.constraint_ends.assign(in_.constraints.size(), {-1, -1});
    for (std::size_t c = 0; c < in_.constraints.size(); ++c) {
      const int a = point_node_[in_.constraints[c].a], b = point_node_[in_.constraints[c].b];
      if (a == b) continue;
      out_.constraint_ends[c] = {a, b};
      segments_.push_back({static_cast<int>(c), a, b});
    }
  }

  const Vec2& at(int point) const { return points_[point].approx; }

  // Every pair of segments whose boxes touch, and every point that lies on no segment's end
  // against the segments, turned into events.
  void classify_pairs() {
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int>;
    std::vector<Box> boxes;
    boxes.reserve(segments_.size() + 16);
    std::vector<char> is_end(points_.size(), 0);
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      const Vec2 &a = at(segments_[s].a), &b = at(segments_[s].b);
      is_end[segments_[s].a] = is_end[segments_[s].b] = 1;
      boxes.emplace_back(CGAL::Bbox_2(std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()),
                                      std::max(a.y(), b.y())),
                         static_cast<int>(s));
    }
    // A point that ends no segment (an isolated point, the end of a zero-length input) can still
    // lie on a segment: it is a box of its own, with info -1 - point.
    for (std::size_t p = 0; p < points_.size(); ++p)
      if (!is_end[p]) boxes.emplace_back(CGAL::Bbox_2(at(p).x(), at(p).y(), at(p).x(), at(p).y()), -1 - static_cast<int>(p));

    std::vector<std::pair<int, int>> pairs;
    // Segments whose boxes overlap are a few per segment in a drawing; a soup of long curves
    // across each other has quadratically many, each a likely crossing: bounded before they fill
    // memory (8 per triangle allowed: 64 bytes).
    const std::size_t max_pairs = in_.max_triangles > SIZE_MAX / 8 ? SIZE_MAX : 8 * in_.max_triangles;
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
      if (pairs.size() == max_pairs)
        base::check_triangles(SIZE_MAX, in_.max_triangles,
                              "more than " + std::to_string(max_pairs) + " pairs of the curves' segments lie across each other");
      pairs.emplace_back(std::max(x.info(), y.info()), std::min(x.info(), y.info()));
    });
    // The box intersection's order is not the same from run to run: sort for determinism.
    std::sort(pairs.begin(), pairs.end());
    // Each pair is examined on its own, side by side, in blocks (what a block finds, about 200
    // bytes a pair, is held until it is added); what they find is added in the sorted order.
    constexpr std::size_t kBlock = 1 << 12;
    std::vector<Found> found;
    for (std::size_t first = 0; first < pairs.size(); first += kBlock) {
      const std::size_t n = std::min(kBlock, pairs.size() - first);
      found.assign(n, Found{});
      base::for_each_part(n, [&](std::size_t i) { found[i] = examine(pairs[first + i]); }, 256);
      for (std::size_t i = 0; i < n; ++i) add(pairs[first + i], found[i]);
    }
  }

  // What a pair of boxes holds: points strictly inside segments (the events, at most four: two
  // collinear segments), or a proper crossing of two segments, at parameters t_s and t_q, with
  // its position (place_crossing).
  struct Found {
    std::array<Event, 4> points{};
    int point_count = 0;
    bool crossing = false;
    Interval t_s{0}, t_q{0};
    std::array<Interval, 2> box{Interval(0), Interval(0)};
    Vec2 approx = Vec2::Zero();
  };

  // A pair of boxes: s > q segments, or segment s and point −1 − q, or two points (s < 0).
  Found examine(const std::pair<int, int>& pair) const {
    Found f;
    const auto [s, q] = pair;
    if (s < 0) return f;  // two loose points: distinct, so not one vertex
    if (q < 0)
      point_on_segment(s, -1 - q, f);
    else
      cross(s, q, f);
    return f;
  }

  // Adds what examine found: the events, and a crossing as a new point.
  void add(const std::pair<int, int>& pair, const Found& f) {
    for (int k = 0; k < f.point_count; ++k) events_.push_back(f.points[k]);
    if (!f.crossing) return;
    const auto [s, q] = pair;
    const int node = static_cast<int>(points_.size() + crossings_.size());
    // A triangulation of V vertices has about 2V triangles.
    if (crossings_.size() % 1024 == 0)
      base::check_triangles(2 * (points_.size() + crossings_.size()), in_.max_triangles,
                            "the curves cross each other more than " + std::to_string(crossings_.size()) + " times");
    crossings_.push_back({s, q});
    events_.push_back({s, node, f.t_s});
    events_.push_back({q, node, f.t_q});
    crossing_box_.push_back(f.box);
    crossing_approx_.push_back(f.approx);
  }

  // Notes the event of point p on segment s if p lies strictly inside it.
  void point_on_segment(int s, int p, Found& f) const {
    const Segment& seg = segments_[s];
    if (p == seg.a || p == seg.b) return;
    const Vec2 &a = at(seg.a), &b = at(seg.b), &x = at(p);
    if (geometry::orientation(a, b, x) != 0) return;
    if (!strictly_between(a, b, x)) return;
    f.points[f.point_count++] = {s, p, point_parameter(seg, x)};
  }

  // x on the line through a and b: is it strictly between them? Exact on doubles.
  static bool strictly_between(const Vec2& a, const Vec2& b, const Vec2& x) {
    const int axis = std::abs(b.x() - a.x()) >= std::abs(b.y() - a.y()) ? 0 : 1;
    const double lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
    return lo < x[axis] && x[axis] < hi;
  }

  void cross(int s, int q, Found& f) const {
    const Segment &S = segments_[s], &Q = segments_[q];
    const Vec2 &a = at(S.a), &b = at(S.b), &c = at(Q.a), &d = at(Q.b);
    const int o1 = geometry::orientation(a, b, c), o2 = geometry::orientation(a, b, d);
    if (o1 * o2 > 0) return;
    if (o1 == 0 && o2 == 0) {  // collinear: each end strictly inside the other segment is an event
      point_on_segment(s, Q.a, f);
      point_on_segment(s, Q.b, f);
      point_on_segment(q, S.a, f);
      point_on_segment(q, S.b, f);
      return;
    }
    const int o3 = geometry::orientation(c, d, a), o4 = geometry::orientation(c, d, b);
    if (o3 * o4 > 0) return;
    if (o1 * o2 < 0 && o3 * o4 < 0) {  // a proper crossing: a new point
      f.crossing = true;
      f.t_s = crossing_parameter(S, Q);
      f.t_q = crossing_parameter(Q, S);
      place_crossing(s, q, f);
      return;
    }
    // They touch at one point, an end of one of them (the lines are not the same).
    if (o1 == 0) point_on_segment(s, Q.a, f);
    if (o2 == 0) point_on_segment(s, Q.b, f);
    if (o3 == 0) point_on_segment(q, S.a, f);
    if (o4 == 0) point_on_segment(q, S.b, f);
  }

  // Parameters along segment s = [a, b] as rationals num / den, in intervals and exactly.
  Interval crossing_parameter(const Segment& s, const Segment& q) const {
    const Vec2 &a = at(s.a), &b = at(s.b), &c = at(q.a), &d = at(q.b);
    const Interval cax = Interval(c.x()) - a.x(), cay = Interval(c.y()) - a.y();
    const Interval dcx = Interval(d.x()) - c.x(), dcy = Interval(d.y()) - c.y();
    const Interval bax = Interval(b.x()) - a.x(), bay = Interval(b.y()) - a.y();
    return (cax * dcy - cay * dcx) / (bax * dcy - bay * dcx);
  }
  mpq_class exact_crossing_parameter(const Segment& s, const Segment& q) const {
    const Vec2 &a = at(s.a), &b = at(s.b), &c = at(q.a), &d = at(q.b);
    const mpq_class cax = mpq_class(c.x()) - a.x(), cay = mpq_class(c.y()) - a.y();
    const mpq_class dcx = mpq_class(d.x()) - c.x(), dcy = mpq_class(d.y()) - c.y();
    const mpq_class bax = mpq_class(b.x()) - a.x(), bay = mpq_class(b.y()) - a.y();
    return mpq_class(cax * dcy - cay * dcx) / mpq_class(bax * dcy - bay * dcx);
  }
  Interval point_parameter(const Segment& s, const Vec2& x) const {
    const Vec2 &a = at(s.a), &b = at(s.b);
    const Interval bax = Interval(b.x()) - a.x(), bay = Interval(b.y()) - a.y();
    return ((Interval(x.x()) - a.x()) * bax + (Interval(x.y()) - a.y()) * bay) / (bax * bax + bay * bay);
  }
  mpq_class exact_point_parameter(const Segment& s, const Vec2& x) const {
    const Vec2 &a = at(s.a), &b = at(s.b);
    const mpq_class bax = mpq_class(b.x()) - a.x(), bay = mpq_class(b.y()) - a.y();
    return mpq_class((mpq_class(x.x()) - a.x()) * bax + (mpq_class(x.y()) - a.y()) * bay) / mpq_class(bax * bax + bay * bay);
  }
  mpq_class exact_parameter(const Event& e) const {
    const Segment& s = segments_[e.segment];
    if (e.node < static_cast<int>(points_.size())) return exact_point_parameter(s, at(e.node));
    const auto& [s1, s2] = crossings_[e.node - points_.size()];
    return exact_crossing_parameter(s, segments_[s1 == e.segment ? s2 : s1]);
  }

  // The position of the crossing of segments s and q, at parameter f.t_s on s: an interval box
  // around it and the double the mesh takes (the box's middle). Nearly parallel segments give a
  // wide box: then the position is computed exactly, and the double is the nearest one.
  void place_crossing(int s, int q, Found& f) const {
    const Vec2 &a = at(segments_[s].a), &b = at(segments_[s].b);
    f.box = {Interval(a.x()) + f.t_s * (Interval(b.x()) - a.x()), Interval(a.y()) + f.t_s * (Interval(b.y()) - a.y())};
    const auto tight = [](const Interval& x) {
      return std::isfinite(x.inf()) && std::isfinite(x.sup()) &&
             x.sup() - x.inf() <= 0x1p-48 * std::max(std::abs(x.inf()), std::abs(x.sup()));
    };
    if (tight(f.box[0]) && tight(f.box[1])) {
      f.approx = {CGAL::to_double(f.box[0]), CGAL::to_double(f.box[1])};
    } else {
      const ExactPoint e = exact_crossing_of(s, q);
      f.box = {Interval(CGAL::to_interval(e.x)), Interval(CGAL::to_interval(e.y))};
      f.approx = geometry::nearest_double(e);
    }
  }
  ExactPoint exact_crossing_of(int s, int q) const {
    const Segment& seg = segments_[s];
    const mpq_class t = exact_crossing_parameter(seg, segments_[q]);
    const Vec2 &a = at(seg.a), &b = at(seg.b);
    return ExactPoint(mpq_class(a.x() + t * (mpq_class(b.x()) - a.x())), mpq_class(a.y() + t * (mpq_class(b.y()) - a.y())));
  }
  ExactPoint exact_crossing(int crossing) const {
    const auto& [s, q] = crossings_[crossing];
    return exact_crossing_of(s, q);
  }

  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(int x, int y) {
    x = find(x);
    y = find(y);
    if (x != y) parent_[std::max(x, y)] = std::min(x, y);  // an input point stays the root
  }

  // Sorts each segment's events along it; events at the same parameter are one point.
  void order_events() {
    parent_.resize(points_.size() + crossings_.size());
    std::iota(parent_.begin(), parent_.end(), 0);
    std::stable_sort(events_.begin(), events_.end(), [](const Event& x, const Event& y) { return x.segment < y.segment; });
    const auto less = [&](const Event& x, const Event& y) {
      if (x.t.sup() < y.t.inf()) return true;
      if (y.t.sup() < x.t.inf() || x.node == y.node) return false;
      return exact_parameter(x) < exact_parameter(y);
    };
    const auto same = [&](const Event& x, const Event& y) {
      if (x.node == y.node) return true;
      if (x.t.sup() < y.t.inf() || y.t.sup() < x.t.inf()) return false;
      return exact_parameter(x) == exact_parameter(y);
    };
    for (std::size_t i = 0; i < events_.size();) {
      std::size_t j = i;
      while (j < events_.size() && events_[j].segment == events_[i].segment) ++j;
      std::sort(events_.begin() + i, events_.begin() + j, less);
      for (std::size_t k = i + 1; k < j; ++k)
        if (same(events_[k - 1], events_[k])) unite(events_[k - 1].node, events_[k].node);
      i = j;
    }
  }

  // One vertex per class of nodes, numbered along a Hilbert curve through the rounded positions.
  void number_vertices() {
    std::vector<int> roots;
    std::vector<ArrangementVertex> verts;
    for (std::size_t n = 0; n < parent_.size(); ++n) {
      if (find(static_cast<int>(n)) != static_cast<int>(n)) continue;
      roots.push_back(static_cast<int>(n));
      if (n < points_.size()) {
        verts.push_back(points_[n]);
      } else {
        ArrangementVertex v;
        v.approx = crossing_approx_[n - points_.size()];
        verts.push_back(v);
      }
    }
    std::vector<Ki::Point_2> positions;
    positions.reserve(verts.size());
    for (const ArrangementVertex& v : verts) positions.emplace_back(v.approx.x(), v.approx.y());
    std::vector<std::size_t> order(verts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    using Traits = CGAL::Spatial_sort_traits_adapter_2<Ki, CGAL::Pointer_property_map<Ki::Point_2>::type>;
    CGAL::hilbert_sort(order.begin(), order.end(), Traits(CGAL::make_property_map(positions)));

    vertex_of_node_.assign(parent_.size(), -1);
    out_.vertices.resize(verts.size());
    node_of_vertex_.resize(verts.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
      out_.vertices[i] = verts[order[i]];
      vertex_of_node_[roots[order[i]]] = static_cast<int>(i);
      node_of_vertex_[i] = roots[order[i]];
    }
    for (std::size_t n = 0; n < parent_.size(); ++n) vertex_of_node_[n] = vertex_of_node_[find(static_cast<int>(n))];
    for (auto& ends : out_.constraint_ends)
      if (ends[0] >= 0) ends = {vertex_of_node_[ends[0]], vertex_of_node_[ends[1]]};
  }

  // The vertices whose rounded position is another's.
  std::vector<int> sharing_rounded_positions() const {
    std::unordered_map<Vec2, int, PointHash, PointEqual> first;
    first.reserve(out_.vertices.size());
    std::vector<int> out;
    for (std::size_t v = 0; v < out_.vertices.size(); ++v) {
      const auto [it, fresh] = first.emplace(out_.vertices[v].approx, static_cast<int>(v));
      if (fresh) continue;
      out.push_back(it->second);
      out.push_back(static_cast<int>(v));
    }
    return out;
  }

  bool is_crossing(int v) const { return node_of_vertex_[v] >= static_cast<int>(points_.size()); }
  // Does the vertex stand at a rounded position instead of its exact one?
  bool moved(int v) const { return is_crossing(v) && !held_[v]; }

  // Every vertex on a segment that has a held crossing on it.
  std::vector<int> on_segments_through_held() const {
    std::vector<char> marked(segments_.size(), 0);
    for (const Event& e : events_) marked[e.segment] |= held_[vertex_of_node_[e.node]];
    std::vector<int> out;
    for (const Event& e : events_)
      if (marked[e.segment]) out.push_back(vertex_of_node_[e.node]);
    return out;
  }

  // These crossings take their rational positions (and the doubles nearest to them).
  void hold_exact(const std::vector<int>& vertices) {
    for (int v : vertices) {
      if (!is_crossing(v) || held_[v]) continue;
      held_[v] = 1;
      const int crossing = node_of_vertex_[v] - static_cast<int>(points_.size());
      out_.vertices[v].set_exact(exact_crossing(crossing));
    }
  }

  // The pieces of every segment, in segment order, with the segments that share each.
  void make_pieces() {
    std::vector<std::pair<int, int>> piece_segment;  // (piece, constraint)
    std::unordered_map<std::uint64_t, int> piece_of;
    piece_of.reserve(segments_.size() + events_.size());
    const auto add = [&](int u, int w, int constraint) {
      const auto [it, fresh] = piece_of.emplace(mesh::edge_key(u, w), static_cast<int>(out_.pieces.size()));
      if (fresh) out_.pieces.push_back({u, w, 0, 0});
      piece_segment.emplace_back(it->second, constraint);
    };
    std::size_t e = 0;
    for (std::size_t s = 0; s < segments_.size(); ++s) {
      int last = vertex_of_node_[segments_[s].a];
      for (; e < events_.size() && events_[e].segment == static_cast<int>(s); ++e) {
        const int v = vertex_of_node_[events_[e].node];
        if (v == last) continue;
        add(last, v, segments_[s].constraint);
        last = v;
      }
      if (last != vertex_of_node_[segments_[s].b]) add(last, vertex_of_node_[segments_[s].b], segments_[s].constraint);
    }
    std::stable_sort(piece_segment.begin(), piece_segment.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    out_.piece_constraints.reserve(piece_segment.size());
    for (std::size_t k = 0; k < piece_segment.size(); ++k) {
      Piece& p = out_.pieces[piece_segment[k].first];
      if (k == 0 || piece_segment[k - 1].first != piece_segment[k].first) p.first = static_cast<int>(k);
      p.last = static_cast<int>(k) + 1;
      out_.piece_constraints.push_back(piece_segment[k].second);
    }
  }

  // The exact position of a vertex's point and the interval box around it.
  ExactPoint exact_of(int vertex) const {
    const int node = node_of_vertex_[vertex];
    if (node < static_cast<int>(points_.size())) return ExactPoint(points_[node].approx);
    if (held_[vertex]) return out_.vertices[vertex].exact;
    return exact_crossing(node - static_cast<int>(points_.size()));
  }
  std::array<Interval, 2> box_of(int vertex) const {
    const int node = node_of_vertex_[vertex];
    if (node < static_cast<int>(points_.size())) return {Interval(at(node).x()), Interval(at(node).y())};
    return crossing_box_[node - points_.size()];
  }

  // The triangulation of the vertices with every piece as a constraint: on the rounded positions
  // with K = Ki, then certified; at the exact positions with K = Ke.
  enum class Outcome {
    ok,
    unrounded,  // some triangles invert at the exact positions: their moved vertices are listed
    broken,     // a piece is crossed or split (Ki: at rounded positions) or two vertices coincide
  };

  template <class K>
  Outcome build_cdt(std::vector<int>& unrounded) {
    out_.triangles.clear();
    unrounded.clear();
    Cdt<K> cdt;
    std::vector<typename Cdt<K>::Vertex_handle> handles(out_.vertices.size());
    typename Cdt<K>::Face_handle hint;
    for (std::size_t i = 0; i < out_.vertices.size(); ++i) {
      const ArrangementVertex& v = out_.vertices[i];
      typename K::Point_2 p(v.approx.x(), v.approx.y());
      if constexpr (std::is_same_v<K, Ke>)
        if (v.exact_needed) p = typename K::Point_2(exact_number(v.exact.x), exact_number(v.exact.y));
      handles[i] = cdt.insert(p, hint);
      if (handles[i]->info().i >= 0) return Outcome::broken;  // two vertices at one position
      handles[i]->info().i = static_cast<int>(i);
      hint = handles[i]->face();
    }
    try {
      for (const Piece& p : out_.pieces) {
        // Most pieces are edges already: marking them directly saves CGAL's search along the
        // piece, whose orientation tests meet the collinear vertices of the segment and, with
        // exact constructions, evaluate them with rationals.
        typename Cdt<K>::Face_handle f;
        int i = 0;
        if (cdt.tds().is_edge(handles[p.u], handles[p.w], f, i)) {
          f->set_constraint(i, true);
          f->neighbor(i)->set_constraint(cdt.mirror_index(f, i), true);
        } else {
          cdt.insert_constraint(handles[p.u], handles[p.w]);
        }
      }
    } catch (const std::exception&) {  // two pieces cross once rounded
      return Outcome::broken;
    }
    for (const Piece& p : out_.pieces) {
      typename Cdt<K>::Face_handle f;
      int i = 0;
      // Not an edge: a rounded vertex fell on the piece, which CGAL split there.
      if (!cdt.is_edge(handles[p.u], handles[p.w], f, i) || !f->is_constrained(i)) return Outcome::broken;
    }

    out_.triangles.reserve(cdt.number_of_faces());
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      std::array<int, 3> t{f->vertex(0)->info().i, f->vertex(1)->info().i, f->vertex(2)->info().i};
      if (!counter_clockwise_exactly(t))
        for (int v : t)
          if (moved(v)) unrounded.push_back(v);
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      out_.triangles.push_back(t);
    }
    if (!unrounded.empty()) return Outcome::unrounded;
    std::sort(out_.triangles.begin(), out_.triangles.end());
    return Outcome::ok;
  }

  // The triangle is counter-clockwise at its vertices' positions (CGAL's exact predicates made
  // it so); is it at their exact positions? Only a crossing at a rounded position has moved.
  bool counter_clockwise_exactly(const std::array<int, 3>& t) const {
    if (!moved(t[0]) && !moved(t[1]) && !moved(t[2])) return true;
    const auto a = box_of(t[0]), b = box_of(t[1]), c = box_of(t[2]);
    const Interval det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (det.inf() > 0) return true;
    return geometry::orientation(exact_of(t[0]), exact_of(t[1]), exact_of(t[2])) > 0;
  }

  const Input& in_;
  Triangulation out_;
  std::vector<ArrangementVertex> points_;  // unique input points
  std::vector<int> point_node_;            // input point -> unique point
  std::vector<Segment> segments_;
  std::vector<std::array<int, 2>> crossings_;  // the two segments of each crossing
  std::vector<std::array<Interval, 2>> crossing_box_;
  std::vector<Vec2> crossing_approx_;
  std::vector<Event> events_;
  std::vector<int> parent_;  // union-find over nodes (unique points, then crossings)
  std::vector<int> vertex_of_node_, node_of_vertex_;
  std::vector<char> held_;  // per vertex: a crossing held at its exact position
};

}  // namespace

std::optional<Triangulation> triangulate_arrangement(const Input& input) { return Builder(input).run(); }

}  // namespace curvemesh::triangulate::detail
