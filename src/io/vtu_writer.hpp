#pragma once
// VTK XML UnstructuredGrid (.vtu, ASCII) output of the triangles of a HighOrderMesh, for
// ParaView and meshio: linear triangles as VTK_TRIANGLE (5), quadratic and cubic ones as
// VTK_LAGRANGE_TRIANGLE (69), which ParaView draws curved. Cell data: "triangle" (the index of
// the triangle in the mesh), "physical" (its physical tag) and any arrays given. Feature lines
// are not written. Coordinates with 17 significant digits; the text depends only on the input.
#include <string>
#include <vector>

#include "io/high_order_mesh.hpp"

namespace curvemesh::io {

struct VtuCellScalars {
  std::string name;            // letters, digits, '_' and '-' only
  std::vector<double> values;  // one per triangle
};

// Throws std::logic_error if the mesh has a structure_error() or an array does not have one
// value per triangle or has a bad name.
std::string vtu_string(const HighOrderMesh& mesh, const std::vector<VtuCellScalars>& cell_scalars = {});
void write_vtu(const HighOrderMesh& mesh, const std::string& path,
               const std::vector<VtuCellScalars>& cell_scalars = {});

}  // namespace curvemesh::io
