#!/usr/bin/env python3
"""Command-line contract of quadratic meshes (`curvemesh mesh --order 2`) and their `check`.

Every bundled drawing is meshed with --order 2 and the .msh is read back by an independent reader
(the Gmsh Python API; meshio too): 6-node triangles (Gmsh type 9) and 3-node lines (type 8) only;
every element's det J, a polynomial of degree 2, decided positive here with exact rationals
(fractions.Fraction on the doubles as read): its six Bernstein coefficients, or, where one is not
positive, its exact minimum over the closed triangle (corners, the critical points of its edges and
of its inside); every primary line within the curve tolerance of the drawing's curves (as
`curvemesh features` reads them), its middle node on one, and no farther than --stats says.
`curvemesh check` accepts each file and refuses a folded quadratic triangle; the VTU holds
VTK_QUADRATIC_TRIANGLE cells, the SVG draws quadratic edges as Q commands; a tighter
--curve-tolerance splits more edges and still holds.

usage: order2_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def path(name):
    return os.path.join(tmp.name, name)


# ---------------------------------------------------------------------------------------------
# Reading the file with Gmsh.

def read_with_gmsh(msh):
    """{"nodes": {tag: (x, y)}, "triangles": {type: [[tags]]}, "lines": {type: [([tags], physical)]}}."""
    import gmsh
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(msh)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        nodes = {int(t): (float(coords[3 * i]), float(coords[3 * i + 1])) for i, t in enumerate(tags)}
        triangles, lines = {}, {}
        for dim, entity in gmsh.model.getEntities():
            physical = gmsh.model.getPhysicalGroupsForEntity(dim, entity)
            types, _, node_tags = gmsh.model.mesh.getElements(dim, entity)
            for kind, flat in zip(types, node_tags):
                n = gmsh.model.mesh.getElementProperties(kind)[3]
                elements = [[int(x) for x in flat[k:k + n]] for k in range(0, len(flat), n)]
                if dim == 2:
                    triangles.setdefault(int(kind), []).extend(elements)
                elif dim == 1:
                    tag = int(physical[0]) if len(physical) else 0
                    lines.setdefault(int(kind), []).extend((e, tag) for e in elements)
        return {"nodes": nodes, "triangles": triangles, "lines": lines}
    finally:
        gmsh.finalize()


# ---------------------------------------------------------------------------------------------
# det J of the P2 map, exactly. Nodes in Gmsh's order: corners 0 (u, v) = (0, 0), 1 (1, 0),
# 2 (0, 1), then the middles of edges 0-1, 1-2, 2-0.

def bernstein_det(p):
    """The six Bernstein coefficients (degree 2) of det J, keyed by (i, j, k) = the powers of
    (1 - u - v, u, v). The control net keeps the corners; an edge's control point is
    2m - (a + b)/2. x_u = 2 sum (P[g+e1] - P[g+e0]) B1_g, x_v likewise with e2, so the coefficient
    at d is 4 / C(d) sum over g + h = d of (U_g x V_h), C the multinomial 2!/(i! j! k!)."""
    ctrl = {(2, 0, 0): p[0], (0, 2, 0): p[1], (0, 0, 2): p[2]}
    for (a, b, m, key) in ((0, 1, 3, (1, 1, 0)), (1, 2, 4, (0, 1, 1)), (2, 0, 5, (1, 0, 1))):
        ctrl[key] = tuple(2 * p[m][c] - (p[a][c] + p[b][c]) / 2 for c in range(2))
    ones = ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    add = lambda g, e: tuple(x + y for x, y in zip(g, e))
    U = {g: tuple(ctrl[add(g, ones[1])][c] - ctrl[add(g, ones[0])][c] for c in range(2)) for g in ones}
    V = {g: tuple(ctrl[add(g, ones[2])][c] - ctrl[add(g, ones[0])][c] for c in range(2)) for g in ones}
    out = {}
    for g in ones:
        for h in ones:
            d = add(g, h)
            out[d] = out.get(d, 0) + U[g][0] * V[h][1] - U[g][1] * V[h][0]
    multinomial = lambda d: 2 // (math.factorial(d[0]) * math.factorial(d[1]) * math.factorial(d[2]))
    return {d: 4 * c / multinomial(d) for d, c in out.items()}


def det_at(p, u, v):
    """det J at (u, v) from the derivatives of the Lagrange basis: another route to the same
    polynomial."""
    l0 = 1 - u - v
    du = (1 - 4 * l0, 4 * u - 1, 0, 4 * (l0 - u), 4 * v, -4 * v)
    dv = (1 - 4 * l0, 0, 4 * v - 1, -4 * u, 4 * u, 4 * (l0 - v))
    xu = [sum(du[i] * p[i][c] for i in range(6)) for c in range(2)]
    xv = [sum(dv[i] * p[i][c] for i in range(6)) for c in range(2)]
    return xu[0] * xv[1] - xu[1] * xv[0]


def exact_minimum(p):
    """The minimum of det J (a quadratic a + b u + c v + d u^2 + e u v + f v^2) over the closed
    triangle: at a corner, at the critical point of an edge or of the inside, all rational."""
    at = lambda u, v: det_at(p, Fraction(u), Fraction(v))
    half = Fraction(1, 2)
    a = at(0, 0)
    d, f = 2 * (at(1, 0) - 2 * at(half, 0) + a), 2 * (at(0, 1) - 2 * at(0, half) + a)
    b, c = at(1, 0) - a - d, at(0, 1) - a - f
    e = at(1, 1) - a - b - c - d - f  # (1, 1) is outside the triangle, but the polynomial is the same
    inside = lambda u, v: u >= 0 and v >= 0 and u + v <= 1
    values = [at(0, 0), at(1, 0), at(0, 1)]
    if 4 * d * f - e * e != 0:
        det = 4 * d * f - e * e
        u, v = (-2 * f * b + e * c) / det, (-2 * d * c + e * b) / det
        if inside(u, v):
            values.append(at(u, v))
    if d != 0 and inside(-b / (2 * d), 0):
        values.append(at(-b / (2 * d), 0))
    if f != 0 and inside(0, -c / (2 * f)):
        values.append(at(0, -c / (2 * f)))
    if d - e + f != 0:
        t = -(b - c + e - 2 * f) / (2 * (d - e + f))
        if inside(t, 1 - t):
            values.append(at(t, 1 - t))
    return min(values)


def jacobian_positive(points):
    """Exact: True when det J > 0 on the whole closed element."""
    p = [(Fraction(x), Fraction(y)) for x, y in points]
    coefficients = bernstein_det(p)
    # The corner coefficients are det J at the corners: the two routes must agree exactly.
    assert coefficients[(2, 0, 0)] == det_at(p, Fraction(0), Fraction(0))
    assert coefficients[(0, 2, 0)] == det_at(p, Fraction(1), Fraction(0))
    if all(c > 0 for c in coefficients.values()):
        return True  # the polynomial is at least its smallest coefficient
    return exact_minimum(p) > 0


# The exact test itself, on elements whose answer is known: straight, bent within the limit (det J =
# 1 - 4hu for edge 0-1's middle raised by h: valid for h < 1/4), at the limit, folded.
unit = [(0, 0), (1, 0), (0, 1), (0.5, 0), (0.5, 0.5), (0, 0.5)]
bent = lambda h: [unit[0], unit[1], unit[2], (0.5, h), unit[4], unit[5]]
check("exact test: a straight triangle is valid", jacobian_positive(unit))
check("exact test: a bent edge within the limit is valid", jacobian_positive(bent(0.24)))
check("exact test: at the limit det J is 0 at a corner: invalid", not jacobian_positive(bent(0.25)))
check("exact test: beyond the opposite side: invalid", not jacobian_positive(bent(1.5)))
check("exact test: clockwise corners: invalid", not jacobian_positive([unit[0], unit[2], unit[1], unit[5], unit[4], unit[3]]))
# Positive everywhere although one Bernstein coefficient is negative: decided by the minimum.
subtle = [(0, 0), (40, 0), (0, 40), (18, 9), (15, 22), (-7, 10)]
check("exact test: a negative coefficient over a positive det J",
      min(bernstein_det([(Fraction(x), Fraction(y)) for x, y in subtle]).values()) < 0 and jacobian_positive(subtle))
check("exact test: a fold inside, positive at the corners", not jacobian_positive(
    [(0, 0), (40, 0), (0, 40), (8, -4), (27, 29), (10, 13)]))


# ---------------------------------------------------------------------------------------------
# Distances to the drawing's curves.

def bez(c, t):
    s = 1 - t
    w = (s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t)
    return tuple(sum(w[i] * c[i][k] for i in range(4)) for k in range(2))


def bez_d(c, t):
    s = 1 - t
    w = (-3 * s * s, 3 * s * s - 6 * s * t, 6 * s * t - 3 * t * t, 3 * t * t)
    return tuple(sum(w[i] * c[i][k] for i in range(4)) for k in range(2))


def bez_dd(c, t):
    s = 1 - t
    w = (6 * s, -12 * s + 6 * t, 6 * s - 12 * t, 6 * t)
    return tuple(sum(w[i] * c[i][k] for i in range(4)) for k in range(2))


class Curves:
    """The drawing's cubic curves, sampled once. The distance from a point to the nearest one:
    Newton's method from every sample that may be nearest to the nearest point (no farther than
    the nearest sample of all plus its curve's largest sample spacing) and nearer than its
    neighbours: a curve that crosses itself has a local minimum on each branch."""

    def __init__(self, curves):
        import numpy as np
        self.curves = curves
        self.ts = np.linspace(0, 1, 129)
        self.samples = np.array([[bez(c, t) for t in self.ts] for c in curves])  # (curves, 129, 2)
        self.spacing = np.linalg.norm(np.diff(self.samples, axis=1), axis=2).max(axis=1)

    def newton(self, c, t, p):
        for _ in range(30):  # on f(t) = (B(t) - p)·B'(t) = 0, kept in [0, 1]
            b, d1, d2 = bez(c, t), bez_d(c, t), bez_dd(c, t)
            f = (b[0] - p[0]) * d1[0] + (b[1] - p[1]) * d1[1]
            df = d1[0] * d1[0] + d1[1] * d1[1] + (b[0] - p[0]) * d2[0] + (b[1] - p[1]) * d2[1]
            if df <= 0:
                break
            t = min(max(t - f / df, 0.0), 1.0)
        return math.dist(bez(c, t), p)

    def distance(self, p):
        import numpy as np
        d = np.hypot(self.samples[:, :, 0] - p[0], self.samples[:, :, 1] - p[1])
        best = float(d.min())
        padded = np.pad(d, ((0, 0), (1, 1)), constant_values=np.inf)
        local = (d <= padded[:, :-2]) & (d <= padded[:, 2:]) & (d <= best + self.spacing[:, None])
        for i, k in zip(*np.nonzero(local)):
            best = min(best, self.newton(self.curves[i], float(self.ts[k]), p))
        return best


def drawing_curves(svg):
    out = path("features.json")
    r = run("features", svg, "-o", out)
    if r.returncode != 0:
        return None
    with open(out) as f:
        return [[(c["p"][2 * i], c["p"][2 * i + 1]) for i in range(4)] for c in json.load(f)["curves"]]


def quadratic_point(a, b, m, s):
    """The line element (ends a, b, middle m at s = 1/2) at s."""
    return tuple((1 - s) * (1 - 2 * s) * a[k] + 4 * s * (1 - s) * m[k] + s * (2 * s - 1) * b[k] for k in range(2))


# ---------------------------------------------------------------------------------------------

def mesh_and_verify(name, svg, *options):
    """Meshes `svg` at order 2 and checks the file from outside; returns the statistics."""
    msh, stats_path = path(name + ".msh"), path(name + ".json")
    r = run("mesh", svg, "-o", msh, "--order", "2", "--stats", stats_path, *options)
    check(f"{name}: exit 0", r.returncode == 0, r.stderr)
    if r.returncode != 0:
        return None
    with open(stats_path) as f:
        stats = json.load(f)
    mesh = read_with_gmsh(msh)
    check(f"{name}: Gmsh reads 6-node triangles (type 9) only", list(mesh["triangles"]) == [9], str(list(mesh["triangles"])))
    check(f"{name}: Gmsh reads 3-node lines (type 8) only", list(mesh["lines"]) == [8], str(list(mesh["lines"])))
    triangles = mesh["triangles"].get(9, [])
    check(f"{name}: as many triangles as --stats says", len(triangles) == stats["mesh"]["triangles"],
          f"{len(triangles)} vs {stats['mesh']['triangles']}")
    nodes = mesh["nodes"]
    invalid = [k for k, t in enumerate(triangles) if not jacobian_positive([nodes[n] for n in t])]
    check(f"{name}: every element's det J positive, exactly", not invalid, f"{len(invalid)} invalid, first {invalid[:5]}")

    # Primary lines: within the tolerance of the drawing's curves, the middle node on one.
    curve = stats["curve"]
    tolerance = curve["tolerance"]
    check(f"{name}: no primary edge left beyond the tolerance", curve["beyond_tolerance"] == 0, str(curve))
    curves = Curves(drawing_curves(svg))
    d = stats["mesh"]["max_edge_distance"] / stats["mesh"]["max_edge_distance_rel"] if stats["mesh"]["max_edge_distance"] else 1
    worst, worst_middle, primary = 0.0, 0.0, 0
    for element, physical in mesh["lines"].get(8, []):
        if physical != 1:
            continue
        primary += 1
        a, b, m = (nodes[n] for n in element)
        worst_middle = max(worst_middle, curves.distance(m))
        for i in range(17):
            worst = max(worst, curves.distance(quadratic_point(a, b, m, i / 16)))
    check(f"{name}: primary lines", primary == curve["primary_edges"] > 0, f"{primary} vs {curve['primary_edges']}")
    check(f"{name}: middle nodes on the curves", worst_middle <= 1e-9 * d, f"{worst_middle} (d {d})")
    check(f"{name}: primary lines within the tolerance {tolerance:.3g}", worst <= tolerance * (1 + 1e-9), f"{worst}")
    # --stats measures each line to its own curve from the same parameter: at least what is
    # measured here to the nearest curve (up to Newton's last digits), and within the tolerance.
    check(f"{name}: --stats max_edge_distance within the tolerance", stats["mesh"]["max_edge_distance"] <= tolerance,
          str(stats["mesh"]))
    check(f"{name}: --stats max_edge_distance at least the distance measured here",
          worst <= stats["mesh"]["max_edge_distance"] * (1 + 1e-6) + 1e-12 * d,
          f"here {worst}, --stats {stats['mesh']['max_edge_distance']}")

    # `curvemesh check` accepts the file and measures the same distance.
    c = run("check", msh, "--svg", svg, "--json")
    check(f"{name}: curvemesh check exit 0", c.returncode == 0, c.stdout + c.stderr)
    if c.returncode == 0:
        ours = json.loads(c.stdout)
        check(f"{name}: check sees order 2 and no invalid element", ours["order"] == 2 and ours["invalid"] == 0, c.stdout)
        check(f"{name}: check's feature distance within the tolerance", ours["max_feature_distance"] <= tolerance * (1 + 1e-9),
              c.stdout)
    return stats


splits = {}
for example in sorted(os.listdir(examples)):
    if example.endswith(".svg"):
        stats = mesh_and_verify(example, os.path.join(examples, example))
        if stats:
            splits[example] = stats["curve"]["tolerance_splits"]

# A tighter tolerance: more edges along the curves, still within it.
source = os.path.join(examples, "open-curves.svg")
tight = mesh_and_verify("open-curves-tight", source, "--curve-tolerance", "1e-6")
if tight:
    check("tight tolerance: edges split for it", tight["curve"]["tolerance_splits"] > splits.get("open-curves.svg", 0),
          str(tight["curve"]))
    check("tight tolerance: relative to d", abs(tight["curve"]["tolerance_rel"] - 1e-6) < 1e-15, str(tight["curve"]))
r = run("mesh", source, "-o", path("bad.msh"), "--order", "4")
check("--order 4 is a usage error (exit 2)", r.returncode == 2, r.stderr)
r = run("mesh", source, "-o", path("bad.msh"), "--order", "2", "--curve-tolerance", "-1")
check("a negative --curve-tolerance is a usage error (exit 2)", r.returncode == 2, r.stderr)

# meshio reads the same elements; the VTU has quadratic triangles; the SVG quadratic edges.
msh, vtu, drawing = path("shapes.msh"), path("shapes.vtu"), path("shapes.svg")
r = run("mesh", os.path.join(examples, "overlapping-shapes.svg"), "-o", msh, "--order", "2", "--vtu", vtu, "--svg", drawing)
check("outputs: exit 0", r.returncode == 0, r.stderr)
try:
    import meshio
    m = meshio.read(msh)
    check("meshio: triangle6 and line3 cells", {c.type for c in m.cells} == {"triangle6", "line3"}, str({c.type for c in m.cells}))
    v = meshio.read(vtu)
    check("vtu: quadratic triangles (VTK type 22)", [c.type for c in v.cells] == ["triangle6"], str([c.type for c in v.cells]))
    with open(vtu) as f:
        check("vtu: cell type 22 written", "\n22\n" in f.read())
    mesh_cells = next(c.data for c in m.cells if c.type == "triangle6")
    check("vtu: the .msh's triangles, node for node", (v.cells[0].data == mesh_cells).all())
except Exception as e:  # a reader failure is a finding
    check("meshio reads the outputs", False, repr(e))
with open(drawing) as f:
    text = f.read()
check("svg: quadratic edges drawn as Q commands", " Q " in text and " C " not in text, text[:300])
# XDMF (FEniCSx's format) takes quadratic triangles: Triangle_6 cells, Edge_3 facets.
xdmf = path("shapes.xdmf")
r = run("mesh", os.path.join(examples, "overlapping-shapes.svg"), "-o", path("x.msh"), "--order", "2", "--xdmf", xdmf)
check("xdmf: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    with open(xdmf) as f:
        text = f.read()
    check("xdmf: Triangle_6 cells and Edge_3 facets", 'TopologyType="Triangle_6"' in text and '"Edge_3"' in text, text[:400])
    check("xdmf: the HDF5 file beside it", os.path.exists(path("shapes.h5")))
a, b = path("det-a.msh"), path("det-b.msh")
run("mesh", os.path.join(examples, "overlapping-shapes.svg"), "-o", a, "--order", "2")
run("mesh", os.path.join(examples, "overlapping-shapes.svg"), "-o", b, "--order", "2")
with open(a, "rb") as fa, open(b, "rb") as fb:
    check("determinism: byte-identical quadratic .msh", fa.read() == fb.read())

# `check` refuses a folded quadratic triangle (edge 0-1's middle beyond the opposite corner) and
# accepts the straight one, in both file versions; the exact test here agrees.
for version, header in (("2.2", "2.2 0 8"), ("4.1", "4.1 0 8")):
    for label, points, valid in (("straight", unit, True), ("folded", bent(1.5), False)):
        p = path(f"{label}-{version}.msh")
        with open(p, "w") as f:
            f.write(f"$MeshFormat\n{header}\n$EndMeshFormat\n")
            if version == "2.2":
                f.write("$Nodes\n6\n" + "".join(f"{i + 1} {x!r} {y!r} 0\n" for i, (x, y) in enumerate(points)))
                f.write("$EndNodes\n$Elements\n1\n1 9 2 4 1 1 2 3 4 5 6\n$EndElements\n")
            else:
                f.write("$Entities\n0 0 1 0\n1 0 0 0 1 1.5 0 0 0\n$EndEntities\n")
                f.write("$Nodes\n1 6 1 6\n2 1 0 6\n" + "".join(f"{i + 1}\n" for i in range(6)))
                f.write("".join(f"{x!r} {y!r} 0\n" for x, y in points) + "$EndNodes\n")
                f.write("$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 4 5 6\n$EndElements\n")
        r = run("check", p, "--json")
        verdict = json.loads(r.stdout) if r.stdout.strip().startswith("{") else {}
        check(f"check {label} quadratic triangle ({version}): exit {0 if valid else 1}",
              r.returncode == (0 if valid else 1) and verdict.get("order") == 2 and verdict.get("invalid") == (0 if valid else 1),
              r.stdout + r.stderr)
        check(f"exact test here agrees on the {label} one ({version})",
              jacobian_positive([read_with_gmsh(p)["nodes"][n] for n in range(1, 7)]) == valid)

finish()
