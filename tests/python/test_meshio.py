"""Mesh.to_meshio(): the mesh meshio reads from our own .msh file, node order and blocks included,
with every group as a cell set; meshio writes it (Gmsh 4.1 and 2.2; VTU when linear or quadratic)
and reads back the same geometry."""
import numpy as np
import pytest

import curvemesh

meshio = pytest.importorskip("meshio")


def cells_by_type(m):
    """{cell type: sorted list of (physical tag, the cell's node coordinates in cell order)}:
    the geometry, independent of node numbering and of cell order, dependent on node order."""
    physical = m.cell_data.get("gmsh:physical")
    out = {}
    for b, block in enumerate(m.cells):
        xyz = m.points[block.data]
        if xyz.shape[-1] == 2:
            xyz = np.concatenate([xyz, np.zeros(xyz.shape[:-1] + (1,))], axis=-1)
        tags = physical[b] if physical is not None else np.zeros(len(block.data), dtype=int)
        rows = out.setdefault(block.type, [])
        rows += [(int(t), tuple(c.ravel().tolist())) for t, c in zip(tags, xyz)]
    return {k: sorted(v) for k, v in out.items()}


def assert_same_geometry(a, b, tags=True):
    ga, gb = cells_by_type(a), cells_by_type(b)
    assert set(ga) == set(gb)
    for cell_type in ga:
        if tags:
            assert ga[cell_type] == gb[cell_type], cell_type
        else:
            assert [c for _, c in ga[cell_type]] == [c for _, c in gb[cell_type]], cell_type


ORDERS = {"cubic": 3, "quadratic": 2, "linear": 1}
# meshio's cell types per order: (lines, triangles).
CELL_TYPES = {1: ("line", "triangle"), 2: ("line3", "triangle6"), 3: ("line4", "triangle10")}


@pytest.fixture(scope="module", params=[(o, r) for o in ORDERS for r in (False, True)],
                ids=[f"{o}{'-regions' if r else ''}" for o in ORDERS for r in (False, True)])
def case(request, examples, tmp_path_factory):
    name, regions = request.param
    order = ORDERS[name]
    m = curvemesh.mesh(examples / "overlapping-shapes.svg", order=order, regions=regions)
    folder = tmp_path_factory.mktemp(name)
    m.write(folder / "own.msh")
    return m, folder, order


def test_to_meshio_is_our_msh_as_meshio_reads_it(case):
    m, folder, order = case
    mine = m.to_meshio()
    own = meshio.read(folder / "own.msh")
    assert mine.points.shape == (len(m.nodes), 3) and np.all(mine.points[:, 2] == 0)
    assert np.array_equal(mine.points, own.points)
    # Block for block, cell for cell, node for node: one block per set of groups (lines) and per
    # group (triangles); gmsh:physical each cell's first group, gmsh:geometrical its entity.
    assert [b.type for b in mine.cells] == [b.type for b in own.cells]
    for a, b in zip(mine.cells, own.cells):
        assert np.array_equal(a.data, b.data)
    for key in ["gmsh:physical", "gmsh:geometrical"]:
        assert len(mine.cell_data[key]) == len(own.cell_data[key])
        for a, b in zip(mine.cell_data[key], own.cell_data[key]):
            assert np.array_equal(a, b), key
    assert {k: list(v) for k, v in mine.field_data.items()} == {k: list(v) for k, v in own.field_data.items()}
    # Nodes on the entities Gmsh would put them on; the file puts them all on surface 1.
    assert np.all(own.point_data["gmsh:dim_tags"] == (2, 1))
    dim_tags = mine.point_data["gmsh:dim_tags"]
    on_lines = np.zeros(len(m.nodes), dtype=bool)
    on_lines[m.lines.ravel()] = True
    assert np.all(dim_tags[on_lines, 0] == 1) and np.all(dim_tags[~on_lines, 0] == 2)
    for block, geometrical in zip(mine.cells, mine.cell_data["gmsh:geometrical"]):
        assert np.any((dim_tags[:, 0] == block.dim) & (dim_tags[:, 1] == geometrical[0]))


def test_cell_sets_hold_every_group(case):
    """A cell set per group name holding exactly the lines of line_groups and the triangles of
    triangle_groups in that group (an element's outline and its region share its name); where the
    name is one group's alone, meshio's own reading of the file has the same set."""
    m, folder, order = case
    mine, own = m.to_meshio(), meshio.read(folder / "own.msh")
    named = {}
    for g, (dim, name) in m.groups.items():
        named.setdefault(name, []).append(g)
    assert set(mine.cell_sets) == set(named)
    for name, ids in named.items():
        cells = sorted(tuple(block.data[i]) for block, members in zip(mine.cells, mine.cell_sets[name])
                       for i in members)
        expect = sorted([tuple(l) for l, g in zip(m.lines, m.line_groups) if set(ids) & set(g)]
                        + [tuple(t) for t, g in zip(m.triangles, m.triangle_groups) if g in ids])
        assert cells == expect, name
        if len(ids) == 1:
            assert [list(a) for a in mine.cell_sets[name]] == [list(a) for a in own.cell_sets[name]], name


@pytest.mark.parametrize("file_format", ["gmsh", "gmsh22"])
def test_meshio_writes_it_as_gmsh(case, file_format):
    m, folder, _ = case
    path = folder / f"meshio-{file_format}.msh"
    meshio.write(path, m.to_meshio(), file_format=file_format)
    assert_same_geometry(meshio.read(path), meshio.read(folder / "own.msh"))


def test_meshio_writes_it_as_vtu(case):
    m, folder, order = case
    if order == 3:
        with pytest.raises(Exception):  # meshio has no VTK type for "triangle10"
            meshio.write(folder / "meshio.vtu", m.to_meshio())
        return
    meshio.write(folder / "meshio.vtu", m.to_meshio())
    back = meshio.read(folder / "meshio.vtu")
    assert_same_geometry(back, meshio.read(folder / "own.msh"))


def test_our_vtu_has_the_same_triangles(case):
    """Our own .vtu (VTK quadratic or Lagrange triangles, whose node order is Gmsh's) holds the
    triangles of to_meshio() node for node."""
    m, folder, order = case
    m.write(folder / "own.vtu")
    vtu = meshio.read(folder / "own.vtu")
    mine = m.to_meshio()
    triangle_type = CELL_TYPES[order][1]
    if order == 2:
        assert [b.type for b in vtu.cells] == ["triangle6"]  # VTK_QUADRATIC_TRIANGLE
    vtu_triangles = [b for b in vtu.cells if b.data.shape[1] == m.triangles.shape[1]]
    assert vtu_triangles
    a = sorted(tuple(c.ravel()) for c in mine.points[mine.cells_dict[triangle_type]])
    b = sorted(tuple(c.ravel()) for block in vtu_triangles for c in vtu.points[block.data])
    assert a == b


def test_curved_nodes_sit_where_gmsh_order_says(case):
    """In Gmsh's (and meshio's) triangle10, nodes 3-8 are two per edge 0-1, 1-2, 2-0 and node 9
    is inside; in triangle6, nodes 3-5 are the middles of edges 0-1, 1-2, 2-0: checked on the
    straight triangles, where they sit at thirds (at the middles)."""
    m, _, order = case
    if order == 1:
        return
    t = m.nodes[m.triangles]
    c0, c1, c2 = t[:, 0], t[:, 1], t[:, 2]
    if order == 2:
        expect = np.stack([(c0 + c1) / 2, (c1 + c2) / 2, (c2 + c0) / 2], axis=1)
    else:
        expect = np.stack([(2 * c0 + c1) / 3, (c0 + 2 * c1) / 3, (2 * c1 + c2) / 3, (c1 + 2 * c2) / 3,
                           (2 * c2 + c0) / 3, (c2 + 2 * c0) / 3, (c0 + c1 + c2) / 3], axis=1)
    size = np.linalg.norm(c1 - c0, axis=1)[:, None]
    straight = np.all(np.linalg.norm(t[:, 3:] - expect, axis=2) < 1e-6 * size, axis=1)
    assert straight.sum() > len(t) / 2  # most triangles are straight; on them the order holds


def test_line_tags_in_cell_data(case):
    m, _, _ = case
    mine = m.to_meshio()
    names = {v[0]: k for k, v in mine.field_data.items()}
    lines = {}
    for block, physical in zip(mine.cells, mine.cell_data["gmsh:physical"]):
        if block.dim == 1:
            lines.update({tuple(c): names[p] for c, p in zip(block.data, physical)})
    assert lines == {tuple(c): t for c, t in zip(m.lines, m.line_tags)}
