#!/usr/bin/env python3
"""Command-line contract of `curvemesh mesh --strokes areas`: a stroke-only icon (examples/
stroked-icon.svg: round caps and joins, a circle, a curve, a line, a polyline, a dashed line) meshed
with --strokes areas --regions --domain painted covers what librsvg paints (the painted pixels of
its rendering at high resolution, weighted by their coverage) to 0.5 %; each stroke is a region
named ELEMENT.stroke; the mesh is certified by `curvemesh check`; --domain painted alone reads
strokes as areas too; and the default, --strokes lines, gives the same bytes as no option and no
stroke region.

usage: strokes_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, read_png  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
icon = os.path.join(examples, "stroked-icon.svg")
tmp = tempfile.TemporaryDirectory()


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def mesh(name, *extra):
    out = os.path.join(tmp.name, name)
    r = run("mesh", icon, "-o", out + ".msh", "--stats", out + ".json", "-q", *extra)
    stats = {}
    if r.returncode == 0:
        with open(out + ".json") as f:
            stats = json.load(f)
    return r, out, stats


def png_alpha(path):
    """The alpha channel of a PNG (what rsvg-convert writes) as floats in [0, 1]."""
    return read_png(path)[..., 3] / 255.0


# --- the painted area: librsvg's rendering against the mesh's -------------------------------
pixels = 2400  # 100 per unit of the 24 × 24 viewBox
png = os.path.join(tmp.name, "icon.png")
r = subprocess.run(["rsvg-convert", "-w", str(pixels), "-h", str(pixels), icon, "-o", png], capture_output=True, text=True)
check("rsvg-convert renders the icon", r.returncode == 0, r.stderr)
rendered = png_alpha(png).sum() * (24.0 / pixels) ** 2
check("the rendering paints something", rendered > 10, rendered)

r, out, stats = mesh("areas", "--strokes", "areas", "--regions", "--domain", "painted")
check("mesh --strokes areas --regions --domain painted succeeds", r.returncode == 0, r.stderr[-800:])
regions = stats.get("regions", [])
names = sorted(x["name"] for x in regions)
area = sum(x["area"] for x in regions)
print(f"painted area: mesh {area:.4f}, rsvg-convert {rendered:.4f} ({100 * (area - rendered) / rendered:+.3f} %)")
check("the mesh covers the painted area within 0.5 %", abs(area - rendered) <= 0.005 * rendered,
      f"mesh {area}, rendered {rendered}")
for element in ("face", "smile", "brow", "check", "ground"):
    check(f"a region {element}.stroke", f"{element}.stroke" in names, names)
check("no background in the painted domain", "background" not in names, names)
check("every region is a stroke's, painted black", all(x["name"].endswith(".stroke") and x["fill"] == "#000000"
                                                       for x in regions), regions)
c = run("check", out + ".msh")
check("curvemesh check certifies the mesh", c.returncode == 0, (c.stdout + c.stderr)[-800:])

# The dashed line: 4 dashes of 2 with round caps of radius 1 (the dash pattern 2 3 along 18).
ground = [x for x in regions if x["name"] == "ground.stroke"]
dashes = 4 * (2 * 2 + 3.141592653589793)
check("the dashed line's area is its four capped dashes'", ground and abs(ground[0]["area"] - dashes) < 1e-3 * dashes,
      ground)

# --domain painted implies --strokes areas.
r2, _, stats2 = mesh("painted", "--domain", "painted")
check("--domain painted alone succeeds", r2.returncode == 0, r2.stderr[-800:])
check("--domain painted alone reads strokes as areas (the same mesh)",
      stats2.get("domain", {}).get("triangles") == stats.get("domain", {}).get("triangles"), stats2.get("domain"))

# --domain filled keeps fills alone: the icon fills nothing, strokes read as areas or not.
r6 = run("mesh", icon, "-o", os.path.join(tmp.name, "filled.msh"), "--strokes", "areas", "--domain", "filled")
check("--strokes areas --domain filled: the icon fills nothing (exit 1)", r6.returncode == 1 and "is empty" in r6.stderr,
      r6.stderr[-500:])

# Bending tighter than half the width: a cubic whose radius of curvature falls to 2.57 under a
# stroke of width 8, circles of radius at and above half their widths (against rsvg-convert), and
# one below (the union SVG 2 sweeps is a disc, π(r + w/2)²; cairo's stroker leaves a hole there).
def tight_drawing(name, shapes):
    path = os.path.join(tmp.name, name + ".svg")
    with open(path, "w") as f:
        f.write('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-10 -10 60 40" fill="none" stroke="#000" '
                f'stroke-linecap="round" stroke-linejoin="round">{shapes}</svg>')
    out = os.path.join(tmp.name, name)
    r = run("mesh", path, "-o", out + ".msh", "--stats", out + ".json", "-q", "--regions", "--domain", "painted")
    check(f"{name}: mesh --domain painted succeeds", r.returncode == 0, r.stderr[-500:])
    if r.returncode != 0:
        return path, None
    with open(out + ".json") as f:
        return path, sum(x["area"] for x in json.load(f)["regions"])


tight, tight_area = tight_drawing("tight", '<path d="M0 0 C 30 0 30 10 20 12" stroke-width="8"/>'
                                           '<circle cx="38" cy="20" r="2" stroke-width="4"/>'
                                           '<circle cx="4" cy="22" r="2" stroke-width="3"/>')
r = subprocess.run(["rsvg-convert", "-w", "2400", "-h", "1600", tight, "-o", png], capture_output=True, text=True)
tight_rendered = png_alpha(png).sum() * (60.0 / 2400) ** 2
if tight_area is not None:
    print(f"tight bends: mesh {tight_area:.4f}, rsvg-convert {tight_rendered:.4f}")
    check("tight bends cover what rsvg-convert paints within 0.5 %",
          abs(tight_area - tight_rendered) <= 0.005 * tight_rendered, (tight_area, tight_rendered))
_, disc_area = tight_drawing("disc", '<circle cx="38" cy="4" r="2" stroke-width="8"/>')
check("a circle of radius below half its width paints a disc", disc_area is not None and
      abs(disc_area - math.pi * 6 ** 2) < 1e-6 * math.pi * 36, disc_area)

# A filled and stroked element: two regions, the stroke painted over the fill's edge.
shapes = os.path.join(examples, "overlapping-shapes.svg")
areas_of = {}
for strokes in ("lines", "areas"):
    out = os.path.join(tmp.name, "shapes-" + strokes)
    r7 = run("mesh", shapes, "-o", out + ".msh", "--stats", out + ".json", "-q", "--regions", "--strokes", strokes)
    check(f"overlapping-shapes.svg --strokes {strokes} --regions succeeds", r7.returncode == 0, r7.stderr[-500:])
    if r7.returncode == 0:
        with open(out + ".json") as f:
            areas_of[strokes] = {x["name"]: x["area"] for x in json.load(f)["regions"]}
if len(areas_of) == 2:
    a, l = areas_of["areas"], areas_of["lines"]
    check("the filled and stroked rect has a fill region and a .stroke region", "rect#1" in a and "rect#1.stroke" in a, a)
    check("the stroke covers the edge of the fill", a.get("rect#1", 0) < l.get("rect#1", 0), (a, l))
    check("a stroke without fill is a .stroke region alone", "ellipse#3.stroke" in a and "ellipse#3" not in a, a)

# --- the default is unchanged --------------------------------------------------------------------
r3, plain, _ = mesh("plain", "--regions")
r4, lines, stats4 = mesh("lines", "--regions", "--strokes", "lines")
check("--strokes lines and no option both succeed", r3.returncode == 0 and r4.returncode == 0, r3.stderr + r4.stderr)
with open(plain + ".msh", "rb") as a, open(lines + ".msh", "rb") as b:
    check("--strokes lines writes the same bytes as the default", a.read() == b.read())
check("--strokes lines has no stroke region", not any(x["name"].endswith(".stroke") for x in stats4.get("regions", [])),
      stats4.get("regions"))

# A mitred rectangle outline: its painted area is exactly 2·(132 + 96) = 456, corners included. The
# inner sides meet at the inner corners (no notch to the path's corner inside the band), so the mesh's
# border follows the inner rectangle exactly instead of a chord across each corner.
rect = os.path.join(tmp.name, "rect.svg")
with open(rect, "w") as f:
    f.write('<svg xmlns="http://www.w3.org/2000/svg" viewBox="210 -5 145 105">'
            '<rect x="216" y="0" width="132" height="96" fill="none" stroke="#000"/></svg>')
rect_stats = os.path.join(tmp.name, "rect.json")
r9 = run("mesh", rect, "-o", os.path.join(tmp.name, "rect.msh"), "--domain", "painted", "--regions", "--stats", rect_stats)
rect_area = None
if r9.returncode == 0:
    with open(rect_stats) as f:
        rect_area = sum(x["area"] for x in json.load(f)["regions"])
check("a mitred rectangle's painted area is 456 (within 1e-9)", rect_area is not None and abs(rect_area - 456) < 456e-9,
      (rect_area, r9.stderr[-500:]))

# A hairline (0.1 wide in a drawing 100 across, a tenth of the default mu): mu and epsilon shrink
# until its two sides and its centre line stay apart, and its painted area is its width times the
# perimeter (a closed polygon with mitred joins, every angle wide enough for the mitre limit).
def triangle_stroke(path, width):
    with open(path, "w") as f:
        f.write('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
                f'<path d="M10 10 L90 20 L50 90 Z" fill="none" stroke="black" stroke-width="{width}"/></svg>')


corners = [(10, 10), (90, 20), (50, 90)]
perimeter = sum(math.dist(corners[i], corners[(i + 1) % 3]) for i in range(3))
hairline = os.path.join(tmp.name, "hairline.svg")
triangle_stroke(hairline, 0.1)
hair_stats = os.path.join(tmp.name, "hairline.json")
r7 = run("mesh", hairline, "-o", os.path.join(tmp.name, "hairline.msh"), "--domain", "painted", "--regions",
         "--stats", hair_stats)
hair_area = None
if r7.returncode == 0:
    with open(hair_stats) as f:
        hair_area = sum(x["area"] for x in json.load(f)["regions"] if x["name"].endswith(".stroke"))
check("a hairline a tenth of mu wide paints its width times its perimeter (within 1e-6 of it)",
      hair_area is not None and abs(hair_area - 0.1 * perimeter) < 1e-6 * 0.1 * perimeter,
      (hair_area, 0.1 * perimeter, r7.stderr[-500:]))
# Narrower than --min-stroke-width (5e-4 of the diagonal): it paints nothing, and the messages say
# which option keeps it, not that nothing is stroked.
finer = os.path.join(tmp.name, "finer.svg")
triangle_stroke(finer, 0.005)
r8 = run("mesh", finer, "-o", os.path.join(tmp.name, "finer.msh"), "--domain", "painted")
check("a stroke below --min-stroke-width: exit 1, naming the option rather than a drawing without strokes",
      r8.returncode == 1 and "--min-stroke-width" in r8.stderr and "filled or stroked" not in r8.stderr, r8.stderr)
check("... and the warning says it is narrower and paints nothing",
      "1 stroke is narrower than --min-stroke-width" in r8.stderr and "paint nothing" in r8.stderr, r8.stderr)

# Stroke sides within a hair of another curve: a vertex the optimization left off its curve had, in
# these drawings, a neighbour between it and every place on the curve. The neighbour moves out of
# the way first (cleared_projections), so every primary edge follows its curve, and the mesh is
# certified by the checker. Whether a given mesh puts a neighbour in the way depends on the
# optimization's order of work: the clearing must happen in one of the drawings at least (else
# this no longer tests it), and no drawing may have a straight primary edge.
openclipart = "/usr/share/openclipart/svg"
cleared = {}
for drawing in ("recreation/holiday/shamrock_for_march_natha_01.svg", "food/beverages/teacup_ganson.svg",
                "recreation/party/cone1_ganson.svg"):
    path = os.path.join(openclipart, drawing)
    check(f"{drawing} is installed (Debian's openclipart-svg)", os.path.exists(path))
    if not os.path.exists(path):
        continue
    out = os.path.join(tmp.name, os.path.basename(drawing))
    r9 = run("mesh", path, "-o", out + ".msh", "--stats", out + ".json", "--domain", "painted", "-q")
    check(f"{drawing}: meshed with --domain painted", r9.returncode == 0, r9.stderr[-500:])
    if r9.returncode != 0:
        continue
    with open(out + ".json") as f:
        curve = json.load(f)["curve"]
    cleared[drawing] = curve.get("cleared_projections", 0)
    check(f"{drawing}: every primary edge follows its curve", curve["straight_primary_edges"] == 0, curve)
    c9 = run("check", out + ".msh", "--json")
    check(f"{drawing}: certified by curvemesh check", c9.returncode == 0 and json.loads(c9.stdout)["invalid"] == 0,
          c9.stdout + c9.stderr)
if os.path.isdir(openclipart):
    check("a neighbour in the way moved, and the vertex reached its curve, in one of the drawings at least",
          sum(cleared.values()) >= 1, cleared)

r5 = run("mesh", icon, "-o", os.path.join(tmp.name, "bad.msh"), "--strokes", "wide")
check("--strokes refuses another value", r5.returncode == 2, r5.stderr)

finish()
