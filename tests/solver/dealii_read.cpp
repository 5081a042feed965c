// What deal.II makes of a Gmsh .msh file, read by its own reader (GridIn<2>::read_msh): the
// triangles by material id (the file's physical surface groups) with their count and area, the
// boundary faces by boundary id (its physical line groups) with their count and length, as JSON on
// standard output. An independent consumer for tests/solver/dealii_test.py; exit 1 with deal.II's
// message when it refuses the file.
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <exception>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>

namespace {

struct Measure {
  int count = 0;
  double size = 0;
};

void print(const char* name, const std::map<int, Measure>& groups) {
  std::cout << "\"" << name << "\": {";
  const char* separator = "";
  for (const auto& [id, m] : groups) {
    std::cout << separator << "\"" << id << "\": [" << m.count << ", " << m.size << "]";
    separator = ", ";
  }
  std::cout << "}";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: dealii_read MESH.msh\n";
    return 2;
  }
  dealii::Triangulation<2> triangulation;
  dealii::GridIn<2> in;
  in.attach_triangulation(triangulation);
  std::ifstream file(argv[1]);
  try {
    in.read_msh(file);
  } catch (const std::exception& e) {
    std::cerr << "deal.II refuses " << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
  std::map<int, Measure> materials, boundaries;
  for (const auto& cell : triangulation.active_cell_iterators()) {
    Measure& m = materials[int(cell->material_id())];
    ++m.count;
    m.size += cell->measure();
    for (const unsigned f : cell->face_indices())
      if (cell->face(f)->at_boundary()) {
        Measure& b = boundaries[int(cell->face(f)->boundary_id())];
        ++b.count;
        b.size += cell->face(f)->measure();
      }
  }
  std::cout << std::setprecision(17) << "{\"cells\": " << triangulation.n_active_cells() << ", ";
  print("materials", materials);
  std::cout << ", ";
  print("boundaries", boundaries);
  std::cout << "}\n";
  return 0;
}
