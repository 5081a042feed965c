#!/usr/bin/env python3
"""The same bytes whatever the thread count: `curvemesh mesh --threads 1, 2 and 4` writes the same
.msh, .svg and .vtu files and the same statistics (but for the seconds) on the examples and on
peer-set drawings, curved, order 2, linear and with strokes as areas; `check --threads` gives the
same verdicts; `batch` passes its --threads on to every child; a thread count out of range is a
usage error.

usage: threads_test.py CURVEMESH_BINARY EXAMPLES_DIR [SVG_ROOT]
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
root = sys.argv[3] if len(sys.argv) > 3 else "/usr/share/openclipart/svg"
PEERS = ["plants/cacuts_01.svg", "geography/map_of_slovenia_in_euro_01.svg", "food/spaghetti_bw.svg"]


def without_seconds(value):
    if isinstance(value, dict):
        return {k: without_seconds(v) for k, v in value.items() if k != "seconds"}
    if isinstance(value, list):
        return [without_seconds(v) for v in value]
    return value


def outputs(tmp, drawing, extra, threads):
    base = os.path.join(tmp, f"{os.path.basename(drawing)}.{'_'.join(extra) or 'curved'}.{threads}")
    run = subprocess.run([binary, "mesh", drawing, "-o", base + ".msh", "--svg", base + ".svg", "--vtu", base + ".vtu",
                          "--stats", base + ".json", "-q", "--threads", str(threads)] + extra,
                         capture_output=True, text=True)
    if run.returncode != 0:
        return run.returncode, None
    files = {}
    for suffix in (".msh", ".svg", ".vtu"):
        with open(base + suffix, "rb") as f:
            files[suffix] = f.read()
    with open(base + ".json") as f:
        files[".json"] = without_seconds(json.load(f))
    return 0, files


with tempfile.TemporaryDirectory() as tmp:
    runs = [(d, []) for d in sorted(glob.glob(os.path.join(examples, "*.svg")))]
    runs += [(os.path.join(root, p), []) for p in PEERS if os.path.exists(os.path.join(root, p))]
    check("the peer-set drawings are installed (Debian's openclipart-svg)", len(runs) > len(PEERS))
    runs += [(os.path.join(root, PEERS[0]), ["--order", "2"]), (os.path.join(root, PEERS[1]), ["--linear"]),
             (os.path.join(examples, "stroked-icon.svg"), ["--strokes", "areas", "--regions", "--domain", "painted"])]
    for drawing, extra in runs:
        name = f"{os.path.basename(drawing)} {' '.join(extra)}".strip()
        code, one = outputs(tmp, drawing, extra, 1)
        check(f"{name}: meshes with one thread", code == 0, f"exit {code}")
        if code != 0:
            continue
        for threads in (2, 4):
            code, many = outputs(tmp, drawing, extra, threads)
            check(f"{name}: meshes with {threads} threads", code == 0, f"exit {code}")
            if code != 0:
                continue
            for suffix in (".msh", ".svg", ".vtu", ".json"):
                check(f"{name}: {suffix} with {threads} threads is the one-thread file", many[suffix] == one[suffix],
                      "they differ")

    # check: the same verdicts for every thread count.
    msh = os.path.join(tmp, "cacuts_01.svg.curved.1.msh")
    if os.path.exists(msh):
        verdicts = []
        for threads in (1, 4):
            run = subprocess.run([binary, "check", "--json", "--threads", str(threads), msh], capture_output=True,
                                 text=True)
            check(f"check --threads {threads} certifies the mesh", run.returncode == 0, run.stderr)
            verdicts.append(run.stdout)
        check("check gives the same report with 1 and 4 threads", verdicts[0] == verdicts[1], str(verdicts))

    # batch: --threads goes to every child once (as given, not twice), and the mesh is mesh's.
    drawing = os.path.join(examples, "overlapping-shapes.svg")
    out = os.path.join(tmp, "batch")
    run = subprocess.run([binary, "batch", drawing, "-o", out, "--jobs", "1", "--threads", "2"], capture_output=True,
                         text=True)
    check("batch --threads 2 meshes and certifies", run.returncode == 0, run.stderr[-500:])
    alone = os.path.join(tmp, "alone.msh")
    subprocess.run([binary, "mesh", drawing, "-o", alone, "-q"], check=True)
    batch_msh = os.path.join(out, "overlapping-shapes.msh")
    if os.path.exists(batch_msh):
        with open(batch_msh, "rb") as a, open(alone, "rb") as b:
            check("batch's mesh is the one `mesh` writes", a.read() == b.read())

    # Out of range: a usage error, before anything runs.
    for bad in ("-1", "5000", "two"):
        run = subprocess.run([binary, "mesh", drawing, "-o", os.path.join(tmp, "bad.msh"), "--threads", bad],
                             capture_output=True, text=True)
        check(f"mesh --threads {bad} is a usage error", run.returncode == 2, f"exit {run.returncode}")
        run = subprocess.run([binary, "check", alone, "--threads", bad], capture_output=True, text=True)
        check(f"check --threads {bad} is a usage error", run.returncode == 2, f"exit {run.returncode}")
finish()
