#!/usr/bin/env python3
"""Command-line contract of `curvemesh solve stokes`: flow through a drawing from the box's left
side to its right side, around every curve.

The VTU must read in meshio with finite velocity (z = 0), pressure and speed (= |velocity|) at
every node; the velocity must vanish on every wall node (the drawing's lines and the box's top
and bottom sides, taken from `curvemesh mesh` of the same drawing, which meshes it the same way)
and follow the parabolic inflow on the left side; a region closed off by curves holds fluid at
rest; output is deterministic; --straight and the PNG work; bad input exits 1 with a message and
bad options exit 2.

usage: stokes_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import os
import re
import struct
import subprocess
import sys
import tempfile

import meshio
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
drawing = os.path.join(examples, "overlapping-shapes.svg")


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def path(name):
    return os.path.join(tmp.name, name)


def png_size(file):
    with open(file, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return struct.unpack(">II", head[16:24])


# The wall nodes: every node of a primary or secondary line, and of the box's top and bottom
# sides, as meshed by `curvemesh mesh` with the same (default) options.
r = run("mesh", drawing, "-o", path("mesh.msh"))
check("mesh: exit 0", r.returncode == 0, r.stderr)
msh = meshio.read(path("mesh.msh"))
names = {name: tag for name, (tag, dim) in msh.field_data.items() if dim == 1}
box_lo, box_hi = msh.points[:, :2].min(axis=0), msh.points[:, :2].max(axis=0)
d = float(np.linalg.norm(box_hi - box_lo))
tol = 1e-9 * d
wall_nodes, wall_corners, left_nodes = set(), set(), set()
for block, tags in zip(msh.cells, msh.cell_data["gmsh:physical"]):
    if not block.type.startswith("line"):
        continue
    for nodes, tag in zip(block.data, tags):
        if tag in (names["primary"], names["secondary"]):
            wall_nodes.update(nodes.tolist())
            wall_corners.update(nodes[:2].tolist())
        elif tag == names["boundary"]:
            ends = msh.points[nodes[:2], :2]
            if np.all(np.abs(ends[:, 1] - box_lo[1]) <= tol) or np.all(np.abs(ends[:, 1] - box_hi[1]) <= tol):
                wall_nodes.update(nodes.tolist())
                wall_corners.update(nodes[:2].tolist())
            elif np.all(np.abs(ends[:, 0] - box_lo[0]) <= tol):
                left_nodes.update(nodes.tolist())
check("mesh: walls and an inlet found", len(wall_nodes) > 100 and len(left_nodes) > 3,
      f"{len(wall_nodes)} wall nodes, {len(left_nodes)} inlet nodes")


def points_at(points, where):
    """Indices of the VTU points at each given position (a cut mesh has several copies)."""
    out = []
    for x in where:
        out.extend(np.nonzero(np.linalg.norm(points - x, axis=1) <= tol)[0].tolist())
    return np.array(sorted(set(out)), dtype=int)


results = {}
for name, extra in (("curved", []), ("straight", ["--straight"])):
    vtu, png = path(f"{name}.vtu"), path(f"{name}.png")
    r = run("solve", "stokes", drawing, "-o", vtu, "--png", png, "--width", "240", "--inflow-speed", "2", *extra)
    check(f"{name}: exit 0", r.returncode == 0, r.stderr)
    if r.returncode != 0:
        continue
    check(f"{name}: prints unknowns and times",
          re.search(r"stokes: \d+ velocity unknowns .* assembly [0-9.]+ s, solve [0-9.]+ s", r.stdout) is not None,
          r.stdout)
    held = re.search(r"held: (\d+) for closed regions", r.stdout)
    # The rounded rectangle, the circle, the ellipse and the polygon close off regions of their own.
    check(f"{name}: closed regions get a pressure reference", held is not None and int(held.group(1)) >= 4, r.stdout)
    check(f"{name}: PNG of the asked width", png_size(png) is not None and png_size(png)[0] == 240, str(png_size(png)))
    try:
        m = meshio.read(vtu)
    except Exception as e:  # noqa: BLE001 - any reader failure is the finding
        check(f"{name}: meshio reads the VTU", False, repr(e))
        continue
    pd = m.point_data
    check(f"{name}: arrays velocity, pressure, speed", {"velocity", "pressure", "speed"} <= set(pd), str(list(pd)))
    if not {"velocity", "pressure", "speed"} <= set(pd):
        continue
    u, p, s = pd["velocity"], pd["pressure"].reshape(-1), pd["speed"].reshape(-1)
    n = len(m.points)
    check(f"{name}: one value per node", u.shape == (n, 3) and p.shape == (n,) and s.shape == (n,),
          f"{u.shape} {p.shape} {s.shape} for {n} points")
    check(f"{name}: finite", np.isfinite(u).all() and np.isfinite(p).all() and np.isfinite(s).all())
    check(f"{name}: planar velocity", np.all(u[:, 2] == 0))
    check(f"{name}: speed is |velocity|", np.allclose(s, np.linalg.norm(u, axis=1), rtol=1e-12, atol=0))
    top = s.max()
    check(f"{name}: the fluid moves", top > 1.0, f"highest speed {top}")
    points = m.points[:, :2]
    walls = points_at(points, msh.points[sorted(wall_nodes), :2])
    # Every wall node once per side (straight triangles have their corners only).
    expected = len(wall_nodes) if name == "curved" else len(wall_corners)
    check(f"{name}: wall nodes found in the VTU", len(walls) >= expected, f"{len(walls)} of {expected}")
    worst = s[walls].max() if len(walls) else np.inf
    check(f"{name}: no slip on the walls", worst <= 1e-12 * top, f"speed {worst} at a wall node, highest {top}")
    inlet = points_at(points, msh.points[sorted(left_nodes), :2])
    y = (points[inlet, 1] - box_lo[1]) / (box_hi[1] - box_lo[1])
    profile = 2 * 4 * y * (1 - y)
    inflow_ok = np.allclose(u[inlet, 0], profile, rtol=0, atol=1e-9) and np.all(np.abs(u[inlet, 1]) <= 1e-9)
    check(f"{name}: parabolic inflow on the left side", len(inlet) > 0 and inflow_ok,
          f"largest difference {np.abs(u[inlet, 0] - profile).max() if len(inlet) else None}")
    # Inside the rounded rectangle (20..240 × 20..180, corners of radius 24), whose outline is a wall
    # all round: closed off, whatever the circle and the ellipse cut it into. (The box its corners'
    # centres span, so that a mesh of any size has nodes there.)
    inside = (points[:, 0] > 44) & (points[:, 0] < 216) & (points[:, 1] > 44) & (points[:, 1] < 156)
    pocket = np.nonzero(inside)[0]
    check(f"{name}: fluid at rest in a closed region", len(pocket) > 0 and s[pocket].max() <= 1e-12 * top,
          f"{len(pocket)} nodes, highest speed {s[pocket].max() if len(pocket) else None}")
    results[name] = m

if "curved" in results and "straight" in results:
    # The same mesh with another map: the straight triangles' nodes are the cubic ones' corners,
    # and the flows differ there.
    mc, ml = results["curved"], results["straight"]
    check("straight: fewer nodes (corners only)", len(ml.points) < len(mc.points),
          f"{len(ml.points)} vs {len(mc.points)}")
    corner_of = {tuple(x): i for i, x in enumerate(mc.points[:, :2].tolist())}
    found = [corner_of.get(tuple(x)) for x in ml.points[:, :2].tolist()]
    check("straight: its nodes are nodes of the cubic mesh", all(i is not None for i in found))
    if all(i is not None for i in found):
        difference = np.abs(mc.point_data["speed"][found] - ml.point_data["speed"]).max()
        check("straight: another flow", difference > 1e-6 * mc.point_data["speed"].max(), f"difference {difference}")

# A drawing with nothing in the box: Poiseuille flow, which P2-P1 holds exactly,
#   u = 4 U s (1 - s) with s = (y - y0) / H,   p = 8 mu U / H^2 (x1 - x).
with open(path("empty.svg"), "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"/>\n')
r = run("solve", "stokes", path("empty.svg"), "-o", path("empty.vtu"), "--viscosity", "3", "--inflow-speed", "2")
check("empty box: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    m = meshio.read(path("empty.vtu"))
    x, y = m.points[:, 0], m.points[:, 1]
    height = y.max() - y.min()
    s = (y - y.min()) / height
    u = m.point_data["velocity"]
    p = m.point_data["pressure"].reshape(-1)
    exact_p = 8 * 3 * 2 / height**2 * (x.max() - x)
    check("empty box: Poiseuille velocity", np.abs(u[:, 0] - 2 * 4 * s * (1 - s)).max() <= 1e-10 * 2
          and np.abs(u[:, 1]).max() <= 1e-10 * 2, f"{np.abs(u[:, 0] - 2 * 4 * s * (1 - s)).max()}")
    check("empty box: Poiseuille pressure", np.abs(p - exact_p).max() <= 1e-10 * exact_p.max(),
          f"{np.abs(p - exact_p).max()} of {exact_p.max()}")

# The colour scale of the picture: another top colour, another picture.
r = run("solve", "stokes", drawing, "--png", path("scaled.png"), "--width", "240", "--inflow-speed", "2",
        "--colour-top", "100")
with open(path("curved.png"), "rb") as a, open(path("scaled.png"), "rb") as b:
    check("--colour-top: another picture", r.returncode == 0 and a.read() != b.read(), r.stderr)

# Deterministic: the same VTU again, byte for byte.
r = run("solve", "stokes", drawing, "-o", path("again.vtu"), "--inflow-speed", "2")
with open(path("curved.vtu"), "rb") as a, open(path("again.vtu"), "rb") as b:
    check("deterministic VTU", r.returncode == 0 and a.read() == b.read())

# Bad input: exit 1 and say why.
r = run("solve", "stokes", path("missing.svg"), "-o", path("x.vtu"))
check("missing file: exit 1", r.returncode == 1, f"{r.returncode}: {r.stderr}")
check("missing file: message names the file", "missing.svg" in r.stderr, r.stderr)
with open(path("garbage.svg"), "w") as f:
    f.write("this is <not an svg drawing\n")
r = run("solve", "stokes", path("garbage.svg"), "-o", path("x.vtu"))
check("garbage SVG: exit 1", r.returncode == 1, f"{r.returncode}: {r.stderr}")
check("garbage SVG: message", "garbage.svg" in r.stderr and len(r.stderr.strip()) > 20, r.stderr)
check("garbage SVG: no output", not os.path.exists(path("x.vtu")))
# Bad options: usage errors.
for option in (["--viscosity", "0"], ["--viscosity", "inf"], ["--inflow-speed", "-1"], ["--colour-top", "0"],
               ["--domain", "nowhere"]):
    r = run("solve", "stokes", drawing, "-o", path("x.vtu"), *option)
    check(f"{' '.join(option)}: exit 2", r.returncode == 2 and len(r.stderr) > 0, f"{r.returncode}: {r.stderr}")

finish()
