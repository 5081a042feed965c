#pragma once
// Gmsh .msh output (ASCII 4.1 by default, 2.2 on request) of a linear triangle mesh: triangles
// (type 2) in the physical surface "domain", tagged edges as lines (type 1) in the physical
// groups "primary", "secondary" and "boundary". Coordinates are written with 17 significant
// digits, so reading the file back gives the very doubles of the mesh; the text depends on
// nothing but the mesh.
#include <string>

#include "mesh/tri_mesh.hpp"

namespace curvemesh::io {

struct MshOptions {
  int version = 41;  // 41: ASCII 4.1; 22: ASCII 2.2
};

// Physical tags: lines by what they lie on, and the triangles.
inline constexpr int kPhysicalPrimary = 1, kPhysicalSecondary = 2, kPhysicalBoundary = 3, kPhysicalDomain = 4;

// Throws std::logic_error if a vertex still has an exact (unrounded) position or the version is
// not 41 or 22.
std::string msh_string(const mesh::TriMesh& mesh, const MshOptions& options = {});
void write_msh(const mesh::TriMesh& mesh, const std::string& path, const MshOptions& options = {});

}  // namespace curvemesh::io
