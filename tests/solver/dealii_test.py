#!/usr/bin/env python3
"""deal.II reads curvemesh's linear meshes: `--linear --msh-boundary-only` writes the border's
lines alone, each in one physical group, which deal.II's own reader (GridIn<2>::read_msh, through
dealii_read) takes as boundary ids, with the regions' groups as material ids. What deal.II makes
of the file must be what `--stats` says is in it: the triangles of each region with their area,
and the border's faces with their length (in total, and per boundary id as meshio reads the
file's line groups). The whole file, whose lines are in several groups and inside the domain too, is
what deal.II refuses ("More than one tag is not supported", "boundary id for an internal face"):
the reason the option exists.

usage: dealii_test.py CURVEMESH_BINARY DEALII_READ_BINARY EXAMPLES_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

import meshio

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from checks import check, finish  # noqa: E402

binary, reader, examples = sys.argv[1:4]
tmp = tempfile.TemporaryDirectory()
SHARED = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 6">'
          '<path id="left" d="M 1 1 L 5 1 L 5 5 L 1 5 Z" fill="red"/>'
          '<path id="right" d="M 5 1 L 9 1 L 9 5 L 5 5 Z" fill="blue"/></svg>')
shared = os.path.join(tmp.name, "shared.svg")
with open(shared, "w") as f:
    f.write(SHARED)


def close(a, b):
    return abs(a - b) <= 1e-9 * max(1.0, abs(b))


def mesh(name, svg, *options):
    out = os.path.join(tmp.name, name)
    subprocess.run([binary, "mesh", svg, "-q", "-o", out + ".msh", "--stats", out + ".json", *options], check=True)
    with open(out + ".json") as f:
        return out + ".msh", json.load(f)


def dealii(path):
    r = subprocess.run([reader, path], capture_output=True, text=True)
    return (json.loads(r.stdout) if r.returncode == 0 else None), r


CASES = [
    ("shapes-filled", os.path.join(examples, "overlapping-shapes.svg"), ["--regions", "--domain", "filled"]),
    ("shapes-box", os.path.join(examples, "overlapping-shapes.svg"), ["--regions"]),
    ("shared-side", shared, ["--regions", "--domain", "filled"]),
]
for name, svg, options in CASES:
    for version in ("4.1", "2.2"):
        case = f"{name}-{version}"
        path, stats = mesh(case, svg, "--linear", "--msh-boundary-only", "--msh-version", version, *options)
        got, run = dealii(path)
        check(f"{case}: deal.II reads it", got is not None, run.stderr[-400:])
        if got is None:
            continue
        groups = {(g["dim"], g["id"]): g for g in stats["groups"]}
        regions = {str(i): g for (d, i), g in groups.items() if d == 2}
        check(f"{case}: every triangle, by region (material id), with its area",
              got["cells"] == sum(g["triangles"] for g in regions.values())
              and set(got["materials"]) == set(regions)
              and all(got["materials"][i][0] == g["triangles"] and close(got["materials"][i][1], g["area"])
                      for i, g in regions.items()), (got["materials"], regions))
        border = groups[(1, 5)]
        faces = sum(c for c, _ in got["boundaries"].values())
        length = sum(s for _, s in got["boundaries"].values())
        check(f"{case}: the border's faces and length", faces == border["lines"] and close(length, border["length"]),
              (faces, length, border))
        file = meshio.read(path)
        per_group = {}
        for block, tags in zip(file.cells, file.cell_data["gmsh:physical"]):
            if block.dim == 1:
                for t in tags:
                    per_group[str(t)] = per_group.get(str(t), 0) + 1
        check(f"{case}: boundary ids are the file's line groups",
              {i: c for i, (c, _) in got["boundaries"].items()} == per_group, (got["boundaries"], per_group))

    path, _ = mesh(f"{name}-whole", svg, "--linear", *options)
    got, run = dealii(path)
    check(f"{name}: the whole file (interior lines too) is what deal.II refuses", got is None and run.returncode == 1,
          run.stdout[-200:])

finish()
