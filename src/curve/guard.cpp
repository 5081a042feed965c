// Steps 4 and 5: the two moves that can raise the worst energy of what they change — a vertex
// brought onto its curve late, an edge put on its curve in step 5 — kept only when the triangles
// around them end no worse than they were (above the stop energy), if need be after the
// operations of step 4 have repaired them; otherwise taken back, operations and all.
#include <functional>

#include "curve/steps.hpp"

namespace curvemesh::curve::detail {

namespace {

std::vector<int> sorted_unique(std::vector<int> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

// How many triangles at `vertices` are not certified.
int uncertified(const Curving& cv, const std::vector<int>& vertices) {
  int count = 0;
  for (int t : triangles_at(cv.mesh, vertices)) count += cv.form.scaled(t) <= 0;
  return count;
}

// Whether the worst energy at `vertices` is at most `bound`.
bool at_most(const Curving& cv, const std::vector<int>& vertices, double bound) {
  return worst_of(cv, triangles_at(cv.mesh, vertices),
                  std::nextafter(bound, std::numeric_limits<double>::infinity())) <= bound;
}

// One round of repair around the centres: step 4's operations on the triangles at `wide` above
// the stop energy (each tried and judged in a journal level of its own), the centres and their
// neighbours moved, the centre nodes of the triangles at `wide` smoothed.
void repair_round(Curving& cv, const std::vector<int>& centres, const std::vector<int>& wide) {
  TriMesh& m = cv.mesh;
  for (int t : triangles_at(m, wide))
    if (m.alive(t) && cv.energy(t) > cv.options.stop_amips) improve_triangle(cv, t);
  for (int c : centres) {
    if (m.triangles_of(c).empty()) continue;
    const std::vector<int> ring = m.neighbours(c);
    move_corner(cv, c);
    for (int w : ring) move_corner(cv, w);
  }
  for (int t : triangles_at(m, wide)) smooth_centre(cv, t);
}

}  // namespace

std::vector<int> vertices_near(const TriMesh& m, const std::vector<int>& centres, int rings) {
  std::vector<int> near = sorted_unique(centres);
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int> more = near;
    for (int v : near)
      for (int w : m.neighbours(v)) more.push_back(w);
    near = sorted_unique(std::move(more));
  }
  return near;
}

std::vector<int> triangles_at(const TriMesh& m, const std::vector<int>& vertices) {
  std::vector<int> triangles;
  for (int v : vertices)
    triangles.insert(triangles.end(), m.triangles_of(v).begin(), m.triangles_of(v).end());
  return sorted_unique(std::move(triangles));
}

double worst_of(const Curving& cv, const std::vector<int>& triangles, double bound) {
  return worst_over(
      triangles, [&cv](int t, double b) { return cv.energy(t, b); }, bound);
}

// `move()` makes the move under the mesh's journal (left open) and returns true, or takes itself
// back and returns false; `undo()` takes a made move back (rolling the journal back). Judged on
// the triangles at the centres and their neighbours (what the move changes) and, after a repair,
// also on those within three rings (what the repair may change): each set at most max(stop
// energy, its worst before), and no more of the latter uncertified than before (a move may leave
// some for the repair). The move alone changes only the first set, so it is judged on that one:
// the second then holds by itself.
// When the move alone is worse, it is taken back, then made again under a journal level of its
// own and followed by up to four rounds of repair (repair_round). Still worse, the level is
// rolled back: the move and its repair go together, and the mesh and its nodes are as they were
// before the move.
bool keep_unless_worse(Curving& cv, const std::vector<int>& centres, const std::function<bool()>& move,
                       const std::function<void()>& undo) {
  TriMesh& m = cv.mesh;
  const double stop = cv.options.stop_amips;
  const std::vector<int> around = vertices_near(m, centres, 1);
  const double bound_around = std::max(stop, worst_of(cv, triangles_at(m, around)));
  const int uncertified_around = uncertified(cv, around);
  if (!move()) return false;
  if (uncertified(cv, around) <= uncertified_around && at_most(cv, around, bound_around)) {
    m.commit();
    return true;
  }
  undo();
  const std::vector<int> wide = vertices_near(m, centres, 3);
  const double bound_wide = std::max(stop, worst_of(cv, triangles_at(m, wide)));
  const int uncertified_wide = uncertified(cv, wide);
  const Stats stats_before = cv.stats;
  m.open_journal();
  if (!move()) {  // it was made once from this very state
    m.commit();
    return false;
  }
  m.commit();  // the move's own level, into the repair's
  bool good = false;
  for (int round = 0; round < 4 && !good; ++round) {
    repair_round(cv, centres, wide);
    good = uncertified(cv, wide) <= uncertified_wide && at_most(cv, around, bound_around) &&
           at_most(cv, wide, bound_wide);
  }
  if (good) {
    m.commit();
    ++cv.stats.repaired_moves;
    return true;
  }
  m.rollback();
  cv.stats = stats_before;
  ++cv.stats.refused_moves;
  return false;
}

}  // namespace curvemesh::curve::detail
