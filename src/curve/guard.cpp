// Steps 4 and 5: the two moves that can raise the worst energy of what they change — a vertex
// brought onto its curve late, an edge put on its curve in step 5 — kept only when the triangles
// around them end no worse than they were (above the stop energy), if need be after the
// operations of step 4 have repaired them; otherwise taken back, operations and all.
#include <functional>

#include "curve/builder.hpp"

namespace curvemesh::curve::detail {

std::vector<int> Builder::vertices_near(const std::vector<int>& centres, int rings) const {
  const TriMesh& m = out_.linear;
  std::vector<int> near = centres;
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int> more = near;
    for (int v : near)
      for (int w : m.neighbours(v)) more.push_back(w);
    std::sort(more.begin(), more.end());
    more.erase(std::unique(more.begin(), more.end()), more.end());
    near = std::move(more);
  }
  return near;
}

std::vector<int> Builder::triangles_at(const std::vector<int>& vertices) const {
  const TriMesh& m = out_.linear;
  std::vector<int> triangles;
  for (int v : vertices) triangles.insert(triangles.end(), m.triangles_of(v).begin(), m.triangles_of(v).end());
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
  return triangles;
}

double Builder::worst_of(const std::vector<int>& triangles, double bound) const {
  return worst_over(triangles, [this](int t, double b) { return energy(t, b); }, bound);
}

// `move()` makes the move under the mesh's journal (left open) and returns true, or takes itself
// back and returns false; `undo()` takes a made move back (rolling the journal back). Judged on
// the triangles at the centres and their neighbours (what the move changes) and, after a repair,
// also on those within three rings (what the repair may change): each set at most max(stop
// energy, its worst before), and no more of the latter uncertified than before (a move may leave
// some for the repair). The move alone changes only the first set, so it is judged on that one:
// the second then holds by itself.
// When the move alone is worse, it is taken back, then made again under a journal level of its
// own and followed by up to four rounds of repair: step 4's operations on the triangles there
// above the stop energy (each tried and judged in a level inside that one, kept only if it
// lowers the worst of what it changes), the centres and their neighbours moved, the centres of
// the triangles smoothed. Still worse, the level is rolled back: the move and its repair go
// together, and the mesh and its nodes are as they were before the move.
bool Builder::keep_unless_worse(const std::vector<int>& centres, const std::function<bool()>& move,
                                const std::function<void()>& undo) {
  TriMesh& m = out_.linear;
  const auto uncertified = [&](const std::vector<int>& vertices) {
    int count = 0;
    for (int t : triangles_at(vertices)) count += scaled_[t] <= 0;
    return count;
  };
  const auto at_most = [&](const std::vector<int>& vertices, double bound) {
    return worst_of(triangles_at(vertices), std::nextafter(bound, std::numeric_limits<double>::infinity())) <= bound;
  };
  const std::vector<int> around = vertices_near(centres, 1);
  const double bound_around = std::max(o_.stop_amips, worst_of(triangles_at(around)));
  const int uncertified_around = uncertified(around);
  if (!move()) return false;
  if (uncertified(around) <= uncertified_around && at_most(around, bound_around)) {
    m.commit();
    return true;
  }
  undo();
  const std::vector<int> wide = vertices_near(centres, 3);
  const double bound_wide = std::max(o_.stop_amips, worst_of(triangles_at(wide)));
  const int uncertified_wide = uncertified(wide);
  const auto within = [&] {
    return uncertified(wide) <= uncertified_wide && at_most(around, bound_around) && at_most(wide, bound_wide);
  };
  const Stats stats_before = s_;
  m.open_journal();
  if (!move()) {  // it was made once from this very state
    m.commit();
    return false;
  }
  m.commit();  // the move's own level, into the repair's
  bool good = false;
  for (int round = 0; round < 4 && !good; ++round) {
    for (int t : triangles_at(wide))
      if (m.alive(t) && energy(t) > o_.stop_amips) improve_triangle(t);
    for (int c : centres) {
      if (m.triangles_of(c).empty()) continue;
      const std::vector<int> ring = m.neighbours(c);
      move_corner(c);
      for (int w : ring) move_corner(w);
    }
    for (int t : triangles_at(wide)) smooth_centre(t);
    good = within();
  }
  if (good) {
    m.commit();
    ++s_.repaired_moves;
    return true;
  }
  m.rollback();
  s_ = stats_before;
  ++s_.refused_moves;
  return false;
}

}  // namespace curvemesh::curve::detail
