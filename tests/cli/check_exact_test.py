#!/usr/bin/env python3
"""`curvemesh check` (a certificate in doubles with a rigorous error bound, rationals only where it
cannot decide) against `curvemesh check --exact` (every element in rationals): the same order,
triangles, invalid and undecided counts and the same smallest scaled Jacobian, to the last digit,

- on every bundled drawing meshed at orders 1, 2 and 3, as it is, with --regions and with
  --domain filled (where the drawing fills something), and in the Gmsh 2.2 format;
- on hand-made meshes of nearly degenerate elements, where the doubles cannot decide and the
  element must go to the rationals (exact_fallbacks counts it), and of inverted ones, which the
  doubles must refuse alone: linear triangles collinear or within 2^-50 of it, of size 1e-170
  (whose products underflow) and 1e200 (whose products overflow); quadratic and cubic ones whose
  det J is 0, or positive by 2^-50 of its scale, at a corner; folded ones.

usage: check_exact_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
COMPARED = ["order", "triangles", "invalid", "undecided", "min_scaled_jacobian"]


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def path(name):
    return os.path.join(tmp.name, name)


def both(msh):
    """The filtered and the exact report of a file (None where check printed no JSON)."""
    reports = []
    for extra in ([], ["--exact"]):
        r = run("check", msh, "--json", *extra)
        try:
            reports.append(json.loads(r.stdout))
        except json.JSONDecodeError:
            reports.append(None)
            check(f"{msh} {extra}: a JSON verdict", False, r.stderr)
    return reports


def compare(name, msh):
    filtered, exact = both(msh)
    if filtered is None or exact is None:
        return None
    for key in COMPARED:
        check(f"{name}: {key}", filtered[key] == exact[key], f"filtered {filtered[key]!r}, exact {exact[key]!r}")
    check(f"{name}: --exact decides every element in rationals", exact["exact_fallbacks"] == exact["triangles"],
          str(exact))
    return filtered


# ---------------------------------------------------------------------------------------------
# The meshes the bundled drawings make.

meshed = refused = 0
for svg in sorted(glob.glob(os.path.join(examples, "*.svg"))):
    stem = os.path.splitext(os.path.basename(svg))[0]
    for order in (1, 2, 3):
        for extra in ([], ["--regions"], ["--domain", "filled"], ["--msh-version", "2.2"]):
            name = f"{stem} order {order} {' '.join(extra)}".strip()
            msh = path("m.msh")
            r = run("mesh", svg, "-o", msh, "--order", str(order), "-q", *extra)
            if extra[:2] == ["--domain", "filled"] and "nothing of the drawing is filled" in r.stderr:
                check(f"{name}: refused as empty", r.returncode == 1, r.stderr)
                refused += 1
                continue
            check(f"{name}: meshed", r.returncode == 0, r.stderr)
            if r.returncode != 0:
                continue
            report = compare(name, msh)
            if report is not None:
                meshed += 1
                check(f"{name}: valid", report["invalid"] == 0, str(report))
check("every drawing meshed and compared in every way", meshed + refused == 12 * len(glob.glob(os.path.join(examples, "*.svg"))),
      f"{meshed} meshes, {refused} refused as empty")


# ---------------------------------------------------------------------------------------------
# Hand-made elements, one file each, written as Gmsh 2.2 with every double as Python's repr
# (which reads back as the same double).

GMSH_TYPE = {3: 2, 6: 9, 10: 21}


def write_msh(name, triangles):
    """One triangle per node list; nodes are not shared."""
    nodes = [p for t in triangles for p in t]
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", str(len(nodes))]
    lines += [f"{i + 1} {x!r} {y!r} 0" for i, (x, y) in enumerate(nodes)]
    lines += ["$EndNodes", "$Elements", str(len(triangles))]
    first = 1
    for k, t in enumerate(triangles):
        ids = " ".join(str(first + i) for i in range(len(t)))
        lines.append(f"{k + 1} {GMSH_TYPE[len(t)]} 2 4 1 {ids}")
        first += len(t)
    lines.append("$EndElements")
    with open(path(name), "w") as f:
        f.write("\n".join(lines) + "\n")
    return path(name)


def p3_straight(a, b, c):
    """Gmsh's 10 nodes of the straight triangle a, b, c."""
    def at(u, v):
        return (a[0] + u * (b[0] - a[0]) + v * (c[0] - a[0]), a[1] + u * (b[1] - a[1]) + v * (c[1] - a[1]))
    third, two = 1 / 3, 2 / 3
    return [a, b, c, at(third, 0), at(two, 0), at(two, third), at(third, two), at(0, two), at(0, third),
            at(third, third)]


def p2_straight(a, b, c):
    def mid(p, q):
        return ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
    return [a, b, c, mid(a, b), mid(b, c), mid(c, a)]


def scaled(nodes, s):
    return [(x * s, y * s) for x, y in nodes]


TINY = 2.0 ** -50
# A cubic triangle whose det J is 0 at corner 0 and positive everywhere else: the map
# (9 (u + v), 9 v (u + v)), whose det J is 81 (u + v), its nodes integers. Moving node 3, at
# (u, v) = (1/3, 0), by (0, ε) turns the Bézier control next to corner 0 on edge 0→1 by (0, 3ε),
# which makes det J = −81 ε at corner 0.
def p3_corner(eps):
    n = [(3.0 * (i + j), 1.0 * j * (i + j)) for i, j in
         [(0, 0), (3, 0), (0, 3), (1, 0), (2, 0), (2, 1), (1, 2), (0, 2), (0, 1), (1, 1)]]
    n[3] = (n[3][0], n[3][1] + eps)
    return n


# A quadratic triangle whose det J at corner 0 is (−x1 + 4 x3) × (−x2 + 4 x5) = (4δ, 2) × (0, 2) = 8δ.
def p2_corner(delta):
    return [(0.0, 0.0), (2.0, 0.0), (0.0, 2.0), (0.5 + delta, 0.5), (1.0, 1.0), (0.0, 1.0)]


# name: (triangles, invalid, exact_fallbacks)
CASES = {
    "p1 positive far from the origin": ([[(1e8, 1e8), (1e8 + 1, 1e8), (1e8, 1e8 + 1)]], 0, 0),
    "p1 inverted": ([[(0.0, 0.0), (0.0, 1.0), (1.0, 0.0)]], 1, 0),
    "p1 collinear": ([[(0.0, 0.0), (1.0, 1.0), (3.0, 3.0)]], 1, 1),
    "p1 within 2^-50 of collinear, positive": ([[(0.0, 0.0), (1.0, 1.0), (3.0, 3.0 + 4 * TINY)]], 0, 1),
    "p1 within 2^-50 of collinear, inverted": ([[(0.0, 0.0), (1.0, 1.0), (3.0, 3.0 - 4 * TINY)]], 1, 1),
    "p1 of size 1e-170": ([[(0.0, 0.0), (1e-170, 0.0), (0.0, 1e-170)]], 0, 1),
    "p1 of size 1e-170, inverted": ([[(0.0, 0.0), (0.0, 1e-170), (1e-170, 0.0)]], 1, 1),
    "p1 of size 1e200": ([[(0.0, 0.0), (1e200, 0.0), (0.0, 1e200)]], 0, 1),
    "p1 mixed": ([[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)], [(0.0, 0.0), (1.0, 1.0), (3.0, 3.0)],
                  [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0)]], 2, 1),
    "p2 straight": ([p2_straight((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))], 0, 0),
    "p2 positive, decided by subdivision": ([[(0, 0), (40, 0), (0, 40), (18, 9), (15, 22), (-7, 10)]], 0, 0),
    "p2 folded": ([[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.5, 1.5), (0.5, 0.5), (0.0, 0.5)]], 1, 0),
    "p2 zero at a corner": ([p2_corner(0.0)], 1, 1),
    "p2 positive by 2^-50 at a corner": ([p2_corner(TINY)], 0, 1),
    "p2 negative by 2^-50 at a corner": ([p2_corner(-TINY)], 1, 1),
    "p2 of size 1e-170": ([scaled(p2_straight((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)), 1e-170)], 0, 1),
    "p3 straight": ([p3_straight((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))], 0, 0),
    "p3 folded": ([[(0, 0), (1, 0), (0, 1), (1 / 3, 0), (2 / 3, 0), (2 / 3, 1 / 3), (1 / 3, 2 / 3), (0, 2 / 3),
                    (0.8, 0.8), (1 / 3, 1 / 3)]], 1, 0),
    "p3 zero at a corner": ([p3_corner(0.0)], 1, 1),
    "p3 positive by 2^-50 at a corner": ([p3_corner(-TINY)], 0, 1),
    "p3 negative by 2^-50 at a corner": ([p3_corner(TINY)], 1, 1),
    "p3 of size 1e-170": ([scaled(p3_straight((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)), 1e-170)], 0, 1),
    "p3 of size 1e200": ([scaled(p3_straight((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)), 1e200)], 0, 1),
}

for name, (triangles, invalid, fallbacks) in CASES.items():
    msh = write_msh(name.replace(" ", "-").replace("^", "") + ".msh", triangles)
    report = compare(name, msh)
    if report is None:
        continue
    check(f"{name}: invalid", report["invalid"] == invalid, str(report))
    check(f"{name}: undecided", report["undecided"] == 0, str(report))
    check(f"{name}: elements decided in rationals", report["exact_fallbacks"] == fallbacks, str(report))
    check(f"{name}: no seconds unless asked", "seconds" not in report, str(report))
    timed = json.loads(run("check", msh, "--json", "--timing").stdout)
    seconds = timed.get("seconds", {})
    check(f"{name}: --timing: the seconds reading and certifying",
          sorted(seconds) == ["certify", "read"] and all(isinstance(v, float) and v >= 0 for v in seconds.values()),
          str(timed))
    r = run("check", msh)
    check(f"{name}: exit code", r.returncode == (1 if invalid else 0), r.stdout + r.stderr)

finish()
