#!/usr/bin/env python3
"""Command-line contract of `curvemesh mesh --linear`, every output certified by the independent
checker tests/tools/msh_check.py (exact orientation from the written text, Gmsh and meshio read it):
the bundled examples in both file versions, the target edge length on a unit square, determinism,
Triangle .poly input, nasty inputs (many segments through a point, overlapping collinear segments,
segments shorter than 1e-12 d, points on segments), copies scaled by 1e-6 and 1e6, bad input, a
dense soup from scripts/random-soup.

usage: mesh_test.py CURVEMESH_BINARY EXAMPLES_DIR
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


def mesh(name, source, *extra):
    out = os.path.join(tmp.name, name + ".msh")
    stats = os.path.join(tmp.name, name + ".json")
    r = subprocess.run([binary, "mesh", source, "-o", out, "--linear", "--stats", stats, *extra],
                       capture_output=True, text=True, timeout=300)
    return r, out, stats


def certify(name, path):
    """The checker's verdict and its measurements (JSON)."""
    r = subprocess.run([sys.executable, checker, path, "--json"], capture_output=True, text=True, timeout=300)
    check(f"{name}: independent checker accepts the mesh", r.returncode == 0, (r.stdout + r.stderr)[-500:])
    try:
        return json.loads(r.stdout)
    except json.JSONDecodeError:
        return {}


def write(name, text):
    path = os.path.join(tmp.name, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def poly(points, segments):
    lines = [f"{len(points)} 2 0 0"]
    lines += [f"{i + 1} {x!r} {y!r}" for i, (x, y) in enumerate(points)]
    lines += [f"{len(segments)} 0"]
    lines += [f"{i + 1} {a + 1} {b + 1}" for i, (a, b) in enumerate(segments)]
    lines += ["0"]
    return "\n".join(lines) + "\n"


# The bundled examples, in both file versions.
for example in sorted(os.listdir(examples)):
    if not example.endswith(".svg"):
        continue
    for version in ("4.1", "2.2"):
        name = f"{example}-{version}"
        r, out, _ = mesh(name, os.path.join(examples, example), "--msh-version", version)
        check(f"{name}: exit 0", r.returncode == 0, r.stderr)
        if r.returncode == 0:
            report = certify(name, out)
            check(f"{name}: has primary or secondary feature edges",
                  report.get("lines", {}).get("primary", 0) + report.get("lines", {}).get("secondary", 0) > 0,
                  str(report.get("lines")))

# --no-features: no primary line, only secondary ones (the stats say the same of the features),
# certified like any other mesh; the same drawing has primary lines by default.
example = os.path.join(examples, "overlapping-shapes.svg")
r, out, stats = mesh("no-features", example, "--no-features")
check("--no-features: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    report = certify("--no-features", out)
    lines = report.get("lines", {})
    check("--no-features: no primary line, secondary lines", lines.get("primary", 0) == 0 and lines.get("secondary", 0) > 0,
          str(lines))
    with open(stats) as f:
        features = json.load(f).get("features", {})
    check("--no-features: the stats count no primary section", features.get("primary_sections") == 0
          and features.get("secondary_segments", 0) > 0, str(features))
    with_features = certify("with-features", mesh("with-features", example)[1])
    check("with features the same drawing has primary lines", with_features.get("lines", {}).get("primary", 0) > 0,
          str(with_features.get("lines")))

# Target edge length: a unit square with -l 0.05 has mean edge length within 25 % of 0.05 d.
square = write("square.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1 1">'
                              '<rect width="1" height="1" fill="none" stroke="black"/></svg>')
r, out, stats = mesh("square", square, "-l", "0.05")
check("square: exit 0", r.returncode == 0, r.stderr)
if r.returncode == 0:
    report = certify("square", out)
    target = 0.05 * math.sqrt(2)
    mean = report.get("mean_edge_length", 0)
    check("square: mean edge length within 25 % of 0.05 d", abs(mean - target) <= 0.25 * target,
          f"mean {mean}, target {target}")

# Determinism: the same input and options give the same bytes.
first = mesh("det-a", os.path.join(examples, "overlapping-shapes.svg"))[1]
second = mesh("det-b", os.path.join(examples, "overlapping-shapes.svg"))[1]
with open(first, "rb") as a, open(second, "rb") as b:
    check("determinism: byte-identical .msh", a.read() == b.read())

# Nasty inputs, as Triangle .poly files (all secondary).
star = [(0.0, 0.0)] + [(math.cos(2 * math.pi * k / 60), math.sin(2 * math.pi * k / 60)) for k in range(60)]
nasty = {
    "through-one-point": poly(star, [(0, k) for k in range(1, 61)]),
    "collinear-overlaps": poly([(0, 0), (1, 0), (0.25, 0), (0.75, 0), (0.5, 0), (2, 0), (0, 1)],
                               [(0, 1), (2, 3), (4, 5), (0, 5), (1, 6)]),
    "tiny-segments": poly([(0, 0), (1, 1), (0.5, 0.5), (0.5 + 1e-13, 0.5), (0.2, 0.7), (0.2, 0.7 + 1e-13)],
                          [(0, 1), (2, 3), (4, 5)]),
    "points-on-segments": poly([(0, 0), (1, 0), (0.5, 0), (0.25, 0), (1, 1), (0.5, 0.5)], [(0, 1), (0, 4)]),
    "crossing-grid": poly([(i / 7, 0) for i in range(8)] + [(i / 7, 1) for i in range(8)] +
                          [(0, j / 7) for j in range(8)] + [(1, j / 7) for j in range(8)],
                          [(i, 8 + i) for i in range(8)] + [(16 + j, 24 + j) for j in range(8)]),
}
for name, text in nasty.items():
    r, out, _ = mesh(name, write(name + ".poly", text))
    check(f"{name}: exit 0", r.returncode == 0, r.stderr)
    if r.returncode == 0:
        certify(name, out)

# Scaled copies: the same mesh up to scale.
base_points = [(0.1 * math.cos(k) + 0.5 * (k % 3), 0.3 * math.sin(2 * k) + 0.2 * (k % 5)) for k in range(12)]
base_segments = [(k, (k + 1) % 12) for k in range(12)] + [(0, 6), (3, 9)]
meshes = {}
for scale in (1.0, 1e-6, 1e6):
    name = f"scaled-{scale:g}"
    r, out, stats = mesh(name, write(name + ".poly", poly([(x * scale, y * scale) for x, y in base_points], base_segments)))
    check(f"{name}: exit 0", r.returncode == 0, r.stderr)
    if r.returncode == 0:
        report = certify(name, out)
        meshes[scale] = report
if len(meshes) == 3:
    for scale in (1e-6, 1e6):
        a, b = meshes[1.0], meshes[scale]
        check(f"scale {scale:g}: same triangle count", a.get("triangles") == b.get("triangles"),
              f"{a.get('triangles')} vs {b.get('triangles')}")
        check(f"scale {scale:g}: same min angle", abs(a.get("min_angle_deg", 0) - b.get("min_angle_deg", 1)) < 1e-6,
              f"{a.get('min_angle_deg')} vs {b.get('min_angle_deg')}")

# Bad input: exit 1, one line naming the file, no output written.
bad = {
    "missing.svg": None,
    "bad.poly": "3 2 0 0\n1 0 0\n2 1 0\n",  # truncated
    "nan.poly": "2 2 0 0\n1 0 0\n2 nan 1\n1 0\n1 1 2\n0\n",
    "dangling.poly": "2 2 0 0\n1 0 0\n2 1 1\n1 0\n1 1 3\n0\n",
    "not-svg.svg": '<html xmlns="http://www.w3.org/1999/xhtml"/>',
}
for name, text in bad.items():
    source = os.path.join(tmp.name, name) if text is None else write(name, text)
    out = os.path.join(tmp.name, name + ".msh")
    r = subprocess.run([binary, "mesh", source, "-o", out, "--linear"], capture_output=True, text=True, timeout=60)
    check(f"{name}: exit 1", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
    check(f"{name}: one line naming the file", len(r.stderr.strip().splitlines()) == 1 and name in r.stderr, r.stderr)
    check(f"{name}: no output", not os.path.exists(out))
# Nothing drawn (a file of gradient definitions): the canvas is meshed, with a warning.
r, out, stats = mesh("empty", write("empty.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="10 20 300 200">'
                                    '<defs><linearGradient id="g"/></defs></svg>'))
check("empty drawing: exit 0 with a warning", r.returncode == 0 and "nothing is drawn" in r.stderr, r.stderr)
if r.returncode == 0:
    certify("empty drawing", out)
    with open(out) as f:
        text = f.read()
    nodes = text[text.index("$Nodes"):text.index("$EndNodes")].splitlines()
    xy = [tuple(map(float, l.split()[:2])) for l in nodes if len(l.split()) == 3]
    xs, ys = [p[0] for p in xy], [p[1] for p in xy]
    check("empty drawing: the mesh covers the viewBox", min(xs) <= 10 and max(xs) >= 310 and min(ys) <= 20 and max(ys) >= 220,
          (min(xs), max(xs), min(ys), max(ys)))
# Success says what was written in one line on stdout; -q says nothing; the parameters are
# checked together before anything runs.
example = os.path.join(examples, "overlapping-shapes.svg")
out = os.path.join(tmp.name, "said.msh")
r = subprocess.run([binary, "mesh", example, "-o", out], capture_output=True, text=True, timeout=120)
said = r.stdout.strip().splitlines()
check("mesh prints one line", r.returncode == 0 and len(said) == 1 and out in said[0] and "triangles" in said[0]
      and "max AMIPS" in said[0] and "scaled Jacobian" in said[0] and r.stderr == "", (r.stdout, r.stderr))
r = subprocess.run([binary, "mesh", example, "-o", out, "--linear", "-q"], capture_output=True, text=True, timeout=120)
check("mesh -q prints nothing", r.returncode == 0 and r.stdout == "" and r.stderr == "", (r.stdout, r.stderr))
r = subprocess.run([binary, "mesh", example, "-o", os.path.join(tmp.name, "never.msh"), "--mu", "0.01", "--epsilon", "0.005"],
                   capture_output=True, text=True, timeout=60)
check("epsilon below mu: exit 2 naming both", r.returncode == 2 and "--epsilon" in r.stderr and "--mu" in r.stderr
      and not os.path.exists(os.path.join(tmp.name, "never.msh")), r.stderr)
# Progress: a run longer than about 2 s says where it is on stderr, plain lines when stderr is
# not a terminal, one line redrawn in place (and cleared) when it is; -q silences it.
fine = ["mesh", example, "-o", out, "--linear", "-l", "0.002"]  # about 5 s: well past the 2 s
r = subprocess.run([binary, *fine], capture_output=True, text=True, timeout=300)
lines = r.stderr.splitlines()
passes = [l for l in lines if l.startswith(f"curvemesh: {example}: optimize pass ")]
check("progress: plain lines with stage, pass, triangles, worst energy, time",
      r.returncode == 0 and len(passes) >= 1 and all("triangles" in l and "max AMIPS" in l and l.endswith(" s)") for l in passes)
      and len(lines) == len([l for l in lines if l.startswith(f"curvemesh: {example}: ")]), r.stderr[-800:])
r = subprocess.run([binary, *fine, "-q"], capture_output=True, text=True, timeout=300)
check("progress: -q silences it", r.returncode == 0 and r.stderr == "" and r.stdout == "", r.stderr[-300:])
import pty  # noqa: E402
primary, secondary = pty.openpty()
proc = subprocess.Popen([binary, *fine], stdout=subprocess.DEVNULL, stderr=secondary)
os.close(secondary)
seen = b""
while True:
    try:
        chunk = os.read(primary, 4096)
    except OSError:
        break
    if not chunk:
        break
    seen += chunk
proc.wait(timeout=300)
os.close(primary)
text = seen.decode(errors="replace")
check("progress on a terminal: one line redrawn in place, cleared at the end",
      proc.returncode == 0 and "\r\x1b[K" in text and "optimize pass" in text and "\n" not in text.strip("\r\x1b[K")
      and text.endswith("\r\x1b[K"), repr(text[-300:]))
# The soups of docs/measurements/performance.md (scripts/random-soup): the same file for the same
# arguments, and a small dense one (every pair of curves crossing) meshes and certifies, its
# crossings triangulated on their rounded positions.
soup_script = os.path.join(examples, "..", "scripts", "random-soup")
soups = [subprocess.run([sys.executable, soup_script, "40", "--dense"], capture_output=True, text=True) for _ in range(2)]
check("random-soup: deterministic, exit 0", all(x.returncode == 0 for x in soups) and soups[0].stdout == soups[1].stdout
      and soups[0].stdout.count("<path") == 40, soups[0].stderr[-300:])
dense = os.path.join(tmp.name, "dense40.svg")
with open(dense, "w") as f:
    f.write(soups[0].stdout)
r, out, stats = mesh("dense40", dense)
check("dense soup of 40 cubics meshes", r.returncode == 0, r.stderr[-500:])
if r.returncode == 0:
    certify("dense soup of 40 cubics", out)
    with open(stats) as f:
        method = json.load(f)["triangulate"]["method"]
    check("dense soup: crossings triangulated rounded and certified", method == "rounded", method)
bad = subprocess.run([sys.executable, soup_script, "0"], capture_output=True, text=True)
check("random-soup 0: usage error", bad.returncode == 2 and "at least 1" in bad.stderr, bad.stderr[-300:])

r = subprocess.run([binary, "mesh", "--help"], capture_output=True, text=True)
check("mesh --help", r.returncode == 0 and "--linear" in r.stdout and "--msh-version" in r.stdout, r.stdout[-300:])

finish()
