#include "mesh/schedule.hpp"

#include <algorithm>
#include <stdexcept>

namespace curvemesh::mesh {

namespace {

struct Placed {
  Vec2 p;
  int v;
};

// Halves vertices [first, last) of `order` at the median until each part has at most `size`
// (positions copied beside the numbers: the selection reads them many times).
void halve(std::vector<Placed>& order, std::size_t first, std::size_t last, std::size_t size, Parts& parts) {
  if (last - first <= size) {
    for (std::size_t i = first; i < last; ++i) parts.of[order[i].v] = parts.count;
    ++parts.count;
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
  halve(order, first, mid, size, parts);
  halve(order, mid, last, size, parts);
}

}  // namespace

void mark_inner(const TriMesh& m, Parts& parts) {
  parts.inner.assign(m.vertex_count(), 0);
  for (int v = 0; v < m.vertex_count(); ++v) parts.inner[v] = parts.of[v] >= 0;
  // One sweep over the triangles, in memory order: the corners of a triangle across parts are not inner.
  for (int t = 0; t < m.triangle_slots(); ++t) {
    const Triangle& tri = m.triangle(t);
    if (tri[0] < 0) continue;
    if (parts.of[tri[0]] != parts.of[tri[1]] || parts.of[tri[0]] != parts.of[tri[2]])
      parts.inner[tri[0]] = parts.inner[tri[1]] = parts.inner[tri[2]] = 0;
  }
}

Parts spatial_parts(const TriMesh& m, int size) {
  // The journal is one list: operations side by side cannot record into it.
  if (m.journal_open()) throw std::logic_error("mesh::spatial_parts: the mesh's journal is open");
  Parts parts;
  parts.of.assign(m.vertex_count(), -1);
  std::vector<Placed> order;
  for (int v = 0; v < m.vertex_count(); ++v)
    if (!m.triangles_of(v).empty()) order.push_back({m.point(v), v});
  if (!order.empty()) halve(order, 0, order.size(), static_cast<std::size_t>(std::max(1, size)), parts);
  mark_inner(m, parts);
  return parts;
}

}  // namespace curvemesh::mesh
