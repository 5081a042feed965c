"""curvemesh.mesh(): the same files as the command line, the inputs it takes, the arrays it gives,
the errors it raises."""
import json
import pathlib
import re
import warnings

import numpy as np
import pytest

import curvemesh

DRAWINGS = ["diffusion-curves", "open-curves", "overlapping-shapes", "square-with-hole", "transforms-and-use"]

# Every option, each away from its default, as the command line and as mesh() take it.
ALL_OPTIONS_CLI = [
    "--mu", "0.0015", "--epsilon", "0.004", "--eps-m", "1e-7", "-l", "0.08", "--min-edge-length", "2e-4",
    "--min-angle", "12", "--junction-angle", "15", "--max-iterations", "30", "--stop-amips", "8",
    "--box-margin", "0.1", "--curved-stop-amips", "15", "--max-curved-passes", "6",
]
ALL_OPTIONS = dict(
    mu=0.0015, epsilon=0.004, eps_m=1e-7, edge_length=0.08, min_edge_length=2e-4, min_angle=12,
    junction_angle=15, max_iterations=30, stop_amips=8, box_margin=0.1, curved_stop_amips=15,
    max_curved_passes=6,
)


def cli_files(run_cli, tmp_path, svg, *options):
    """The .msh (4.1 and 2.2), .vtu and .svg files the command line writes for `svg`."""
    out = tmp_path / "cli"
    out.mkdir(exist_ok=True)
    run_cli("mesh", svg, "-o", out / "m.msh", "--vtu", out / "m.vtu", "--svg", out / "m.svg", *options)
    run_cli("mesh", svg, "-o", out / "m22.msh", "--msh-version", "2.2", *options)
    return {name: (out / name).read_bytes() for name in ["m.msh", "m.vtu", "m.svg", "m22.msh"]}


def python_files(m, tmp_path):
    out = tmp_path / "py"
    out.mkdir(exist_ok=True)
    m.write(out / "m.msh")
    m.write(str(out / "m.vtu"))
    m.write(out / "m.svg")
    m.write(out / "m22.msh", msh_version=22)
    return {name: (out / name).read_bytes() for name in ["m.msh", "m.vtu", "m.svg", "m22.msh"]}


def assert_same_files(cli, py):
    for name in cli:
        assert py[name] == cli[name], f"{name} differs from the command line's"


@pytest.mark.parametrize("name", DRAWINGS)
def test_curved_files_are_the_command_lines(name, examples, run_cli, tmp_path):
    svg = examples / f"{name}.svg"
    assert_same_files(cli_files(run_cli, tmp_path, svg), python_files(curvemesh.mesh(str(svg)), tmp_path))


@pytest.mark.parametrize("name", ["overlapping-shapes", "transforms-and-use"])
def test_linear_files_are_the_command_lines(name, examples, run_cli, tmp_path):
    svg = examples / f"{name}.svg"
    cli = cli_files(run_cli, tmp_path, svg, "--linear", "-l", "0.1")
    m = curvemesh.mesh(svg, linear=True, edge_length=0.1)
    assert m.order == 1
    assert_same_files(cli, python_files(m, tmp_path))


@pytest.mark.parametrize("tolerance", [0, 1e-6])
def test_quadratic_files_are_the_command_lines(tolerance, examples, run_cli, tmp_path):
    svg = examples / "open-curves.svg"
    cli = cli_files(run_cli, tmp_path, svg, "--order", "2", "--curve-tolerance", str(tolerance))
    m = curvemesh.mesh(svg, order=2, curve_tolerance=tolerance)
    assert m.order == 2 and m.triangles.shape[1] == 6 and m.lines.shape[1] == 3
    assert_same_files(cli, python_files(m, tmp_path))
    assert m.stats["curve"]["tolerance_rel"] == (tolerance or curvemesh.OPTIONS["epsilon"])
    assert m.stats["mesh"]["max_edge_distance_rel"] <= m.stats["curve"]["tolerance_rel"]


@pytest.mark.parametrize("linear", [False, True])
def test_every_option_as_on_the_command_line(linear, examples, run_cli, tmp_path):
    svg = examples / "overlapping-shapes.svg"
    cli = cli_files(run_cli, tmp_path, svg, *ALL_OPTIONS_CLI, *(["--linear"] if linear else []))
    m = curvemesh.mesh(svg, linear=linear, **ALL_OPTIONS)
    assert_same_files(cli, python_files(m, tmp_path))
    default = curvemesh.mesh(svg, linear=linear)
    assert len(default.triangles) != len(m.triangles)  # the options did change the mesh


def test_no_features_is_the_command_lines(examples, run_cli, tmp_path):
    svg = examples / "overlapping-shapes.svg"
    cli = cli_files(run_cli, tmp_path, svg, "--no-features", "-l", "0.1")
    m = curvemesh.mesh(svg, features=False, edge_length=0.1)
    assert_same_files(cli, python_files(m, tmp_path))
    assert "primary" not in set(m.line_tags) and "secondary" in set(m.line_tags)
    assert "primary" in set(curvemesh.mesh(svg, edge_length=0.1).line_tags)
    with pytest.raises(TypeError):
        curvemesh.mesh(svg, features=0)


def test_svg_text_and_path_inputs(examples, run_cli, tmp_path):
    svg = examples / "transforms-and-use.svg"
    cli = cli_files(run_cli, tmp_path, svg, "-l", "0.1")
    text = svg.read_text(encoding="utf-8")
    for source in [svg, str(svg), text, "\n  \t" + text]:
        assert_same_files(cli, python_files(curvemesh.mesh(source, edge_length=0.1), tmp_path))


def test_relative_path(examples, run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(examples)
    m = curvemesh.mesh("square-with-hole.svg")
    assert len(m.triangles) > 0


def test_stats_are_the_command_lines(examples, run_cli, tmp_path):
    svg = examples / "overlapping-shapes.svg"
    run_cli("mesh", svg, "-o", tmp_path / "m.msh", "--stats", tmp_path / "s.json")
    cli = json.loads((tmp_path / "s.json").read_text())
    py = curvemesh.mesh(svg).stats
    assert isinstance(py, dict)

    def without_times(d):
        kept = {k: v for k, v in d.items() if k not in ("seconds", "input")}
        return {k: without_times(v) if isinstance(v, dict) else v for k, v in kept.items()}

    assert without_times(py) == without_times(cli)
    assert set(py["seconds"]) == set(cli["seconds"]) - {"write"}  # meshing writes nothing


@pytest.mark.parametrize("order", [1, 2, 3])
def test_arrays(order, examples):
    m = curvemesh.mesh(examples / "overlapping-shapes.svg", order=order)
    per_triangle, per_line = {1: (3, 2), 2: (6, 3), 3: (10, 4)}[order]
    assert m.order == order
    assert m.nodes.dtype == np.float64 and m.nodes.ndim == 2 and m.nodes.shape[1] == 2
    assert m.triangles.dtype == np.int64 and m.triangles.shape[1] == per_triangle
    assert m.lines.dtype == np.int64 and m.lines.shape[1] == per_line
    n, k = len(m.nodes), len(m.lines)
    assert len(m.triangles) > 0 and k > 0
    assert m.triangles.min() >= 0 and m.triangles.max() < n
    assert m.lines.min() >= 0 and m.lines.max() < n
    assert np.all(np.isfinite(m.nodes))
    assert m.line_tags.shape == (k,) and m.line_tags.dtype.kind == "U"
    assert set(m.line_tags) == {"primary", "secondary", "boundary"}
    assert m.line_curves.dtype == np.int64 and m.line_curves.shape == (k,)
    assert np.all((m.line_curves == -1) == (m.line_tags == "boundary"))
    assert m.line_curves.max() >= 0
    assert m.stats["mesh"]["triangles"] > 0
    assert m.warnings == []
    # Corners come first and run counter-clockwise with y up: clockwise in SVG's y-down space.
    a, b, c = (m.nodes[m.triangles[:, i]] for i in range(3))
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert np.all(cross > 0) or np.all(cross < 0)
    # Read-only and the same object each time.
    assert m.nodes is m.nodes
    with pytest.raises(ValueError):
        m.nodes[0, 0] = 1.0
    assert re.match(r"<curvemesh\.Mesh order=[123]: \d+ nodes, \d+ triangles, \d+ lines>", repr(m))


def test_arrays_match_the_msh_file(examples, tmp_path):
    """The arrays are the file's: nodes in order, lines grouped by tag then triangles."""
    m = curvemesh.mesh(examples / "square-with-hole.svg")
    m.write(tmp_path / "m.msh", msh_version=22)
    lines = (tmp_path / "m.msh").read_text().splitlines()
    start = lines.index("$Nodes")
    count = int(lines[start + 1])
    nodes = np.array([[float(v) for v in line.split()[1:3]] for line in lines[start + 2 : start + 2 + count]])
    assert np.array_equal(nodes, m.nodes)
    start = lines.index("$Elements")
    elements = [list(map(int, line.split())) for line in lines[start + 2 : lines.index("$EndElements")]]
    triangles = np.array([e[5:] for e in elements if e[1] == 21]) - 1
    assert np.array_equal(triangles, m.triangles)
    order = {"primary": 1, "secondary": 2, "boundary": 3}
    # 2.2 writes a line once per group: its kind's copy is the one the arrays hold.
    file_lines = sorted((e[3], tuple(np.array(e[5:]) - 1)) for e in elements if e[1] == 26 and e[3] in (1, 2, 3))
    ours = sorted((order[t], tuple(l)) for t, l in zip(m.line_tags, m.lines))
    assert file_lines == ours


def physical_groups(path):
    """{id: (dimension, name, sorted element node lists)} of a .msh file, as Gmsh reads it."""
    gmsh = pytest.importorskip("gmsh")
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(str(path))
        tags = gmsh.model.mesh.getNodes()[0]
        assert np.array_equal(tags, np.arange(1, len(tags) + 1))  # node tag k is node k - 1
        out = {}
        for dim, tag in gmsh.model.getPhysicalGroups():
            elements = []
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                for t, nodes in zip(*gmsh.model.mesh.getElements(dim, entity)[::2]):
                    size = gmsh.model.mesh.getElementProperties(t)[3]
                    elements += [tuple(e) for e in (np.array(nodes, dtype=np.int64).reshape(-1, size) - 1).tolist()]
            out[tag] = (dim, gmsh.model.getPhysicalName(dim, tag), sorted(elements))
        return out
    finally:
        gmsh.finalize()


@pytest.mark.parametrize("order", [1, 2, 3])
def test_groups_are_the_files(order, examples, tmp_path):
    """groups, line_groups and triangle_groups are the physical groups of the .msh file as Gmsh
    reads it, and those --stats lists."""
    m = curvemesh.mesh(examples / "overlapping-shapes.svg", order=order, regions=True, domain="filled")
    m.write(tmp_path / "m.msh")
    ours = {}
    for g, (dim, name) in m.groups.items():
        if dim == 1:
            elements = [tuple(line) for line, groups in zip(m.lines.tolist(), m.line_groups) if g in groups]
        else:
            elements = [tuple(t) for t in m.triangles[m.triangle_groups == g].tolist()]
        ours[g] = (dim, name, sorted(elements))
    assert ours == physical_groups(tmp_path / "m.msh")
    assert [(s["dim"], s["id"], s["name"]) for s in m.stats["groups"]] == [(d, g, n) for g, (d, n) in m.groups.items()]
    assert m.triangle_groups.shape == (len(m.triangles),) and len(m.line_groups) == len(m.lines)
    tag_ids = {"primary": 1, "secondary": 2, "boundary": 3}
    assert [int(g[0]) for g in m.line_groups] == [tag_ids[t] for t in m.line_tags]
    with pytest.raises(ValueError):
        m.line_groups[0][0] = 7


def test_xdmf_is_the_command_lines(examples, run_cli, tmp_path):
    svg = examples / "overlapping-shapes.svg"
    for folder in ["cli", "py"]:
        (tmp_path / folder).mkdir()
    run_cli("mesh", svg, "--order", "2", "--regions", "-o", tmp_path / "cli/m.msh", "--xdmf", tmp_path / "cli/m.xdmf")
    m = curvemesh.mesh(svg, order=2, regions=True)
    m.write(tmp_path / "py/m.xdmf")
    for name in ["m.xdmf", "m.h5"]:
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    with pytest.raises(ValueError, match="XDMF has no triangle of order 3"):
        curvemesh.mesh(svg).write(tmp_path / "py/cubic.xdmf")
    assert not (tmp_path / "py/cubic.xdmf").exists() and not (tmp_path / "py/cubic.h5").exists()


@pytest.mark.parametrize("order", [2, 3])
def test_check(order, examples, run_cli, tmp_path):
    m = curvemesh.mesh(examples / "overlapping-shapes.svg", order=order)
    m.write(tmp_path / "m.msh")
    cli = json.loads(run_cli("check", tmp_path / "m.msh", "--json").stdout)
    path = tmp_path / "m.msh"
    for report in [curvemesh.check(m), curvemesh.check(path), curvemesh.check(str(path)), curvemesh.check(m, threads=1),
                   curvemesh.check(path, threads=3)]:
        assert set(report) == {"order", "triangles", "invalid", "undecided", "min_scaled_jacobian", "exact_fallbacks"}
        assert report["order"] == order and report["invalid"] == 0 and report["undecided"] == 0
        assert report["triangles"] == len(m.triangles)
        for key in report:
            assert report[key] == cli[key]
    # Every element in rationals: the same verdict and figure as the command's --exact.
    cli_exact = json.loads(run_cli("check", tmp_path / "m.msh", "--json", "--exact").stdout)
    for report in [curvemesh.check(m, exact=True), curvemesh.check(path, exact=True)]:
        assert report["exact_fallbacks"] == report["triangles"] == len(m.triangles)
        for key in report:
            assert report[key] == cli_exact[key]
        for key in ("order", "triangles", "invalid", "undecided", "min_scaled_jacobian"):
            assert report[key] == cli[key]
    with pytest.raises(ValueError):
        curvemesh.check(tmp_path / "missing.msh")
    with pytest.raises(TypeError):
        curvemesh.check(42)
    for threads, message in ((-1, r"--threads \(-1\) must be an integer in \[0, 4096\]"),
                             (4097, r"--threads \(4097\) is out of range")):
        with pytest.raises(ValueError, match=message):
            curvemesh.check(m, threads=threads)
    for threads in (1.5, True):  # as mesh() takes the option
        with pytest.raises(TypeError, match="threads must be"):
            curvemesh.check(m, threads=threads)


def test_version(run_cli):
    assert re.fullmatch(r"\d+\.\d+\.\d+", curvemesh.__version__)
    # One version: the module, the library and the command line say the same.
    assert run_cli("--version").stdout.strip() == f"curvemesh {curvemesh.__version__}"


def test_options_and_defaults():
    assert set(curvemesh.OPTIONS) == {
        "mu", "epsilon", "eps_m", "edge_length", "min_edge_length", "min_angle", "junction_angle", "order", "linear",
        "curve_tolerance", "max_iterations", "stop_amips", "box_margin", "curved_stop_amips", "max_curved_passes",
        "features", "max_input_mb", "max_elements", "max_curves", "max_triangles", "regions", "domain", "stop_after",
        "strokes", "min_stroke_width", "threads",
    }
    assert curvemesh.OPTIONS["regions"] is False and curvemesh.OPTIONS["domain"] == "box"
    assert curvemesh.OPTIONS["strokes"] == "lines"
    assert curvemesh.OPTIONS["stop_after"] == "curve"
    assert curvemesh.OPTIONS["edge_length"] == 0.05 and curvemesh.OPTIONS["linear"] is False
    assert curvemesh.OPTIONS["order"] == 3 and curvemesh.OPTIONS["curve_tolerance"] == 0.0
    assert curvemesh.OPTIONS["max_curves"] == 500000 and curvemesh.OPTIONS["max_triangles"] == 2000000
    assert curvemesh.OPTIONS["threads"] == 0


def test_a_limit_reached_raises_the_command_lines_message(run_cli, tmp_path, examples):
    svg = examples / "overlapping-shapes.svg"
    for option, flag in (("max_curves", "--max-curves"), ("max_triangles", "--max-triangles")):
        message = cli_message(run_cli, "mesh", svg, "-o", tmp_path / "limited.msh", flag, "3")
        with pytest.raises(ValueError) as error:
            curvemesh.mesh(svg, **{option: 3})
        assert str(error.value) == message
        assert flag in message
    with pytest.raises(ValueError):
        curvemesh.mesh(svg, max_curves=0)


def test_a_path_with_a_nul_is_a_value_error_as_in_open(tmp_path, examples):
    m = curvemesh.mesh(examples / "overlapping-shapes.svg", linear=True)
    for path in (str(tmp_path / "out.vtu") + "\0.msh", tmp_path / "x\0y.msh"):
        with pytest.raises(ValueError, match="embedded null byte"):
            m.write(path)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="embedded null byte"):
        curvemesh.mesh(str(examples / "overlapping-shapes.svg") + "\0.poly")
    with pytest.raises(ValueError, match="embedded null byte"):
        curvemesh.check(str(tmp_path / "a.msh\0"))


def test_writing_over_the_drawing_is_refused(tmp_path, examples):
    drawing = tmp_path / "drawing.svg"
    drawing.write_bytes((examples / "overlapping-shapes.svg").read_bytes())
    before = drawing.read_bytes()
    m = curvemesh.mesh(drawing, linear=True)
    with pytest.raises(ValueError, match="refusing to write over an input"):
        m.write(drawing)
    assert drawing.read_bytes() == before


# --- errors ---------------------------------------------------------------------------------------


def cli_message(run_cli, *args):
    result = run_cli(*args, check=False)
    assert result.returncode != 0
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("curvemesh: ")
    return line[len("curvemesh: ") :]


def test_bad_svg_raises_the_readers_message(run_cli, tmp_path):
    broken = tmp_path / "broken.svg"
    broken.write_text("<svg><path d='M 0 0 L 1 1'/>")  # not well-formed
    message = cli_message(run_cli, "mesh", broken, "-o", tmp_path / "broken.msh")
    with pytest.raises(ValueError) as error:
        curvemesh.mesh(broken)
    assert str(error.value) == message
    assert not (tmp_path / "broken.msh").exists()
    for text, message in [
        ("<svg", "<svg>: line 1: not well-formed XML"),
        ("<html/>", "<svg>: line 1, <html>: the root element is <html>, not <svg>"),
        ('<svg><path d="M 0 0 L 1e999 0"/></svg>', "<svg>: line 1, <path>: bad path data"),
    ]:
        with pytest.raises(ValueError, match="^" + re.escape(message)):
            curvemesh.mesh(text)


def test_warnings_are_the_command_lines(run_cli, tmp_path):
    bad = tmp_path / "bad.svg"
    bad.write_text('<svg xmlns="http://www.w3.org/2000/svg">\n<path d="M 0 0 L 10 0 L 10"/>\n</svg>\n')
    stderr = run_cli("mesh", bad, "-o", tmp_path / "bad.msh").stderr
    with pytest.warns(curvemesh.CurvemeshWarning) as issued:
        m = curvemesh.mesh(bad)
    assert m.warnings == ["line 2, <path>: path data ends inside a command; drawn up to there"]
    for w in m.warnings:
        assert f"curvemesh: {bad}: warning: {w}" in stderr
    # Issued through Python's warnings, as the command line prints them, from the caller's line.
    assert [str(w.message) for w in issued] == [f"{bad}: {w}" for w in m.warnings]
    assert all(w.filename == __file__ for w in issued)
    with pytest.warns(curvemesh.CurvemeshWarning, match="^<svg>: nothing is drawn; meshing the canvas alone$"):
        assert curvemesh.mesh('<svg xmlns="http://www.w3.org/2000/svg"></svg>').warnings == [
            "nothing is drawn; meshing the canvas alone"
        ]
    with pytest.warns(curvemesh.CurvemeshWarning):
        assert curvemesh.mesh(bad.read_text()).warnings == m.warnings  # SVG text: the same warnings
    with warnings.catch_warnings():  # a filter makes them errors
        warnings.simplefilter("error", curvemesh.CurvemeshWarning)
        with pytest.raises(curvemesh.CurvemeshWarning):
            curvemesh.mesh(bad)


def test_regions_domain_and_stop_after_as_on_the_command_line(examples, run_cli, tmp_path):
    svg = examples / "overlapping-shapes.svg"
    cases = [
        (dict(regions=True), ["--regions"]),
        (dict(domain="filled"), ["--domain", "filled"]),
        (dict(regions=True, domain="evenodd", order=1), ["--regions", "--domain", "evenodd", "--order", "1"]),
        (dict(stop_after="optimize"), ["--stop-after", "optimize"]),
        (dict(strokes="areas", regions=True, order=1), ["--strokes", "areas", "--regions", "--order", "1"]),
        (dict(domain="painted", order=1), ["--domain", "painted", "--order", "1"]),
    ]
    for options, cli in cases:
        run_cli("mesh", svg, *cli, "-o", tmp_path / "cli.msh", "--msh-version", "2.2")
        curvemesh.mesh(svg, **options).write(tmp_path / "py.msh", msh_version="2.2")
        assert (tmp_path / "py.msh").read_bytes() == (tmp_path / "cli.msh").read_bytes(), options
    assert curvemesh.mesh(svg, stop_after="triangulate").order == 1
    assert len(curvemesh.mesh(svg, domain="filled").triangles) < len(curvemesh.mesh(svg).triangles)
    with pytest.raises(ValueError, match="--domain .'inside'. must be one of box, filled, evenodd, painted, outside"):
        curvemesh.mesh(svg, domain="inside")
    with pytest.raises(TypeError):
        curvemesh.mesh(svg, regions="yes")


def test_missing_file_raises_the_command_lines_message(run_cli, tmp_path):
    missing = tmp_path / "missing.svg"
    message = cli_message(run_cli, "mesh", missing, "-o", tmp_path / "m.msh")
    with pytest.raises(ValueError) as error:
        curvemesh.mesh(missing)
    assert str(error.value) == message


@pytest.mark.parametrize(
    "options, message",
    [
        (dict(mu=0.001, epsilon=0.0005), "--epsilon (0.0005) must be at least --mu (0.001)"),
        (dict(edge_length=-0.1), "--edge-length (-0.1) must be a positive number"),
        (dict(mu=0), "--mu (0) must be a positive number"),
        (dict(mu=float("nan")), "--mu (nan) must be a positive number"),
        (dict(min_stroke_width=0), "--min-stroke-width (0) must be a positive number"),
        (dict(threads=-1), "--threads (-1) must be an integer in [0, 4096]"),
        (dict(min_angle=90), "--min-angle (90) must be in [0.1, 60]"),
        (dict(max_iterations=-1), "--max-iterations (-1) must be a non-negative integer"),
        (dict(max_curved_passes=2**40), "--max-curved-passes (1099511627776) is out of range"),
    ],
)
def test_invalid_values_raise_value_error(options, message, examples):
    with pytest.raises(ValueError) as error:
        curvemesh.mesh(examples / "square-with-hole.svg", **options)
    assert str(error.value) == message
    with pytest.raises(ValueError):
        curvemesh.mesh_curves(np.zeros((1, 4, 2)), **options)


def test_invalid_value_message_is_the_command_lines(examples, run_cli, tmp_path):
    message = cli_message(run_cli, "mesh", examples / "square-with-hole.svg", "-o", tmp_path / "m.msh",
                          "--mu", "0.001", "--epsilon", "0.0005")
    with pytest.raises(ValueError) as error:
        curvemesh.mesh(examples / "square-with-hole.svg", mu=0.001, epsilon=0.0005)
    assert str(error.value) == message


@pytest.mark.parametrize(
    "options, word",
    [
        (dict(edge_lenght=0.1), "edge_lenght"),
        (dict(l=0.1), "'l'"),
        (dict(mu="0.1"), "mu"),
        (dict(linear=1), "linear"),
        (dict(max_iterations=2.5), "max_iterations"),
        (dict(edge_length=True), "edge_length"),
    ],
)
def test_unknown_options_and_wrong_types_raise_type_error(options, word, examples):
    with pytest.raises(TypeError, match=re.escape(word)):
        curvemesh.mesh(examples / "square-with-hole.svg", **options)
    with pytest.raises(TypeError, match=re.escape(word)):
        curvemesh.mesh_curves(np.zeros((1, 4, 2)), **options)


def test_numpy_scalars_are_taken(examples, tmp_path):
    svg = examples / "square-with-hole.svg"
    a = curvemesh.mesh(svg, edge_length=np.float32(0.25), max_iterations=np.int64(20), linear=np.bool_(True))
    b = curvemesh.mesh(svg, edge_length=float(np.float32(0.25)), max_iterations=20, linear=True)
    assert np.array_equal(a.triangles, b.triangles) and np.array_equal(a.nodes, b.nodes)


def test_wrong_input_type():
    with pytest.raises(TypeError):
        curvemesh.mesh(42)
    with pytest.raises(TypeError):
        curvemesh.mesh(None)


def test_output_errors_raise_os_error(examples, tmp_path):
    m = curvemesh.mesh(examples / "square-with-hole.svg", linear=True)
    with pytest.raises(OSError):
        m.write(tmp_path / "no-such-folder" / "m.msh")
    with pytest.raises(OSError):
        m.write(tmp_path / "m.txt")
    for bad in [3, "3", 4.1, True, None]:
        with pytest.raises(ValueError):
            m.write(tmp_path / "m.msh", msh_version=bad)


def test_msh_version_spelled_as_the_command_line(examples, run_cli, tmp_path):
    svg = examples / "square-with-hole.svg"
    m = curvemesh.mesh(svg, linear=True)
    for cli_name, names in [("4.1", ["4.1", 41, "41"]), ("2.2", ["2.2", 22, "22"])]:
        run_cli("mesh", svg, "--linear", "--msh-version", cli_name, "-o", tmp_path / f"cli{cli_name}.msh")
        cli = (tmp_path / f"cli{cli_name}.msh").read_bytes()
        for k, name in enumerate(names):
            m.write(tmp_path / f"py{cli_name}-{k}.msh", msh_version=name)
            assert (tmp_path / f"py{cli_name}-{k}.msh").read_bytes() == cli
    with pytest.raises(TypeError):
        curvemesh.Mesh(None)


# --- mesh_curves ----------------------------------------------------------------------------------

K = 0.5522847498307936  # a quarter circle's cubic: control points at this fraction of the radius


def circle(cx, cy, r):
    k = K * r
    return [
        [[cx + r, cy], [cx + r, cy + k], [cx + k, cy + r], [cx, cy + r]],
        [[cx, cy + r], [cx - k, cy + r], [cx - r, cy + k], [cx - r, cy]],
        [[cx - r, cy], [cx - r, cy - k], [cx - k, cy - r], [cx, cy - r]],
        [[cx, cy - r], [cx + k, cy - r], [cx + r, cy - k], [cx + r, cy]],
    ]


def test_mesh_curves_circle():
    m = curvemesh.mesh_curves(circle(50, 50, 40), edge_length=0.1)
    assert m.order == 3 and m.triangles.shape[1] == 10
    primary = m.line_tags == "primary"
    assert primary.any()
    assert set(m.line_curves[primary]) == {0, 1, 2, 3}
    # Every node of a primary line lies on the circle (the cubics' own error is 2.7e-4 r).
    r = np.hypot(*(m.nodes[m.lines[primary]].reshape(-1, 2) - 50).T)
    assert np.allclose(r, 40, rtol=3e-4)
    assert curvemesh.check(m)["invalid"] == 0


def test_mesh_curves_as_the_readers_curves(tmp_path):
    """The circle's cubics as an array mesh as the same cubics drawn as an SVG path do."""
    curves = np.array(circle(50, 50, 40))
    d = f"M {curves[0, 0, 0]!r} {curves[0, 0, 1]!r} " + " ".join(
        "C " + " ".join(f"{x!r} {y!r}" for x, y in c[1:]) for c in curves
    )
    svg = (
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
        f'<path d="{d}" fill="none" stroke="black"/></svg>'
    )
    a = curvemesh.mesh_curves(curves.tolist(), edge_length=0.1)
    b = curvemesh.mesh(svg, edge_length=0.1)
    a.write(tmp_path / "a.msh")
    b.write(tmp_path / "b.msh")
    assert (tmp_path / "a.msh").read_bytes() == (tmp_path / "b.msh").read_bytes()
    assert np.array_equal(a.line_curves, b.line_curves)


def test_mesh_curves_open_and_crossing():
    curves = np.array(
        [
            [[0, 0], [30, 40], [60, -40], [100, 0]],
            [[50, -30], [40, 0], [60, 10], [50, 30]],
            [[10, 20], [30, 20], [70, 20], [90, 20]],
        ],
        dtype=np.float32,
    )
    m = curvemesh.mesh_curves(curves, edge_length=0.05)
    assert curvemesh.check(m)["invalid"] == 0
    assert set(m.line_curves[m.line_curves >= 0]) <= {0, 1, 2}
    linear = curvemesh.mesh_curves(curves, linear=True)
    assert linear.triangles.shape[1] == 3 and linear.lines.shape[1] == 2


@pytest.mark.parametrize("shape", [(4, 2), (1, 3, 2), (2, 4, 3), (1, 4, 2, 1), (4,)])
def test_mesh_curves_wrong_shape(shape):
    with pytest.raises(ValueError, match=re.escape("(n, 4, 2)")):
        curvemesh.mesh_curves(np.ones(shape))


def test_mesh_curves_bad_values():
    for bad in [float("nan"), float("inf"), -float("inf")]:
        curves = np.array(circle(0, 0, 1))
        curves[2, 1, 0] = bad
        with pytest.raises(ValueError, match="not a finite number"):
            curvemesh.mesh_curves(curves)
    with pytest.raises(ValueError):
        curvemesh.mesh_curves([[["a", "b"]] * 4])
    with pytest.raises(ValueError):
        curvemesh.mesh_curves(np.zeros((0, 4, 2)))


def test_mesh_curves_takes_views():
    curves = np.array(circle(50, 50, 40))
    strided = np.zeros((8, 4, 2))
    strided[::2] = curves
    a = curvemesh.mesh_curves(strided[::2], edge_length=0.2)
    b = curvemesh.mesh_curves(curves, edge_length=0.2)
    assert np.array_equal(a.nodes, b.nodes) and np.array_equal(a.triangles, b.triangles)


def test_docstrings():
    for thing in [curvemesh, curvemesh.mesh, curvemesh.mesh_curves, curvemesh.check, curvemesh.Mesh,
                  curvemesh.Mesh.write, curvemesh.Mesh.to_meshio]:
        assert thing.__doc__ and len(thing.__doc__) > 40, thing
    for name in ["order", "nodes", "triangles", "lines", "line_tags", "line_curves", "triangle_groups", "line_groups",
                 "groups", "stats", "warnings"]:
        assert getattr(curvemesh.Mesh, name).__doc__, name


def test_path_like(examples, tmp_path):
    class Where:
        def __fspath__(self):
            return str(examples / "square-with-hole.svg")

    m = curvemesh.mesh(Where(), linear=True)
    m.write(pathlib.PurePosixPath(tmp_path / "m.svg"))
    assert (tmp_path / "m.svg").read_bytes().startswith(b"<?xml")
