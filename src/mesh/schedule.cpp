#include "mesh/schedule.hpp"

#include <algorithm>
#include <stdexcept>

namespace curvemesh::mesh {

namespace {

struct Placed {
  Vec2 p;  // the coordinates the cut halves
  int v;
};

// Halves vertices [first, last) of `order` at the median until each part has at most `size`
// (positions copied beside the numbers: the selection reads them many times).
void halve(std::vector<Placed>& order, std::size_t first, std::size_t last, std::size_t size, Cut& cut) {
  if (last - first <= size) {
    for (std::size_t i = first; i < last; ++i) cut.of[order[i].v] = cut.count;
    ++cut.count;
    return;
  }
  Vec2 lo = order[first].p, hi = lo;
  for (std::size_t i = first; i < last; ++i) {
    lo = lo.cwiseMin(order[i].p);
    hi = hi.cwiseMax(order[i].p);
  }
  const int axis = hi.x() - lo.x() >= hi.y() - lo.y() ? 0 : 1;
  const std::size_t mid = first + (last - first) / 2;
  const auto at = [&](std::size_t i) { return order.begin() + static_cast<std::ptrdiff_t>(i); };
  std::nth_element(at(first), at(mid), at(last), [&](const Placed& a, const Placed& b) {
    return a.p[axis] < b.p[axis] || (a.p[axis] == b.p[axis] && a.v < b.v);
  });
  halve(order, first, mid, size, cut);
  halve(order, mid, last, size, cut);
}

// `turned`: the coordinates turned by 45° (and scaled by √2): (x + y, y − x).
Cut cut_of(const TriMesh& m, std::size_t size, bool turned) {
  Cut cut;
  cut.of.assign(m.vertex_count(), -1);
  std::vector<Placed> order;
  for (int v = 0; v < m.vertex_count(); ++v) {
    if (m.triangles_of(v).empty()) continue;
    const Vec2& p = m.point(v);
    order.push_back({turned ? Vec2(p.x() + p.y(), p.y() - p.x()) : p, v});
  }
  if (!order.empty()) halve(order, 0, order.size(), size, cut);
  return cut;
}

}  // namespace

void mark_inner(const TriMesh& m, Cut& cut) {
  cut.inner.assign(m.vertex_count(), 0);
  for (int v = 0; v < m.vertex_count(); ++v) cut.inner[v] = cut.of[v] >= 0;
  // One sweep over the triangles, in memory order: the corners of a triangle across parts are not inner.
  for (int t = 0; t < m.triangle_slots(); ++t) {
    const Triangle& tri = m.triangle(t);
    if (tri[0] < 0) continue;
    if (cut.of[tri[0]] != cut.of[tri[1]] || cut.of[tri[0]] != cut.of[tri[2]])
      cut.inner[tri[0]] = cut.inner[tri[1]] = cut.inner[tri[2]] = 0;
  }
}

Parts spatial_parts(const TriMesh& m, int size) {
  // The journal is one list: operations side by side cannot record into it.
  if (m.journal_open()) throw std::logic_error("mesh::spatial_parts: the mesh's journal is open");
  const auto most = static_cast<std::size_t>(std::max(1, size));
  Parts parts{cut_of(m, most, false), cut_of(m, most, true)};
  mark_inner(m, parts.first);
  mark_inner(m, parts.second);
  return parts;
}

}  // namespace curvemesh::mesh
