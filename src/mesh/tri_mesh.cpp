#include "mesh/tri_mesh.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace curvemesh::mesh {

int TriMesh::add_vertex(const Vec2& p, const VertexTag& tag) {
  record(-1, {.kind = Change::Kind::add_vertex});
  points_.push_back(p);
  vertex_tags_.push_back(tag);
  exact_index_.push_back(-1);
  vertex_triangles_.emplace_back();
  tagged_.emplace_back();
  has_tagged_.push_back(0);
  return vertex_count() - 1;
}

int TriMesh::add_triangle(int a, int b, int c) {
  const int t = triangle_slots();
  record(-1, {.kind = Change::Kind::add_triangle});
  triangles_.push_back({a, b, c});
  link(t);
  alive_triangles_.add(1);
  return t;
}

void TriMesh::link(int t) {
  for (int v : triangles_[t]) vertex_triangles_[v].push_back(t);
}

void TriMesh::unlink(int t) {
  for (int v : triangles_[t]) {
    auto& list = vertex_triangles_[v];
    list.erase(std::find(list.begin(), list.end(), t));
  }
}

void TriMesh::remove_triangle(int t) {
  if (!alive(t)) return;
  record(triangles_[t][0], {.kind = Change::Kind::remove_triangle, .index = t, .corners = triangles_[t]});
  unlink(t);
  triangles_[t] = {-1, -1, -1};
  alive_triangles_.add(-1);
}

void TriMesh::set_triangle(int t, const Triangle& corners) {
  record(triangles_[t][0], {.kind = Change::Kind::set_triangle, .index = t, .corners = triangles_[t]});
  unlink(t);
  triangles_[t] = corners;
  link(t);
}

void TriMesh::set_position(int v, const Vec2& p) {
  record(v, {.kind = Change::Kind::position, .index = v, .point = points_[v], .exact_index = exact_index_[v]});
  points_[v] = p;
  exact_index_[v] = -1;
}

void TriMesh::set_exact_position(int v, const ExactPoint& p) {
  if (lane_of_) throw std::logic_error("TriMesh::set_exact_position while the journal is split");
  record(v, {.kind = Change::Kind::position, .index = v, .point = points_[v], .exact_index = exact_index_[v]});
  points_[v] = geometry::nearest_double(p);
  exact_index_[v] = static_cast<int>(exact_points_.size());
  exact_points_.push_back(p);
}

ExactPoint TriMesh::exact_or_double(int v) const {
  return has_exact(v) ? exact(v) : ExactPoint(points_[v]);
}

int TriMesh::exact_vertex_count() const {
  return static_cast<int>(
      std::count_if(exact_index_.begin(), exact_index_.end(), [](int i) { return i >= 0; }));
}

void TriMesh::set_tag(int v, const VertexTag& tag) {
  record(v, {.kind = Change::Kind::tag, .index = v, .tag = vertex_tags_[v]});
  vertex_tags_[v] = tag;
}

const EdgeFeature* TriMesh::feature(int a, int b) const {
  if (!has_tagged_[a] || !has_tagged_[b]) return nullptr;
  for (const TaggedEdge& e : tagged_[a])
    if (e.other == b) return &e.feature;
  return nullptr;
}

void TriMesh::put_feature(int a, int b, const EdgeFeature& f) {
  for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
    auto& list = tagged_[x];
    const auto it =
        std::lower_bound(list.begin(), list.end(), y, [](const TaggedEdge& e, int v) { return e.other < v; });
    if (it != list.end() && it->other == y) {
      it->feature = f;  // the lists keep their length: vertices apart may retag their own edges side by side
    } else {
      list.insert(it, {y, f});
      has_tagged_[x] = 1;
    }
  }
}

void TriMesh::erase_feature(int a, int b) {
  for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
    auto& list = tagged_[x];
    const int other = y;  // clang 14 cannot capture a structured binding
    const auto it =
        std::find_if(list.begin(), list.end(), [other](const TaggedEdge& e) { return e.other == other; });
    if (it != list.end()) list.erase(it);
    has_tagged_[x] = !list.empty();
  }
}

void TriMesh::set_feature(int a, int b, const EdgeFeature& f) {
  if (!log_at(std::min(a, b)).marks.empty()) {
    const EdgeFeature* old = feature(a, b);
    record(std::min(a, b), {.kind = Change::Kind::feature,
            .lo = std::min(a, b),
            .hi = std::max(a, b),
            .feature = old ? std::optional(*old) : std::nullopt});
  }
  put_feature(a, b, f);
}

void TriMesh::clear_feature(int a, int b) {
  if (!log_at(std::min(a, b)).marks.empty()) {
    const EdgeFeature* old = feature(a, b);
    if (!old) return;
    record(std::min(a, b), {.kind = Change::Kind::feature, .lo = std::min(a, b), .hi = std::max(a, b), .feature = *old});
  }
  erase_feature(a, b);
}

void TriMesh::record(int at, Change change) {
  if (lane_of_ && at < 0) throw std::logic_error("TriMesh: a vertex or triangle added while the journal is split");
  Log& log = log_at(at);
  if (!log.marks.empty()) log.changes.push_back(std::move(change));
}

void TriMesh::open_journal() {
  if (lane_of_) throw std::logic_error("TriMesh::open_journal with no vertex while the journal is split");
  open_journal(0);
}

void TriMesh::commit() {
  if (lane_of_) throw std::logic_error("TriMesh::commit with no vertex while the journal is split");
  commit(0);
}

void TriMesh::rollback() {
  if (lane_of_) throw std::logic_error("TriMesh::rollback with no vertex while the journal is split");
  rollback(0);
}

void TriMesh::open_journal(int at) {
  Log& log = log_at(at);
  log.marks.push_back(log.changes.size());
  if (!lane_of_) attributes_.open();
}

void TriMesh::commit(int at) {
  Log& log = log_at(at);
  if (log.marks.empty()) throw std::logic_error("TriMesh::commit with no open journal");
  log.marks.pop_back();
  if (log.marks.empty()) log.changes.clear();
  if (!lane_of_) attributes_.commit();
}

void TriMesh::rollback(int at) {
  Log& log = log_at(at);
  if (log.marks.empty()) throw std::logic_error("TriMesh::rollback with no open journal");
  for (; log.changes.size() > log.marks.back(); log.changes.pop_back()) undo(log.changes.back());
  log.marks.pop_back();
  if (!lane_of_) attributes_.rollback();
}

void TriMesh::split_journal(const std::vector<int>& part_of, int parts) {
  if (journal_open()) throw std::logic_error("TriMesh::split_journal with the journal open or split");
  if (attributes_.has_members()) throw std::logic_error("TriMesh::split_journal with stores attached");
  if (static_cast<int>(part_of.size()) < vertex_count())
    throw std::logic_error("TriMesh::split_journal: a vertex without a part");
  lanes_.assign(static_cast<std::size_t>(std::max(parts, 0)), Log{});
  lane_of_ = &part_of;
}

void TriMesh::join_journal() {
  for (const Log& log : lanes_)
    if (!log.marks.empty()) throw std::logic_error("TriMesh::join_journal with a part's level open");
  lanes_.clear();
  lane_of_ = nullptr;
}

void TriMesh::undo(const Change& c) {
  switch (c.kind) {
    case Change::Kind::add_vertex:
      points_.pop_back();
      vertex_tags_.pop_back();
      exact_index_.pop_back();
      vertex_triangles_.pop_back();
      tagged_.pop_back();
      has_tagged_.pop_back();
      break;
    case Change::Kind::add_triangle:
      unlink(triangle_slots() - 1);
      triangles_.pop_back();
      alive_triangles_.add(-1);
      break;
    case Change::Kind::remove_triangle:
      triangles_[c.index] = c.corners;
      link(c.index);
      alive_triangles_.add(1);
      break;
    case Change::Kind::set_triangle:
      unlink(c.index);
      triangles_[c.index] = c.corners;
      link(c.index);
      break;
    case Change::Kind::position:
      points_[c.index] = c.point;
      exact_index_[c.index] = c.exact_index;  // exact points are only appended: the old one is there
      break;
    case Change::Kind::tag:
      vertex_tags_[c.index] = c.tag;
      break;
    case Change::Kind::feature:
      if (c.feature)
        put_feature(c.lo, c.hi, *c.feature);
      else
        erase_feature(c.lo, c.hi);
      break;
  }
}

std::vector<std::pair<std::array<int, 2>, EdgeFeature>> TriMesh::sorted_features() const {
  std::vector<std::pair<std::array<int, 2>, EdgeFeature>> out;
  for (int lo = 0; lo < vertex_count(); ++lo)
    for (const TaggedEdge& e : tagged_[lo])
      if (lo < e.other) out.push_back({{lo, e.other}, e.feature});
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

std::vector<int> TriMesh::edge_triangles(int a, int b) const {
  std::vector<int> out;
  for (int t : vertex_triangles_[a]) {
    const auto& tri = triangles_[t];
    if (tri[0] == b || tri[1] == b || tri[2] == b) out.push_back(t);
  }
  return out;
}

std::vector<int> TriMesh::neighbours(int v) const {
  std::vector<int> out;
  for (int t : vertex_triangles_[v])
    for (int w : triangles_[t])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Without exact positions at all (most meshes), no vertex needs a look in exact_index_.
int TriMesh::orientation(int a, int b, int c) const {
  if (exact_points_.empty() || (!has_exact(a) && !has_exact(b) && !has_exact(c)))
    return geometry::orientation(points_[a], points_[b], points_[c]);
  return geometry::orientation(exact_or_double(a), exact_or_double(b), exact_or_double(c));
}

int TriMesh::orientation(int t) const {
  const auto& tri = triangles_[t];
  return orientation(tri[0], tri[1], tri[2]);
}

int TriMesh::orientation_with(int a, int b, int c, int moved, const Vec2& p) const {
  const auto exact_at = [&](int v) { return v == moved ? ExactPoint(p) : exact_or_double(v); };
  const auto inexact = [&](int v) { return v != moved && has_exact(v); };
  if (exact_points_.empty() || (!inexact(a) && !inexact(b) && !inexact(c))) {
    const auto at = [&](int v) -> const Vec2& { return v == moved ? p : points_[v]; };
    return geometry::orientation(at(a), at(b), at(c));
  }
  return geometry::orientation(exact_at(a), exact_at(b), exact_at(c));
}

std::vector<int> TriMesh::compact() {
  if (journal_open()) throw std::logic_error("TriMesh::compact with an open journal");
  const int n = vertex_count();
  std::vector<int> remap(n, -1);
  int next = 0;
  for (int v = 0; v < n; ++v)
    if (!vertex_triangles_[v].empty() || vertex_tags_[v].isolated) remap[v] = next++;

  std::vector<Vec2> points(next);
  std::vector<VertexTag> tags(next);
  std::vector<int> exact_index(next, -1);
  std::vector<ExactPoint> exact_points;
  for (int v = 0; v < n; ++v) {
    const int w = remap[v];
    if (w < 0) continue;
    points[w] = points_[v];
    tags[w] = vertex_tags_[v];
    if (exact_index_[v] >= 0) {
      exact_index[w] = static_cast<int>(exact_points.size());
      exact_points.push_back(exact_points_[exact_index_[v]]);
    }
  }
  std::vector<Triangle> triangles;
  triangles.reserve(alive_triangles_);
  for (const auto& tri : triangles_)
    if (tri[0] >= 0) triangles.push_back({remap[tri[0]], remap[tri[1]], remap[tri[2]]});
  // The renumbering keeps the order of vertices (a vertex moves to the same or a lower index):
  // each vertex's lists move down in place, the tagged ones stay sorted, and t_lo stays with the
  // lower end. The incidence lists are refilled below.
  for (int v = 0; v < n; ++v) {
    const int w = remap[v];
    if (w < 0) continue;
    std::vector<TaggedEdge>& list = tagged_[v];
    std::erase_if(list, [&](const TaggedEdge& e) { return remap[e.other] < 0; });
    for (TaggedEdge& e : list) e.other = remap[e.other];
    if (w == v) continue;
    tagged_[w] = std::move(list);
    vertex_triangles_[w] = std::move(vertex_triangles_[v]);
  }
  tagged_.resize(next);
  vertex_triangles_.resize(next);
  has_tagged_.resize(next);
  for (int v = 0; v < next; ++v) has_tagged_[v] = !tagged_[v].empty();

  points_ = std::move(points);
  vertex_tags_ = std::move(tags);
  exact_index_ = std::move(exact_index);
  exact_points_ = std::move(exact_points);
  triangles_ = std::move(triangles);
  // The incidence lists, refilled in triangle order. A list keeps its memory when that is at
  // least its size and at most twice it, and is allocated once at its size otherwise: removed
  // elements must not keep their memory, and allocating every list anew on every compaction
  // (growing by doubling, as links do, allocated five times per vertex) cost more than the refill.
  std::vector<int> degree(next, 0);
  for (const auto& tri : triangles_)
    for (int v : tri) ++degree[v];
  for (int v = 0; v < next; ++v) {
    std::vector<int>& list = vertex_triangles_[v];
    const auto size = static_cast<std::size_t>(degree[v]);
    list.clear();
    if (list.capacity() < size || list.capacity() > 2 * size) {
      std::vector<int> fresh;
      fresh.reserve(size);
      list.swap(fresh);
    }
  }
  for (int t = 0; t < triangle_slots(); ++t)
    for (int v : triangles_[t]) vertex_triangles_[v].push_back(t);
  alive_triangles_.n = triangle_slots();
  return remap;
}

std::optional<std::string> TriMesh::structure_error() const {
  std::ostringstream err;
  int alive_count = 0;
  for (int t = 0; t < triangle_slots(); ++t) {
    if (!alive(t)) continue;
    ++alive_count;
    const auto& tri = triangles_[t];
    for (int i = 0; i < 3; ++i) {
      const int v = tri[i];
      if (v < 0 || v >= vertex_count() || v == tri[(i + 1) % 3]) {
        err << "triangle " << t << " has a bad vertex " << v;
        return err.str();
      }
      const auto& list = vertex_triangles_[v];
      if (std::find(list.begin(), list.end(), t) == list.end()) {
        err << "vertex " << v << " does not list its triangle " << t;
        return err.str();
      }
    }
    if (orientation(t) <= 0) {
      err << "triangle " << t << " (" << tri[0] << ", " << tri[1] << ", " << tri[2] << ") is "
          << (orientation(t) == 0 ? "degenerate" : "inverted");
      return err.str();
    }
  }
  if (alive_count != alive_triangles_) return std::string("alive-triangle count is stale");
  for (int v = 0; v < vertex_count(); ++v)
    for (int t : vertex_triangles_[v]) {
      const auto& tri = triangles_[t];
      if (!alive(t) || (tri[0] != v && tri[1] != v && tri[2] != v)) {
        err << "vertex " << v << " lists triangle " << t << " that does not use it";
        return err.str();
      }
    }
  for (int a = 0; a < vertex_count(); ++a)
    for (const TaggedEdge& e : tagged_[a]) {
      const int b = e.other;
      if (b >= vertex_count() || edge_triangles(a, b).empty()) {
        err << "tagged edge (" << a << ", " << b << ") is not in the mesh";
        return err.str();
      }
      const EdgeFeature* back = feature(b, a);
      if (!back || !(*back == e.feature)) {
        err << "tagged edge (" << a << ", " << b << ") has another tag at " << b;
        return err.str();
      }
    }
  return std::nullopt;
}

}  // namespace curvemesh::mesh
