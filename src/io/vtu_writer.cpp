#include "io/vtu_writer.hpp"

#include <cstdio>
#include <stdexcept>

#include "io/output_file.hpp"

namespace curvemesh::io {

namespace {

// Node k of a VTK Lagrange triangle is node kVtkFromGmsh[order-1][k] of the Gmsh triangle.
// VTK (vtkHigherOrderTriangle: BarycentricIndex, SetParametricCoords) lists the corners, then
// the inner nodes of edges 0→1, 1→2, 2→0, each from its first corner, then the interior nodes
// as a smaller triangle in the same order; Gmsh's types 2, 9 and 21 list them the same way,
// so up to order 3 the two orders agree and the map is the identity. It is kept explicit
// because orders differ between the two for other element shapes (quadrangles, tetrahedra).
constexpr int kVtkFromGmsh[3][10] = {
    {0, 1, 2},
    {0, 1, 2, 3, 4, 5},
    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9},
};
// The cell type per order: VTK_TRIANGLE, VTK_QUADRATIC_TRIANGLE (6 nodes, the same order; read by
// every VTK reader, Lagrange cells only by newer ones) and VTK_LAGRANGE_TRIANGLE.
constexpr int kVtkCellType[3] = {5, 22, 69};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool valid_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
      return false;
  return true;
}

}  // namespace

std::string vtu_string(const HighOrderMesh& m, const std::vector<VtuCellScalars>& cell_scalars,
                       const std::vector<VtuPointArray>& point_arrays) {
  if (auto error = m.structure_error()) throw std::logic_error("vtu: " + *error);
  const int triangles = m.triangle_count();
  for (const VtuCellScalars& s : cell_scalars) {
    if (!valid_name(s.name) || s.name == "triangle" || s.name == "physical")
      throw std::logic_error("vtu: bad cell array name '" + s.name + "'");
    if (static_cast<int>(s.values.size()) != triangles)
      throw std::logic_error("vtu: cell array " + s.name + " has " + std::to_string(s.values.size()) +
                             " values for " + std::to_string(triangles) + " triangles");
  }
  for (const VtuPointArray& a : point_arrays) {
    if (!valid_name(a.name) || (a.components != 1 && a.components != 3))
      throw std::logic_error("vtu: bad point array '" + a.name + "'");
    if (a.values.size() != std::size_t(a.components) * m.nodes.size())
      throw std::logic_error("vtu: point array " + a.name + " has " + std::to_string(a.values.size()) + " values for " +
                             std::to_string(m.nodes.size()) + " nodes");
  }
  const int size = m.triangle_size();
  const int* vtk_from_gmsh = kVtkFromGmsh[m.order - 1];

  std::string t;
  t += "<?xml version=\"1.0\"?>\n";
  t += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n";
  t += "<UnstructuredGrid>\n";
  t += "<Piece NumberOfPoints=\"" + std::to_string(m.nodes.size()) + "\" NumberOfCells=\"" +
       std::to_string(triangles) + "\">\n";
  t += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const geometry::Vec2& p : m.nodes) t += number(p.x()) + " " + number(p.y()) + " 0\n";
  t += "</DataArray>\n</Points>\n";
  t += "<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (int tri = 0; tri < triangles; ++tri) {
    const auto nodes = m.triangle(tri);
    for (int k = 0; k < size; ++k) {
      t += std::to_string(nodes[vtk_from_gmsh[k]]);
      t += k + 1 < size ? ' ' : '\n';
    }
  }
  t += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (int tri = 0; tri < triangles; ++tri) t += std::to_string(long(tri + 1) * size) + "\n";
  t += "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  const std::string type = std::to_string(kVtkCellType[m.order - 1]) + "\n";
  for (int tri = 0; tri < triangles; ++tri) t += type;
  t += "</DataArray>\n</Cells>\n";
  t += "<CellData Scalars=\"triangle\">\n<DataArray type=\"Int32\" Name=\"triangle\" format=\"ascii\">\n";
  for (int tri = 0; tri < triangles; ++tri) t += std::to_string(tri) + "\n";
  t += "</DataArray>\n<DataArray type=\"Int32\" Name=\"physical\" format=\"ascii\">\n";
  for (int tri = 0; tri < triangles; ++tri) t += std::to_string(m.triangle_physical[tri]) + "\n";
  t += "</DataArray>\n";
  for (const VtuCellScalars& s : cell_scalars) {
    t += "<DataArray type=\"Float64\" Name=\"" + s.name + "\" format=\"ascii\">\n";
    for (double v : s.values) t += number(v) + "\n";
    t += "</DataArray>\n";
  }
  t += "</CellData>\n";
  if (!point_arrays.empty()) {
    t += "<PointData>\n";
    for (const VtuPointArray& a : point_arrays) {
      t += "<DataArray type=\"Float64\" Name=\"" + a.name + "\" NumberOfComponents=\"" + std::to_string(a.components) +
           "\" format=\"ascii\">\n";
      for (std::size_t i = 0; i < a.values.size(); ++i)
        t += number(a.values[i]) + ((i + 1) % a.components == 0 ? "\n" : " ");
      t += "</DataArray>\n";
    }
    t += "</PointData>\n";
  }
  t += "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return t;
}

void write_vtu(const HighOrderMesh& mesh, const std::string& path,
               const std::vector<VtuCellScalars>& cell_scalars, const std::vector<VtuPointArray>& point_arrays) {
  write_file_atomically(path, vtu_string(mesh, cell_scalars, point_arrays));
}

}  // namespace curvemesh::io
