#pragma once
// The part of a meshed drawing a problem lives on, cut by the pipeline for the commands that
// solve on it (app/ never cuts a mesh itself): `solve --domain`'s names, the same classification
// as `mesh --domain` (regions/faces.hpp).
#include <curvemesh/parameters.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/high_order_mesh.hpp"
#include "pipeline/meshed_drawing.hpp"

namespace curvemesh::pipeline {

struct DomainMesh {
  io::HighOrderMesh mesh;
  std::vector<int> line_origin;  // per line of `mesh`: its line in the drawing's whole mesh
};

// The triangles of the drawing's mesh in `domain`, as `mesh --domain` keeps them. Nothing when the
// domain is empty. `filled` and `painted` need a drawing meshed with its paint read
// (Parameters::regions; for `painted`, strokes as areas).
std::optional<DomainMesh> cut_domain(const MeshedDrawing& drawing, Domain domain);

// Why `domain` came out empty, for a message: "no part of the box is enclosed by its curves".
// `has_fills`, `has_strokes`: whether the drawing fills some element, strokes some as an area.
std::string empty_domain_reason(Domain domain, bool has_fills, bool has_strokes);

// A domain's name, as every command and the Python module spell it.
std::string domain_name(Domain domain);

// The domains' names, as every command and the Python module spell them (Domain's order).
std::vector<std::string> domain_names();

// `mesh` with only the nodes some triangle uses (a straight map leaves the cubic nodes unused);
// node_origin gets each kept node's number in `mesh`.
io::HighOrderMesh used_nodes(const io::HighOrderMesh& mesh, std::vector<int>& node_origin);

}  // namespace curvemesh::pipeline
