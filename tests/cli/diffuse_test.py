#!/usr/bin/env python3
"""Command-line contract of `curvemesh diffuse` (diffusion curves).

A circle with two colours: the inside takes its right colour, the outside its left one (an SVG
circle runs clockwise on screen), on the curved and on the straight map; a line drawn rightwards
is red above and blue below (left is on screen, y down), and the other way round when drawn
leftwards; parts no curve borders take --background; the VTU has the colour at its nodes; the
output is deterministic; bad input exits 1, bad usage 2. PNG files are read with zlib only.

usage: diffuse_test.py CURVEMESH_BINARY
"""
import os
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary = sys.argv[1]
tmp = tempfile.TemporaryDirectory()


def path(name):
    return os.path.join(tmp.name, name)


def run(*args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=600)


def write(name, body):
    with open(path(name), "w") as f:
        f.write('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">' + body + "</svg>")
    return path(name)


def read_png(file):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB PNG."""
    with open(file, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour_type = struct.unpack(">IIBB", body[:10])
            assert (depth, colour_type) == (8, 2), "not 8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = 3 * width
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = previous[i]
            c = previous[i - 3] if i >= 3 else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[3 * x:3 * x + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def pixel_at(picture, box, x, y):
    """The pixel whose area holds the drawing's point (x, y); box = (x0, y0, x1, y1) of the picture."""
    width, height, rows = picture
    px = int((x - box[0]) / (box[2] - box[0]) * width)
    py = int((y - box[1]) / (box[3] - box[1]) * height)
    return rows[py][px]


def close(got, want, tol):
    return all(abs(g - w) <= tol for g, w in zip(got, want))


# The mesh's box is the drawing's bounding box grown by 5% of its diagonal on every side.
def box_of(x0, y0, x1, y1):
    margin = 0.05 * ((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5
    return (x0 - margin, y0 - margin, x1 + margin, y1 + margin)


# --- A circle: inside is its right colour, outside its left, exactly (each part of the cut
# mesh is held by one colour only).
circle = write("circle.svg", '<circle cx="50" cy="50" r="30" data-color-left="#ffcc00" data-color-right="#3366ff"/>')
box = box_of(20, 20, 80, 80)
for linear in (False, True):
    name = "circle " + ("straight" if linear else "cubic")
    out = path(name.replace(" ", "-") + ".png")
    r = run("diffuse", circle, "-o", out, "--width", "120", *(["--straight"] if linear else []))
    check(f"{name}: exit 0", r.returncode == 0, r.stderr)
    check(f"{name}: times printed", all(s in r.stdout for s in ("meshing", "assembly", "solve", "rasterization")),
          r.stdout)
    if r.returncode != 0:
        continue
    picture = read_png(out)
    check(f"{name}: size", picture[:2] == (120, 120), str(picture[:2]))
    for x, y in [(50, 50), (50, 23), (35, 65)]:
        got = pixel_at(picture, box, x, y)
        check(f"{name}: inside at ({x}, {y}) is the right colour", got == (0x33, 0x66, 0xff), str(got))
    for x, y in [(50, 17), (20, 20), (80, 80), (box[0] + 0.5, box[1] + 0.5)]:
        got = pixel_at(picture, box, x, y)
        check(f"{name}: outside at ({x}, {y}) is the left colour", got == (0xff, 0xcc, 0x00), str(got))

# Deterministic: the same picture twice.
again = path("circle-again.png")
r = run("diffuse", circle, "-o", again, "--width", "120")
with open(path("circle-cubic.png"), "rb") as a, open(again, "rb") as b:
    check("deterministic PNG", r.returncode == 0 and a.read() == b.read())

# --- A line drawn rightwards is red above and blue below on screen; drawn leftwards, the other
# way round. Two isolated points make the box square.
points = '<path d="M50 0 L50 0"/><path d="M50 100 L50 100"/>'
box = box_of(10, 0, 90, 100)
for d, above, below in [("M10 50 L90 50", (255, 0, 0), (0, 0, 255)), ("M90 50 L10 50", (0, 0, 255), (255, 0, 0))]:
    svg = write("line.svg", points + f'<path d="{d}" data-color-left="red" data-color-right="blue"/>')
    out = path("line.png")
    r = run("diffuse", svg, "-o", out, "--width", "200")
    check(f"line {d}: exit 0", r.returncode == 0, r.stderr)
    if r.returncode != 0:
        continue
    picture = read_png(out)
    got_above, got_below = pixel_at(picture, box, 50, 49), pixel_at(picture, box, 50, 51)
    check(f"line {d}: just above is {above}", close(got_above, above, 26), str(got_above))
    check(f"line {d}: just below is {below}", close(got_below, below, 26), str(got_below))

# --- Parts no curve borders take the background: a drawing of isolated points only.
svg = write("points.svg", points + '<path d="M10 50 L10 50"/>')
out = path("points.png")
r = run("diffuse", svg, "-o", out, "--width", "40", "--background", "#102030")
check("points only: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    _, _, rows = read_png(out)
    colours = {p for row in rows for p in row}
    check("points only: every pixel is the background", colours == {(0x10, 0x20, 0x30)}, str(sorted(colours)[:5]))
    check("points only: the part is reported", "1 part with no curve" in r.stdout, r.stdout)

# --- VTU: the cut mesh with the colour at its nodes.
vtu = path("circle.vtu")
r = run("diffuse", circle, "-o", path("v.png"), "--width", "40", "--vtu", vtu)
check("vtu: exit 0", r.returncode == 0, r.stderr)
try:
    import meshio

    m = meshio.read(vtu)
    colour = m.point_data.get("colour")
    check("vtu: colour at the nodes", colour is not None and colour.shape == (len(m.points), 3),
          str(None if colour is None else colour.shape))
    if colour is not None:
        check("vtu: colours are the two given ones",
              all(min(abs(c - [1, 0.8, 0]).max(), abs(c - [0.2, 0.4, 1]).max()) < 1e-9 for c in colour))
except ImportError:
    print("meshio not available: VTU contents not checked")

# --- A bad side colour is a warning, not an error.
svg = write("bad-colour.svg", '<circle cx="50" cy="50" r="30" data-color-left="bluish"/>')
r = run("diffuse", svg, "-o", path("bad-colour.png"), "--width", "40")
check("bad colour: exit 0", r.returncode == 0, r.stderr)
check("bad colour: warned", 'data-color-left="bluish"' in r.stderr, r.stderr)

# --- Bad input exits 1, bad usage 2.
with open(path("broken.svg"), "w") as f:
    f.write("<svg><path d='M0 0 L")
with open(path("html.svg"), "w") as f:
    f.write("<html><body/></html>")
for name, args in [
    ("missing file", [path("missing.svg")]),
    ("malformed XML", [path("broken.svg")]),
    ("not SVG", [path("html.svg")]),
]:
    r = run("diffuse", *args, "-o", path("x.png"))
    check(f"{name}: exit 1", r.returncode == 1, f"{r.returncode} {r.stderr}")
    check(f"{name}: says why", r.stderr.startswith("curvemesh: "), r.stderr)
    check(f"{name}: no picture", not os.path.exists(path("x.png")))
r = run("diffuse", circle, "-o", os.path.join(tmp.name, "no-such-dir", "x.png"))
check("unwritable output: exit 1", r.returncode == 1, f"{r.returncode} {r.stderr}")
for name, args in [
    ("no output", [circle]),
    ("bad background", [circle, "-o", path("x.png"), "--background", "nope"]),
    ("width too small", [circle, "-o", path("x.png"), "--width", "2"]),
]:
    r = run("diffuse", *args)
    check(f"{name}: exit 2", r.returncode == 2, f"{r.returncode} {r.stderr}")
r = run("diffuse", "--help")
check("help: defines left", r.returncode == 0 and "left" in r.stdout and "y points down" in r.stdout, r.stdout)

finish()
