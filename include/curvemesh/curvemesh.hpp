#pragma once
// curvemesh: coarse, curved, analysis-ready triangle meshes from vector drawings (the TriWild
// method, Hu et al., SIGGRAPH 2019). The whole public C++ API: read a drawing (an SVG file, SVG
// text, or cubic Bézier curves given by their control points), mesh it with Parameters, get
// the mesh as plain arrays, write it, check it. Plain standard C++: no type of the libraries
// the engine uses (CGAL, Eigen, GMP) appears here.
//
//   #include <curvemesh/curvemesh.hpp>
//   curvemesh::Parameters p;
//   p.edge_length_rel = 0.02;
//   const curvemesh::Mesh m = curvemesh::mesh_file("drawing.svg", p);
//   m.write("drawing.msh");
//
// Every failure throws curvemesh::Error (curvemesh/parameters.hpp), whose message is the one the
// command line prints. The implementation is the shared library libcurvemesh (CMake:
// find_package(curvemesh CONFIG) and target curvemesh::curvemesh). The functions keep no state
// between calls: several threads may mesh at once.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "curvemesh/export.hpp"
#include "curvemesh/parameters.hpp"

namespace curvemesh {

// "0.1.0"
CURVEMESH_API const char* version();

// What a feature line of the mesh lies on.
enum class LineTag {
  primary,    // a curve of the drawing, reproduced exactly by curved edges
  secondary,  // a piece of a curve kept within ε by straight edges
  boundary,   // a side of the meshed box
};

// "primary", "secondary", "boundary".
CURVEMESH_API const char* tag_name(LineTag tag);

// A physical group of the mesh: what a solver selects feature lines or triangles by. The .msh
// file's physical groups, with the same ids and names (`curvemesh mesh --stats` lists them). Ids
// are unique across both dimensions: 1 primary, 2 secondary, 3 boundary (lines by LineTag), 4
// domain (the triangles, without Parameters::regions), 5 border (the lines around the meshed
// domain), then one per drawn element whose curves lines lie on (6 + its index among the drawn
// elements), then one per region (Parameters::regions), numbered after every drawn element so
// that a region's id does not depend on Parameters::domain.
struct Group {
  int dimension = 0;  // 1: feature lines, 2: triangles
  int id = 0;         // its physical tag
  std::string name;   // "primary", ..., "border", a drawn element's id (else TAG#INDEX), a region's
};

// A cubic Bézier curve by its four control points, (x, y) each, in the drawing's units.
using Curve = std::array<std::array<double, 2>, 4>;

// A finished mesh: certified (every curved triangle's Jacobian is positive on the whole
// triangle), with its nodes, triangles and feature lines as plain arrays. Copies share them. A
// default-constructed Mesh is empty (order 0, no nodes) and cannot be written.
class CURVEMESH_API Mesh {
 public:
  // Parameters::order: 3, cubic triangles of 10 nodes and lines of 4; 2, quadratic triangles of 6
  // nodes and lines of 3; 1, triangles of 3 and lines of 2.
  int order() const;
  // How many nodes: the length of nodes().
  std::size_t node_count() const;
  // How many triangles: triangles() holds nodes_per_triangle() ids for each.
  std::size_t triangle_count() const;
  // How many feature lines: lines() holds nodes_per_line() ids for each.
  std::size_t line_count() const;

  // (x, y) per node, in the drawing's units (SVG's user space: y points down).
  const std::vector<std::array<double, 2>>& nodes() const;
  // Node ids, nodes_per_triangle() per triangle, in Gmsh's order: the corners counter-clockwise
  // (as seen with y up), then the order − 1 nodes on each edge 0→1, 1→2, 2→0 from its first
  // corner on (two for order 3, the middle for order 2), then order 3's centre.
  const std::vector<std::int64_t>& triangles() const;
  // 10 for order 3, 6 for order 2, 3 for order 1 (0 when empty).
  int nodes_per_triangle() const;
  // Node ids of the feature lines, nodes_per_line() per line: both ends, then the inner nodes.
  const std::vector<std::int64_t>& lines() const;
  // order + 1: 4, 3 or 2 (0 when empty).
  int nodes_per_line() const;
  // Per line: what it lies on (a curve followed exactly, a curve kept within ε, the box).
  const std::vector<LineTag>& line_tags() const;
  // Per line: the input curve it lies on (the index of a curve given to mesh_curves, or of the
  // reader's curve in document order), -1 for the box's sides (and for every line of a .poly
  // file, which has no curves).
  const std::vector<std::int64_t>& line_curves() const;

  // Per triangle: the id of its group (dimension 2): its region's with Parameters::regions, else
  // 4 (domain).
  const std::vector<int>& triangle_groups() const;
  // Per line: the ids of every group (dimension 1) it is in, ascending: its LineTag's (1, 2 or
  // 3), 5 when it lies on the border of the meshed domain, then the group of each drawn element
  // whose curve it lies on (several where their curves coincide).
  const std::vector<std::vector<int>>& line_groups() const;
  // Every group some triangle or line is in, by dimension, then id.
  const std::vector<Group>& groups() const;

  // The statistics `curvemesh mesh --stats` writes (counts, quality, seconds per stage), as JSON;
  // without the seconds spent writing, which the file has.
  const std::string& stats_json() const;
  // What the reader warned about (elements it skipped, a drawing with nothing drawn).
  const std::vector<std::string>& warnings() const;

  // Writes the mesh by the path's extension: ".msh" (Gmsh, `msh_version` 41 or 22), ".vtu" (VTK
  // quadratic or Lagrange triangles), ".xdmf" (XDMF for FEniCSx, with its HDF5 data in the ".h5"
  // file of the same name beside it; orders 1 and 2) or ".svg" (a drawing of the mesh). The file
  // is the very one the command line writes for the same drawing and parameters, written whole or
  // not at all (never through a link planted beside it; an XDMF file and its data both or
  // neither). Throws Error (output) when it cannot be written, the extension (in any case) is none
  // of these or the Mesh is empty, and Error (invalid_parameters) for another msh_version, XDMF of
  // a cubic mesh, or a path that is the drawing the Mesh was read from.
  void write(const std::string& path, int msh_version = 41) const;

  struct Impl;

 private:
  friend Mesh make_mesh(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> impl_;
};

// Meshes an SVG file (gzip-compressed too, .svgz: told by its gzip header) or a Triangle .poly
// file (points and segments, all secondary).
CURVEMESH_API Mesh mesh_file(const std::string& path, const Parameters& parameters = {});
// Meshes SVG text; `name` is what messages call it.
CURVEMESH_API Mesh mesh_svg(const std::string& svg_text, const Parameters& parameters = {},
                            const std::string& name = "<svg>");
// Meshes cubic Bézier curves as the reader's curves would be (no fill, no colour). A coordinate
// that is not a finite number is refused (Error, invalid_input).
CURVEMESH_API Mesh mesh_curves(const std::vector<Curve>& curves, const Parameters& parameters = {});

// The verdict of `curvemesh check` on a mesh as a file holds it: every element's Jacobian
// determinant decided on the whole element as exact rationals on the coordinates as written
// decide it.
struct CheckReport {
  // The elements' order as the file holds them: 1 (3 nodes), 2 (6 nodes) or 3 (10 nodes).
  int order = 0;
  // How many triangles were checked.
  std::size_t triangles = 0;
  std::size_t invalid = 0;         // elements not certified positive (0 for a valid mesh)
  std::size_t undecided = 0;       // of those, the ones the exact test could not decide
  double min_scaled_jacobian = 0;  // over the elements
  // How many elements were decided with exact rationals: those the certificate in doubles left
  // undecided (nearly degenerate ones), or all of them with CheckOptions::exact.
  std::size_t exact_fallbacks = 0;
};

// How `check` and `check_file` decide (`curvemesh check`'s options).
struct CheckOptions {
  // Decide every element with exact rationals (`--exact`). By default a certificate in doubles
  // with a rigorous bound on its rounding errors decides first and rationals only what it cannot:
  // the same verdicts, many times faster.
  bool exact = false;
  // Threads the check may use (`--threads`; 0: every hardware thread); the verdicts are the same.
  int threads = 0;
};

// Checks a Gmsh .msh file (of any 2D triangle mesh of order 1, 2 or 3). Throws Error
// (invalid_input) when the file cannot be read.
CURVEMESH_API CheckReport check_file(const std::string& msh_path, const CheckOptions& options = {});
// Checks the mesh as its .msh file would hold it (written with 17 significant digits, read back:
// the same doubles). An empty Mesh gives an empty report.
CURVEMESH_API CheckReport check(const Mesh& mesh, const CheckOptions& options = {});

}  // namespace curvemesh
