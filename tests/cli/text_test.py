#!/usr/bin/env python3
"""Text meshed as its glyphs: `curvemesh mesh --regions --domain filled` on a drawing of text, its
filled area against the painted area of rsvg-convert's rendering of the same drawing at high
resolution (librsvg finds and shapes fonts through fontconfig and HarfBuzz too, so both draw the
same face), the mesh certified by `curvemesh check` and by tests/tools/msh_check.py, the text's
region named by its id (else text#INDEX), and the warning for a family that is not installed.

usage: text_test.py CURVEMESH_BINARY
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish, read_png  # noqa: E402

binary = sys.argv[1]
here = os.path.dirname(os.path.abspath(__file__))
checker = os.path.join(here, "..", "tools", "msh_check.py")
tmp = tempfile.TemporaryDirectory()

# Two texts: a bold sans-serif word with a kerned pair (AV) and an italic serif word anchored at
# its middle inside a scaled group; the second text without an id.
DRAWING = """<svg xmlns="http://www.w3.org/2000/svg" width="300" height="160" viewBox="0 0 300 160">
  <text id="word" x="12" y="70" font-family="DejaVu Sans" font-size="56" font-weight="bold">AVote</text>
  <g transform="translate(150 0) scale(1.25)">
    <text y="115" style="font-family: serif; font-style: italic; font-size: 36px"
          text-anchor="middle">g<tspan fill="#c02020">lyph</tspan>s</text>
  </g>
</svg>
"""


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def write(name, text):
    path = os.path.join(tmp.name, name)
    with open(path, "w") as f:
        f.write(text)
    return path


drawing = write("text.svg", DRAWING)
out = os.path.join(tmp.name, "text")
r = run("mesh", drawing, "-o", out + ".msh", "--stats", out + ".json", "--regions", "--domain", "filled")
check("text: meshed, exit 0", r.returncode == 0, r.stderr[-800:])
check("text: no warning (every family installed)", "warning" not in r.stderr, r.stderr[-800:])
stats = {}
if r.returncode == 0:
    with open(out + ".json") as f:
        stats = json.load(f)
regions = stats.get("regions", [])
names = [g["name"] for g in regions]
# The red tspan is a second region of its text element (regions are per element and fill).
check("text: a region per text element and fill, by its id else text#INDEX",
      [n for n in names if n != "background"] == ["word", "text#3", "text#3@2"], names)
filled = sum(g["area"] for g in regions if g["name"] != "background")
check("text: the domain is the filled glyphs alone",
      filled > 0 and all(g["triangles"] == 0 for g in regions if g["name"] == "background"), regions)

r = run("check", out + ".msh")
check("text: curvemesh check certifies the mesh", r.returncode == 0, (r.stdout + r.stderr)[-800:])
r = subprocess.run([sys.executable, checker, out + ".msh"], capture_output=True, text=True, timeout=600)
check("text: the independent checker accepts the mesh", r.returncode == 0, (r.stdout + r.stderr)[-500:])

# rsvg-convert at 16 pixels per user unit: the painted area is the sum of the pixels' coverage
# (alpha), which anti-aliasing makes exact for the pixels the outline crosses, up to rounding.
rsvg = shutil.which("rsvg-convert")
check("rsvg-convert is installed (Debian's librsvg2-bin)", rsvg is not None)
if rsvg and filled > 0:
    zoom = 16
    png = os.path.join(tmp.name, "text.png")
    r = subprocess.run([rsvg, "--zoom", str(zoom), drawing, "-o", png], capture_output=True, text=True, timeout=300)
    check("rsvg-convert renders the drawing", r.returncode == 0, r.stderr)
    if r.returncode == 0:
        image = read_png(png)
        painted = image[..., 3].astype(float).sum() / 255.0 / zoom ** 2
        print(f"text: filled area {filled:.3f} in the mesh, {painted:.3f} painted by rsvg-convert "
              f"({100 * (filled / painted - 1):+.3f} %)")
        check("text: the mesh's filled area is rsvg-convert's painted area within 0.2 %",
              abs(filled - painted) <= 0.002 * painted, (filled, painted))

# A family that is not installed: a warning naming it and what was drawn instead; still meshed.
missing = write("missing.svg", DRAWING.replace('font-family="DejaVu Sans"', 'font-family="No Such Family 1234"'))
r = run("mesh", missing, "-o", os.path.join(tmp.name, "missing.msh"), "--regions")
check("missing family: meshed, exit 0", r.returncode == 0, r.stderr[-800:])
check("missing family: warned, naming it and the substitute",
      "'No Such Family 1234' is not installed: drawn in" in r.stderr, r.stderr[-800:])

finish()
