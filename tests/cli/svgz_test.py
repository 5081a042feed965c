#!/usr/bin/env python3
"""Compressed drawings (.svgz, gzip as Inkscape saves them), made here by Python's gzip module: the
same mesh as the plain drawing through `mesh`, `features` and `batch`, a drawing told by its gzip
header whatever its name, streams of several members; a decompression bomb refused by the input
limit with little memory, a stream cut short or corrupt refused with exit 1.

usage: svgz_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import gzip
import json
import os
import resource
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1:3]
tmp_dir = tempfile.TemporaryDirectory()
tmp = tmp_dir.name
plain = os.path.join(examples, "overlapping-shapes.svg")
with open(plain, "rb") as f:
    svg = f.read()


def path(name):
    return os.path.join(tmp, name)


def write(name, data):
    with open(path(name), "wb") as f:
        f.write(data)
    return path(name)


def run(*args):
    return subprocess.run([binary, *map(str, args)], capture_output=True, text=True)


def read(name):
    with open(path(name), "rb") as f:
        return f.read()


run("mesh", plain, "-o", path("plain.msh"), "-q")
run("features", plain, "-o", path("plain.json"))
half = len(svg) // 2
cases = {
    "compressed.svgz": gzip.compress(svg),
    "two-members.svgz": gzip.compress(svg[:half]) + gzip.compress(svg[half:]),
    "named-svg.svg": gzip.compress(svg, compresslevel=1),
}
for name, data in cases.items():
    drawing = write(name, data)
    r = run("mesh", drawing, "-o", path(name + ".msh"), "-q")
    check(f"{name}: meshed", r.returncode == 0, r.stderr)
    check(f"{name}: the plain drawing's mesh", r.returncode == 0 and read(name + ".msh") == read("plain.msh"))
r = run("features", path("compressed.svgz"), "-o", path("compressed.json"))
with open(path("plain.json")) as a, open(path("compressed.json")) as b:
    check("features: the plain drawing's curves", r.returncode == 0 and json.load(a)["curves"] == json.load(b)["curves"],
          r.stderr)

# batch: a folder's .svgz is a drawing; beside a .svg of the same name, both get outputs of their own.
folder = path("folder")
os.mkdir(folder)
write("folder/shapes.svgz", gzip.compress(svg))
write("folder/shapes.svg", svg)
r = run("batch", folder, "-o", path("out"), "--jobs", "1")
with open(path("out/report.jsonl")) as f:
    rows = [json.loads(line) for line in f]
check("batch: both drawings meshed, each to its own file",
      r.returncode == 0 and len(rows) == 2 and all(x["status"] == "ok" for x in rows)
      and len({x["output"] for x in rows}) == 2, (r.stderr[-300:], rows))

# A bomb: 200 MB of white space in a comment, about 200 kB compressed, against the 64 MB default.
# Written a megabyte at a time: this process stays small, so the child's peak (which counts what it
# shares with this process until it runs curvemesh) is curvemesh's own.
with gzip.open(path("bomb.svgz"), "wb", compresslevel=9) as f:
    f.write(svg[: svg.index(b"<svg")] + b"<!--")
    for _ in range(200):
        f.write(b" " * (1 << 20))
    f.write(b"-->" + svg[svg.index(b"<svg"):])
r = run("mesh", path("bomb.svgz"), "-o", path("bomb.msh"))
peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
check("bomb: refused by the input limit, exit 1",
      r.returncode == 1 and "once decompressed" in r.stderr and "--max-input-mb" in r.stderr, r.stderr)
check("bomb: no more memory than the limit and a little", peak_mb < 64 + 100, peak_mb)
check("bomb: no output", not os.path.exists(path("bomb.msh")))

compressed = gzip.compress(svg)
for name, data, says in [("cut.svgz", compressed[: len(compressed) // 2], "ends early"),
                         ("corrupt.svgz", compressed[:10] + bytes(range(256)) * 4, "not a valid gzip stream")]:
    r = run("mesh", write(name, data), "-o", path(name + ".msh"))
    check(f"{name}: exit 1 saying why", r.returncode == 1 and says in r.stderr, (r.returncode, r.stderr))

finish()
