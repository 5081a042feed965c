#!/usr/bin/env python3
"""Command-line contract of `curvemesh features`: exit codes, one-line errors naming the file,
no partial output on failure, the JSON keys later stages read.

usage: cli_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]


def run(*args, timeout=60):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=timeout)


SVG = '<svg xmlns="http://www.w3.org/2000/svg">{}</svg>'
deep = "<svg>" + "<g>" * 200000 + "</g>" * 200000 + "</svg>"
bomb = "<!DOCTYPE svg [<!ENTITY a0 'xxxxxxxxxxxxxxxx'>" + "".join(
    f"<!ENTITY a{i} '{('&a%d;' % (i - 1)) * 16}'>" for i in range(1, 12)) + "]><svg class='&a11;'/>"
exp_use = "<svg><defs><line id='l0' x2='1'/>" + "".join(
    f"<g id='l{i}'><use href='#l{i-1}'/><use href='#l{i-1}'/></g>" for i in range(1, 48)) + "</defs><use href='#l47'/></svg>"
bad_inputs = {
    "not-xml.svg": "this is not XML at all",
    "truncated.svg": SVG.format('<path d="M0 0 L 10 10"/><g><path d="M 1 2')[:-10],
    "no-svg-root.svg": "<html><body/></html>",
    "empty.svg": "",
    "nan.svg": SVG.format('<path d="M 0 0 L NaN 4"/>'),
    "inf.svg": SVG.format('<rect width="Infinity" height="3"/>'),
    "overflow.svg": SVG.format('<path d="M 0 0 L 1e999 4"/>'),
    "unknown-command.svg": SVG.format('<path d="M 0 0 K 4 4"/>'),
    "use-cycle.svg": SVG.format('<g id="a"><use href="#b"/></g><g id="b"><use href="#a"/></g>'),
    "deep.svg": deep,
    "entity-bomb.svg": bomb,
    "exponential-use.svg": exp_use,
    "binary.svg": "\x00\x01\x02\xff\xfe garbage",
}

with tempfile.TemporaryDirectory() as tmp:
    # Good input: exit 0, the documented keys, an SVG drawing.
    for example in sorted(os.listdir(examples)):
        if not example.endswith(".svg"):
            continue
        out, drawing = os.path.join(tmp, example + ".json"), os.path.join(tmp, example + ".out.svg")
        r = run("features", os.path.join(examples, example), "-o", out, "--svg", drawing)
        check(f"{example} exit 0", r.returncode == 0, r.stderr)
        if r.returncode == 0:
            data = json.load(open(out))
            for key in ("bbox", "curves", "points", "warnings"):
                check(f"{example} has {key}", key in data, list(data))
            check(f"{example} has curves", len(data["curves"]) > 0)
            c = data["curves"][0]
            check(f"{example} curve keys", len(c["p"]) == 8 and {"source", "stroke", "fill"} <= set(c), c)
            check(f"{example} bbox", len(data["bbox"]) == 4 and data["bbox"][0] <= data["bbox"][2], data["bbox"])
            check(f"{example} drawing", open(drawing).read().startswith("<?xml"))

    # Feature processing: the keys later stages read, and its parameters checked.
    out = os.path.join(tmp, "processed.json")
    r = run("features", os.path.join(examples, "open-curves.svg"), "-o", out, "--processed", "--svg", out + ".svg")
    check("processed exit 0", r.returncode == 0, r.stderr)
    if r.returncode == 0:
        data = json.load(open(out))
        for key in ("sections", "segments", "feature_points", "parameters"):
            check(f"processed has {key}", key in data, list(data))
        s = data["sections"][0]
        check("section keys", {"curve", "t", "p", "kind", "polyline"} <= set(s) and s["kind"] in ("primary", "secondary"), s)
    r = run("features", os.path.join(examples, "open-curves.svg"), "-o", out, "--processed", "--epsilon", "1e-4")
    check("epsilon below mu exit 2", r.returncode == 2 and "--epsilon" in r.stderr, r.stderr)
    r = run("features", os.path.join(examples, "open-curves.svg"), "-o", out, "--processed", "--mu", "-1")
    check("negative mu exit 2", r.returncode == 2, r.stderr)

    # Deterministic: the same input gives the same bytes.
    a, b = os.path.join(tmp, "a.json"), os.path.join(tmp, "b.json")
    ex = os.path.join(examples, "transforms-and-use.svg")
    run("features", ex, "-o", a, "--processed")
    run("features", ex, "-o", b, "--processed")
    check("deterministic output", open(a, "rb").read() == open(b, "rb").read())

    # Bad input: exit 1, one line naming the file, no output file.
    for name, text in bad_inputs.items():
        path = os.path.join(tmp, name)
        with open(path, "w", encoding="latin-1") as f:
            f.write(text)
        out = os.path.join(tmp, name + ".json")
        r = run("features", path, "-o", out, "--svg", out + ".svg")
        lines = r.stderr.strip().splitlines()
        check(f"{name} exit 1", r.returncode == 1, f"exit {r.returncode}, stderr {r.stderr[:300]!r}")
        check(f"{name} one line", len(lines) == 1, r.stderr[:500])
        check(f"{name} names the file", name in r.stderr, r.stderr[:300])
        check(f"{name} no output", not os.path.exists(out) and not os.path.exists(out + ".svg"))
        check(f"{name} no temporary left", not any(".tmp." in f for f in os.listdir(tmp)), os.listdir(tmp))

    r = run("features", os.path.join(tmp, "does-not-exist.svg"), "-o", os.path.join(tmp, "x.json"))
    check("missing file exit 1", r.returncode == 1 and "does-not-exist.svg" in r.stderr, r.stderr)
    r = run("features", tmp, "-o", os.path.join(tmp, "x.json"))
    check("directory exit 1", r.returncode == 1 and "is a folder, not a regular file" in r.stderr, r.stderr)
    r = run("features", ex, "-o", os.path.join(tmp, "no-such-dir", "x.json"))
    check("unwritable output exit 1", r.returncode == 1 and "no-such-dir" in r.stderr, r.stderr)

    # --eps-m is one parameter: it also decides which paths the reader turns into points. A path
    # 1e-4 of d long is a curve at the default (1e-8) and a point at 1e-3.
    tiny = os.path.join(tmp, "tiny.svg")
    with open(tiny, "w") as f:
        f.write(SVG.format('<path d="M 0 0 L 100 100"/><path d="M 50 20 L 50.01 20.01"/>'))
    counts = {}
    for eps in ("1e-8", "1e-3"):
        r = run("features", tiny, "-o", a, "--eps-m", eps)
        data = json.load(open(a)) if r.returncode == 0 else {"curves": [], "points": []}
        counts[eps] = (len(data["curves"]), len(data["points"]))
    check("--eps-m reaches the reader", counts == {"1e-8": (2, 0), "1e-3": (1, 1)}, counts)
    r = run("features", tiny, "-o", b, "--degenerate-tolerance", "1e-3")
    check("--degenerate-tolerance is --eps-m", r.returncode == 0 and open(a, "rb").read() == open(b, "rb").read(), r.stderr)

    # The command list: one line per command; the paragraph under the command's own help.
    h = run("--help")
    listed = [line.split()[0] for line in h.stdout.splitlines() if line.startswith("  ") and not line.strip().startswith("-")]
    check("--help lists every command once", listed == ["features", "mesh", "check", "batch", "report", "verify", "solve", "diffuse"],
          h.stdout)
    check("--help lines are short", all(len(line) <= 130 for line in h.stdout.splitlines()), h.stdout)
    h = run("mesh", "--help")
    check("mesh --help has the paragraph", "certified to have a positive Jacobian" in h.stdout, h.stdout[:500])

    # Usage errors: exit 2; help: exit 0 and explains the options.
    check("no subcommand exit 2", run().returncode == 2)
    check("unknown option exit 2", run("features", ex, "-o", a, "--frobnicate").returncode == 2)
    check("missing -o exit 2", run("features", ex).returncode == 2)
    h = run("features", "--help")
    check("help exit 0", h.returncode == 0 and "--svg" in h.stdout and "--output" in h.stdout, h.stdout)

finish()
