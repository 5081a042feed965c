#pragma once
// XDMF 3 output of a HighOrderMesh: FEniCSx's own format, the XML (.xdmf) and its arrays in an
// HDF5 file beside it (.h5), as dolfinx writes them and as dolfinx.io.XDMFFile reads them by
// default. Three grids share the nodes: "mesh" (the triangles: read_mesh(name="mesh")),
// "cell_tags" (each triangle's physical tag: read_meshtags(mesh, "cell_tags")) and "facet_tags"
// (each feature line's drawn element, else its kind: read_meshtags(mesh, "facet_tags") once the mesh has its facets,
// mesh.topology.create_connectivity(1, 2)). ParaView opens it too. Orders 1 and 2 only: XDMF's
// topology types stop at Triangle_6 and Edge_3 (dolfinx 0.5 reads no 10-node triangle from XDMF;
// order 3 goes through .msh). Both files depend only on the mesh.
#include <memory>
#include <string>

#include "io/high_order_mesh.hpp"

namespace curvemesh::io {

// Whether xdmf_files takes meshes of this order (1 or 2).
bool xdmf_order_supported(int order);

// The HDF5 file beside an XDMF file: its path with the extension replaced by ".h5"
// ("out/m.xdmf" -> "out/m.h5"; ".h5" appended when the name has no extension).
std::string xdmf_data_path(const std::string& xdmf_path);

struct XdmfFiles {
  std::string xml;   // the .xdmf text, naming the data file by its name alone (the two travel together)
  std::string data;  // the .h5 file's bytes
};

// An HDF5 file in memory, for xdmf_files to fill.
struct Hdf5File;
struct Hdf5FileDeleter {
  void operator()(Hdf5File* file) const noexcept;
};
using Hdf5FilePtr = std::unique_ptr<Hdf5File, Hdf5FileDeleter>;

// An HDF5 file in memory made ahead of xdmf_files: HDF5 initialised and the file's own structures
// made, a fixed few milliseconds that are most of the writing of a small mesh, which a caller with
// other work to do first (meshing) can have done on another thread. The serial HDF5 library is
// not thread-safe: nothing else may call HDF5 until this has returned. Nothing when HDF5 fails
// (xdmf_files then tries again and says why).
Hdf5FilePtr start_hdf5_file() noexcept;

// The two files for `mesh`, the XML naming the data file `data_name`, the data made in `file`
// (one of start_hdf5_file's, or a new one when none). A facet has one tag in dolfinx: a line in
// several physical groups (line_groups) carries the first drawn element's it lies on, else its
// kind's (primary, secondary, boundary); the .msh has them all. The bytes depend only on the mesh.
// Throws std::invalid_argument for an order xdmf_order_supported refuses, std::logic_error if the
// mesh has a structure_error(), std::runtime_error if HDF5 fails.
XdmfFiles xdmf_files(const HighOrderMesh& mesh, const std::string& data_name, Hdf5FilePtr file = nullptr);

}  // namespace curvemesh::io
