#pragma once
// VTK XML UnstructuredGrid (.vtu, ASCII) output of the triangles of a HighOrderMesh, for
// ParaView and meshio: linear triangles as VTK_TRIANGLE (5), quadratic ones as
// VTK_QUADRATIC_TRIANGLE (22), cubic ones as VTK_LAGRANGE_TRIANGLE (69); ParaView draws both
// curved. Cell data: "triangle" (the index of
// the triangle in the mesh), "physical" (its physical tag) and any arrays given; point data: any
// arrays given (fields of a solution at the nodes). Feature lines
// are not written. Coordinates with 17 significant digits; the text depends only on the input.
#include <string>
#include <vector>

#include "io/high_order_mesh.hpp"

namespace curvemesh::io {

struct VtuCellScalars {
  std::string name;            // letters, digits, '_' and '-' only
  std::vector<double> values;  // one per triangle
};

struct VtuPointArray {
  std::string name;            // letters, digits, '_' and '-' only
  int components = 1;          // 1 (scalar) or 3 (vector; 2D vectors with z = 0)
  std::vector<double> values;  // components per node, node after node
};

// Throws std::logic_error if the mesh has a structure_error() or an array does not have one
// value per triangle (components per node) or has a bad name.
std::string vtu_string(const HighOrderMesh& mesh, const std::vector<VtuCellScalars>& cell_scalars = {},
                       const std::vector<VtuPointArray>& point_arrays = {});
void write_vtu(const HighOrderMesh& mesh, const std::string& path,
               const std::vector<VtuCellScalars>& cell_scalars = {},
               const std::vector<VtuPointArray>& point_arrays = {});

}  // namespace curvemesh::io
