#!/usr/bin/env python3
"""Command-line contract of `curvemesh verify convergence` and `curvemesh solve inflate`.

verify convergence --json: one JSON object with p3_geometry and p1_geometry, each with h, l2
(at least 4 levels) and rate_l2; P2 on the cubic map converges at L2 rate >= 2.7 and at least
0.4 above the straight map of the same meshes, whose rate is at most 2.2 (its O(h²) geometric
error). solve inflate: a VTU that meshio reads with a height at every node, zero on the domain's
border and positive inside; an OBJ and a PLY surface; the straight map gives the same number of
nodes; bad input and usage errors exit 1 and 2 with a message.

usage: fem_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import re
import os
import subprocess
import sys
import tempfile

import meshio
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
root = tmp.name


def run(*args, timeout=600):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=timeout)


# --- verify convergence -----------------------------------------------------------------------
r = run("verify", "convergence", "--json")
check("verify convergence exits 0", r.returncode == 0, r.stderr[-500:])
try:
    result = json.loads(r.stdout)
except json.JSONDecodeError as e:
    result = {}
    check("verify convergence prints one JSON object", False, str(e))
for key in ("p3_geometry", "p1_geometry"):
    s = result.get(key, {})
    check(f"{key} has h, l2, rate_l2", all(k in s for k in ("h", "l2", "rate_l2")), str(list(s)))
    h, l2 = s.get("h", []), s.get("l2", [])
    check(f"{key}: at least 4 levels", len(h) >= 4 and len(h) == len(l2), f"{len(h)} h, {len(l2)} l2")
    check(f"{key}: h shrinks", all(a > b for a, b in zip(h, h[1:])), str(h))
    if len(h) >= 2:
        # The reported rate is the least-squares slope of the reported numbers.
        slope = np.polyfit(np.log(h), np.log(l2), 1)[0]
        check(f"{key}: rate_l2 is the slope of log l2 over log h", abs(slope - s["rate_l2"]) < 1e-9,
              f"{slope} vs {s['rate_l2']}")
curved = result.get("p3_geometry", {}).get("rate_l2", 0)
straight = result.get("p1_geometry", {}).get("rate_l2", 9)
print(f"L2 rates: cubic map {curved:.3f}, straight map {straight:.3f}")
check("cubic map: L2 rate >= 2.7", curved >= 2.7, f"{curved}")
check("cubic map: at least 0.4 above the straight map", curved >= straight + 0.4, f"{curved} vs {straight}")
check("straight map: L2 rate <= 2.2 (geometric error)", straight <= 2.2, f"{straight}")
p3, p1 = result.get("p3_geometry", {}), result.get("p1_geometry", {})
check("same meshes for both maps", p3.get("triangles") == p1.get("triangles"), "")
check("cubic map more accurate on every level",
      all(a < b for a, b in zip(p3.get("l2", []), p1.get("l2", []))), f"{p3.get('l2')} vs {p1.get('l2')}")

r = run("verify", "convergence", "--edge-lengths", "0.05")
check("one level is a usage error (exit 2)", r.returncode == 2, f"exit {r.returncode}")

# --- solve inflate ----------------------------------------------------------------------------
drawing = os.path.join(examples, "overlapping-shapes.svg")
vtu, png, obj, ply = (os.path.join(root, f"inflate.{e}") for e in ("vtu", "png", "obj", "ply"))
r = run("solve", "inflate", drawing, "-o", vtu, "--png", png, "--surface", obj, "--height", "0.2")
check("solve inflate exits 0", r.returncode == 0, r.stderr[-500:])
check("solve inflate prints its time", "solve" in r.stdout and " s" in r.stdout, r.stdout)
try:
    m = meshio.read(vtu)
    height = np.asarray(m.point_data["height"])
    cells = m.cells_dict.get("lagrange_triangle", m.cells_dict.get("VTK_LAGRANGE_TRIANGLE"))
    check("VTU: cubic Lagrange triangles", cells is not None and cells.shape[1] == 10, str(m.cells_dict.keys()))
    check("VTU: finite heights", np.all(np.isfinite(height)), "")
    # The border: edges used by one triangle only (corners of the 10-node elements).
    count = {}
    for c in cells:
        for a, b in ((c[0], c[1]), (c[1], c[2]), (c[2], c[0])):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    border = {v for e, n in count.items() if n == 1 for v in e}
    check("height 0 on the border", max(abs(height[v]) for v in border) < 1e-9,
          f"max {max(abs(height[v]) for v in border)}")
    diag = np.linalg.norm(np.ptp(m.points[:, :2], axis=0))
    check("highest point near --height·d", 0.15 * diag < height.max() < 0.25 * diag, f"{height.max()} for d={diag}")
except Exception as e:  # noqa: BLE001
    check("VTU readable by meshio", False, repr(e))
check("PNG written", os.path.exists(png) and open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n", "")
try:
    surface = meshio.read(obj)
    check("OBJ surface has triangles", len(surface.cells_dict.get("triangle", [])) > 0, "")
    check("OBJ surface lifts", surface.points[:, 2].max() > 0, "")
except Exception as e:  # noqa: BLE001
    check("OBJ readable by meshio", False, repr(e))

r = run("solve", "inflate", drawing, "--straight", "-o", vtu, "--surface", ply)
check("solve inflate --straight exits 0", r.returncode == 0, r.stderr[-500:])
try:
    m1 = meshio.read(vtu)
    check("--straight: straight triangles", "triangle" in m1.cells_dict, str(m1.cells_dict.keys()))
    check("PLY written", open(ply).read(3) == "ply", "")
except Exception as e:  # noqa: BLE001
    check("--straight VTU readable", False, repr(e))

# The solvers' domains are mesh's, by the same names: a stroke-only icon's painted domain is the
# triangles `mesh --domain painted` keeps.
icon = os.path.join(examples, "stroked-icon.svg")
r = run("solve", "inflate", icon, "--domain", "painted", "-o", vtu)
m_icon = re.search(r"(\d+) triangles in the domain", r.stderr)
r2 = run("mesh", icon, "--domain", "painted", "-o", os.path.join(root, "icon.msh"))
m_mesh = re.search(r"(\d+) triangles of order 3", r2.stdout + r2.stderr)
check("solve --domain painted: the triangles of mesh --domain painted",
      r.returncode == 0 and r2.returncode == 0 and m_icon and m_mesh and m_icon.group(1) == m_mesh.group(1),
      r.stderr[-400:] + r2.stderr[-400:])

bad = os.path.join(root, "bad.svg")
with open(bad, "w") as f:
    f.write("<svg><path d='M 0 0 L")
for args, code, what in ((["solve", "inflate", os.path.join(root, "missing.svg"), "-o", vtu], 1, "missing file"),
                         (["solve", "inflate", bad, "-o", vtu], 1, "malformed SVG"),
                         (["solve", "inflate", os.path.join(examples, "open-curves.svg"), "-o", vtu], None, "open curves"),
                         (["solve", "inflate", drawing, "--domain", "nowhere"], 2, "bad --domain"),
                         (["solve", "inflate", drawing, "--domain", "inside"], 2, "--domain inside (evenodd's name)"),
                         (["solve"], 2, "no problem named")):
    r = run(*args)
    if code is None:
        # Open curves enclose nothing: either an empty domain (exit 1 with a message) or a result.
        check(f"{what}: exit 0 or 1 with a message", r.returncode == 0 or (r.returncode == 1 and r.stderr), r.stderr)
    else:
        check(f"{what}: exit {code}", r.returncode == code and r.stderr.strip() != "", f"exit {r.returncode}: {r.stderr}")

finish()
