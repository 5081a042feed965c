#pragma once
// Gmsh .msh output (ASCII 4.1 by default, 2.2 on request) of a triangle mesh of order 1, 2 or 3:
// triangles (types 2, 9, 21) and feature lines (types 1, 8, 26) in physical groups ("primary",
// "secondary", "boundary", "border" and the drawing's own for lines, "domain" or the regions for
// triangles), one geometric entity per set of groups so that Gmsh shows them. A line in several
// groups is one element of an entity with several physical tags in 4.1, and one element per group
// in 2.2, which has a single physical tag per element (each copy in an elementary entity of its
// own, so that Gmsh, which takes groups from entities, counts it once per group). Every node is
// written once and shared by the elements that use it, node i as tag i + 1. Coordinates are
// written with 17 significant digits, so reading the file back gives the very doubles of the mesh;
// the text depends on nothing but the mesh.
#include <string>

#include "io/high_order_mesh.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::io {

struct MshOptions {
  int version = 41;  // 41: ASCII 4.1; 22: ASCII 2.2
  // Only the lines in the group "border", each in exactly one group: the lowest of its further
  // groups above "border" (a drawn element's), else its line_physical. For readers that refuse a
  // line inside the mesh or a line in two groups (deal.II's GridIn::read_msh).
  bool boundary_only = false;
};

// Elements are written grouped by entity (lines, then triangles; lines by their sets of groups,
// triangles by tag, each ascending), in their order within a group; node i is node tag i + 1.
// Throws std::logic_error if the mesh
// has a structure_error(), a physical name holds a '"' or a line break, or the version is not
// 41 or 22.
std::string msh_string(const HighOrderMesh& mesh, const MshOptions& options = {});
void write_msh(const HighOrderMesh& mesh, const std::string& path, const MshOptions& options = {});

// The linear mesh of `mesh` (see linear_mesh). Throws std::logic_error if a vertex still has an
// exact (unrounded) position or the version is not 41 or 22.
std::string msh_string(const mesh::TriMesh& mesh, const MshOptions& options = {});
void write_msh(const mesh::TriMesh& mesh, const std::string& path, const MshOptions& options = {});

}  // namespace curvemesh::io
