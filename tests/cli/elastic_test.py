#!/usr/bin/env python3
"""Command-line contract of `curvemesh solve elastic` on examples/square-with-hole.svg (the paper's
§5.1 set-up): the VTU reads in meshio with a 3-component displacement; the body's top side (its
smallest y) does not move, everything else moves down (+y, SVG's y axis points down); the deformed
VTU is the mesh moved by the displacement; the PNG is a picture of the asked width; Newton's
iterations are reported and the last residual is below the tolerance; no gravity gives no
displacement; the drawing scaled by 10 deforms 10 times as much (lengths are in units of d);
output is deterministic; bad input exits 1, bad options exit 2.

usage: elastic_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
svg = os.path.join(examples, "square-with-hole.svg")
tmp = tempfile.TemporaryDirectory()


def path(name):
    return os.path.join(tmp.name, name)


def run(*args):
    return subprocess.run([binary, "solve", "elastic", *args], capture_output=True, text=True, timeout=600)


def write(name, text):
    with open(path(name), "w") as f:
        f.write(text)
    return path(name)


def read_json(r):
    try:
        return json.loads(r.stdout)
    except json.JSONDecodeError:
        return {}


# The paper's set-up, curved and straight.
for mode, extra in (("curved", []), ("straight", ["--straight"])):
    vtu, deformed, png = path(f"{mode}.vtu"), path(f"{mode}-deformed.vtu"), path(f"{mode}.png")
    r = run(svg, "-o", vtu, "--deformed", deformed, "--png", png, "--width", "300", "--probe", "50", "90", "--json",
            *extra)
    check(f"{mode}: exit 0", r.returncode == 0, r.stderr)
    if r.returncode != 0:
        continue
    report = read_json(r)
    check(f"{mode}: converged", report.get("converged") is True, r.stdout[-300:])
    newton = report.get("newton", [])
    check(f"{mode}: several Newton iterations, the last below the tolerance",
          len(newton) >= 3 and newton[-1]["residual"] <= 1e-10 * newton[0]["residual"],
          [it["residual"] for it in newton])
    check(f"{mode}: the energy falls at every iteration",
          all(b["energy"] <= a["energy"] for a, b in zip(newton, newton[1:])),
          [it["energy"] for it in newton])
    mesh = meshio.read(vtu)
    # The file holds only the nodes its triangles use.
    used = np.zeros(len(mesh.points), dtype=bool)
    used[np.unique(mesh.cells[0].data)] = True
    points = mesh.points[:, :2]
    cell_type = mesh.cells[0].type
    check(f"{mode}: cells of the map's order",
          cell_type == ("triangle" if mode == "straight" else "VTK_LAGRANGE_TRIANGLE"),
          cell_type)
    u = mesh.point_data.get("displacement")
    check(f"{mode}: 3-component displacement at every node", u is not None and u.shape == (len(points), 3),
          None if u is None else u.shape)
    if u is None:
        continue
    d = report.get("diagonal", 1.0)
    scale = np.abs(u).max()
    check(f"{mode}: every node is a triangle's", used.all(), (~used).sum())
    points, u, all_points, all_u = points[used], u[used], points, u
    check(f"{mode}: z component is 0", np.all(u[:, 2] == 0))
    # Hung: the body's topmost nodes (the square's top side, y = 10) stay put.
    top = points[:, 1] <= points[:, 1].min() + 1e-6 * d
    check(f"{mode}: the top side is hung", abs(points[:, 1].min() - 10) < 1e-9 and top.sum() >= 5, top.sum())
    check(f"{mode}: zero displacement at the hung nodes", np.abs(u[top]).max() <= 1e-12 * scale, np.abs(u[top]).max())
    # Gravity pulls down: +y in the drawing's coordinates.
    check(f"{mode}: everything else moves down", u[~top, 1].min() > 0, u[~top, 1].min())
    check(f"{mode}: a visible sag (1 % to 20 % of d)", 0.01 * d < u[:, 1].max() < 0.2 * d, u[:, 1].max() / d)
    bottom = np.abs(points[:, 1] - 90) < 1e-9
    check(f"{mode}: the bottom side sags", bottom.sum() > 0 and u[bottom, 1].min() > 0.5 * u[:, 1].max())
    # By symmetry the bottom side sags most at its middle, the probe's point: no node of the side
    # sags more (to the mesh's asymmetry), and it is no more than the body's largest.
    probe = report.get("probe", [0, 0])
    check(f"{mode}: the probe (bottom middle) sags at least as much as the bottom side's nodes",
          u[bottom, 1].max() * (1 - 1e-4) <= probe[1] <= u[:, 1].max(), (probe, u[bottom, 1].max(), u[:, 1].max()))
    moved = meshio.read(deformed)
    # Triangle by triangle (both files list them in the same order): the deformed nodes are the
    # nodes moved by the displacement (the straight map's deformed mesh is of order 2, x + u being
    # quadratic: compare its corners).
    cells, moved_cells = mesh.cells[0].data, moved.cells[0].data
    k = 10 if mode == "curved" else 3
    same = len(cells) == len(moved_cells)
    check(f"{mode}: deformed mesh has the same triangles", same, (len(cells), len(moved_cells)))
    if same:
        shift = np.abs(moved.points[moved_cells[:, :k], :2] - (all_points[cells[:, :k]] + all_u[cells[:, :k], :2]))
        check(f"{mode}: deformed nodes = nodes + displacement", shift.max() <= 1e-12 * d, shift.max())
    if mode != "curved":
        check(f"{mode}: deformed mesh of order 2 (VTK's quadratic triangle)", moved.cells[0].type == "triangle6"
              and moved.cells[0].data.shape[1] == 6, moved.cells[0].type)
    with open(png, "rb") as f:
        head = f.read(24)
    check(f"{mode}: PNG of the asked width",
          head[:8] == b"\x89PNG\r\n\x1a\n" and int.from_bytes(head[16:20], "big") == 300)

# Determinism: the same VTU twice.
r1 = run(svg, "-o", path("a.vtu"))
r2 = run(svg, "-o", path("b.vtu"))
check("deterministic VTU", r1.returncode == 0 and r2.returncode == 0 and
      open(path("a.vtu"), "rb").read() == open(path("b.vtu"), "rb").read())

# The text report names the iterations and the time.
check("text report: Newton iterations and time", "converged after" in r1.stdout and " s (assembly" in r1.stdout,
      r1.stdout)

# No gravity: no displacement.
r = run(svg, "-o", path("still.vtu"), "--gravity", "0")
check("no gravity: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    u = meshio.read(path("still.vtu")).point_data["displacement"]
    check("no gravity: zero displacement", np.abs(u).max() == 0, np.abs(u).max())

# Lengths in units of d: the drawing scaled by 10 moves 10 times as far (in physical units it would
# move 100 times as far). The mesher gives the scaled drawing a slightly different mesh, so the
# factor holds to the discretization error (0.1 % here): 1 %.
big = write("big.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1000 1000">'
            '<rect x="100" y="100" width="800" height="800"/><circle cx="500" cy="500" r="200"/></svg>')
small = read_json(run(svg, "--probe", "50", "90", "--json"))
large = read_json(run(big, "--probe", "500", "900", "--json"))
if "probe" in small and "probe" in large:
    check("scaled drawing: 10 times the displacement", abs(large["probe"][1] / small["probe"][1] - 10) < 0.1,
          (small["probe"], large["probe"]))
else:
    check("scaled drawing: probes found", False, (small, large))

# Load steps reach the same equilibrium.
stepped = read_json(run(svg, "--probe", "50", "90", "--json", "--load-steps", "3"))
check("load steps: same probe value", "probe" in stepped and "probe" in small
      and abs(stepped["probe"][1] - small["probe"][1]) < 1e-8 * abs(small["probe"][1]), stepped.get("probe"))
check("load steps: three of them", stepped.get("newton", [{}])[-1].get("load_step") == 3)

# Bad input: exit 1 with a message.
open_curve = write("open.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
                   '<path d="M 1 1 L 9 9" stroke="black" fill="none"/></svg>')
for name, args in (("missing file", [path("nothing.svg")]),
                   ("not SVG", [write("bad.svg", "this is not a drawing")]),
                   ("nothing enclosed", [open_curve]),
                   ("Newton cannot converge in one iteration", [svg, "--max-iterations", "1"]),
                   ("unwritable output", [svg, "-o", path("no/such/dir/out.vtu")])):
    r = run(*args)
    check(f"{name}: exit 1", r.returncode == 1, (r.returncode, r.stderr))
    check(f"{name}: says why", r.stderr.strip().startswith("curvemesh:") or "curvemesh:" in r.stderr, r.stderr)

# Bad options: exit 2.
for name, args in (("Poisson's ratio 0.5", ["--poisson", "0.5"]), ("negative Young's modulus", ["--youngs", "-1"]),
                   ("probe with one number", ["--probe", "1"]), ("no load steps", ["--load-steps", "0"])):
    r = run(svg, *args)
    check(f"{name}: exit 2", r.returncode == 2, (r.returncode, r.stderr))

finish()
