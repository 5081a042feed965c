#!/usr/bin/env python3
"""Hostile input to `curvemesh mesh`, `features` and `check`: what is not a regular file of a
bounded size, malformed UTF-8, entity and style-sheet bombs, drawings too small or too large for
doubles. Each is refused at once with exit 1 and a message naming the file and the reason (never
exit 3, an internal error); the examples scaled to both ends of the range of sizes are meshed,
curved and linear, and certified by `curvemesh check`.

usage: hostile_input_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
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
SVG = '<svg xmlns="http://www.w3.org/2000/svg">{}</svg>'


def run(*args, timeout=120):
    """The run, or None when it did not end within `timeout` (a guard: a refusal is immediate)."""
    try:
        return subprocess.run([binary, *args], capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def refused(name, r, *fragments):
    """Exit 1 with one message holding every fragment."""
    if r is None:
        check(f"{name}: ends", False, "still running after the guard's timeout")
        return
    err = r.stderr.decode("utf-8", "replace")
    check(f"{name}: exit 1", r.returncode == 1, f"exit {r.returncode}: {err}")
    for f in fragments:
        check(f"{name}: says {f!r}", f in err, err)


def write(path, data):
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    return path


def triangle(size):
    return SVG.format(f'<path d="M0 0 L{size!r} 0 L{size / 2!r} {0.8 * size!r} Z"/>')


def scaled(text, scale):
    """`text` with everything inside the root drawn scaled by `scale` about the origin."""
    root = re.search(r"<svg\b[^>]*>", text)
    end = text.rindex("</svg>")
    return text[:root.end()] + f'<g transform="scale({scale!r})">' + text[root.end():end] + "</g>" + text[end:]


def extent(features_json):
    """The drawing's diagonal (tight bounds) and the largest diagonal or coordinate of its control
    points, from `curvemesh features`."""
    data = json.load(open(features_json))
    x0, y0, x1, y1 = data["bbox"]
    xs = [c["p"][i] for c in data["curves"] for i in range(0, 8, 2)] + [p[0] for p in data["points"]]
    ys = [c["p"][i] for c in data["curves"] for i in range(1, 8, 2)] + [p[1] for p in data["points"]]
    control = max(math.hypot(max(xs) - min(xs), max(ys) - min(ys)), max(map(abs, xs + ys)))
    return math.hypot(x1 - x0, y1 - y0), control


with tempfile.TemporaryDirectory() as tmp:
    path = lambda name: os.path.join(tmp, name)  # noqa: E731
    msh = path("out.msh")

    # Not regular files: a FIFO without a writer would block a plain open for ever.
    fifo = path("fifo.svg")
    os.mkfifo(fifo)
    refused("mesh FIFO", run("mesh", fifo, "-o", msh, "-q"), fifo + ": is a FIFO, not a regular file")
    refused("features FIFO", run("features", fifo, "-o", path("f.json")), "is a FIFO")
    fifo_msh = path("fifo.msh")
    os.mkfifo(fifo_msh)
    refused("check FIFO", run("check", fifo_msh), fifo_msh + ": is a FIFO, not a regular file")
    refused("mesh /dev/zero", run("mesh", "/dev/zero", "-o", msh, "-q"), "/dev/zero: is a character device")
    refused("check /dev/zero", run("check", "/dev/zero"), "/dev/zero: is a character device")
    refused("mesh folder", run("mesh", tmp, "-o", msh, "-q"), tmp + ": is a folder, not a regular file")
    refused("check folder", run("check", tmp), tmp + ": is a folder")
    refused("mesh missing", run("mesh", path("missing.svg"), "-o", msh, "-q"), "missing.svg: cannot open the file")

    # Larger than the limit: a sparse file of 65 MiB (no disk taken), above the default 64.
    for suffix in (".svg", ".poly"):
        big = path("big" + suffix)
        with open(big, "wb") as f:
            f.truncate(65 << 20)
        refused(f"mesh 65 MiB {suffix}", run("mesh", big, "-o", msh, "-q"),
                big + ": the file is larger than the limit of 64 MiB (65 MiB; --max-input-mb raises it)")
    # `check`'s own limit (default 2048 MiB, a cubic mesh of two million triangles is about 500).
    r = run("mesh", os.path.join(examples, "square-with-hole.svg"), "-o", msh, "-q")
    check("mesh square-with-hole", r is not None and r.returncode == 0, r and r.stderr)
    r = run("check", msh, "--max-input-mb", "0.001")
    refused("check above --max-input-mb", r, msh + ": the file is larger than the limit", "--max-input-mb raises it")
    r = run("check", msh, "--max-input-mb", "1")
    check("check within --max-input-mb", r is not None and r.returncode == 0, r and r.stderr)
    r = run("check", "--help")
    check("check --help names --max-input-mb", r is not None and b"--max-input-mb" in r.stdout, r and r.stdout)

    # Malformed UTF-8 (once exit 3 in the JSON library): repaired, with a warning, the JSON valid.
    bad = write(path("utf8.svg"), b'<svg xmlns="http://www.w3.org/2000/svg"><path class="\xff" '
                                  b'd="M0 0 L10 0 L5 8 Z" fill="r\xffed" id="t\xff"/></svg>')
    out = path("utf8.json")
    r = run("features", bad, "-o", out)
    check("features on malformed UTF-8: exit 0", r is not None and r.returncode == 0, r and r.stderr)
    if r is not None and r.returncode == 0:
        data = json.loads(open(out, "rb").read().decode("utf-8"))  # strict: fails on a malformed byte
        check("the id repaired", data["sources"][0]["id"] == "t\ufffd", data["sources"])
        check("the warning", any("invalid UTF-8 replaced by U+FFFD (3 bytes, the first at line 1)" in w
                                 for w in data["warnings"]), data["warnings"])

    # Entities referred to by many attributes, and style sheets whose cost multiplies.
    entities = "<!ENTITY e0 '" + "fill:red;" * 11 + "x'>" + "".join(
        f"<!ENTITY e{k} '{('&e%d;' % (k - 1)) * 10}'>" for k in range(1, 4))
    many = '<path style="&e3;" d="M0 0 L1 1"/>' * 1000
    refused("entity budget", run("features", write(path("entities.svg"), f"<!DOCTYPE svg [{entities}]>" + SVG.format(many)),
                                 "-o", out),
            "entity references expand to more than 16777216 characters in all (a limit of the reader)")
    sheet = "<style>" + ",".join([".a"] * 10000) + "{" + "fill:red;" * 10000 + "}</style>"
    refused("style sheet", run("features", write(path("css.svg"), SVG.format(sheet + '<path class="a" d="M0 0 L1 1"/>' * 10)),
                               "-o", out),
            "matching the style sheets takes more steps", "(a limit of the reader)")

    # Drawings too small or too large for doubles: refused with the reason, curved or linear (once
    # exit 3, a collapse to one point with exit 0, and "its size is 1").
    for size, message in ((1e-160, "the drawing is 1.3e-160 across, smaller than 1e-100: too small to mesh in "
                                    "double precision; scale it up"),
                          (1e-162, "the drawing is 1.3e-162 across, smaller than 1e-100"),
                          (1e200, "the drawing reaches a coordinate of 1e+200, beyond 1e+100: too large to mesh in "
                                  "double precision; scale it down")):
        svg = write(path(f"triangle-{size!r}.svg"), triangle(size))
        for mode in ([], ["--linear"]):
            refused(f"triangle {size!r} {mode}", run("mesh", svg, "-o", msh, "-q", *mode), svg + ": " + message)

    # The examples at both ends of the range: meshed and certified.
    for example in sorted(e for e in os.listdir(examples) if e.endswith(".svg")):
        text = open(os.path.join(examples, example)).read()
        r = run("features", os.path.join(examples, example), "-o", out)
        check(f"{example}: read", r is not None and r.returncode == 0, r and r.stderr)
        diagonal, control = extent(out)
        for end, scale in (("small", 1.02e-100 / diagonal), ("large", 0.98e100 / control)):
            svg = write(path(f"{end}-{example}"), scaled(text, scale))
            for mode in ([], ["--linear"]):
                name = f"{example} at the {end} end {mode}"
                r = run("mesh", svg, "-o", msh, "-q", *mode)
                check(f"{name}: meshed", r is not None and r.returncode == 0, r and r.stderr)
                if r is None or r.returncode != 0:
                    continue
                r = run("check", msh, "--json")
                report = json.loads(r.stdout) if r is not None and r.returncode == 0 else {}
                check(f"{name}: certified", report.get("invalid") == 0 and report.get("triangles", 0) > 0,
                      r and (r.stdout, r.stderr))

finish()
