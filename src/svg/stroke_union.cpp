#include "svg/stroke_union.hpp"

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <climits>
#include <deque>
#include <unordered_set>
#include <utility>

#include "geometry/bezier_analysis.hpp"

namespace curvemesh::svg {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Kernel::Point_2;

// The jump of the winding number across a piece of segment, taken along the piece from its
// lexicographically smaller end: the winding number on its left minus that on its right. A
// segment of a loop adds +1 along its own direction; pieces of several segments lying on one
// another add up.
struct Sum {
  int operator()(int a, int b) const { return a + b; }
};
using Traits = CGAL::Arr_curve_data_traits_2<CGAL::Arr_segment_traits_2<Kernel>, int, Sum>;
using Arrangement = CGAL::Arrangement_2<Traits, CGAL::Arr_face_extended_dcel<Traits, int>>;
using Halfedge = Arrangement::Halfedge_const_handle;

// The number of pairs of segments whose boxes meet, counted up to `limit` + 1.
std::size_t meeting_pairs(const std::vector<std::pair<Vec2, Vec2>>& segments, std::size_t limit) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
  std::vector<Box> boxes;
  boxes.reserve(segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const auto& [a, b] = segments[i];
    double lo[2] = {std::min(a.x(), b.x()), std::min(a.y(), b.y())};
    double hi[2] = {std::max(a.x(), b.x()), std::max(a.y(), b.y())};
    boxes.emplace_back(lo, hi, i);
  }
  std::size_t pairs = 0;
  struct Enough {};
  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box&, const Box&) {
      if (++pairs > limit) throw Enough{};
    });
  } catch (const Enough&) {
  }
  return pairs;
}

std::size_t distinct_ends(const std::vector<std::pair<Vec2, Vec2>>& segments) {
  std::vector<std::pair<double, double>> ends;
  for (const auto& [a, b] : segments) ends.emplace_back(a.x(), a.y()), ends.emplace_back(b.x(), b.y());
  std::sort(ends.begin(), ends.end());
  return static_cast<std::size_t>(std::unique(ends.begin(), ends.end()) - ends.begin());
}

// Each face's winding number: 0 on the unbounded face, then across each halfedge h from its
// face (on its left) to its twin's, minus h's jump.
void wind(Arrangement& arr) {
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) f->set_data(INT_MIN);
  std::deque<Arrangement::Face_handle> queue{arr.unbounded_face()};
  arr.unbounded_face()->set_data(0);
  const auto visit = [&](Arrangement::Ccb_halfedge_circulator first, int w) {
    auto h = first;
    do {
      const int jump = h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? h->curve().data() : -h->curve().data();
      const Arrangement::Face_handle other = h->twin()->face();
      if (other->data() == INT_MIN) {
        other->set_data(w - jump);
        queue.push_back(other);
      }
    } while (++h != first);
  };
  while (!queue.empty()) {
    const Arrangement::Face_handle f = queue.front();
    queue.pop_front();
    if (!f->is_unbounded()) visit(f->outer_ccb(), f->data());
    for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner) visit(*inner, f->data());
  }
}

bool painted(Arrangement::Face_const_handle f) {
  return f->data() != 0;
}

// Whether h is on the edge of the painted area with the painted side on its left.
bool on_edge(Halfedge h) {
  return painted(h->face()) && !painted(h->twin()->face());
}

bool every_edge_on_edge(const Arrangement& arr) {
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const Halfedge h = e;
    if (!on_edge(h) && !on_edge(h->twin())) return false;
  }
  return true;
}

// The loop of the painted area's edge through h: at each vertex, the next edge is found by turning
// round it through the painted faces from h's successor.
std::vector<Point> loop_from(Halfedge h, std::unordered_set<const void*>& used) {
  std::vector<Point> corners;
  const Halfedge first = h;
  do {
    used.insert(&*h);
    corners.push_back(h->source()->point());
    Halfedge next = h->next();
    while (!on_edge(next)) next = next->twin()->next();
    h = next;
  } while (h != first);
  return corners;
}

// A closed subpath of lines through the corners that are not collinear with their neighbours.
Subpath subpath_of(const std::vector<Point>& corners) {
  std::vector<Vec2> kept;
  const std::size_t n = corners.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point& before = corners[(i + n - 1) % n];
    const Point& after = corners[(i + 1) % n];
    if (CGAL::collinear(before, corners[i], after)) continue;
    const Vec2 p(CGAL::to_double(corners[i].x()), CGAL::to_double(corners[i].y()));
    if (kept.empty() || kept.back() != p) kept.push_back(p);
  }
  while (kept.size() > 1 && kept.back() == kept.front()) kept.pop_back();
  Subpath sp;
  sp.closed = true;
  if (kept.size() < 2) return sp;
  sp.start = kept[0];
  for (std::size_t i = 0; i < kept.size(); ++i) sp.segments.push_back(CubicBezier::line(kept[i], kept[(i + 1) % kept.size()]));
  return sp;
}

}  // namespace

std::optional<std::vector<Subpath>> painted_edge(const std::vector<Subpath>& outline, double tolerance,
                                                 std::size_t max_pairs) {
  std::vector<std::pair<Vec2, Vec2>> segments;
  for (const Subpath& sp : outline)
    for (const CubicBezier& c : sp.segments) {
      if (!geometry::is_straight(c, tolerance)) return std::nullopt;
      if (c.p[0] != c.p[3]) segments.emplace_back(c.p[0], c.p[3]);
    }
  if (meeting_pairs(segments, max_pairs) > max_pairs) return std::nullopt;
  std::vector<Traits::Curve_2> curves;
  curves.reserve(segments.size());
  for (const auto& [a, b] : segments) {
    const Point pa(a.x(), a.y()), pb(b.x(), b.y());
    curves.emplace_back(Kernel::Segment_2(pa, pb), CGAL::compare_xy(pa, pb) == CGAL::SMALLER ? 1 : -1);
  }
  Arrangement arr;
  CGAL::insert(arr, curves.begin(), curves.end());
  wind(arr);
  // No crossing and nothing inside (a rectangle's band, most strokes): the outline as it is.
  if (arr.number_of_vertices() == distinct_ends(segments) && every_edge_on_edge(arr)) return outline;
  std::vector<Subpath> out;
  std::unordered_set<const void*> used;
  for (auto e = arr.halfedges_begin(); e != arr.halfedges_end(); ++e) {
    const Halfedge h = e;
    if (!on_edge(h) || used.count(&*h)) continue;
    Subpath sp = subpath_of(loop_from(h, used));
    if (!sp.segments.empty()) out.push_back(std::move(sp));
  }
  return out;
}

}  // namespace curvemesh::svg
