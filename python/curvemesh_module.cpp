// The compiled half of the Python module `curvemesh` (`curvemesh._curvemesh`): the public C++ API
// (curvemesh/curvemesh.hpp) and nothing else, bound with pybind11. The Python half
// (curvemesh/__init__.py) gives it its surface: option names, input kinds, the Mesh class.
//
// Arrays leave here as new NumPy arrays, each copied once from the mesh's vectors. The GIL is
// released while the library works (meshing, writing, checking), so Python threads mesh in
// parallel. curvemesh::Error becomes ValueError (invalid input or parameters), OSError (output)
// or RuntimeError (internal), with the message the command line prints.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "curvemesh/curvemesh.hpp"

namespace py = pybind11;

namespace {

static_assert(sizeof(std::array<double, 2>) == 2 * sizeof(double), "nodes are packed (x, y) pairs");
static_assert(sizeof(curvemesh::Curve) == 8 * sizeof(double), "a curve is 4 packed (x, y) pairs");

// A new (rows, columns) array holding a copy of `data`.
template <class T>
py::array_t<T> table(const T* data, std::size_t rows, std::size_t columns) {
  py::array_t<T> out({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(columns)});
  if (rows * columns > 0) std::memcpy(out.mutable_data(), data, rows * columns * sizeof(T));
  return out;
}

template <class T>
py::array_t<T> column(const T* data, std::size_t rows) {
  py::array_t<T> out(static_cast<py::ssize_t>(rows));
  if (rows > 0) std::memcpy(out.mutable_data(), data, rows * sizeof(T));
  return out;
}

constexpr curvemesh::LineTag kTags[] = {curvemesh::LineTag::primary, curvemesh::LineTag::secondary,
                                        curvemesh::LineTag::boundary};

// The index of each line's tag in kTags (and in LINE_TAG_NAMES).
py::array_t<std::uint8_t> line_tag_codes(const curvemesh::Mesh& m) {
  const std::vector<curvemesh::LineTag>& tags = m.line_tags();
  py::array_t<std::uint8_t> out(static_cast<py::ssize_t>(tags.size()));
  std::uint8_t* code = out.mutable_data();
  for (std::size_t i = 0; i < tags.size(); ++i) {
    std::size_t k = 0;
    while (k + 1 < std::size(kTags) && kTags[k] != tags[i]) ++k;
    code[i] = static_cast<std::uint8_t>(k);
  }
  return out;
}

// (n, 4, 2) control points as the API's curves. The library refuses a point that is not finite.
std::vector<curvemesh::Curve> curves_of(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& points) {
  if (points.ndim() != 3 || points.shape(1) != 4 || points.shape(2) != 2)
    throw py::value_error(
        "control points must have shape (n, 4, 2): one cubic Bezier curve of 4 (x, y) "
        "points per row");
  std::vector<curvemesh::Curve> curves(static_cast<std::size_t>(points.shape(0)));
  if (!curves.empty()) std::memcpy(curves.data(), points.data(), curves.size() * sizeof(curvemesh::Curve));
  return curves;
}

const char* kind_name(curvemesh::ParameterOption::Kind kind) {
  switch (kind) {
    case curvemesh::ParameterOption::Kind::number:
      return "number";
    case curvemesh::ParameterOption::Kind::integer:
      return "integer";
    case curvemesh::ParameterOption::Kind::flag:
      return "flag";
    case curvemesh::ParameterOption::Kind::choice:
      return "choice";
  }
  return "?";
}

py::list option_dicts() {
  py::list out;
  const curvemesh::Parameters defaults;
  for (const curvemesh::ParameterOption& o : curvemesh::parameter_options()) {
    py::dict d;
    d["python"] = o.python;
    d["option"] = o.option;
    d["symbol"] = o.symbol;
    d["kind"] = kind_name(o.kind);
    d["min"] = o.min;
    d["max"] = o.max;
    d["min_open"] = o.min_open;
    py::list choices;
    for (const char* c : o.choices) choices.append(c);
    d["choices"] = choices;
    d["default"] = o.get(defaults);
    d["help"] = o.help;
    out.append(d);
  }
  return out;
}

curvemesh::ParameterOption option_named(const std::string& python) {
  for (const curvemesh::ParameterOption& o : curvemesh::parameter_options())
    if (python == o.python) return o;
  throw py::key_error(python);
}

// A new int64 array of `ids`.
py::array_t<std::int64_t> id_column(const std::vector<int>& ids) {
  const std::vector<std::int64_t> wide(ids.begin(), ids.end());
  return column(wide.data(), wide.size());
}

py::dict report_dict(const curvemesh::CheckReport& r) {
  py::dict d;
  d["order"] = r.order;
  d["triangles"] = r.triangles;
  d["invalid"] = r.invalid;
  d["undecided"] = r.undecided;
  d["min_scaled_jacobian"] = r.min_scaled_jacobian;
  d["exact_fallbacks"] = r.exact_fallbacks;
  return d;
}


// curvemesh::Error as the Python exception its kind stands for, with its message.
void translate_errors() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const curvemesh::Error& e) {
      switch (e.kind()) {
        case curvemesh::Error::Kind::invalid_parameters:
        case curvemesh::Error::Kind::invalid_input:
          PyErr_SetString(PyExc_ValueError, e.what());
          break;
        case curvemesh::Error::Kind::output:
          PyErr_SetString(PyExc_OSError, e.what());
          break;
        default:
          PyErr_SetString(PyExc_RuntimeError, e.what());
          break;
      }
    }
  });
}

// Parameters and the table of their options.
void bind_parameters(py::module_& m) {
  py::class_<curvemesh::Parameters>(m, "Parameters",
                                    "The parameters (curvemesh::Parameters); fields through get/set_parameter.")
      .def(py::init<>())
      .def("validate", &curvemesh::Parameters::validate,
           "Raises ValueError naming the first inconsistent parameter by its command-line option.");
  m.def("parameter_options", &option_dicts,
        "Every option of Parameters as the command line defines it (curvemesh::parameter_options()): a list of "
        "dicts with python, option, symbol, kind, min, max, min_open, choices, default, help.");
  m.def(
      "set_parameter",
      [](curvemesh::Parameters& p, const std::string& name, double value) {
        const curvemesh::ParameterOption& o = option_named(name);
        o.check(value);  // before the field's type holds it: -1 is no count
        o.set(p, value);
      },
      "Sets the option with this Python name to a number (a flag 0 or 1, a choice its index); ValueError, "
      "with the library's message, for a value outside its range.");
  m.def(
      "get_parameter", [](const curvemesh::Parameters& p, const std::string& name) { return option_named(name).get(p); },
      "The option with this Python name as a number.");
}

// The Mesh class: its arrays, statistics, warnings and writing.
void bind_mesh(py::module_& m) {
  py::class_<curvemesh::Mesh>(m, "Mesh", "A finished mesh (curvemesh::Mesh); curvemesh.Mesh wraps it.")
      .def_property_readonly("order", &curvemesh::Mesh::order, "3 (cubic), 2 (quadratic) or 1 (linear).")
      .def(
          "nodes",
          [](const curvemesh::Mesh& self) {
            return table(reinterpret_cast<const double*>(self.nodes().data()), self.node_count(), 2);
          },
          "A new float64 array (N, 2) of the nodes.")
      .def(
          "triangles",
          [](const curvemesh::Mesh& self) {
            return table(self.triangles().data(), self.triangle_count(),
                         static_cast<std::size_t>(self.nodes_per_triangle()));
          },
          "A new int64 array (M, 10), (M, 6) or (M, 3) of node ids, in Gmsh's order.")
      .def(
          "lines",
          [](const curvemesh::Mesh& self) {
            return table(self.lines().data(), self.line_count(),
                         static_cast<std::size_t>(self.nodes_per_line()));
          },
          "A new int64 array (K, 4), (K, 3) or (K, 2) of node ids: both ends, then the inner nodes.")
      .def("line_tag_codes", &line_tag_codes, "A new uint8 array (K,): each line's index in LINE_TAG_NAMES.")
      .def(
          "line_curves",
          [](const curvemesh::Mesh& self) {
            return column(self.line_curves().data(), self.line_curves().size());
          },
          "A new int64 array (K,): the input curve each line lies on, -1 for the box's sides.")
      .def(
          "triangle_groups", [](const curvemesh::Mesh& self) { return id_column(self.triangle_groups()); },
          "A new int64 array (M,): each triangle's group id.")
      .def(
          "line_groups",
          [](const curvemesh::Mesh& self) {
            py::list out;
            for (const std::vector<int>& ids : self.line_groups()) out.append(id_column(ids));
            return out;
          },
          "A new list of K new int64 arrays: each line's group ids, ascending.")
      .def(
          "groups",
          [](const curvemesh::Mesh& self) {
            py::list out;
            for (const curvemesh::Group& g : self.groups()) out.append(py::make_tuple(g.dimension, g.id, g.name));
            return out;
          },
          "A new list of (dimension, id, name) of every group, by dimension then id.")
      .def_property_readonly("stats_json", &curvemesh::Mesh::stats_json, "The statistics as JSON text.")
      .def_property_readonly("warnings", &curvemesh::Mesh::warnings, "What the reader warned about.")
      .def(
          "write",
          [](const curvemesh::Mesh& self, const std::string& path, int msh_version) {
            py::gil_scoped_release release;
            self.write(path, msh_version);
          },
          py::arg("path"), py::arg("msh_version") = 41,
          "Writes the mesh by the path's extension (.msh, .vtu, .xdmf, .svg); `path` is bytes or str.");
}

// Meshing and checking, the GIL released while the library works.
void bind_functions(py::module_& m) {
  m.def(
      "mesh_file",
      [](const std::string& path, curvemesh::Parameters parameters) {
        py::gil_scoped_release release;
        return curvemesh::mesh_file(path, parameters);
      },
      py::arg("path"), py::arg("parameters"), "Meshes an SVG (or .poly) file; `path` is bytes or str.");
  m.def(
      "mesh_svg",
      [](const std::string& text, curvemesh::Parameters parameters, const std::string& name) {
        py::gil_scoped_release release;
        return curvemesh::mesh_svg(text, parameters, name);
      },
      py::arg("text"), py::arg("parameters"), py::arg("name") = "<svg>", "Meshes SVG text.");
  m.def(
      "mesh_curves",
      [](const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
         curvemesh::Parameters parameters) {
        std::vector<curvemesh::Curve> curves = curves_of(points);
        py::gil_scoped_release release;
        return curvemesh::mesh_curves(curves, parameters);
      },
      py::arg("control_points"), py::arg("parameters"),
      "Meshes cubic Bezier curves given as a float64 array (n, 4, 2) of control points.");
  m.def(
      "check_file",
      [](const std::string& path, bool exact, int threads) {
        curvemesh::CheckReport r;
        {
          py::gil_scoped_release release;
          r = curvemesh::check_file(path, {.exact = exact, .threads = threads});
        }
        return report_dict(r);
      },
      py::arg("path"), py::arg("exact") = false, py::arg("threads") = 0,
      "Checks a Gmsh .msh file (every element in rationals when exact); a dict of the verdict.");
  m.def(
      "check",
      [](const curvemesh::Mesh& mesh, bool exact, int threads) {
        curvemesh::CheckReport r;
        {
          py::gil_scoped_release release;
          r = curvemesh::check(mesh, {.exact = exact, .threads = threads});
        }
        return report_dict(r);
      },
      py::arg("mesh"), py::arg("exact") = false, py::arg("threads") = 0,
      "Checks a mesh as its .msh file would hold it (every element in rationals when exact); a dict "
      "of the verdict.");
}

}  // namespace

PYBIND11_MODULE(_curvemesh, m) {
  m.doc() =
      "The compiled part of curvemesh: the public C++ API bound as it is. Use the package `curvemesh`, "
      "not this module.";
  translate_errors();

  m.def("version", &curvemesh::version, "The library's version, e.g. '0.1.0'.");

  py::tuple names(std::size(kTags));
  for (std::size_t k = 0; k < std::size(kTags); ++k) names[k] = py::str(curvemesh::tag_name(kTags[k]));
  m.attr("LINE_TAG_NAMES") = names;

  bind_parameters(m);
  bind_mesh(m);
  bind_functions(m);
}
