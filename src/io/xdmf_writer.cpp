#include "io/xdmf_writer.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <span>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/hdf5_library.hpp"

namespace curvemesh::io {

// An HDF5 file made in memory (the core driver, no backing store), so that its bytes go through
// the same all-or-nothing, no-link writing as every other output. The driver grows its buffer by
// `expected_bytes` at a time: the file's size foreseen, so that it is allocated once, and no
// larger (each page of memory first touched costs).
struct Hdf5File {
  explicit Hdf5File(std::size_t expected_bytes) {
    fapl_ = h5.Pcreate(h5.P_FILE_ACCESS);
    if (fapl_ < 0 || h5.Pset_fapl_core(fapl_, expected_bytes, 0) < 0) throw std::runtime_error("HDF5: no in-memory file");
    file_ = h5.Fcreate("curvemesh.h5", Hdf5Library::F_ACC_TRUNC, H5P_DEFAULT, fapl_);
    if (file_ < 0) throw std::runtime_error("HDF5: cannot create an in-memory file");
  }
  ~Hdf5File() {
    if (file_ >= 0) h5.Fclose(file_);
    if (fapl_ >= 0) h5.Pclose(fapl_);
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  // Makes the group at `path` ("/mesh").
  void group(const std::string& path) {
    const hid_t properties = untimed(h5.Pcreate(h5.P_GROUP_CREATE));
    const hid_t g = h5.Gcreate2(file_, path.c_str(), H5P_DEFAULT, properties, H5P_DEFAULT);
    h5.Pclose(properties);
    if (g < 0) throw std::runtime_error("HDF5: cannot make group " + path);
    h5.Gclose(g);
  }

  // Writes a (rows, columns) array at `path` ("/mesh/topology"), in a group made before.
  template <class T>
  void write(const std::string& path, const std::vector<T>& values, std::size_t columns) {
    const hsize_t dims[2] = {values.size() / std::max<std::size_t>(columns, 1), columns};
    const hid_t type = std::is_floating_point_v<T> ? h5.T_NATIVE_DOUBLE : h5.T_NATIVE_INT64;
    const hid_t space = h5.Screate_simple(columns > 1 ? 2 : 1, dims, nullptr);
    const hid_t properties = untimed(h5.Pcreate(h5.P_DATASET_CREATE));
    const hid_t set = h5.Dcreate2(file_, path.c_str(), type, space, H5P_DEFAULT, properties, H5P_DEFAULT);
    const herr_t written = set < 0 ? -1 : h5.Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    if (set >= 0) h5.Dclose(set);
    h5.Pclose(properties);
    h5.Sclose(space);
    if (written < 0) throw std::runtime_error("HDF5: cannot write " + path);
  }

  // The file's bytes.
  std::string bytes() {
    if (h5.Fflush(file_, H5F_SCOPE_GLOBAL) < 0) throw std::runtime_error("HDF5: cannot flush");
    const ssize_t size = h5.Fget_file_image(file_, nullptr, 0);
    std::string out(size > 0 ? std::size_t(size) : 0, '\0');
    if (size <= 0 || h5.Fget_file_image(file_, out.data(), out.size()) != size)
      throw std::runtime_error("HDF5: cannot read the file image");
    return out;
  }

 private:
  // Object creation properties without the times HDF5 records by default: the same mesh gives
  // the same bytes.
  hid_t untimed(hid_t properties) {
    if (properties < 0 || h5.Pset_obj_track_times(properties, 0) < 0) throw std::runtime_error("HDF5: no properties");
    return properties;
  }

  Hdf5Library h5;  // first: the last destroyed
  hid_t fapl_ = -1, file_ = -1;
};

// The step of a file made before its size is known (start_hdf5_file): a small mesh's in one.
constexpr std::size_t kStartedFileStep = std::size_t(1) << 18;

void Hdf5FileDeleter::operator()(Hdf5File* file) const noexcept {
  delete file;
}

namespace {

// XDMF's names of the element types. Its node orders are VTK's, which for triangles up to order 2
// and lines are Gmsh's (the corners, then the inner nodes edge by edge): the arrays go as they are.
const char* triangle_type(int order) {
  return order == 1 ? "Triangle" : "Triangle_6";
}
const char* line_type(int order) {
  return order == 1 ? "Polyline" : "Edge_3";
}

std::vector<std::int64_t> wide(std::span<const int> v) {
  return std::vector<std::int64_t>(v.begin(), v.end());
}

// The XML of one DataItem: a (rows, columns) array in the data file.
std::string data_item(const std::string& data_name, const std::string& path, std::size_t rows, int columns,
                      bool real) {
  std::ostringstream s;
  s << "<DataItem Dimensions=\"" << rows;
  if (columns > 1) s << ' ' << columns;
  s << "\" NumberType=\"" << (real ? "Float" : "Int") << "\" Precision=\"8\" Format=\"HDF\">" << data_name << ':'
    << path << "</DataItem>";
  return s.str();
}

// The one tag dolfinx keeps of a line in several groups: the most specific, the first drawn
// element it lies on (what a boundary condition selects), else what it lies on.
int facet_tag(const HighOrderMesh& m, int l) {
  if (!m.line_groups.empty())
    for (int g : m.line_groups[std::size_t(l)])
      if (g >= kFirstDrawingGroup) return g;
  return m.line_physical[std::size_t(l)];
}

// Each line's facet tag.
std::vector<int> facet_tags(const HighOrderMesh& m) {
  std::vector<int> tags(std::size_t(m.line_count()));
  for (int l = 0; l < m.line_count(); ++l) tags[std::size_t(l)] = facet_tag(m, l);
  return tags;
}

// A grid of elements with their tags on the nodes of the grid "mesh" (referred to, not repeated),
// its arrays written to `h5` under /NAME.
void tag_grid(std::ostream& xml, Hdf5File& h5, const std::string& data_name, const std::string& name,
              const char* type, int size, const std::vector<int>& nodes, const std::vector<int>& tags) {
  h5.group("/" + name);
  h5.write("/" + name + "/topology", wide(nodes), std::size_t(size));
  h5.write("/" + name + "/values", wide(tags), 1);
  xml << "    <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
      << "      <xi:include xpointer=\"xpointer(/Xdmf/Domain/Grid[@Name='mesh']/Geometry)\"/>\n"
      << "      <Topology TopologyType=\"" << type << "\" NumberOfElements=\"" << tags.size()
      << "\" NodesPerElement=\"" << size << "\">\n"
      << "        " << data_item(data_name, "/" + name + "/topology", tags.size(), size, false) << "\n"
      << "      </Topology>\n"
      << "      <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
      << "        " << data_item(data_name, "/" + name + "/values", tags.size(), 1, false) << "\n"
      << "      </Attribute>\n"
      << "    </Grid>\n";
}

}  // namespace

bool xdmf_order_supported(int order) {
  return order == 1 || order == 2;
}

std::string xdmf_data_path(const std::string& xdmf_path) {
  std::filesystem::path p(xdmf_path);
  if (p.has_extension() && p.filename() != p.extension()) p.replace_extension(".h5");
  else p += ".h5";
  return p.string();
}

Hdf5FilePtr start_hdf5_file() noexcept {
  try {
    return Hdf5FilePtr(new Hdf5File(kStartedFileStep));
  } catch (...) {
    return nullptr;
  }
}

XdmfFiles xdmf_files(const HighOrderMesh& m, const std::string& data_name, Hdf5FilePtr file) {
  if (!xdmf_order_supported(m.order))
    throw std::invalid_argument("XDMF has no triangle of order " + std::to_string(m.order) + " (orders 1 and 2)");
  if (auto error = m.structure_error()) throw std::logic_error("xdmf: " + *error);
  // The arrays' bytes (the triangles twice: the mesh's and the cell tags' topology), and room for
  // HDF5's own structures (a few kilobytes).
  const std::size_t values = 2 * m.nodes.size() + 2 * m.triangles.size() + m.triangle_physical.size() +
                             m.lines.size() + m.line_physical.size();
  if (!file) file.reset(new Hdf5File(8 * values + (std::size_t(1) << 16)));
  Hdf5File& h5 = *file;
  std::vector<double> xy;
  xy.reserve(2 * m.nodes.size());
  for (const geometry::Vec2& p : m.nodes) xy.insert(xy.end(), {p.x(), p.y()});
  h5.group("/mesh");
  h5.write("/mesh/geometry", xy, 2);
  h5.write("/mesh/topology", wide(m.triangles), std::size_t(m.triangle_size()));
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
      << "      <Topology TopologyType=\"" << triangle_type(m.order) << "\" NumberOfElements=\"" << m.triangle_count()
      << "\" NodesPerElement=\"" << m.triangle_size() << "\">\n"
      << "        " << data_item(data_name, "/mesh/topology", m.triangle_count(), m.triangle_size(), false) << "\n"
      << "      </Topology>\n"
      << "      <Geometry GeometryType=\"XY\">\n"
      << "        " << data_item(data_name, "/mesh/geometry", m.nodes.size(), 2, true) << "\n"
      << "      </Geometry>\n"
      << "    </Grid>\n";
  tag_grid(xml, h5, data_name, "cell_tags", triangle_type(m.order), m.triangle_size(), m.triangles,
           m.triangle_physical);
  tag_grid(xml, h5, data_name, "facet_tags", line_type(m.order), m.line_size(), m.lines, facet_tags(m));
  xml << "  </Domain>\n"
      << "</Xdmf>\n";
  return {xml.str(), h5.bytes()};
}

}  // namespace curvemesh::io
