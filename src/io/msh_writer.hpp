#pragma once
// Gmsh .msh output (ASCII 4.1 by default, 2.2 on request) of a triangle mesh of order 1, 2 or 3:
// triangles (types 2, 9, 21) and feature lines (types 1, 8, 26) in physical groups, one
// geometric entity per group so that Gmsh shows them ("primary", "secondary", "boundary" for
// lines, "domain" for triangles by default). Every node is written once and shared by the
// elements that use it. Coordinates are written with 17 significant digits, so reading the file
// back gives the very doubles of the mesh; the text depends on nothing but the mesh.
#include <string>

#include "io/high_order_mesh.hpp"
#include "mesh/tri_mesh.hpp"

namespace curvemesh::io {

struct MshOptions {
  int version = 41;  // 41: ASCII 4.1; 22: ASCII 2.2
};

// Elements are written grouped by physical tag (lines, then triangles, each by ascending tag),
// in their order within a group; node i is node tag i + 1. Throws std::logic_error if the mesh
// has a structure_error(), a physical name holds a '"' or a line break, or the version is not
// 41 or 22.
std::string msh_string(const HighOrderMesh& mesh, const MshOptions& options = {});
void write_msh(const HighOrderMesh& mesh, const std::string& path, const MshOptions& options = {});

// The linear mesh of `mesh` (see linear_mesh). Throws std::logic_error if a vertex still has an
// exact (unrounded) position or the version is not 41 or 22.
std::string msh_string(const mesh::TriMesh& mesh, const MshOptions& options = {});
void write_msh(const mesh::TriMesh& mesh, const std::string& path, const MshOptions& options = {});

}  // namespace curvemesh::io
