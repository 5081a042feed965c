#pragma once
// Gmsh .msh input: ASCII 4.1 and 2.2 files holding a planar triangle mesh of order 1, 2 or 3
// (element types 2, 9, 21), with line elements (1, 8, 26) of the same order; point elements
// (15) are skipped, other $-sections than $MeshFormat, $PhysicalNames, $Entities, $Nodes and
// $Elements are ignored. Node tags may be any positive integers; nodes keep the order of the
// file, elements too. An element takes the first physical tag of its entity (4.1) or its first
// tag (2.2); 0 when it has none. A line also keeps its entity's further physical tags (4.1) as its
// further groups; a 2.2 line written once per group is read as that many lines.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "io/high_order_mesh.hpp"

namespace curvemesh::io {

// Anything the reader cannot take: the message names the line and section and says what is
// wrong (binary file, parametric nodes, z ≠ 0, non-finite coordinates, mixed orders, unknown
// element types, missing nodes, truncated or malformed sections).
class MshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What `curvemesh check` reads at most by default, in MiB: a cubic mesh of two million triangles
// (the default limit on triangles) takes about 0.5 GiB as .msh.
inline constexpr double kDefaultMaxMshMb = 2048;

HighOrderMesh parse_msh(std::string_view text);
// As parse_msh; the message starts with the path. Also throws MshError if the file cannot be read,
// is not a regular file (a FIFO or a device is refused without waiting on it) or is larger than
// `max_bytes` (the message names `limit_option`, what raises the limit).
HighOrderMesh read_msh(const std::string& path, std::uint64_t max_bytes, const std::string& limit_option);

}  // namespace curvemesh::io
