#pragma once
// The triangle mesh every stage after features works on: flat index arrays (geogram style),
// vertex-to-triangle incidence, and tags saying what each vertex and edge lies on.
//
// Coordinates are doubles, except for vertices created by intersecting input segments whose
// rational position could not be rounded without inverting a triangle: those keep an exact
// position (§4.1, the hybrid kernel of TetWild) until an operation moves them to doubles.
// Orientation is always decided exactly on the coordinates as stored.
#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/predicates.hpp"
#include "geometry/vec2.hpp"
#include "mesh/journal.hpp"

namespace curvemesh::mesh {

using geometry::ExactPoint;
using geometry::Vec2;

enum class EdgeKind : std::uint8_t { interior, primary, secondary, boundary };

// What a tagged edge lies on. Interior edges have no entry.
struct EdgeFeature {
  EdgeKind kind = EdgeKind::interior;
  // primary: the soup curve; secondary: the soup curve the input segment approximates (-1 when
  // the input had no curves, e.g. a .poly file); boundary: -1.
  int curve = -1;
  // primary: index of the features section; secondary: index of the input secondary segment;
  // boundary: the box side (0 bottom, 1 right, 2 top, 3 left).
  int source = -1;
  // primary: the curve parameters at the edge's lower- and higher-numbered vertex.
  double t_lo = 0, t_hi = 0;
  bool operator==(const EdgeFeature&) const = default;
};

enum class VertexKind : std::uint8_t {
  free,       // no tagged edge: moves in the plane
  secondary,  // on secondary edges only: moves in the plane while they stay in the ε-envelope
  primary,    // on one primary curve (inside a section): moves only along the curve (App. A)
  boundary,   // on one side of the box: moves only along it
  fixed,      // box corner, curve or section end, isolated point, crossing of curves or of a
              // curve and the box: stays
};

struct VertexTag {
  VertexKind kind = VertexKind::free;
  int section = -1;       // primary: the features section (one curve, one interval) it lies on
  double t = 0;           // primary: its parameter on the section's soup curve
  int side = -1;          // boundary: the box side
  bool on_curve = true;   // primary: false while it sits on the chord, before projection (Fig. 8)
  bool isolated = false;  // an isolated input point: never removed
  bool operator==(const VertexTag&) const = default;
};

using Triangle = std::array<int, 3>;  // counter-clockwise

// A tagged edge as its vertex sees it: the other end, and the tag.
struct TaggedEdge {
  int other;
  EdgeFeature feature;
};

inline std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(a < b ? a : b), hi = static_cast<std::uint32_t>(a < b ? b : a);
  return (std::uint64_t{lo} << 32) | hi;
}

class TriMesh {
 public:
  // --- building ---
  int add_vertex(const Vec2& p, const VertexTag& tag = {});
  // Adds a triangle; the caller guarantees counter-clockwise order.
  int add_triangle(int a, int b, int c);
  void remove_triangle(int t);  // marks it dead; `compact` reclaims it
  // Replaces the corners of an alive triangle (counter-clockwise), updating incidence.
  void set_triangle(int t, const Triangle& corners);
  void set_position(int v, const Vec2& p);              // also drops an exact position
  void set_exact_position(int v, const ExactPoint& p);  // keeps `point(v)` as its nearest double
  void set_tag(int v, const VertexTag& tag);
  void set_feature(int a, int b, const EdgeFeature& f);
  void clear_feature(int a, int b);

  // --- reading ---
  int vertex_count() const { return static_cast<int>(points_.size()); }
  int triangle_slots() const { return static_cast<int>(triangles_.size()); }  // dead ones included
  int triangle_count() const { return alive_triangles_; }
  const Vec2& point(int v) const { return points_[v]; }
  const VertexTag& tag(int v) const { return vertex_tags_[v]; }
  bool has_exact(int v) const { return exact_index_[v] >= 0; }
  const ExactPoint& exact(int v) const { return exact_points_[exact_index_[v]]; }
  // The vertex position as a rational (exact if it has one, else its double, which is rational).
  ExactPoint exact_or_double(int v) const;
  int exact_vertex_count() const;
  const Triangle& triangle(int t) const { return triangles_[t]; }
  bool alive(int t) const { return triangles_[t][0] >= 0; }
  const std::vector<int>& triangles_of(int v) const { return vertex_triangles_[v]; }
  const EdgeFeature* feature(int a, int b) const;
  // The tagged edges at v, by increasing other end (the order of `neighbours`). Changing a tag
  // invalidates the list.
  const std::vector<TaggedEdge>& tagged_edges(int v) const { return tagged_[v]; }
  // The tagged edges sorted by (lower, higher) vertex: a deterministic order for output.
  std::vector<std::pair<std::array<int, 2>, EdgeFeature>> sorted_features() const;
  // Alive triangles containing edge (a, b): one on the box, two inside.
  std::vector<int> edge_triangles(int a, int b) const;
  // The vertices joined to v by an edge, in increasing order.
  std::vector<int> neighbours(int v) const;
  // Exact orientation of a triangle with the coordinates as stored (+1 means valid).
  int orientation(int t) const;
  int orientation(int a, int b, int c) const;
  // Same, with vertex `moved` placed at `p` (a double position) instead.
  int orientation_with(int a, int b, int c, int moved, const Vec2& p) const;

  // Removes dead triangles and vertices no triangle uses (except isolated points, which cannot be
  // unused in a valid mesh); renumbers everything. Returns the old-to-new vertex map (-1 = removed).
  std::vector<int> compact();

  // --- taking changes back ---
  // While a journal level is open, every change above is recorded, and so is every change to the
  // stores attached to journal() (mesh/journal.hpp). `rollback` takes back the changes of the
  // innermost level (the mesh is then as it was when that level opened, up to the order of
  // incidence lists); `commit` hands them to the enclosing level, or keeps them for good at the
  // outermost one. Used to try an operation — or a move and its repair — and judge the outcome
  // afterwards. `compact` is not allowed while a level is open.
  void open_journal();
  void rollback();
  void commit();
  // A level is open, or the journal is split (below).
  bool journal_open() const { return !log_.marks.empty() || lane_of_ != nullptr; }
  // Where a stage attaches what it keeps beside the mesh, to be taken back with it.
  Journal& journal() { return attributes_; }

  // While parts of the mesh run operations side by side (mesh/schedule.hpp), each part has a
  // journal of its own: split_journal gives one to each part (`part_of[v]`: v's part, from 0 to
  // parts − 1), and an operation at vertex `at` opens, commits and takes back its levels with the
  // calls taking `at`. A change is recorded in the journal of the part of the vertex it is at (a
  // vertex moved or retagged, a corner of a triangle rewritten, the lower end of an edge retagged),
  // which is the operation's own part when it changes the stars of the part's inner vertices only.
  // No vertex or triangle may be added while the journal is split (their numbers would depend on
  // the order of the parts), and the stores attached to journal() cannot follow: splitting refuses
  // a mesh with any, or with a level open; joining, a part with a level open. Unsplit, the calls
  // taking `at` are the calls above.
  void split_journal(const std::vector<int>& part_of, int parts);
  void join_journal();
  void open_journal(int at);
  void rollback(int at);
  void commit(int at);

  // Checks the structural invariants: incidence lists match triangles, every triangle is
  // counter-clockwise (exact), every tagged edge exists. Returns a description of the first
  // violation, or nothing.
  std::optional<std::string> structure_error() const;

 private:
  std::vector<Vec2> points_;
  std::vector<VertexTag> vertex_tags_;
  std::vector<int> exact_index_;  // into exact_points_, -1 when the double is the position
  std::vector<ExactPoint> exact_points_;
  std::vector<Triangle> triangles_;
  std::vector<std::vector<int>> vertex_triangles_;
  // The tagged edges, listed at both ends, each list by increasing other end: a vertex has few
  // (two on a curve, more only where curves meet) and most have none, so a look-up is a short
  // scan of one small array (the operations ask for edge tags all the time; a hash map's nodes
  // were a cache miss each), and a vertex's tagged edges need no walk round its star.
  std::vector<std::vector<TaggedEdge>> tagged_;
  // Per vertex, whether its list is not empty: a byte each, so that the usual look-up (an edge
  // with an end on no tagged edge) reads no list at all.
  std::vector<std::uint8_t> has_tagged_;
  void put_feature(int a, int b, const EdgeFeature& f);  // inserts or overwrites, unrecorded
  void erase_feature(int a, int b);                      // unrecorded; none is fine
  // Atomic: operations in parts of the mesh apart remove triangles side by side (mesh/schedule.hpp).
  struct Count {
    std::atomic<int> n{0};
    Count() = default;
    Count(const Count& o) : n(o.n.load(std::memory_order_relaxed)) {}
    Count& operator=(const Count& o) {
      n.store(o.n.load(std::memory_order_relaxed), std::memory_order_relaxed);
      return *this;
    }
    operator int() const { return n.load(std::memory_order_relaxed); }
    void add(int k) { n.fetch_add(k, std::memory_order_relaxed); }
  };
  Count alive_triangles_;

  struct Change {
    enum class Kind : std::uint8_t {
      add_vertex,
      add_triangle,
      remove_triangle,
      set_triangle,
      position,
      tag,
      feature
    };
    Kind kind;
    int index = -1;  // vertex or triangle
    Triangle corners{};
    Vec2 point = Vec2::Zero();
    int exact_index = -1;
    VertexTag tag{};
    int lo = -1, hi = -1;  // feature: the edge
    std::optional<EdgeFeature> feature = std::nullopt;
  };
  // One journal: the changes, and per open level their count when it opened.
  struct Log {
    std::vector<Change> changes;
    std::vector<std::size_t> marks;
  };
  Log& log_at(int at) { return lane_of_ ? lanes_[(*lane_of_)[at]] : log_; }
  // `at`: the vertex the change is at (split_journal); -1 for an addition.
  void record(int at, Change change);
  void link(int t);    // adds t to its corners' incidence lists
  void unlink(int t);  // removes t from its corners' incidence lists
  void undo(const Change& c);
  Log log_;
  std::vector<Log> lanes_;                 // per part, while the journal is split
  const std::vector<int>* lane_of_ = nullptr;  // the parts of the vertices, while split
  Journal attributes_;
};

}  // namespace curvemesh::mesh
