#!/usr/bin/env python3
"""The curve stage's two moves that can raise the worst energy of what they change — a primary
vertex brought onto its curve late, a straight primary edge put on its curve in step 5 — are
kept only when the triangles around them end no worse than they were (above the stop energy),
if need be after step 4's operations have repaired them, and are otherwise taken back.

Five drawings of the collection exercise every outcome: in `network_cloud_david_klan_01` and
`ape_miele` moves are kept after a repair (`curve.repaired_moves`), in `cormorant-md` a late
projection whose curved edges leave a triangle uncertified is kept after the repair certifies it,
in `fireman_enrique_meza_c_01` (its lettering left out: the glyphs' curves would change the mesh
around the move) a projection to the closest point is refused (`curve.refused_moves`) and the
vertex goes to another place on its curve instead (`curve.projections_elsewhere`), and in `donna_casinista` the closest point would turn the
vertex's star over, and it goes elsewhere on its curve after a repair. Each mesh is certified by
the independent checker (tests/tools/msh_check.py) and every element is at most AMIPS 20 as it
measures them; only where a move was refused may a primary edge be left straight, and in these
two drawings none is; the curve stage ends no worse than it began (its worst energy at most
max(20, the worst on entering step 4)).

usage: guarded_moves_test.py CURVEMESH_BINARY [SVG_ROOT]
"""
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary = sys.argv[1]
root = sys.argv[2] if len(sys.argv) > 2 else "/usr/share/openclipart/svg"
checker = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "msh_check.py")
tmp = tempfile.TemporaryDirectory()

drawings = [
    "computer/network_cloud_david_klan_01.svg",
    "unsorted/ape_miele.svg",
    "animals/birds/cormorant-md.svg",
    "people/fireman_enrique_meza_c_01.svg",
    "unsorted/donna_casinista.svg",
]
for d in drawings:
    check(f"{d} is under {root} (Debian's openclipart-svg, installed by scripts/)", os.path.exists(os.path.join(root, d)))

# Drawings meshed without their <text> elements (the rest of the file as it is).
WITHOUT_TEXT = {"people/fireman_enrique_meza_c_01.svg"}


def source_of(drawing):
    path = os.path.join(root, drawing)
    if drawing not in WITHOUT_TEXT:
        return path
    with open(path, encoding="utf-8") as f:
        text, removed = re.subn(r"<text\b.*?</text>", "", f.read(), flags=re.S)
    check(f"{drawing}: its lettering found and left out", removed > 0, removed)
    copy = os.path.join(tmp.name, os.path.basename(drawing))
    with open(copy, "w", encoding="utf-8") as f:
        f.write(text)
    return copy


totals = {"repaired_moves": 0, "refused_moves": 0, "late_projections": 0, "projections_elsewhere": 0}
straight, elsewhere = {}, {}
for drawing in drawings:
    name = os.path.basename(drawing)
    out, stats_path = os.path.join(tmp.name, name + ".msh"), os.path.join(tmp.name, name + ".json")
    r = subprocess.run([binary, "mesh", source_of(drawing), "-o", out, "--stats", stats_path, "-q"],
                       capture_output=True, text=True, timeout=600)
    check(f"{name}: exit 0", r.returncode == 0, r.stderr[-600:])
    if r.returncode != 0:
        continue
    curve = json.load(open(stats_path))["curve"]
    for key in totals:
        totals[key] += curve.get(key, 0)
    c = subprocess.run([sys.executable, checker, out, "--json"], capture_output=True, text=True, timeout=600)
    check(f"{name}: independent checker accepts the mesh", c.returncode == 0, (c.stdout + c.stderr)[-600:])
    report = json.loads(c.stdout) if c.returncode == 0 else {}
    check(f"{name}: every element at most AMIPS 20 (checker)", report.get("max_amips", 1e9) <= 20,
          report.get("max_amips"))
    check(f"{name}: no worse than on entering step 4",
          curve["max_amips"] <= max(20.0, curve["max_amips_before_smoothing"]),
          f"{curve['max_amips']} after, {curve['max_amips_before_smoothing']} before")
    straight[name] = curve["straight_primary_edges"]
    elsewhere[name] = curve.get("projections_elsewhere", 0)
    if curve["refused_moves"] == 0:
        check(f"{name}: nothing refused, no primary edge straight", curve["straight_primary_edges"] == 0,
              curve["straight_primary_edges"])

check("some moves were kept after a repair by the operations", totals["repaired_moves"] > 0, totals)
check("some moves were refused", totals["refused_moves"] > 0, totals)
check("vertices were projected late", totals["late_projections"] > 0, totals)
# fireman's vertex, refused at its closest point, and donna's, whose star would turn over there,
# are on their curves elsewhere.
for name in ["fireman_enrique_meza_c_01.svg", "donna_casinista.svg"]:
    check(f"{name}: the vertex went elsewhere on its curve", elsewhere.get(name, 0) > 0, elsewhere)
    check(f"{name}: no primary edge straight", straight.get(name) == 0, straight)
finish()
