#include "mesh/schedule.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>

#include "base/parallel.hpp"

namespace curvemesh::mesh {

namespace {

struct Placed {
  Vec2 p;  // the coordinates the cut halves
  int v;
};

// The number of parts halve() makes of n vertices: a function of n alone, so that each half knows
// the number of its first part before the other half is cut, and the halves can be cut side by side.
int parts_of(std::size_t n, std::size_t size) {
  return n <= size ? 1 : parts_of(n / 2, size) + parts_of(n - n / 2, size);
}

// Halves vertices [first, last) of `order` at the median until each part has at most `size`, the
// parts numbered from `part` on in depth-first order (positions copied beside the numbers: the
// selection reads them many times). Each half sorts its own range of `order` and numbers its own
// vertices, so large halves are cut side by side.
void halve(std::vector<Placed>& order, std::size_t first, std::size_t last, std::size_t size, int part,
           std::vector<int>& of) {
  if (last - first <= size) {
    for (std::size_t i = first; i < last; ++i) of[order[i].v] = part;
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
  const int second = part + parts_of(mid - first, size);
  base::both([&] { halve(order, first, mid, size, part, of); },
             [&] { halve(order, mid, last, size, second, of); }, last - first >= 4 * size);
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
  if (order.empty()) return cut;
  halve(order, 0, order.size(), size, 0, cut.of);
  cut.count = parts_of(order.size(), size);
  return cut;
}

}  // namespace

void mark_inner(const TriMesh& m, Cut& cut) {
  cut.inner.assign(m.vertex_count(), 0);
  for (int v = 0; v < m.vertex_count(); ++v) cut.inner[v] = cut.of[v] >= 0;
  // The corners of a triangle across parts are not inner; triangles side by side, and a corner
  // two of them clear is cleared by both (the same byte written twice, atomically).
  base::for_each_part(
      static_cast<std::size_t>(m.triangle_slots()),
      [&](std::size_t t) {
        const Triangle& tri = m.triangle(static_cast<int>(t));
        if (tri[0] < 0) return;
        if (cut.of[tri[0]] != cut.of[tri[1]] || cut.of[tri[0]] != cut.of[tri[2]])
          for (const int c : tri) std::atomic_ref<char>(cut.inner[c]).store(0, std::memory_order_relaxed);
      },
      4096);
}

Parts spatial_parts(const TriMesh& m, int size) {
  // The journal is one list: operations side by side cannot record into it.
  if (m.journal_open()) throw std::logic_error("mesh::spatial_parts: the mesh's journal is open");
  const auto most = static_cast<std::size_t>(std::max(1, size));
  Parts parts;
  const auto make = [&](Cut& cut, bool turned) {
    cut = cut_of(m, most, turned);
    mark_inner(m, cut);
  };
  base::both([&] { make(parts.first, false); }, [&] { make(parts.second, true); });
  return parts;
}

}  // namespace curvemesh::mesh
