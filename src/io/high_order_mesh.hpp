#pragma once
// A plain triangle mesh of geometric order 1, 2 or 3, as files hold it: shared nodes, triangles
// and feature lines as node lists in Gmsh's node order, physical tags and their names. It is
// what the .msh and .vtu writers take and what the .msh reader gives; the meshing stages have
// richer types and convert to this one at the edge.
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vec2.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::io {

// Physical tags: lines by what they lie on, the triangles, and the lines on the border of the
// meshed domain. Tags from kFirstDrawingGroup on are the drawing's own (each drawn element's lines,
// the regions), numbered by the pipeline (regions/groups.hpp).
inline constexpr int kPhysicalPrimary = 1, kPhysicalSecondary = 2, kPhysicalBoundary = 3, kPhysicalDomain = 4,
                     kPhysicalBorder = 5;
inline constexpr int kFirstDrawingGroup = 6;

struct HighOrderMesh {
  // 1, 2 or 3. A triangle has (order+1)(order+2)/2 nodes (Gmsh types 2, 9, 21): the corners,
  // then the inner nodes of edge 0→1, 1→2 and 2→0, each edge's from its first corner on, then
  // the interior node of P3. A line has order+1 nodes (Gmsh types 1, 8, 26): its two ends, then
  // its inner nodes from the first end on.
  int order = 1;
  std::vector<geometry::Vec2> nodes;
  std::vector<int> triangles;          // node indices, triangle_size() per triangle
  std::vector<int> triangle_physical;  // one per triangle; 0 = in no physical group
  std::vector<int> lines;              // node indices, line_size() per line
  std::vector<int> line_physical;      // one per line: what it lies on; 0 = in no physical group
  // The further physical groups of each line (the border, the drawn elements it lies on), each
  // list ascending and without line_physical: empty when no line has any, else one list per line.
  // A line is in several groups at once: one Gmsh entity with several physical tags in .msh 4.1,
  // the element written once per group in 2.2.
  std::vector<std::vector<int>> line_groups;
  // Names of physical groups by (dimension, tag); dimension 1 for lines, 2 for triangles.
  std::map<std::pair<int, int>, std::string> physical_names = default_physical_names();

  static std::map<std::pair<int, int>, std::string> default_physical_names();

  int triangle_size() const { return (order + 1) * (order + 2) / 2; }
  int line_size() const { return order + 1; }
  int triangle_count() const { return order_ok() ? static_cast<int>(triangles.size()) / triangle_size() : 0; }
  int line_count() const { return order_ok() ? static_cast<int>(lines.size()) / line_size() : 0; }
  std::span<const int> triangle(int t) const {
    return std::span<const int>(triangles).subspan(std::size_t(t) * triangle_size(), triangle_size());
  }
  std::span<const int> line(int l) const {
    return std::span<const int>(lines).subspan(std::size_t(l) * line_size(), line_size());
  }

  // Every physical group of line l, ascending: line_physical (when not 0) and line_groups.
  std::vector<int> groups_of_line(int l) const;

  // Appends an element; `node_indices` must have triangle_size() (line_size()) entries.
  void add_triangle(std::span<const int> node_indices, int physical = kPhysicalDomain);
  void add_line(std::span<const int> node_indices, int physical, std::vector<int> groups = {});

  // Why the arrays do not describe a mesh (order not 1..3, array sizes that do not fit the
  // order, node indices out of range, negative physical tags, non-finite coordinates), or
  // nothing when they do.
  std::optional<std::string> structure_error() const;

 private:
  bool order_ok() const { return order >= 1 && order <= 3; }
};

// The linear mesh of a TriMesh: every vertex a node (same indices), the alive triangles in slot
// order in "domain", tagged edges in sorted order as lines in "primary", "secondary" or
// "boundary". Throws std::logic_error if a vertex still has an exact (unrounded) position.
HighOrderMesh linear_mesh(const mesh::TriMesh& mesh);

}  // namespace curvemesh::io
