"""Tests of scripts/region-agreement that need no curvemesh: the document copy, the pixel mapping
(through rsvg-convert), the PNG reader, the comparison, the reading of curvemesh's outputs (on
hand-written files in the format curvemesh --regions is to write), and the whole command with a
fake curvemesh; for --painted, the style that keeps strokes, the exact areas of curved triangles,
the coverage arithmetic and its summary and exit status.

    /usr/bin/python3 -m pytest tests/tools/region_agreement_test.py

Tests that render skip when rsvg-convert (Debian: librsvg2-bin) is missing.
"""
import importlib.machinery
import importlib.util
import json
import os
import pathlib
import shutil
import stat
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
import zlib

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "region-agreement"
SVG_NS = "http://www.w3.org/2000/svg"


def _load():
    loader = importlib.machinery.SourceFileLoader("region_agreement", str(SCRIPT))
    spec = importlib.util.spec_from_loader("region_agreement", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


ra = _load()


def need_rsvg():
    if not shutil.which("rsvg-convert"):
        pytest.skip("rsvg-convert is missing (Debian package librsvg2-bin)")


def render_text(tmp_path, document, box, size, name="doc"):
    """Prepares and renders an SVG text; returns the image."""
    need_rsvg()
    copy = tmp_path / f"{name}.svg"
    copy.write_bytes(ra.prepare_document(document.encode(), box, size))
    return ra.render(str(copy), str(tmp_path / f"{name}.png"))


def colour_at(image, box, point):
    (x, y), = ra.to_pixels([point], box, (image.shape[1], image.shape[0]))
    return ra.colour_name(image[int(y), int(x)])


# ------------------------------------------------------------------------------------------------
# The document copy

ILLUSTRATOR = """<?xml version="1.0" encoding="utf-8"?>
<!-- Generator: <svg width="1"> in a comment before the root -->
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.0//EN" "http://www.w3.org/TR/2001/REC-SVG-20010904/DTD/svg10.dtd" [
\t<!ENTITY ns_svg "http://www.w3.org/2000/svg">
\t<!ENTITY ns_xlink "http://www.w3.org/1999/xlink">
\t<!-- a comment in the subset with > and ] -->
\t<!ENTITY st0 "fill:#00FF00;stroke:#FF0000;stroke-width:10">
]>
<svg  xmlns="&ns_svg;" xmlns:xlink="&ns_xlink;" width='400px'
  height="200px" viewBox="0 0 200 100" data-note="a > b" preserveAspectRatio="xMidYMid slice"
  transform="translate(5 5)" id="root"  style="fill:#00ff00"><rect width="50" height="50" style="&st0;"/>
<g><rect x="100" y="0" width="50" height="50"/></g></svg>
<!-- </svg> in a comment after the root -->
"""


def test_root_attributes_replaced_and_style_appended():
    out = ra.prepare_document(ILLUSTRATOR.encode(), (-10.5, 2, 189.5, 102), (1000, 500)).decode()
    # Everything before the root start tag is kept byte for byte (the DOCTYPE with its entities).
    head = ILLUSTRATOR[:ILLUSTRATOR.index("<svg  xmlns")]
    assert out.startswith(head)
    assert "<!ENTITY st0" in out and out.endswith("</svg>\n<!-- </svg> in a comment after the root -->\n")
    root = ET.fromstring(out)  # expat expands the internal entities
    assert root.tag == f"{{{SVG_NS}}}svg"
    assert root.get("viewBox") == "-10.5 2 200 100"
    assert root.get("width") == "1000" and root.get("height") == "500"
    assert root.get("preserveAspectRatio") == "none"
    assert root.get("transform") is None
    assert root.get("data-note") == "a > b" and root.get("id") == "root" and root.get("style") == "fill:#00ff00"
    last = list(root)[-1]
    assert last.tag == f"{{{SVG_NS}}}style" and last.text == ra.INJECTED_CSS
    assert [child.tag for child in root][:2] == [f"{{{SVG_NS}}}rect", f"{{{SVG_NS}}}g"]
    # The inside of the root is untouched.
    inner = ILLUSTRATOR[ILLUSTRATOR.index('<rect width="50"'):ILLUSTRATOR.rindex("</svg>\n<!--")]
    assert inner + "<style" in out
    # One start tag, each replaced attribute once.
    start_tag = out[out.index("<svg  xmlns"):out.index('preserveAspectRatio="none">')]
    for name in ("viewBox=", "width=", "height="):
        assert start_tag.count(" " + name) == 1


def test_namespaced_root_gets_a_namespaced_style():
    doc = ('<?xml version="1.0"?>\n<svg:svg xmlns:svg="http://www.w3.org/2000/svg" width="10" height="10">'
           '<svg:rect width="5" height="5"/></svg:svg>')
    out = ra.prepare_document(doc.encode(), (0, 0, 10, 10), (100, 100)).decode()
    root = ET.fromstring(out)
    assert root.tag == f"{{{SVG_NS}}}svg"
    assert list(root)[-1].tag == f"{{{SVG_NS}}}style"
    assert "<svg:style " in out and out.endswith("</svg:style></svg:svg>")


def test_root_without_namespace_self_closing_and_bom():
    out = ra.prepare_document(b'\xef\xbb\xbf<svg width="10" height="10"/>', (0, 0, 10, 10), (100, 100))
    assert out.startswith(b"\xef\xbb\xbf<svg ")
    root = ET.fromstring(out)
    assert root.tag == "svg" and list(root)[-1].tag == "style" and root.get("preserveAspectRatio") == "none"


def test_utf8_text_passes_through():
    doc = '<svg xmlns="http://www.w3.org/2000/svg" aria-label="Grüße"><title>日本</title></svg>'.encode()
    out = ra.prepare_document(doc, (0, 0, 1, 1), (10, 10))
    assert "Grüße".encode() in out and "<title>日本</title>".encode() in out
    ET.fromstring(out)


@pytest.mark.parametrize("doc", [b"", b"<!-- only a comment -->", b"plain text", b"<svg width='1'",
                                 b"<svg><rect/></g>", b"<!DOCTYPE svg [ <!ENTITY a 'b'>"])
def test_bad_documents_raise(doc):
    with pytest.raises(ra.DocumentError):
        ra.prepare_document(doc, (0, 0, 1, 1), (10, 10))


def test_image_size_and_pixel_mapping():
    assert ra.image_size((0, 0, 200, 100)) == (1000, 500)
    assert ra.image_size((5, -5, 6, 15), 1000) == (50, 1000)
    assert ra.image_size((0, 0, 1, 1e-9), 1000) == (1000, 1)
    with pytest.raises(ValueError):
        ra.image_size((0, 0, 0, 1))
    px = ra.to_pixels([[-10, 0], [190, 100], [90, 50]], (-10, 0, 190, 100), (1000, 500))
    assert np.allclose(px, [[0, 0], [1000, 500], [500, 250]])


# ------------------------------------------------------------------------------------------------
# PNG reading


def encode_png(pixels, colour_type, kinds):
    """A PNG of an (H, W, C) uint8 array with the given filter type for each row."""
    height, width, channels = pixels.shape
    bpp = channels
    rows, previous = [], np.zeros(width * bpp, np.int32)
    for y in range(height):
        row = pixels[y].reshape(-1).astype(np.int32)
        left = np.concatenate([np.zeros(bpp, np.int32), row[:-bpp]])
        upper_left = np.concatenate([np.zeros(bpp, np.int32), previous[:-bpp]])
        kind = kinds[y]
        if kind == 0:
            predictor = np.zeros_like(row)
        elif kind == 1:
            predictor = left
        elif kind == 2:
            predictor = previous
        elif kind == 3:
            predictor = (left + previous) // 2
        else:
            p = left + previous - upper_left
            pa, pb, pc = abs(p - left), abs(p - previous), abs(p - upper_left)
            predictor = np.where((pa <= pb) & (pa <= pc), left, np.where(pb <= pc, previous, upper_left))
        rows.append(bytes([kind]) + ((row - predictor) & 255).astype(np.uint8).tobytes())
        previous = row

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    data = zlib.compress(b"".join(rows))
    # Split the image data over two IDAT chunks, as encoders may.
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"tEXt", b"Software\0test")
            + chunk(b"IDAT", data[:len(data) // 2]) + chunk(b"IDAT", data[len(data) // 2:]) + chunk(b"IEND", b""))


@pytest.mark.parametrize("kinds", ["all", "simple"])
def test_png_filters_rgba(kinds):
    rng = np.random.default_rng(7)
    pixels = rng.integers(0, 256, size=(37, 23, 4), dtype=np.uint8)
    pixels[5:9, 3:20] = (255, 0, 253, 255)  # some flat runs, as in a rendering
    rows = rng.integers(0, 5 if kinds == "all" else 3, size=37)
    rows[:5] = [0, 1, 2, 3, 4] if kinds == "all" else [0, 1, 2, 0, 1]
    image = ra.read_png(encode_png(pixels, 6, rows))
    assert image.dtype == np.uint8 and image.shape == (37, 23, 4)
    assert np.array_equal(image, pixels)


def test_png_rgb_gets_opaque_alpha(tmp_path):
    rng = np.random.default_rng(3)
    pixels = rng.integers(0, 256, size=(9, 11, 3), dtype=np.uint8)
    path = tmp_path / "rgb.png"
    path.write_bytes(encode_png(pixels, 2, [4, 3, 2, 1, 0, 4, 4, 3, 1]))
    image = ra.read_png(str(path))
    assert np.array_equal(image[..., :3], pixels) and (image[..., 3] == 255).all()


def test_png_rejects_what_it_cannot_read():
    with pytest.raises(ValueError):
        ra.read_png(b"GIF89a")
    good = encode_png(np.zeros((2, 2, 4), np.uint8), 6, [0, 0])
    interlaced = bytearray(good)
    ihdr = good.index(b"IHDR")
    interlaced[ihdr + 4 + 12] = 1  # the interlace byte (the CRC is not checked)
    with pytest.raises(ValueError):
        ra.read_png(bytes(interlaced))


def test_png_of_rsvg(tmp_path):
    need_rsvg()
    # A gradient makes rsvg's encoder use all its filter types; compare with a render of flat colours.
    doc = (f'<svg xmlns="{SVG_NS}" width="64" height="32"><defs><linearGradient id="g">'
           '<stop offset="0" stop-color="#000"/><stop offset="1" stop-color="#fff"/></linearGradient></defs>'
           '<rect width="64" height="16" fill="url(#g)"/><rect y="16" width="32" height="16" fill="#123456"/></svg>')
    (tmp_path / "g.svg").write_text(doc)
    subprocess.run(["rsvg-convert", "-o", str(tmp_path / "g.png"), str(tmp_path / "g.svg")], check=True)
    image = ra.read_png(str(tmp_path / "g.png"))
    assert image.shape == (32, 64, 4)
    assert (image[20:30, 2:30] == (0x12, 0x34, 0x56, 255)).all()
    assert (image[20:30, 34:] == 0).all()
    row = image[8, :, 0].astype(int)
    assert (np.diff(row) >= 0).all() and row[0] < 10 and row[-1] > 245 and (image[:16, :, 3] == 255).all()


# ------------------------------------------------------------------------------------------------
# Rendering through the copy: the pixel mapping and the injected style

TWO_RECTS = f"""<svg xmlns="{SVG_NS}" width="37mm" height="50" viewBox="-20 -10 240 120"
     preserveAspectRatio="xMaxYMin meet">
  <g transform="translate(10 5) scale(2 1)">
    <rect x="0" y="0" width="30" height="40" fill="#ff0000" stroke="#000000" stroke-width="8"/>
  </g>
  <rect x="120" y="50" width="60" height="30" style="fill:#0000ff;opacity:0.5"/>
</svg>"""


def test_pixel_mapping_of_two_rects(tmp_path):
    # The box is not the document's viewBox, and the image has another aspect ratio (5 pixels per
    # unit across, 4 down): the copy shows exactly the box, stretched.
    box, size = (-5.0, -2.0, 195.0, 98.0), (1000, 400)
    image = render_text(tmp_path, TWO_RECTS, box, size)
    assert image.shape == (400, 1000, 4)
    assert colour_at(image, box, (10 + 30, 5 + 20)) == "#ff0000"  # the red rect: (10..70, 5..45)
    assert colour_at(image, box, (150, 65)) == "#0000ff"          # the blue one, opacity forced to 1
    assert colour_at(image, box, (100, 20)) == "transparent"
    # Edges land where the mapping says: just inside/outside the red rect's right side x = 70 (its
    # stroke is gone), and the blue rect's top y = 50.
    assert colour_at(image, box, (69.5, 25)) == "#ff0000" and colour_at(image, box, (70.5, 25)) == "transparent"
    assert colour_at(image, box, (150, 50.5)) == "#0000ff" and colour_at(image, box, (150, 49.5)) == "transparent"
    # Corners of the image: the box's corners.
    assert colour_at(image, box, (-4.9, -1.9)) == "transparent"


IMG = ("data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8DwHwAFBQIAX8jx0gAA"
       "AABJRU5ErkJggg==")
MARKER = ('<marker id="m" markerWidth="40" markerHeight="40" refX="20" refY="20" markerUnits="userSpaceOnUse">'
          '<rect width="40" height="40" fill="#0000ff"/></marker>')
GREEN = 'x="20" y="20" width="60" height="60"'
# (name, body, [(point, colour after the style)]); the drawing is 0..100 both ways, the green
# square 20..80; each case's untreated rendering differs at those points.
CASES = [
    ("stroke attribute", f'<rect {GREEN} fill="#00ff00" stroke="#ff0000" stroke-width="20"/>',
     [((15, 50), "transparent"), ((25, 50), "#00ff00")]),
    ("stroke inline style", f'<rect {GREEN} style="fill:#00ff00;stroke:red;stroke-width:20"/>',
     [((15, 50), "transparent"), ((25, 50), "#00ff00")]),
    ("stroke from the document's style sheet",
     f'<style>#r {{ stroke: red; stroke-width: 20 }}</style><rect id="r" {GREEN} fill="#00ff00"/>',
     [((15, 50), "transparent"), ((25, 50), "#00ff00")]),
    ("opacity attribute", f'<rect {GREEN} fill="#00ff00" opacity="0.5"/>', [((50, 50), "#00ff00")]),
    ("opacity inline style on a group",
     f'<g style="opacity:0.3" opacity="0.5"><rect {GREEN} fill="#00ff00"/></g>', [((50, 50), "#00ff00")]),
    ("fill-opacity", f'<rect {GREEN} style="fill:#00ff00;fill-opacity:0.2"/>', [((50, 50), "#00ff00")]),
    ("fill-opacity inherited", f'<g fill-opacity="0.2"><rect {GREEN} fill="#00ff00"/></g>',
     [((50, 50), "#00ff00")]),
    ("mask", f'<mask id="k"><rect width="30" height="30" fill="white"/></mask>'
             f'<rect {GREEN} style="fill:#00ff00;mask:url(#k)"/>', [((50, 50), "#00ff00")]),
    ("filter", f'<filter id="f"><feFlood flood-color="#0000ff"/></filter><rect {GREEN} fill="#00ff00" '
               'filter="url(#f)"/>', [((50, 50), "#00ff00")]),
    ("blur filter", f'<filter id="f"><feGaussianBlur stdDeviation="10"/></filter>'
                    f'<rect {GREEN} style="fill:#00ff00;filter:url(#f)"/>',
     [((22, 50), "#00ff00"), ((15, 50), "transparent")]),
    ("marker longhands", f'{MARKER}<path d="M20 20 H80 V80 H20 Z" fill="#00ff00" marker-start="url(#m)" '
                         'marker-mid="url(#m)" marker-end="url(#m)"/>',
     [((25, 25), "#00ff00"), ((75, 25), "#00ff00"), ((15, 15), "transparent")]),
    ("marker shorthand inline", f'{MARKER}<path d="M20 20 H80 V80 H20 Z" style="fill:#00ff00;marker:url(#m)"/>',
     [((25, 25), "#00ff00"), ((75, 75), "#00ff00"), ((15, 15), "transparent")]),
    ("marker shorthand in a sheet", f'<style>path {{ marker: url(#m) }}</style>{MARKER}'
                                    '<path d="M20 20 H80 V80 H20 Z" fill="#00ff00"/>',
     [((25, 25), "#00ff00"), ((15, 15), "transparent")]),
    ("image", f'<rect {GREEN} fill="#00ff00"/><image width="100" height="100" preserveAspectRatio="none" '
              f'href="{IMG}"/>', [((50, 50), "#00ff00"), ((10, 10), "transparent")]),
    ("image through use", f'<defs><image id="i" width="100" height="100" preserveAspectRatio="none" '
                          f'href="{IMG}"/></defs><rect {GREEN} fill="#00ff00"/><use href="#i"/>',
     [((50, 50), "#00ff00"), ((10, 10), "transparent")]),
    ("blend mode", f'<rect width="100" height="100" fill="#ff0000"/>'
                   f'<rect {GREEN} fill="#00ff00" style="mix-blend-mode:multiply"/>', [((50, 50), "#00ff00")]),
]


@pytest.mark.parametrize("name,body,probes", CASES, ids=[c[0] for c in CASES])
def test_injected_style_is_honoured(tmp_path, name, body, probes):
    document = f'<svg xmlns="{SVG_NS}" width="100" height="100">{body}</svg>'
    box = (0.0, 0.0, 100.0, 100.0)
    image = render_text(tmp_path, document, box, (200, 200))
    assert [colour_at(image, box, p) for p, _ in probes] == [c for _, c in probes]
    # and untreated, rsvg draws something else at one of the points at least
    raw = tmp_path / "raw.svg"
    raw.write_text(document.replace('width="100" height="100"', 'width="200" height="200" viewBox="0 0 100 100"', 1))
    untreated = ra.render(str(raw), str(tmp_path / "raw.png"))
    assert [colour_at(untreated, box, p) for p, _ in probes] != [c for _, c in probes]


def test_clip_paths_are_kept(tmp_path):
    # The regions apply clip paths: the copy keeps them (the green square cut to 0..30).
    document = (f'<svg xmlns="{SVG_NS}" width="100" height="100"><clipPath id="c"><rect width="30" height="30"/>'
                f'</clipPath><rect {GREEN} fill="#00ff00" clip-path="url(#c)"/></svg>')
    need_rsvg()
    box = (0.0, 0.0, 100.0, 100.0)
    image = render_text(tmp_path, document, box, (200, 200))
    assert colour_at(image, box, (25, 25)) == "#00ff00" and colour_at(image, box, (50, 50)) == "transparent"


def test_text_is_painted_and_images_hidden(tmp_path):
    # Text is meshed as its glyphs, so the copy paints it (without its stroke); images stay hidden.
    document = (f'<svg xmlns="{SVG_NS}" width="100" height="100"><text x="5" y="80" font-size="70" '
                'fill="#0000ff" stroke="#ff0000" stroke-width="6">W</text>'
                '<foreignObject width="100" height="100"><div xmlns="http://www.w3.org/1999/xhtml" '
                'style="background:#00ff00;width:100px;height:100px"/></foreignObject></svg>')
    need_rsvg()
    raw = tmp_path / "raw.svg"
    raw.write_text(document)
    untreated = ra.render(str(raw), str(tmp_path / "raw.png"))
    if not (untreated[..., 3] > 0).any():
        pytest.skip("rsvg-convert draws no text here (no fonts)")
    image = render_text(tmp_path, document, (0, 0, 100, 100), (100, 100))
    opaque = image[image[..., 3] == 255]
    assert len(opaque) > 0 and (opaque[:, :3] == [0, 0, 255]).all(axis=1).any()
    assert not (opaque[:, :3] == [255, 0, 0]).all(axis=1).any()


def test_namespaced_and_doctype_documents_render(tmp_path):
    box = (0.0, 0.0, 200.0, 100.0)
    image = render_text(tmp_path, ILLUSTRATOR, box, (400, 200), "illustrator")
    # the root's transform is gone, the entity's stroke too
    assert colour_at(image, box, (2, 2)) == "#00ff00" and colour_at(image, box, (48, 25)) == "#00ff00"
    assert colour_at(image, box, (52, 25)) == "transparent"
    assert colour_at(image, box, (125, 25)) == "#00ff00"  # fill inherited from the root's style
    prefixed = (f'<svg:svg xmlns:svg="{SVG_NS}" width="10" height="10" viewBox="0 0 10 10">'
                '<svg:rect width="5" height="10" fill="#ff0000" stroke="#000" stroke-width="3" opacity="0.2"/>'
                '</svg:svg>')
    image = render_text(tmp_path, prefixed, (0, 0, 10, 10), (100, 100), "prefixed")
    assert colour_at(image, (0, 0, 10, 10), (4.5, 5)) == "#ff0000"
    assert colour_at(image, (0, 0, 10, 10), (5.5, 5)) == "transparent"


# ------------------------------------------------------------------------------------------------
# The comparison and curvemesh's outputs

REGIONS = [
    {"physical": 1, "name": "background", "fill": "none", "triangles": 0, "area": 0},
    {"physical": 7, "name": "red", "fill": "#ff0000", "triangles": 0, "area": 0},
    {"physical": 8, "name": "blue", "fill": "#00F", "triangles": 0, "area": 0},
    {"physical": 9, "name": "shade", "fill": "url(#g)", "triangles": 0, "area": 0},
]


def test_compare_counts():
    image = np.zeros((100, 200, 4), np.uint8)
    image[:, 100:] = (255, 0, 0, 255)
    image[40:60, 140:160] = (0, 0, 254, 255)  # blue, within the tolerance
    image[0:10, 0:10] = (1, 2, 3, 128)        # partly transparent: not uniform
    box = (0.0, 0.0, 20.0, 10.0)               # 10 pixels per unit
    points = [(5, 5), (15, 2), (15, 5), (15, 5), (15, 5), (0.5, 0.5), (19.9, 5), (10.0, 5), (5, 5), (15, 8), (3, 3)]
    region = [0, 1, 2, 1, 3, 0, 1, 1, 1, 0, -1]
    mesh = ra.MeshRegions(points, region, REGIONS, box)
    assert mesh.fills[:3] == ["none", "#ff0000", "#00F"] and mesh.fills[-1] is None
    result = ra.compare(image, mesh, radius=2, tolerance=2)
    verdict = result.pop("verdict").tolist()
    # background ok, red ok, blue ok, red on blue, gradient skipped, a half-transparent corner (not
    # uniform), too close to the image's edge, on the red/transparent border (not uniform), red on
    # background, background on red, unknown physical tag
    assert verdict == [1, 1, 1, 0, -1, -1, -1, -1, 0, 0, -1]
    assert result["triangles"] == 11 and result["compared"] == 6 and result["agreeing"] == 3
    assert result["agreement"] == 0.5
    assert result["skipped"] == {"gradient": 1, "unknown_fill": 0, "no_region": 1, "at_image_edge": 1,
                                 "not_uniform": 2}
    pairs = {(d["region"], d["pixel"]): d["count"] for d in result["disagreements"]}
    assert pairs == {("red", "#0000fe"): 1, ("red", "transparent"): 1, ("background", "#ff0000"): 1}
    empty = ra.compare(image, ra.MeshRegions(np.zeros((0, 2)), [], REGIONS, box))
    assert empty["agreement"] == 1.0 and empty["compared"] == 0


def test_parse_fill():
    assert ra.parse_fill("#A0b1C2") == ("rgb", (160, 177, 194))
    assert ra.parse_fill("#fff") == ("rgb", (255, 255, 255))
    assert ra.parse_fill("none") == ("none", None)
    assert ra.parse_fill("url(#g) #fff") == ("url", None)
    assert ra.parse_fill("currentColor")[0] == "unknown" and ra.parse_fill(None)[0] == "unknown"


def triangle10(a, b, c):
    """The 10 nodes (Gmsh order) of a straight cubic triangle."""
    a, b, c = (np.asarray(p, float) for p in (a, b, c))
    at = lambda u, v, w: u * a + v * b + w * c  # noqa: E731
    t, s = 1 / 3, 2 / 3
    return [a, b, c, at(s, t, 0), at(t, s, 0), at(0, s, t), at(0, t, s), at(t, 0, s), at(s, 0, t), at(t, t, t)]


def write_msh41(path, points, triangles, physical, lines=(), names=None):
    """A Gmsh 4.1 ASCII file as curvemesh writes it: all nodes in one block, one surface entity per
    physical tag (its triangles), one curve entity (physical 100) for `lines`. triangles: lists of
    3 or 10 node indices (0-based, Gmsh order)."""
    order = len(triangles[0])
    triangle_type, line_type = {3: (2, 1), 10: (21, 26)}[order]
    tags = sorted(set(physical))
    xs, ys = np.asarray(points)[:, 0], np.asarray(points)[:, 1]
    bbox = f"{xs.min()!r} {ys.min()!r} 0 {xs.max()!r} {ys.max()!r} 0"
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(tags) + 1), '1 100 "primary"']
    out += [f'2 {t} "{(names or {}).get(t, f"region {t}")}"' for t in tags]
    out += ["$EndPhysicalNames", "$Entities", f"0 1 {len(tags)} 0", f"1 {bbox} 1 100 0"]
    out += [f"{k + 1} {bbox} 1 {t} 0" for k, t in enumerate(tags)]
    n = len(points)
    out += ["$EndEntities", "$Nodes", f"1 {n} 1 {n}", f"2 1 0 {n}"]
    out += [str(i + 1) for i in range(n)]
    out += [f"{x!r} {y!r} 0" for x, y in points]
    out += ["$EndNodes", "$Elements"]
    blocks = [(1, 1, line_type, list(lines))] if len(lines) else []
    blocks += [(2, k + 1, triangle_type, [tri for tri, p in zip(triangles, physical) if p == t])
               for k, t in enumerate(tags)]
    total = sum(len(b[3]) for b in blocks)
    out.append(f"{len(blocks)} {total} 1 {total}")
    tag = 1
    for dim, entity, kind, elements in blocks:
        out.append(f"{dim} {entity} {kind} {len(elements)}")
        for element in elements:
            out.append(" ".join(str(v) for v in [tag] + [i + 1 for i in element]))
            tag += 1
    out += ["$EndElements", ""]
    with open(path, "w") as f:
        f.write("\n".join(out))


def write_fake_outputs(msh, stats, rects, box, cell=10.0, linear=False, regions=None, painted_only=False):
    """What `curvemesh mesh --regions --stats` is to write, for a drawing of axis-aligned
    rectangles [(x0, y0, x1, y1, fill), ...] (the later on top) whose edges are on the grid of
    `cell`: a grid of the box, each square two triangles, each tagged with the region at its
    centre (physical 1 "background", then 2, 3, ... for the rects), and a few line elements.
    painted_only: the triangles of the rects alone (what --domain painted meshes); stats None: no
    statistics."""
    x0, y0, x1, y1 = box
    nx, ny = int(round((x1 - x0) / cell)), int(round((y1 - y0) / cell))
    points, cells, tags = [], [], []
    for i in range(nx):
        for j in range(ny):
            p = [(x0 + (i + di) * cell, y0 + (j + dj) * cell) for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1))]
            for tri in ((p[0], p[1], p[2]), (p[0], p[2], p[3])):
                centre = np.mean(tri, axis=0)
                physical = 1
                for k, (a, b, c, d, _) in enumerate(rects):
                    if a < centre[0] < c and b < centre[1] < d:
                        physical = 2 + k
                if painted_only and physical == 1:
                    continue
                nodes = [np.asarray(v, float) for v in tri] if linear else triangle10(*tri)
                cells.append(list(range(len(points), len(points) + len(nodes))))
                points.extend(tuple(float(c) for c in v) for v in nodes)
                tags.append(physical)
    lines = [[0, 1], [1, 2]] if linear else [[0, 1, 3, 4], [1, 2, 5, 6]]
    if regions is None:
        regions = [{"physical": 1, "name": "background", "fill": "none"}]
        regions += [{"physical": 2 + k, "name": f"rect{k}", "fill": r[4]} for k, r in enumerate(rects)]
    for entry in regions:
        entry.setdefault("triangles", tags.count(entry["physical"]))
        entry.setdefault("area", 0.0)
    write_msh41(msh, points, cells, tags, lines, {e["physical"]: e["name"] for e in regions})
    if stats is not None:
        with open(stats, "w") as f:
            json.dump({"mesh": {"triangles": len(tags)}, "regions": regions}, f)


RECT_SVG = f"""<?xml version="1.0"?>
<svg xmlns="{SVG_NS}" width="300" height="150" viewBox="0 0 100 50">
  <rect x="10" y="10" width="30" height="30" fill="#ff0000" stroke="#000" stroke-width="4"/>
  <rect x="60" y="10" width="30" height="30" style="fill:#0000ff;fill-opacity:0.3"/>
</svg>
"""
RECTS = [(10, 10, 40, 40, "#ff0000"), (60, 10, 90, 40, "#0000ff")]
BOX = (-10.0, -10.0, 110.0, 60.0)  # a margin around the drawing, as curvemesh's box has


@pytest.mark.parametrize("linear", [False, True])
def test_read_regions(tmp_path, linear):
    msh, stats = str(tmp_path / "m.msh"), str(tmp_path / "s.json")
    write_fake_outputs(msh, stats, RECTS, BOX, linear=linear)
    mesh = ra.read_regions(msh, stats)
    assert mesh.box == BOX
    assert len(mesh.points) == 2 * 12 * 7
    # the first square (-10..0, -10..0): triangles (a, b, c) and (a, c, d), point = centroid
    assert np.allclose(mesh.points[0], (-10 + 20 / 3, -10 + 10 / 3))
    assert np.allclose(mesh.points[1], (-10 + 10 / 3, -10 + 20 / 3))
    fills = mesh.fills
    assert fills.count("#ff0000") == fills.count("#0000ff") == 18 and fills.count("none") == 168 - 36


def test_check_drawing_with_fake_outputs(tmp_path):
    need_rsvg()
    drawing = tmp_path / "rects.svg"
    drawing.write_text(RECT_SVG)

    def reader(msh, stats):
        write_fake_outputs(msh, stats, RECTS, BOX)
        return ra.read_regions(msh, stats)

    job = dict(index=0, path=str(drawing), curvemesh="/bin/true", timeout=10, size=600, radius=2, tolerance=2,
               keep=str(tmp_path / "keep"), linear=False, reader=reader)
    record = ra.check_drawing(job)
    assert record["status"] == "ok", record
    assert record["triangles"] == 168 and record["compared"] == 168 and record["agreement"] == 1.0
    assert record["image"] == [600, 350]
    kept = tmp_path / "keep" / "0000-rects"
    assert {p.name for p in kept.iterdir()} >= {"render.svg", "render.png", "points.svg", "record.json"}


FAKE_CURVEMESH = """#!{python}
# A stand-in for `curvemesh mesh IN -o OUT.msh --regions --stats S.json`: {mode}
import sys
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, {tests!r})
import region_agreement_test as t
args = sys.argv[1:]
assert args[0] == "mesh" and ("--regions" in args or "--domain" in args), args
drawing, msh = args[1], args[args.index("-o") + 1]
stats = args[args.index("--stats") + 1] if "--stats" in args else None
mode = {mode!r}
if mode == "fail" or "broken" in drawing:
    sys.exit("curvemesh: " + drawing + ": no mesh")
if mode.startswith("painted"):
    sys.exit(t.write_painted_fake(args, mode))
regions = None
if mode == "wrong":
    regions = [dict(physical=1, name="background", fill="none"), dict(physical=2, name="rect0", fill="#ff0000"),
               dict(physical=3, name="rect1", fill="#00ff00")]
t.write_fake_outputs(msh, stats, t.RECTS, t.BOX, linear="--linear" in args, regions=regions)
"""


def fake_curvemesh(tmp_path, mode):
    path = tmp_path / f"curvemesh-{mode}"
    path.write_text(FAKE_CURVEMESH.format(python=sys.executable, tests=str(pathlib.Path(__file__).parent), mode=mode))
    path.chmod(path.stat().st_mode | stat.S_IXUSR)
    return str(path)


def run_script(*args):
    return subprocess.run([sys.executable, str(SCRIPT), *args], capture_output=True, text=True, timeout=300)


def test_command_with_a_fake_curvemesh(tmp_path):
    need_rsvg()
    for name in ("a.svg", "b.svg", "broken.svg"):
        (tmp_path / name).write_text(RECT_SVG)
    listing = tmp_path / "list.txt"
    listing.write_text("# drawings\na.svg\n\nb.svg  # the same\n")
    out = tmp_path / "out.json"
    good = fake_curvemesh(tmp_path, "good")
    r = run_script("--curvemesh", good, "--jobs", "2", "--json", str(out), "--linear", str(listing),
                   str(tmp_path / "broken.svg"), "--min-drawings", "0.9")
    assert r.returncode == 0, r.stdout + r.stderr
    records = json.loads(out.read_text())["drawings"]
    assert [os.path.basename(x["path"]) for x in records] == ["a.svg", "b.svg", "broken.svg"]
    assert [x["status"] for x in records] == ["ok", "ok", "mesh-failed"]
    assert records[0]["agreement"] == 1.0 and records[0]["compared"] == 168
    assert "no mesh" in records[2]["message"]
    assert "agreement >= 0.99: 2 of 2 drawings" in r.stdout and "PASS" in r.stdout
    # ... unless failed drawings are limited: one failed, more than --max-failed 0.
    r = run_script("--curvemesh", good, "--linear", str(listing), str(tmp_path / "broken.svg"),
                   "--min-drawings", "0.9", "--max-failed", "0")
    assert r.returncode == 1 and "more than --max-failed 0" in r.stdout and "FAIL" in r.stdout
    r = run_script("--curvemesh", good, "--linear", str(listing), str(tmp_path / "broken.svg"),
                   "--min-drawings", "0.9", "--max-failed", "1")
    assert r.returncode == 0, r.stdout + r.stderr

    # The blue rect claimed green: 18 of 168 triangles disagree.
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "wrong"), "--json", str(out), str(tmp_path / "a.svg"))
    assert r.returncode == 1, r.stdout + r.stderr
    (record,) = json.loads(out.read_text())["drawings"]
    assert record["agreeing"] == 150 and record["compared"] == 168
    assert record["disagreements"] == [{"region": "rect1", "fill": "#00ff00", "pixel": "#0000ff", "count": 18}]
    assert "below 0.99:" in r.stdout and "rect1" in r.stdout and "FAIL" in r.stdout
    # ... which passes a lower bar.
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "wrong"), "--min-agreement", "0.85", str(tmp_path / "a.svg"))
    assert r.returncode == 0, r.stdout + r.stderr

    # Nothing meshed: exit 1, not a pass.
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "fail"), str(tmp_path / "a.svg"))
    assert r.returncode == 1 and "mesh-failed" in r.stdout


def test_usage_errors(tmp_path):
    assert run_script().returncode == 2
    assert run_script("--curvemesh", str(tmp_path / "nothing"), "x.svg").returncode == 2
    assert run_script("--curvemesh", "/bin/true", "--min-agreement", "2", "x.svg").returncode == 2
    assert run_script("--curvemesh", "/bin/true", "--max-failed", "-1", "x.svg").returncode == 2
    assert run_script("--curvemesh", "/bin/true", str(tmp_path / "missing.txt")).returncode == 2


def test_summary_fraction():
    def rec(agreement):
        return {"path": "p", "status": "ok", "triangles": 10, "compared": 10, "agreeing": int(agreement * 10),
                "agreement": agreement, "disagreements": []}

    import io
    records = [rec(1.0)] * 19 + [rec(0.5), {"path": "f", "status": "timeout", "message": "slow"}]
    assert ra.summarize(records, 0.99, 0.95, out=io.StringIO())
    assert not ra.summarize(records, 0.99, 0.96, out=io.StringIO())
    assert not ra.summarize([records[-1]], 0.99, 0.0, out=io.StringIO())
    assert ra.summarize(records, 0.99, 0.95, out=io.StringIO(), max_failed=1)
    assert not ra.summarize(records, 0.99, 0.95, out=io.StringIO(), max_failed=0)


# ------------------------------------------------------------------------------------------------
# --painted: strokes kept, the painted area


def test_painted_css_is_the_injected_one_with_strokes_on():
    # The same switches as the default style but `stroke: none`, and stroke- and stop-opacity too.
    declarations = lambda css: {d.strip() for d in css.replace("{", ";").replace("}", ";").split(";")}  # noqa: E731
    default, painted = declarations(ra.INJECTED_CSS), declarations(ra.PAINTED_CSS)
    assert default - painted == {"stroke: none !important"}
    assert painted - default == {"stroke-opacity: 1 !important", "stop-opacity: 1 !important"}


def render_painted(tmp_path, body, size=200):
    need_rsvg()
    document = f'<svg xmlns="{SVG_NS}" width="100" height="100">{body}</svg>'
    copy = tmp_path / "painted.svg"
    copy.write_bytes(ra.prepare_document(document.encode(), (0, 0, 100, 100), (size, size), ra.PAINTED_CSS))
    return ra.render(str(copy), str(tmp_path / "painted.png"))


@pytest.mark.parametrize("style", ['stroke="#ff0000" stroke-opacity="0.4" opacity="0.5"',
                                   'style="stroke:#ff0000;stroke-opacity:0.4"',
                                   'class="s"'])
def test_painted_css_keeps_strokes_opaque(tmp_path, style):
    sheet = "<style>.s { stroke: #ff0000; stroke-opacity: 0.3 }</style>" if "class" in style else ""
    image = render_painted(tmp_path, f'{sheet}<rect {GREEN} fill="#00ff00" fill-opacity="0.5" '
                                     f'stroke-width="20" {style}/>')
    box = (0, 0, 100, 100)
    # the stroke straddles the edge x = 20 (10..30), over the fill inside; the fill in the middle
    assert [colour_at(image, box, p) for p in [(12, 50), (28, 50), (50, 50), (5, 50)]] == \
        ["#ff0000", "#ff0000", "#00ff00", "transparent"]


@pytest.mark.parametrize("name,body,probes", [c for c in CASES if not c[0].startswith("stroke")],
                         ids=[c[0] for c in CASES if not c[0].startswith("stroke")])
def test_painted_css_still_switches_the_rest_off(tmp_path, name, body, probes):
    image = render_painted(tmp_path, body)
    assert [colour_at(image, (0, 0, 100, 100), p) for p, _ in probes] == [c for _, c in probes]


def test_painted_css_makes_gradient_stops_opaque(tmp_path):
    image = render_painted(tmp_path, '<linearGradient id="g"><stop offset="0" stop-color="#0000ff" stop-opacity="0"/>'
                                     '<stop offset="1" stop-color="#0000ff" stop-opacity="0.2"/></linearGradient>'
                                     f'<rect {GREEN} fill="url(#g)"/>')
    assert (image[45:155, 45:155, 3] == 255).all()


def test_triangle_areas_are_exact_for_cubic_edges():
    a, b, c = (0.0, 0.0), (2.0, 0.0), (0.0, 1.0)
    straight = np.array(triangle10(a, b, c))
    cells = [list(range(10))]
    assert np.allclose(ra.triangle_areas(straight, cells), [1.0])
    # Edge a-b bent to y = -h t (1 - t) (1 + t) (x = 2t): a cubic, adding 2 h / 4 of area.
    h, bent = 0.3, straight.copy()
    bent[3] = (2 / 3, -h * (1 / 3) * (2 / 3) * (4 / 3))
    bent[4] = (4 / 3, -h * (2 / 3) * (1 / 3) * (5 / 3))
    bent[9] += (0.05, -0.07)  # the interior node does not change the area
    assert ra.triangle_areas(bent, cells)[0] == pytest.approx(1.0 + 2 * h / 4, rel=1e-14)
    # A quadratic bulge along x = 2t in 3-node, 6-node and reversed orientation.
    six = np.array([a, b, c, (1.0, -0.5), (1.0, 0.5), (0.0, 0.5)])
    assert ra.triangle_areas(six, [list(range(6))])[0] == pytest.approx(1.0 + 2 * 4 * 0.5 / 6)
    assert np.allclose(ra.triangle_areas(six[:3], [[0, 1, 2], [0, 2, 1]]), [1.0, -1.0])
    with pytest.raises(ValueError):
        ra.triangle_areas(six, [[0, 1, 2, 3]])


def test_read_mesh_area(tmp_path):
    box = (0.0, 0.0, 30.0, 20.0)
    for linear in (False, True):
        msh = str(tmp_path / f"p{linear}.msh")
        write_fake_outputs(msh, None, [(10, 0, 20, 10, "#ff0000")], box, linear=linear, painted_only=True)
        area, triangles, extent = ra.read_mesh_area(msh)
        assert triangles == 2 and area == pytest.approx(100.0) and extent == (10.0, 0.0, 20.0, 10.0)


def test_painted_area_and_coverage():
    image = np.zeros((4, 10, 4), np.uint8)
    image[0, :, 3] = 255   # one full row: 10 pixels
    image[1, :4, 3] = 51   # 4 pixels at 0.2
    box = (-1.0, 2.0, 4.0, 10.0)  # a pixel is 0.5 x 2 units
    assert ra.painted_area(image, box) == pytest.approx((10 + 0.8) * 1.0)
    c = ra.coverage(10.8 * 1.004, 10.8)
    assert c["relative_difference"] == pytest.approx(0.004) and c["matches"]
    c = ra.coverage(10.8 * 0.994, 10.8)
    assert c["relative_difference"] == pytest.approx(-0.006) and not c["matches"]
    assert ra.coverage(10.8 * 0.994, 10.8, max_error=0.01)["matches"]
    assert ra.coverage(0.0, 0.0) == {"mesh_area": 0.0, "rendered_area": 0.0, "relative_difference": 0.0,
                                     "matches": True}
    assert not ra.coverage(1.0, 0.0)["matches"] and ra.coverage(1.0, 0.0)["relative_difference"] is None
    assert ra.coverage(0.0, 2.0)["relative_difference"] == -1.0


# The painted drawing: a red square under a black stroke 4 wide (the stroke 10..40, the fill seen
# 14..36) at half stroke-opacity, and a blue one at fill-opacity 0.3 (both forced to 1).
PAINTED_SVG = f"""<svg xmlns="{SVG_NS}" width="300" height="150" viewBox="0 0 100 50">
  <rect x="12" y="12" width="26" height="26" fill="#ff0000" stroke="#000" stroke-width="4" stroke-opacity="0.5"/>
  <rect x="60" y="10" width="30" height="30" style="fill:#0000ff;fill-opacity:0.3"/>
</svg>
"""
PAINTED_RECTS = [(10, 10, 40, 40, "#000000"), (14, 14, 36, 36, "#ff0000"), (60, 10, 90, 40, "#0000ff")]
PAINTED_NAMES = ["background", "rect0.stroke", "rect0", "rect1"]


def write_painted_fake(args, mode):
    """The fake curvemesh of --painted: the regions mesh (--strokes areas), or the painted domain
    (mode painted-short: without the blue square; painted-empty: curvemesh's empty domain)."""
    msh = args[args.index("-o") + 1]
    if "--domain" not in args:
        assert args[args.index("--strokes") + 1] == "areas", args
        stats = args[args.index("--stats") + 1]
        regions = [dict(physical=1 + k, name=n, fill=f) for k, (n, f) in
                   enumerate(zip(PAINTED_NAMES, ["none"] + [r[4] for r in PAINTED_RECTS]))]
        write_fake_outputs(msh, stats, PAINTED_RECTS, BOX, cell=2.0, regions=regions)
        return 0
    assert args[args.index("--domain") + 1] == "painted" and "--regions" not in args, args
    if mode == "painted-empty":
        print("curvemesh: x.svg: the domain 'painted' is empty (nothing of the drawing is filled or stroked)",
              file=sys.stderr)
        return 1
    rects = PAINTED_RECTS[:2] if mode == "painted-short" else PAINTED_RECTS
    write_fake_outputs(msh, None, rects, BOX, cell=2.0, painted_only=True)
    return 0


def test_check_drawing_painted_with_fake_outputs(tmp_path):
    need_rsvg()
    drawing = tmp_path / "painted.svg"
    drawing.write_text(PAINTED_SVG)
    job = dict(index=0, path=str(drawing), curvemesh=fake_curvemesh(tmp_path, "painted"), timeout=60, size=600,
               radius=2, tolerance=2, keep=None, linear=False, painted=True, max_area_error=0.005)
    record = ra.check_drawing(job)
    assert record["status"] == "ok", record
    assert record["compared"] == record["triangles"] == 2 * 60 * 35 and record["agreement"] == 1.0
    p = record["painted"]
    assert p["rendered_area"] == pytest.approx(1800.0) and p["mesh_area"] == pytest.approx(1800.0)
    assert abs(p["relative_difference"]) < 1e-9 and p["matches"] and p["triangles"] == 2 * 2 * 15 * 15
    assert p["outside_box"] is False
    # Without --painted the stroke is not painted: its ring shows the red fill or nothing.
    def reader(msh, stats):
        write_painted_fake(["mesh", "x.svg", "-o", msh, "--stats", stats, "--strokes", "areas"], "painted")
        return ra.read_regions(msh, stats)

    job.update(painted=False, curvemesh="/bin/true", reader=reader)
    record = ra.check_drawing(job)
    assert record["status"] == "ok" and "painted" not in record
    assert {d["region"] for d in record["disagreements"]} == {"rect0.stroke"}


def test_command_painted(tmp_path):
    need_rsvg()
    drawing = tmp_path / "painted.svg"
    drawing.write_text(PAINTED_SVG)
    out = tmp_path / "out.json"
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "painted"), "--painted", "--json", str(out), str(drawing))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "painted area within 0.5 %: 1 of 1 drawings (100.0 %, required 95.0 %)" in r.stdout
    data = json.loads(out.read_text())
    assert data["painted"] is True and data["max_area_error"] == 0.005
    assert data["drawings"][0]["painted"]["matches"] is True
    # The blue square missing from the painted domain: half the area, agreement still perfect.
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "painted-short"), "--painted", "--json", str(out),
                   str(drawing))
    assert r.returncode == 1 and "painted area within 0.5 %: 0 of 1" in r.stdout and "-50.00" in r.stdout
    assert "agreement >= 0.99: 1 of 1" in r.stdout and "FAIL" in r.stdout
    assert json.loads(out.read_text())["drawings"][0]["painted"]["relative_difference"] == pytest.approx(-0.5, abs=1e-3)
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "painted-short"), "--painted", "--max-area-error", "0.6",
                   str(drawing))
    assert r.returncode == 0, r.stdout + r.stderr
    # An empty painted domain against a painted rendering: off by -100 %, not a failed mesh.
    r = run_script("--curvemesh", fake_curvemesh(tmp_path, "painted-empty"), "--painted", "--json", str(out),
                   str(drawing))
    assert r.returncode == 1 and "-100.000 %" in r.stdout
    (record,) = json.loads(out.read_text())["drawings"]
    assert record["status"] == "ok" and record["painted"]["triangles"] == 0
    assert run_script("--curvemesh", "/bin/true", "--max-area-error", "0.1", "x.svg").returncode == 2


def test_summary_painted():
    def rec(agreement, difference):
        painted = {"mesh_area": 1.0 + difference, "rendered_area": 1.0, "relative_difference": difference,
                   "matches": abs(difference) <= 0.005}
        return {"path": "p", "status": "ok", "triangles": 10, "compared": 10, "agreeing": int(agreement * 10),
                "agreement": agreement, "disagreements": [], "painted": painted}

    import io
    good = [rec(1.0, 0.001)] * 19
    assert ra.summarize(good + [rec(1.0, 0.02)], 0.99, 0.95, out=io.StringIO(), max_area_error=0.005)
    out = io.StringIO()
    assert not ra.summarize(good + [rec(1.0, 0.02)] * 2, 0.99, 0.95, out=out, max_area_error=0.005)
    assert "painted area within 0.5 %: 19 of 21 drawings (90.5 %" in out.getvalue()
    assert "+2.000 % (mesh 1.02, rendered 1)  p" in out.getvalue()
    # the agreement alone still decides too, and without max_area_error areas are not looked at
    assert not ra.summarize(good + [rec(0.5, 0.0)] * 2, 0.99, 0.95, out=io.StringIO(), max_area_error=0.005)
    out = io.StringIO()
    assert ra.summarize(good + [rec(1.0, 0.02)] * 2, 0.99, 0.95, out=out)
    assert "painted" not in out.getvalue()
