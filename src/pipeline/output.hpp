#pragma once
// What a pipeline result becomes: the mesh as files (.msh, .vtu, .svg), as a plain high-order
// mesh, and as the finished drawing the applications solve on.
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/high_order_mesh.hpp"
#include "io/vtu_writer.hpp"
#include "pipeline/meshed_drawing.hpp"
#include "pipeline/pipeline.hpp"

namespace curvemesh::pipeline {

// The result's mesh (curved when it was curved, else linear) as plain arrays: the domain's
// triangles, tagged by region, when the run was asked for them (RunOptions); its lines in the
// groups of regions/groups.hpp (their kind, "border", each drawn element's). What run() made once
// (Result::output); throws std::logic_error when no stage made a mesh.
const io::HighOrderMesh& high_order_mesh(const Result& result);
// The same, made anew from the result's stages (what run() keeps as Result::output).
io::HighOrderMesh make_output_mesh(const Result& result);

// Per line of `mesh` (high_order_mesh of the same result, or the mesh it is made from): the drawn
// elements (indices into result.soup.sources) whose curves it lies on, ascending: the element of
// the curve its feature follows, and where curves of several elements coincide (two shapes sharing
// a side) every one of them, decided at the line's middle (triangulate::SharedPiece); none for a
// side of the box or a line of a .poly file.
std::vector<std::vector<int>> line_elements(const Result& result, const io::HighOrderMesh& mesh);

// What the .vtu carries per triangle beyond its physical tag: with a domain or regions, its
// "face" (in the whole mesh) and, with regions, its "region" (physical tag).
std::vector<io::VtuCellScalars> cell_data(const Result& result);

// The physical groups of `mesh`, by dimension and id, as `--stats` lists them: each one's dim, id,
// name, and lines and total length (lines) or triangles and area (triangles).
nlohmann::ordered_json groups_json(const io::HighOrderMesh& mesh);

// Per line of `mesh` (high_order_mesh of the same result): the soup curve it lies on, from the
// feature of its two ends in result.corners() (the vertices are the mesh's first nodes, same
// ids, or the domain's nodes that were they); -1 for a side of the box, and for a secondary line when the input had no curves (.poly).
std::vector<int> line_curves(const Result& result, const io::HighOrderMesh& mesh);

// Gmsh .msh (version 41 or 22), VTK .vtu, XDMF, and an SVG drawing of the mesh; each written whole or
// not at all (io::OutputError).
void write_msh(const Result& result, const std::string& path, int version = 41);
void write_vtu(const Result& result, const std::string& path);
// XDMF and the HDF5 file beside it (io::xdmf_data_path), both or neither; orders 1 and 2
// (std::invalid_argument for another: io/xdmf_writer.hpp).
void write_xdmf(const Result& result, const std::string& path);
void write_svg(const Result& result, const std::string& path);
// The SVG drawing write_svg writes.
std::string mesh_svg(const Result& result);
// The statistics as `mesh --stats` writes them: JSON, indented, ending in a newline.
std::string stats_text(const Result& result);

// Each soup curve's colour on its two sides: its data-color-left / data-color-right where given,
// else its stroke colour, else its fill colour, else black.
std::vector<SideColours> curve_colours(const svg::FeatureSoup& soup);

// A CSS colour as the drawings' colours are read (svg::parse_color), each channel in [0, 1];
// nothing when `css` is not a colour.
std::optional<std::array<double, 3>> css_colour(const std::string& css);

// The curved result as the applications take it. Throws std::logic_error when it was not curved.
MeshedDrawing meshed_drawing(const Result& result);

// The whole pipeline on SVG text with the parameters (curved), as the applications take it.
// Throws what run() throws.
MeshedDrawing mesh_drawing(const Source& source, const Parameters& parameters = {});

}  // namespace curvemesh::pipeline
