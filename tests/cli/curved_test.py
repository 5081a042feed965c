#!/usr/bin/env python3
"""Command-line contract of curved meshing (`curvemesh mesh`, the default) and of `curvemesh check`.

Every curved output is certified by the independent checker tests/tools/msh_check.py (exact
Bernstein test of det J on the written doubles, shared edge nodes, Gmsh and meshio read it);
`curvemesh check` must agree on valid meshes and refuse folded and malformed ones; the VTU must
read in meshio; output is deterministic. Geometry: meshing a circle with shrinking edges, the
largest distance from the primary edges to the circle falls like h² with --linear and is at the
reader's own tolerance (1e-9 r: its cubics) with cubic edges, which reproduce cubic input exactly.

usage: curved_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
checker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "msh_check.py")
tmp = tempfile.TemporaryDirectory()


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def certify(name, path):
    r = subprocess.run([sys.executable, checker, path, "--json"], capture_output=True, text=True, timeout=600)
    check(f"{name}: independent checker accepts the mesh", r.returncode == 0, (r.stdout + r.stderr)[-600:])
    try:
        return json.loads(r.stdout)
    except json.JSONDecodeError:
        return {}


def path(name):
    return os.path.join(tmp.name, name)


# The bundled examples, curved, in both file versions: certified by the independent checker and
# by `curvemesh check`, every primary edge curved or accounted for.
for example in sorted(os.listdir(examples)):
    if not example.endswith(".svg"):
        continue
    source = os.path.join(examples, example)
    for version in ("4.1", "2.2"):
        name = f"{example}-{version}"
        out, stats = path(name + ".msh"), path(name + ".json")
        r = run("mesh", source, "-o", out, "--msh-version", version, "--stats", stats)
        check(f"{name}: exit 0", r.returncode == 0, r.stderr)
        if r.returncode != 0:
            continue
        report = certify(name, out)
        check(f"{name}: cubic triangles", report.get("curved", 0) == report.get("triangles", -1) > 0,
              f"{report.get('curved')} of {report.get('triangles')}")
        with open(stats) as f:
            s = json.load(f)["curve"]
        check(f"{name}: every primary edge curved or left straight", s["curved_edges"] + s["straight_primary_edges"] == s["primary_edges"], str(s))
        c = run("check", out, "--svg", source, "--json")
        check(f"{name}: curvemesh check exit 0", c.returncode == 0, c.stdout + c.stderr)
        if c.returncode == 0:
            ours = json.loads(c.stdout)
            check(f"{name}: check sees no invalid element", ours["invalid"] == 0, c.stdout)
            check(f"{name}: check counts the triangles", ours["triangles"] == report.get("triangles"), c.stdout)
            # Edges left straight are at most that far from their curve; curved ones reproduce the
            # cubic input exactly.
            check(f"{name}: feature distance within what the mesher recorded",
                  ours["max_feature_distance_rel"] <= s["max_distance_rel"] + 1e-9,
                  f"check {ours['max_feature_distance_rel']}, mesh {s['max_distance_rel']}")

# Determinism, VTU and SVG outputs.
source = os.path.join(examples, "overlapping-shapes.svg")
a, b = path("det-a.msh"), path("det-b.msh")
run("mesh", source, "-o", a, "--vtu", path("o.vtu"), "--svg", path("o.svg"))
run("mesh", source, "-o", b)
with open(a, "rb") as fa, open(b, "rb") as fb:
    check("determinism: byte-identical curved .msh", fa.read() == fb.read())
try:
    import meshio
    m = meshio.read(path("o.vtu"))
    types = {c.type for c in m.cells}
    check("vtu: Lagrange triangles of 10 nodes", all(c.data.shape[1] == 10 for c in m.cells) and len(types) == 1, str(types))
except Exception as e:  # a reader failure is a finding
    check("vtu: meshio reads it", False, str(e))
with open(path("o.svg")) as f:
    drawing = f.read()
check("svg: curved edges drawn as cubic Béziers", " C " in drawing or "C" in drawing.split('d="')[1][:200], drawing[:300])

# `check` refuses what is invalid: a P3 triangle folded by an edge node pushed beyond the opposite
# side (its corners counter-clockwise), and a malformed file.
folded = path("folded.msh")
nodes = [(0, 0), (1, 0), (0, 1), (1 / 3, 0), (2 / 3, 0), (2 / 3, 1 / 3), (1 / 3, 2 / 3), (0, 2 / 3), (0.8, 0.8), (1 / 3, 1 / 3)]
with open(folded, "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n")
    f.writelines(f"{i + 1} {x!r} {y!r} 0\n" for i, (x, y) in enumerate(nodes))
    f.write("$EndNodes\n$Elements\n1\n1 21 2 4 1 " + " ".join(str(i + 1) for i in range(10)) + "\n$EndElements\n")
r = run("check", folded)
check("check: a folded cubic triangle is invalid (exit 1)", r.returncode == 1 and "invalid: 1" in r.stdout, r.stdout + r.stderr)
straight = path("straight.msh")
with open(straight, "w") as f:
    ok_nodes = nodes[:8] + [(0, 1 / 3), (1 / 3, 1 / 3)]
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n")
    f.writelines(f"{i + 1} {x!r} {y!r} 0\n" for i, (x, y) in enumerate(ok_nodes))
    f.write("$EndNodes\n$Elements\n1\n1 21 2 4 1 " + " ".join(str(i + 1) for i in range(10)) + "\n$EndElements\n")
r = run("check", straight)
check("check: a straight cubic triangle is valid (exit 0)", r.returncode == 0 and "invalid: 0" in r.stdout, r.stdout + r.stderr)
broken = path("broken.msh")
with open(broken, "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n")
r = run("check", broken)
check("check: a truncated file is refused (exit 1, a message)", r.returncode == 1 and r.stderr.strip() != "", r.stderr)


# Geometry: a <circle>, meshed with shrinking edges. The reader draws it as cubics within 1e-9·r of
# the circle (svg/arc.hpp); the distance from the primary edges to the circle itself is measured.
def edge_error(msh):
    """Largest distance from the primary line elements (sampled) to the unit circle, and the
    longest primary edge."""
    m = meshio_read(msh)
    worst, h = 0.0, 0.0
    for block, phys in zip(m.cells, m.cell_data["gmsh:physical"]):
        if block.type not in ("line", "line4"):
            continue
        for nodes_, tag in zip(block.data, phys):
            if tag != 1:  # primary
                continue
            pts = [tuple(m.points[n][:2]) for n in nodes_]
            h = max(h, math.dist(pts[0], pts[1]))
            for i in range(9):
                s = i / 8
                if len(pts) == 2:
                    q = tuple(pts[0][d] + s * (pts[1][d] - pts[0][d]) for d in range(2))
                else:  # nodes at s = 0, 1, 1/3, 2/3
                    at, P = (0, 1, 1 / 3, 2 / 3), pts
                    w = [math.prod((s - at[j]) / (at[i] - at[j]) for j in range(4) if j != i) for i in range(4)]
                    q = tuple(sum(w[i] * P[i][d] for i in range(4)) for d in range(2))
                worst = max(worst, abs(math.hypot(*q) - 1))
    return worst, h


def meshio_read(p):
    import meshio
    return meshio.read(p)


disk = path("circle.svg")
with open(disk, "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-1 -1 2 2"><circle r="1" fill="none" stroke="black"/></svg>')
d = 2 * math.sqrt(2)
levels = []
# Edge lengths below the circle's 10° cubics (0.174, 0.062 d), whose ends are vertices of every mesh.
for l in (0.05, 0.025, 0.0125, 0.00625):
    row = {"l": l}
    for mode in ("linear", "cubic"):
        out = path(f"circle-{mode}-{l}.msh")
        extra = ["--linear"] if mode == "linear" else []
        # μ scales with l so that the curve's flatness does not bound the edges instead of l.
        r = run("mesh", disk, "-o", out, "-l", str(l), "--mu", str(l / 20), "--epsilon", str(l / 10), "--min-angle", "30", *extra)
        check(f"circle l={l} {mode}: exit 0", r.returncode == 0, r.stderr)
        if r.returncode == 0:
            certify(f"circle l={l} {mode}", out)
            row[mode], row[mode + "_h"] = edge_error(out)
    levels.append(row)
print("circle: l, h (linear), distance linear, distance cubic (relative to d)")
for row in levels:
    print(f"  {row['l']:<8} {row.get('linear_h', 0):.4f} {row.get('linear', 0) / d:.3e} {row.get('cubic', 0) / d:.3e}")
if all("linear" in row and "cubic" in row for row in levels):
    rates = [math.log(a["linear"] / b["linear"]) / math.log(a["linear_h"] / b["linear_h"]) for a, b in zip(levels, levels[1:])]
    print("  linear rates:", ", ".join(f"{x:.2f}" for x in rates))
    check("circle: linear distance falls like h^2", all(1.7 <= x <= 2.3 for x in rates), str(rates))
    # Within the reader's 1e-9·r of the circle; the edges follow its cubics to round-off.
    check("circle: cubic edges lie on the circle (distance at most 1e-9 r)", all(row["cubic"] <= 1e-9 + 1e-12 * d for row in levels),
          str([row["cubic"] for row in levels]))

finish()
