#pragma once
// The part of a meshed drawing a problem lives on, cut by the pipeline for the commands that
// solve on it (app/ never cuts a mesh itself): `solve --domain`'s names, the same classification
// as `mesh --domain` (regions/faces.hpp).
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

// The triangles of the drawing's mesh in the domain named `name`: box (or all), filled, evenodd
// (or inside), or outside (evenodd's complement). Nothing when the domain is empty. `filled`
// needs a drawing meshed with its paint read (RunOptions::regions).
std::optional<DomainMesh> cut_domain(const MeshedDrawing& drawing, const std::string& name);

// The names cut_domain takes.
std::vector<std::string> domain_names();

// `mesh` with only the nodes some triangle uses (a straight map leaves the cubic nodes unused);
// node_origin gets each kept node's number in `mesh`.
io::HighOrderMesh used_nodes(const io::HighOrderMesh& mesh, std::vector<int>& node_origin);

}  // namespace curvemesh::pipeline
