#!/usr/bin/env python3
"""Command-line contract of `curvemesh mesh --regions` and `--domain`, read back with meshio (an
independent reader) and certified by tests/tools/msh_check.py: one physical surface per visible
element named by its id (else TAG#INDEX) plus "background", the --stats "regions" list, the
region and face of each triangle in the .vtu, areas that add up to the box's, domains that keep
only their triangles and the nodes those use, the --svg picture filled with the elements'
colours and drawn with line widths in the drawing's units, the area of a filled <circle> (πr² to
1e-8, by --stats and by quadrature of the curved triangles), and bad input.

usage: regions_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import contextlib
import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
checker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "msh_check.py")
tmp = tempfile.TemporaryDirectory()
try:
    import meshio
    import numpy as np
except ImportError as e:  # the Debian packages python3-meshio and python3-numpy
    print(f"regions_test: {e}", file=sys.stderr)
    sys.exit(1)


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)


def mesh(name, source, *extra):
    out = os.path.join(tmp.name, name)
    r = run("mesh", source, "-o", out + ".msh", "--stats", out + ".json", "--vtu", out + ".vtu", "--svg",
            out + ".mesh.svg", "-q", *extra)
    stats = {}
    if r.returncode == 0:
        with open(out + ".json") as f:
            stats = json.load(f)
    return r, out, stats


def read(path):
    with contextlib.redirect_stdout(io.StringIO()):
        return meshio.read(path)


def certify(name, path):
    r = subprocess.run([sys.executable, checker, path], capture_output=True, text=True, timeout=300)
    check(f"{name}: independent checker accepts the mesh", r.returncode == 0, (r.stdout + r.stderr)[-500:])


def triangles_of(m):
    """All triangles (the .msh has one block per physical surface)."""
    blocks = [np.asarray(b.data) for b in m.cells if b.type in ("triangle", "triangle10")]
    return np.concatenate(blocks) if blocks else None


def physical_of(m):
    tags = [np.asarray(t) for b, t in zip(m.cells, m.cell_data["gmsh:physical"]) if b.type in ("triangle", "triangle10")]
    return np.concatenate(tags) if tags else None


def write(name, text):
    path = os.path.join(tmp.name, name)
    with open(path, "w") as f:
        f.write(text)
    return path


# --- --regions on a drawing with overlapping filled shapes (curved) ---------------------------
overlapping = os.path.join(examples, "overlapping-shapes.svg")
r, out, stats = mesh("overlapping", overlapping, "--regions")
check("--regions: exit 0", r.returncode == 0, r.stderr)
regions = stats.get("regions", [])
names = [g["name"] for g in regions]
check("--regions: background and one region per visible element, named TAG#INDEX without an id",
      names == ["background", "rect#1", "circle#2", "polygon#4"], names)
check("--regions: fills as #rrggbb, none for the background",
      [g["fill"] for g in regions] == ["none", "#f4d35e", "#0d3b66", "#f95738"], regions)
# Four drawn elements: their lines are groups 6..9, the regions follow from 10, the background first
# (regions/groups.hpp); an element with no fill (the ellipse) has no region.
check("--regions: physical tags after the lines', in paint order", [g["physical"] for g in regions] == [10, 11, 12, 13],
      regions)
m = read(out + ".msh")
tags = physical_of(m)
check("--regions: each triangle's physical tag is a region's, with the listed counts",
      tags is not None and all(int((tags == g["physical"]).sum()) == g["triangles"] for g in regions)
      and len(tags) == sum(g["triangles"] for g in regions), (regions, None if tags is None else np.bincount(tags)))
named = {int(v[0]): k for k, v in m.field_data.items() if int(v[1]) == 2}
check("--regions: the .msh names the physical surfaces", named == {g["physical"]: g["name"] for g in regions}, named)
points = m.points[:, :2]
box_area = (points[:, 0].max() - points[:, 0].min()) * (points[:, 1].max() - points[:, 1].min())
total = sum(g["area"] for g in regions)
check("--regions: the areas add up to the box's", abs(total - box_area) <= 1e-9 * box_area, (total, box_area))
certify("--regions", out + ".msh")
v = read(out + ".vtu")
check("--regions: the .vtu carries each triangle's region and face",
      "region" in v.cell_data and "face" in v.cell_data
      and sorted(set(np.asarray(v.cell_data["region"][0]).astype(int))) == [g["physical"] for g in regions],
      list(v.cell_data))
with open(out + ".mesh.svg") as f:
    picture = f.read()
check("--svg: triangles filled with the elements' colours",
      all(f'fill="{g["fill"]}"' in picture for g in regions[1:]), picture[:300])
width = re.search(r'stroke-width="([0-9.e+-]+)"', picture)
check("--svg: lines are given a width in the drawing's units (about d/1000), not only non-scaling",
      width is not None and 0.0005 * box_area ** 0.5 < float(width.group(1)) < 0.002 * 2 * box_area ** 0.5
      and "non-scaling-stroke" not in picture, width and width.group(0))

# Default meshes are untouched by the option's existence: the same run without --regions has the
# one surface "domain".
r, out_plain, stats_plain = mesh("overlapping-plain", overlapping)
mp = read(out_plain + ".msh")
check("without --regions: one surface, 'domain', no regions in --stats",
      r.returncode == 0 and set(physical_of(mp)) == {4} and "regions" not in stats_plain, stats_plain.keys())

# --- --domain ---------------------------------------------------------------------------------
hole = os.path.join(examples, "square-with-hole.svg")
r, out, stats = mesh("filled", overlapping, "--domain", "filled")
check("--domain filled: exit 0", r.returncode == 0, r.stderr)
f = read(out + ".msh")
tri = triangles_of(f)
used = np.unique(np.concatenate([np.asarray(b.data).ravel() for b in f.cells]))
check("--domain filled: fewer triangles than the box, every node used",
      tri is not None and len(tri) < len(triangles_of(mp)) and len(used) == len(f.points),
      (len(f.points), len(used)))
check("--domain filled: --stats says the domain", stats.get("domain", {}).get("name") == "filled"
      and stats["domain"]["triangles"] == len(tri), stats.get("domain"))
certify("--domain filled", out + ".msh")
r2, out2, stats2 = mesh("filled-regions", overlapping, "--domain", "filled", "--regions")
check("--domain filled --regions: no background region",
      r2.returncode == 0 and [g["name"] for g in stats2["regions"]] == ["rect#1", "circle#2", "polygon#4"],
      stats2.get("regions"))
r, out, stats = mesh("evenodd", hole, "--domain", "evenodd", "--regions")
check("--domain evenodd: exit 0", r.returncode == 0, r.stderr)
areas = {g["name"]: g["area"] for g in stats.get("regions", [])}
check("--domain evenodd on a square with a hole: the ring alone (the hole is even)",
      list(areas) == ["rect#1"], areas)
r, out, stats = mesh("box", hole, "--regions")
check("square with a hole: the white circle is painted over the square",
      [g["name"] for g in stats["regions"]] == ["background", "rect#1", "circle#2"]
      and stats["regions"][2]["fill"] == "#ffffff", stats.get("regions"))
# outside is evenodd's complement: the two meshes share the box's triangles between them.
box_triangles = len(triangles_of(read(out + ".msh")))
r_in, out_in, _ = mesh("evenodd-plain", hole, "--domain", "evenodd")
r_out, out_out, stats_out = mesh("outside", hole, "--domain", "outside", "--regions")
check("--domain outside: exit 0", r_out.returncode == 0 and r_in.returncode == 0, r_out.stderr + r_in.stderr)
if r_out.returncode == 0 and r_in.returncode == 0:
    inside_t, outside_t = len(triangles_of(read(out_in + ".msh"))), len(triangles_of(read(out_out + ".msh")))
    check("--domain outside and evenodd share the box's triangles between them",
          inside_t + outside_t == box_triangles and 0 < outside_t < box_triangles, (inside_t, outside_t, box_triangles))
    check("--domain outside on a square with a hole: the margin and the hole, not the ring",
          [g["name"] for g in stats_out["regions"]] == ["background", "circle#2"], stats_out.get("regions"))
    certify("--domain outside", out_out + ".msh")

# --- the area of a filled circle -------------------------------------------------------------
# The reader's cubics lie within 1e-9·r of the circle and the curved triangles follow them, so the
# mesh of a <circle> is a mesh of the disk: its area is π r² to about 1e-9, as --stats says and as
# Gauss quadrature of det J over each 10-node triangle (Gmsh's node order) measures independently.
def p3_area(m):
    corners = [(0, 0), (1, 0), (0, 1)]
    ref = list(corners)
    for a, b in ((0, 1), (1, 2), (2, 0)):
        for s in (1 / 3, 2 / 3):
            ref.append(tuple((1 - s) * corners[a][i] + s * corners[b][i] for i in range(2)))
    ref.append((1 / 3, 1 / 3))
    powers = [(i, j) for i in range(4) for j in range(4 - i)]
    coef = np.linalg.inv(np.array([[x ** i * y ** j for i, j in powers] for x, y in ref]))
    # det J has degree 4: a collapsed 5×5 Gauss–Legendre rule on the triangle is exact for it.
    g, w = np.polynomial.legendre.leggauss(5)
    g, w = (g + 1) / 2, w / 2
    quad = [(u * (1 - v), v, wu * wv * (1 - v)) for u, wu in zip(g, w) for v, wv in zip(g, w)]
    total = 0.0
    for block in m.cells:
        if block.type != "triangle10":
            continue
        nodes = m.points[np.asarray(block.data)][:, :, :2]  # triangles × 10 × 2
        for x, y, weight in quad:
            dx = np.array([i * x ** (i - 1) * y ** j if i else 0.0 for i, j in powers]) @ coef
            dy = np.array([j * x ** i * y ** (j - 1) if j else 0.0 for i, j in powers]) @ coef
            jx, jy = nodes.transpose(0, 2, 1) @ dx, nodes.transpose(0, 2, 1) @ dy
            total += weight * np.sum(jx[:, 0] * jy[:, 1] - jx[:, 1] * jy[:, 0])
    return total


disk = write("disk.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
                         '<circle id="disk" cx="50" cy="50" r="40" fill="#336699"/></svg>')
r, out, stats = mesh("disk", disk, "--domain", "filled", "--regions")
check("a filled circle: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    want = math.pi * 40 ** 2
    said = [g["area"] for g in stats.get("regions", []) if g["name"] == "disk"]
    check("a filled circle: its --stats area is pi r^2 to 1e-8", len(said) == 1 and abs(said[0] / want - 1) <= 1e-8,
          (said, want))
    measured = p3_area(read(out + ".msh"))
    check("a filled circle: the area of its curved triangles is pi r^2 to 1e-8", abs(measured / want - 1) <= 1e-8,
          (measured, want, measured / want - 1))
    certify("a filled circle", out + ".msh")

# --- fill semantics through the command line ------------------------------------------------------
doc = write("rules.svg", """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 30 12">
  <style>#star2 { fill-rule: evenodd }</style>
  <path id="star1" fill="#112233" d="M 5 1 L 7.35 8 L 1.2 3.7 L 8.8 3.7 L 2.65 8 Z"/>
  <path id="star2" fill="#445566" d="M 15 1 L 17.35 8 L 11.2 3.7 L 18.8 3.7 L 12.65 8 Z"/>
  <path id="open" fill="#778899" d="M 21 1 L 29 1 L 29 9"/>
  <rect x="1" y="10" width="3" height="1" fill="hsl(120, 50%, 50%)"/>
</svg>""")
r, out, stats = mesh("rules", doc, "--regions")
check("an unreadable fill: exit 0, the element unfilled, a warning naming it",
      r.returncode == 0 and "hsl(120, 50%, 50%)" in r.stderr and "left unfilled" in r.stderr, r.stderr)
areas = {g["name"]: g["area"] for g in stats.get("regions", [])}
# The same pentagram twice: nonzero covers its inner pentagon (winding 2), evenodd does not.
check("fill-rule: the evenodd star has less area than the nonzero one",
      "star1" in areas and "star2" in areas and areas["star2"] < areas["star1"] - 1, areas)
check("an open filled path is filled as closed: the triangle 21,1 29,1 29,9 (area 32)",
      abs(areas.get("open", 0) - 32) < 1e-9, areas)

# --- bad input --------------------------------------------------------------------------------
r = run("mesh", overlapping, "-o", os.path.join(tmp.name, "x.msh"), "--domain", "inside-out")
check("--domain with an unknown name: exit 2", r.returncode == 2, r.stderr)
icon = write("icon.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
                         '<path d="M 1 1 C 4 0 6 9 9 2" fill="none" stroke="black"/></svg>')
r, out, stats = mesh("icon", icon, "--regions")
check("a stroke-only drawing: faces and no filled element, said once",
      r.returncode == 0 and r.stderr.count("no element is filled") == 1
      and [g["name"] for g in stats["regions"]] == ["background"], r.stderr)
r, out, stats = mesh("icon-filled", icon, "--domain", "filled")
check("--domain filled of a stroke-only drawing: exit 1, the domain is empty, nothing written",
      r.returncode == 1 and "'filled' is empty" in r.stderr and not os.path.exists(out + ".msh"), r.stderr)
r = run("mesh", "--help")
check("mesh --help explains --regions and --domain", "--regions" in r.stdout and "--domain" in r.stdout
      and "evenodd" in r.stdout, r.stdout[-500:])

finish()
