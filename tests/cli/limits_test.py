#!/usr/bin/env python3
"""Hostile inputs against the documented limits: each drawing or file below is built by the test
to cost far more than a drawing should (a <use> fan-out, a huge path, a style sheet whose rules
multiply, entity references, curves crossing everywhere, a tiny edge length, a picture too large,
a FIFO, /dev/zero), and each run must end with exit 0 or 1 — the message naming the limit and the
option that raises it — at a peak resident memory under the documented bound (2 GB with the
default options). Every run is also capped at 3 GB of address space so that a regression fails
here rather than taking the machine's memory; the subprocess time-out is a guard, not a check.

usage: limits_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import os
import random
import resource
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
PEAK_BOUND_MB = 2048
GUARD_BYTES = 3 << 30


def path(name):
    return os.path.join(tmp.name, name)


def write(name, text):
    with open(path(name), "w") as f:
        f.write(text)
    return path(name)


def cap():
    resource.setrlimit(resource.RLIMIT_AS, (GUARD_BYTES, GUARD_BYTES))


def run(*args, timeout=600):
    """Exit code, stderr and peak resident memory (MB) of one run in a process of its own."""
    start = time.monotonic()
    child = subprocess.Popen([binary, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=cap)
    timer = threading.Timer(timeout, child.kill)
    timer.start()
    err = child.stderr.read().decode(errors="replace")
    _, status, usage = os.wait4(child.pid, 0)
    timer.cancel()
    child.returncode = os.waitstatus_to_exitcode(status)
    return child.returncode, err, usage.ru_maxrss / 1024.0, time.monotonic() - start


def expect(label, args, codes=(1,), says=()):
    code, err, peak_mb, seconds = run(*args)
    print(f"{label}: exit {code}, peak {peak_mb:.0f} MB, {seconds:.1f} s", flush=True)
    check(f"{label}: exit {' or '.join(map(str, codes))}", code in codes, err[-400:])
    check(f"{label}: peak memory under {PEAK_BOUND_MB} MB", peak_mb < PEAK_BOUND_MB, f"{peak_mb:.0f} MB")
    for words in says:
        check(f"{label}: the message says '{words}'", words in err, err[-400:])


svg_head = '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 100 100">'

# A 2 KB file whose <use> levels fan out to 10 million curves.
levels = "".join(f'<g id="g{k}">' + "".join(f'<use xlink:href="#g{k - 1}" x="{i}"/>' for i in range(10)) + "</g>"
                 for k in range(1, 7))
fan = write("fan.svg", svg_head + '<defs><path id="g0" d="M0 0 L1 1 L2 0 L3 1 L4 0 L5 1 L6 0 L7 1 L8 0 L9 1"/>' +
            levels + '</defs><use xlink:href="#g6"/></svg>')
expect("<use> fan-out to 10 million curves", ["mesh", fan, "-o", path("fan.msh"), "-q"], says=["--max-"])

# Just under the limit on curves, but piled on one another: 490,000 curves in a few dozen places,
# thousands of copies each, whose pairs of nearby pieces would number in the billions.
segments = " ".join(f"L{i % 7} {(i * 3) % 5}" for i in range(49))
levels = "".join(f'<g id="h{k}">' + "".join(f'<use xlink:href="#h{k - 1}" x="{i * 1.3:.1f}" y="{k * 0.7:.1f}"/>'
                                            for i in range(10)) + "</g>" for k in range(1, 5))
piled = write("piled.svg", svg_head + f'<defs><path id="h0" d="M0 0 {segments}" fill="none" stroke="black"/>' +
              levels + '</defs><use xlink:href="#h4"/></svg>')
expect("490,000 curves piled on one another", ["mesh", piled, "-o", path("piled.msh"), "-q"],
       says=["too densely", "--max-triangles"])

# A path of 15 million tiny segments in a 60 MB file (under the input size limit).
with open(path("long-path.svg"), "w") as f:
    f.write(svg_head + '<path d="M0 0')
    chunk = "l1 0l0 1" * 100000
    for _ in range(75):
        f.write(chunk)
    f.write('"/></svg>')
expect("a path of 15 million segments", ["mesh", path("long-path.svg"), "-o", path("long.msh"), "-q"],
       says=["--max-curves"])

# A file above --max-input-mb (sparse: its size is what is checked, before it is read).
with open(path("huge.svg"), "wb") as f:
    f.truncate(100 << 20)
expect("a 100 MB file", ["mesh", path("huge.svg"), "-o", path("huge.msh"), "-q"], says=["--max-input-mb"])

# /dev/zero, which never ends, and a FIFO nobody writes to: refused, not read or waited on.
expect("/dev/zero as input", ["mesh", "/dev/zero", "-o", path("zero.msh"), "-q"], says=["not a regular file"])
os.mkfifo(path("input.fifo"))
expect("a FIFO without a writer as input", ["mesh", path("input.fifo"), "-o", path("fifo.msh"), "-q"],
       says=["not a regular file"])

# Entity references: each attribute small, the whole document's expansion enormous.
entity = "M0 0 L1 1 " * 100000
attributes = "".join(f'<path d="&big;" id="p{i}"/>' for i in range(2000))
entities = write("entities.svg", f'<?xml version="1.0"?>\n<!DOCTYPE svg [<!ENTITY big "{entity}">]>\n' + svg_head +
                 attributes + "</svg>")
expect("entity references expanding to 2 GB in all", ["mesh", entities, "-o", path("entities.msh"), "-q"],
       says=["entit"])

# A style sheet whose selector lists and rules multiply: every rule matches every element.
selectors = ",".join(f".c{i}" for i in range(300))
declarations = ";".join(f"fill:#{i % 256:02x}0000" for i in range(300))
rules = "\n".join(f"{selectors}, path {{{declarations}}}" for _ in range(30))
classes = " ".join(f"c{i}" for i in range(300))
paths = "".join(f'<path class="{classes}" d="M{i % 90} 0 l5 5"/>' for i in range(300))
css = write("css.svg", svg_head + f"<style>{rules}</style>" + paths + "</svg>")
expect("a style sheet of rules × classes × elements", ["mesh", css, "-o", path("css.msh"), "-q"], codes=(0, 1))

# Curves crossing everywhere: 3000 long lines, about 2 million crossings.
rng = random.Random(7)
lines = "".join(f'<path d="M{rng.uniform(0, 5):.4f} {rng.uniform(0, 100):.4f} '
                f'L{rng.uniform(95, 100):.4f} {rng.uniform(0, 100):.4f}"/>' for _ in range(3000))
crossings = write("crossings.svg", svg_head + lines + "</svg>")
expect("3000 lines crossing each other", ["mesh", crossings, "-o", path("crossings.msh"), "-q"],
       says=["--max-triangles"])

# A tiny edge length asks for an enormous mesh.
expect("--edge-length 1e-4", ["mesh", os.path.join(examples, "overlapping-shapes.svg"), "-o", path("tiny-l.msh"),
                              "-l", "1e-4", "-q"], says=["--max-triangles"])

# A picture wider than the drawing is long: 20000 pixels across a tall drawing.
tall = write("tall.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 100">'
                         '<path d="M2 10 C 8 30 2 60 8 90" stroke="red" fill="none"/></svg>')
expect("diffuse --width 20000 on a tall drawing", ["diffuse", tall, "-o", path("tall.png"), "--width", "20000"],
       says=["--width"])

# The limits are options: raised, the fan-out is refused by the next one; lowered, a drawing the
# defaults mesh is refused; --memory-limit ends a run that needs more with exit 1.
expect("--max-curves 10 on an example", ["mesh", os.path.join(examples, "transforms-and-use.svg"), "-o",
                                         path("few.msh"), "--max-curves", "10", "-q"], says=["--max-curves"])
expect("--max-elements 3 on an example", ["mesh", os.path.join(examples, "transforms-and-use.svg"), "-o",
                                          path("few.msh"), "--max-elements", "3", "-q"], says=["--max-elements"])
expect("--memory-limit 0.3 on 3000 crossing lines, --max-triangles raised",
       ["mesh", crossings, "-o", path("capped.msh"), "-q", "--max-triangles", "100000000", "--memory-limit", "0.3"],
       says=["out of memory", "--memory-limit"])
check("no run left a mesh behind", not any(n.endswith(".msh") for n in os.listdir(tmp.name)), os.listdir(tmp.name))

sys.exit(finish())
