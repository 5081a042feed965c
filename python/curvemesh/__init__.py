"""curvemesh: coarse, curved, analysis-ready triangle meshes from vector drawings.

The TriWild method (Hu et al., SIGGRAPH 2019) from Python: read a drawing (an SVG file, SVG
text, or cubic Bezier curves given by their control points), mesh it, and get the mesh as NumPy
arrays, as files, or as a meshio mesh.

    import curvemesh
    m = curvemesh.mesh("drawing.svg", edge_length=0.02)
    m.nodes.shape, m.triangles.shape      # (N, 2) float64, (M, 10) int64
    m.write("drawing.msh")                # the very file `curvemesh mesh` writes

Options are the command line's long options with "_" for "-", defined once for both by the
library (curvemesh.OPTIONS lists them with their defaults): the method's (``mu``, ``epsilon``,
``edge_length``, ``order``, ...; ``features=False`` for ``--no-features``; lengths relative to
the diagonal of the drawing's bounding box), what the run gives out (``regions``, ``domain``,
``stop_after``) and the limits (``max_input_mb``, ``max_elements``, ``max_curves``,
``max_triangles``), which bound what a drawing may cost: beyond one, ValueError names it.

Errors: an unreadable drawing or an invalid option value raises ValueError with the message the
command line prints; an unknown option or a value of the wrong type raises TypeError; a file
that cannot be written raises OSError; an internal failure (a mesh that could not be certified)
raises RuntimeError. The library releases the GIL while it meshes, so threads mesh in parallel.
"""

import json
import numbers
import operator
import os
import warnings

import numpy as np

from . import _curvemesh

__all__ = ["Mesh", "CurvemeshWarning", "mesh", "mesh_curves", "check", "OPTIONS", "__version__"]

__version__ = _curvemesh.version()

# Python keyword -> the option as the library defines it (curvemesh::parameter_options(): the
# command line's option, kind, range, choices, default, help): one definition serves both.
_OPTIONS = {o["python"]: o for o in _curvemesh.parameter_options()}


def _default(option):
    value = option["default"]
    if option["kind"] == "flag":
        return bool(value)
    if option["kind"] == "choice":
        return option["choices"][int(value)]
    return int(value) if option["kind"] == "integer" else value


#: The options mesh() and mesh_curves() take, each with its default.
OPTIONS = {name: _default(o) for name, o in _OPTIONS.items()}

# --msh-version's names for the Gmsh formats write() takes.
_MSH_VERSIONS = {"4.1": 41, "41": 41, 41: 41, "2.2": 22, "22": 22, 22: 22}


class CurvemeshWarning(UserWarning):
    """What the reader warns about in a drawing (an element it skipped, a drawing with nothing
    drawn), the warnings the command line prints: mesh() and mesh_curves() issue one each
    through Python's warnings module, so a filter can silence them or make them errors."""


def _warned(mesh, name):
    """`mesh`, each of its warnings issued as a CurvemeshWarning of the caller's caller."""
    for text in mesh.warnings:
        warnings.warn(f"{name}: {text}", CurvemeshWarning, stacklevel=3)
    return mesh


_LINE_TAG_NAMES = np.array(_curvemesh.LINE_TAG_NAMES)


def _number(name, option, value):
    """`value` as the number the library stores for `option`; TypeError for a value of the wrong
    type, ValueError for a name that is not one of a choice's or an integer beyond any range."""
    kind = option["kind"]
    if kind == "flag":
        if not isinstance(value, (bool, np.bool_)):
            raise TypeError(f"{name} must be True or False, not {type(value).__name__}")
        return 1.0 if value else 0.0
    if kind == "choice":
        if not isinstance(value, str):
            raise TypeError(f"{name} must be a str, not {type(value).__name__}")
        if value not in option["choices"]:
            raise ValueError(f"{option['option']} ({value!r}) must be one of {', '.join(option['choices'])}")
        return float(option["choices"].index(value))
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be a number, not bool")
    if kind == "integer":
        try:
            value = operator.index(value)
        except TypeError:
            raise TypeError(f"{name} must be an integer, not {type(value).__name__}") from None
        if not -(2**53) <= value <= option["max"]:  # beyond what the field holds; below its range the library says
            raise ValueError(f"{option['option']} ({value}) is out of range")
        return float(value)
    if not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a number, not {type(value).__name__}")
    return float(value)


def _parameters(function, options):
    """The C++ parameters for `options`; TypeError for an unknown option or a value of the wrong
    type, ValueError (the library's message) for an invalid value."""
    p = _curvemesh.Parameters()
    for name, value in options.items():
        if name not in _OPTIONS:
            raise TypeError(f"{function}() got an unexpected keyword argument '{name}'")
        number = _number(name, _OPTIONS[name], value)
        if name == "linear" and number and options.get("order", 1) != 1:
            raise ValueError(f"linear=True is order=1, not order={options['order']}")
        _curvemesh.set_parameter(p, name, number)
    p.validate()
    return p


def _path(path):
    """A path (str or os.PathLike) as the bytes the file system takes; ValueError for an embedded
    NUL, as Python's own open() (the file system would end the name there)."""
    encoded = os.fsencode(path)
    if b"\0" in encoded:
        raise ValueError("embedded null byte")
    return encoded


class Mesh:
    """A finished triangle mesh, as mesh() and mesh_curves() return it.

    Curved (order 3): cubic triangles of 10 nodes and feature lines of 4; or (``order=2``)
    quadratic triangles of 6 nodes and lines of 3; every triangle's Jacobian certified positive.
    Linear (``order=1``, ``linear=True``): triangles of 3 nodes, lines of 2. Coordinates are in
    the drawing's units (SVG user space: y points down).

    The arrays are read-only and made once, on first use.
    """

    __slots__ = ("_mesh", "_arrays")

    def __init__(self, compiled_mesh):
        """Wraps the compiled library's mesh; use mesh() or mesh_curves() to make one."""
        if not isinstance(compiled_mesh, _curvemesh.Mesh):
            raise TypeError("use curvemesh.mesh() or curvemesh.mesh_curves() to make a Mesh")
        self._mesh = compiled_mesh
        self._arrays = {}

    def _array(self, name, make):
        a = self._arrays.get(name)
        if a is None:
            a = make()
            a.flags.writeable = False
            self._arrays[name] = a
        return a

    @property
    def order(self):
        """3 for a cubic mesh (10-node triangles), 2 for a quadratic one (6-node triangles), 1 for a
        linear one (3-node triangles)."""
        return self._mesh.order

    @property
    def nodes(self):
        """The nodes' (x, y): float64 array of shape (N, 2)."""
        return self._array("nodes", self._mesh.nodes)

    @property
    def triangles(self):
        """Node indices per triangle: int64 array (M, 10), (M, 6) when quadratic, (M, 3) when
        linear.

        Gmsh's node order: the three corners counter-clockwise (as seen with y up), then the
        nodes on each edge 0-1, 1-2, 2-0 from its first corner on (two, or the middle one when
        quadratic), then the centre (cubic).
        """
        return self._array("triangles", self._mesh.triangles)

    @property
    def lines(self):
        """Node indices per feature line: int64 array (K, order + 1): (K, 4), (K, 3) when
        quadratic, (K, 2) when linear; both ends first, then the inner nodes (Gmsh's order)."""
        return self._array("lines", self._mesh.lines)

    @property
    def line_tags(self):
        """What each feature line lies on: a str array (K,) of "primary" (a curve of the
        drawing, followed by curved edges), "secondary" (a piece of a curve kept within
        epsilon by straight edges) or "boundary" (a side of the meshed box)."""
        return self._array("line_tags", lambda: _LINE_TAG_NAMES[self._mesh.line_tag_codes()])

    @property
    def line_curves(self):
        """The input curve each feature line lies on: int64 array (K,), the index of a curve
        given to mesh_curves() or of the reader's curve in document order; -1 for the box's
        sides."""
        return self._array("line_curves", self._mesh.line_curves)

    @property
    def stats(self):
        """The statistics `curvemesh mesh --stats` writes (counts, quality, seconds per stage),
        as a new dict."""
        return json.loads(self._mesh.stats_json)

    @property
    def warnings(self):
        """What the reader warned about (elements it skipped, a drawing with nothing drawn), as a
        new list of str."""
        return list(self._mesh.warnings)

    def write(self, path, msh_version="4.1"):
        """Writes the mesh to `path` (str or os.PathLike) by its extension: ".msh" (Gmsh ASCII,
        ``msh_version`` "4.1" or "2.2" as the command line's --msh-version spells it, or 41 or 22),
        ".vtu" (VTK quadratic or Lagrange triangles), ".xdmf" (XDMF for FEniCSx, its HDF5 data in
        the ".h5" file of the same name beside it; orders 1 and 2) or ".svg" (a drawing of the
        mesh). The file is byte for byte the one the command line writes for the same drawing and
        options, written whole or not at all (an XDMF file and its data both or neither). Raises
        OSError when it cannot be written or the extension is none of these, ValueError for a path
        with a NUL, XDMF of a cubic mesh, or a path that is the drawing the mesh was read from."""
        version = _MSH_VERSIONS.get(msh_version) if isinstance(msh_version, (str, int)) else None
        if version is None or isinstance(msh_version, (bool, np.bool_)):
            raise ValueError(f'msh_version must be "4.1" or "2.2" (41 or 22), not {msh_version!r}')
        self._mesh.write(_path(path), version)

    @property
    def triangle_groups(self):
        """Each triangle's group id (a key of ``groups``): int64 array (M,), its region's with
        ``regions=True``, else 4 (domain)."""
        return self._array("triangle_groups", self._mesh.triangle_groups)

    @property
    def line_groups(self):
        """The ids of every group each feature line is in (keys of ``groups``): a tuple of K int64
        arrays, each ascending: its kind's (1 primary, 2 secondary, 3 boundary), 5 when it lies on
        the border of the meshed domain, then the group of each drawn element whose curve it lies
        on (several where their curves coincide)."""
        groups = self._arrays.get("line_groups")
        if groups is None:
            groups = tuple(self._mesh.line_groups())
            for a in groups:
                a.flags.writeable = False
            self._arrays["line_groups"] = groups
        return groups

    @property
    def groups(self):
        """The physical groups a solver selects lines or triangles by, as the .msh file numbers
        and names them: a new dict {id: (dimension, name)}, dimension 1 for lines and 2 for
        triangles, by dimension then id. Ids are unique across dimensions: 1 primary, 2 secondary,
        3 boundary, 4 domain, 5 border, then one per drawn element (its id, else TAG#INDEX), then
        one per region (``regions=True``), the same whatever ``domain``."""
        return {g: (dim, name) for dim, g, name in self._mesh.groups()}

    def to_meshio(self):
        """The mesh as a meshio.Mesh: the mesh meshio reads from the .msh file write() makes, with
        every group as a cell set.

        Points are (N, 3) with z = 0 (what meshio's readers give and its writers take). Cells come
        as in the file: one block per set of groups its lines are in (``line_groups``; sets in
        ascending order, lines in the order of ``lines`` within each), then one block per triangle
        group (ascending; triangles in the order of ``triangles`` within each); "line4" and
        "triangle10" ("line3" and "triangle6" when quadratic, "line" and "triangle" when linear),
        whose node order in meshio is Gmsh's, the order of ``triangles`` and ``lines``.

        Cell data "gmsh:physical" holds each cell's first (lowest) group, as meshio reads the file,
        and "gmsh:geometrical" its entity (one per block); cell_sets hold every group by its name,
        as a set over the blocks (a drawn element's outline and its region share the name: the set
        holds both); field_data maps each name to [id, dimension] (for a shared name, the
        region's). Point data "gmsh:dim_tags" gives the nodes' entities, classified as Gmsh does
        (those of a feature line on its curve), so that meshio writes Gmsh 4.1 files of it that it
        reads back (write()'s own files put every node on the surface). Gmsh 2.2 needs none of it.

        meshio cannot write "triangle10" to VTU: for a cubic VTU, use write("mesh.vtu").
        """
        import meshio

        points = np.zeros((len(self.nodes), 3))
        points[:, :2] = self.nodes
        line_type, triangle_type = {3: ("line4", "triangle10"), 2: ("line3", "triangle6"), 1: ("line", "triangle")}[
            self.order
        ]
        blocks = [(1, key, rows) for key, rows in _blocks([tuple(g) for g in self.line_groups])]
        blocks += [(2, key, rows) for key, rows in _blocks([(t,) if t > 0 else () for t in self.triangle_groups])]
        cells, physical, geometrical = [], [], []
        entity = {1: 0, 2: 0}
        for dim, key, rows in blocks:
            entity[dim] += 1
            data = self.lines[rows] if dim == 1 else self.triangles[rows]
            cells.append(meshio.CellBlock(line_type if dim == 1 else triangle_type, data))
            physical.append(np.full(len(rows), key[0] if key else 0, dtype=np.int64))
            geometrical.append(np.full(len(rows), entity[dim], dtype=np.int64))
        groups = self.groups
        cell_sets = {}
        for g, (dim, name) in groups.items():
            members = cell_sets.setdefault(name, [np.empty(0, dtype=np.int64) for _ in blocks])
            for b, (block_dim, key, rows) in enumerate(blocks):
                if block_dim == dim and g in key:
                    members[b] = np.arange(len(rows), dtype=np.int64)
        field_data = {name: np.array([g, dim]) for g, (dim, name) in groups.items()}
        return meshio.Mesh(
            points,
            cells,
            point_data={"gmsh:dim_tags": self._node_entities(blocks)},
            cell_data={"gmsh:physical": physical, "gmsh:geometrical": geometrical},
            field_data=field_data,
            cell_sets=cell_sets,
        )

    def _node_entities(self, blocks):
        """(dim, tag) of the Gmsh entity of each node, as Gmsh classifies nodes: a node of a
        feature line on that line's curve entity, else on the surface entity of its triangles
        (where several meet, the first entity's). meshio's Gmsh 4.1 writer makes its entities of
        these, so each entity with cells must hold a node: one whose cells are all on the
        others' takes its last cell's last node."""
        dim_tags = np.empty((len(self.nodes), 2), dtype=np.int64)
        dim_tags[:] = (2, 1)
        cells = {1: [self.lines[rows] for dim, _, rows in blocks if dim == 1],
                 2: [self.triangles[rows] for dim, _, rows in blocks if dim == 2]}
        for dim in (2, 1):
            for e in reversed(range(len(cells[dim]))):
                dim_tags[cells[dim][e].ravel()] = (dim, e + 1)
        for dim in (1, 2):
            for e, data in enumerate(cells[dim]):
                if not np.any((dim_tags[:, 0] == dim) & (dim_tags[:, 1] == e + 1)):
                    dim_tags[data[-1, -1]] = (dim, e + 1)
        return dim_tags

    def __repr__(self):
        return (
            f"<curvemesh.Mesh order={self.order}: {len(self.nodes)} nodes, "
            f"{len(self.triangles)} triangles, {len(self.lines)} lines>"
        )


def _blocks(keys):
    """[(key, rows)]: the rows of `keys` by key, keys ascending, rows in order within each (how the
    .msh file makes its entities: one per set of groups)."""
    rows = {}
    for i, key in enumerate(keys):
        rows.setdefault(key, []).append(i)
    return [(key, np.array(rows[key], dtype=np.int64)) for key in sorted(rows)]


def _is_svg_text(svg):
    return isinstance(svg, str) and svg.lstrip().startswith("<")


def mesh(svg, **options):
    """Meshes a drawing and returns a Mesh.

    `svg` is a path (str or os.PathLike such as pathlib.Path) to an SVG file (gzip-compressed
    too, .svgz; or a Triangle .poly file), or SVG text: a str that starts with "<" after leading
    white space. `options`
    are the command line's long options with "_" for "-":

{options}

    and features (False is --no-features); see curvemesh.OPTIONS for their defaults. Raises
    ValueError with the command line's message when the drawing cannot be read or an option's
    value is invalid, TypeError for an unknown option. Each warning of the reader (Mesh.warnings)
    is issued as a CurvemeshWarning, "INPUT: TEXT" as the command line prints it.
    """
    parameters = _parameters("mesh", options)
    if _is_svg_text(svg):
        return _warned(Mesh(_curvemesh.mesh_svg(svg, parameters)), "<svg>")
    if not isinstance(svg, (str, os.PathLike)):
        raise TypeError(f"svg must be a path or SVG text, not {type(svg).__name__}")
    return _warned(Mesh(_curvemesh.mesh_file(_path(svg), parameters)), os.fspath(svg))


def mesh_curves(control_points, **options):
    """Meshes cubic Bezier curves and returns a Mesh.

    `control_points` is a float array-like of shape (n, 4, 2): one cubic Bezier curve per row,
    its four (x, y) control points. The curves are meshed as the SVG reader's curves would be
    (no fill, no colour); Mesh.line_curves refers to them by row. `options` are those of mesh().
    Raises ValueError for a wrong shape or a point that is not finite.
    """
    parameters = _parameters("mesh_curves", options)
    points = np.asarray(control_points, dtype=np.float64)
    if points.ndim != 3 or points.shape[1:] != (4, 2):
        raise ValueError(
            f"control_points must have shape (n, 4, 2): one cubic Bezier curve of 4 (x, y) points per "
            f"row; got shape {points.shape}"
        )
    return _warned(Mesh(_curvemesh.mesh_curves(np.ascontiguousarray(points), parameters)), "<curves>")


def check(path_or_mesh, exact=False, threads=0):
    """The verdict of `curvemesh check` on a Gmsh .msh file (a path: str or os.PathLike) or on a
    Mesh (as its .msh file holds it): a dict with "order", "triangles", "invalid" (elements not
    certified positive: 0 for a valid mesh), "undecided" (of those, the ones the exact test could
    not decide), "min_scaled_jacobian" and "exact_fallbacks" (the elements decided with exact
    rationals: those the certificate in doubles, with its rigorous error bound, left undecided).
    With exact=True (`--exact`) every element is decided with rationals: the same verdicts, slower.
    threads: how many threads the check may use (the option `threads` of mesh(); 0: every hardware
    thread); the verdicts are the same. Raises ValueError when the file cannot be read or threads
    is out of range, TypeError when threads is not an integer, as mesh() does."""
    threads = int(_curvemesh.get_parameter(_parameters("check", {"threads": threads}), "threads"))
    if isinstance(path_or_mesh, Mesh):
        return _curvemesh.check(path_or_mesh._mesh, bool(exact), threads)
    if not isinstance(path_or_mesh, (str, os.PathLike)):
        raise TypeError(f"check() takes a path or a Mesh, not {type(path_or_mesh).__name__}")
    return _curvemesh.check_file(_path(path_or_mesh), bool(exact), threads)


def _option_list(indent, width=100):
    """The Python names of the options, wrapped for a docstring."""
    lines, line = [], indent
    for name in _OPTIONS:
        if name == "features":
            continue
        piece = name + ", "
        if len(line) + len(piece) > width:
            lines.append(line.rstrip())
            line = indent
        line += piece
    lines.append(line.rstrip().rstrip(","))
    return "\n".join(lines)


mesh.__doc__ = mesh.__doc__.replace("{options}", _option_list(" " * 8))
