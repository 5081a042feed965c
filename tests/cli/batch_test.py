#!/usr/bin/env python3
"""Command-line contract of `curvemesh batch` and `curvemesh report`: the examples plus a malformed
drawing (invalid-input, the others ok, exit 1), a time-out, a memory limit that is too small, a
resumed run (skips, mtimes unchanged) and --force, shards that add up to the whole, list files,
output names that would collide, forwarded mesh options, the report's schema, `curvemesh report`
and its self-contained HTML page, a batch stopped from outside (SIGTERM to it and its children, as a
scheduler sends it; SIGTERM to one child alone; SIGKILL) and run again, a report whose last line
was cut short, hostile file systems and inputs (a link or a FIFO planted where the report goes, an
output that is an input, another drawing of the same name met on resuming, file names that look like
options, control characters and bytes that are not UTF-8 in file names), usage errors and --help.

usage: batch_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import glob
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
root = tmp.name


def run(*args, timeout=120, cwd=None):
    start = time.monotonic()
    r = subprocess.run([binary, *args], capture_output=True, text=True, timeout=timeout, cwd=cwd)
    return r, time.monotonic() - start


def read_report(path):
    try:
        with open(path) as f:
            return [json.loads(line) for line in f if line.strip()]
    except (OSError, json.JSONDecodeError) as e:
        check(f"{path}: readable JSON Lines", False, str(e))
        return []


def by_path(lines):
    return {l["path"]: l for l in lines}


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


SVG = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">{}</svg>'
example_names = sorted(n for n in os.listdir(examples) if n.endswith(".svg"))

# The report's schema: every key on every line, with its JSON type (figures are null where a
# drawing has none: no mesh, or no curved stage).
NUMBER, INT, STR = (int, float), int, str
SCHEMA = {"path": (STR,), "status": (STR,), "seconds": NUMBER, "peak_mb": NUMBER,
          "triangles": (INT, type(None)), "curved_triangles": (INT, type(None)),
          "min_angle_deg": NUMBER + (type(None),), "max_amips": NUMBER + (type(None),),
          "fitted_edges": (INT, type(None)), "straight_primary_edges": (INT, type(None)),
          "max_distance_rel": NUMBER + (type(None),),
          "mean_fit_distance_rel": NUMBER + (type(None),), "check_invalid": (INT, type(None)),
          "message": (STR,)}
STATUSES = {"ok", "invalid-input", "timeout", "out-of-memory", "crash", "invalid-output", "skipped"}


def check_schema(name, lines):
    for l in lines:
        for key, types in SCHEMA.items():
            value = l.get(key, KeyError)
            ok = key in l and isinstance(value, types) and not (isinstance(value, bool))
            check(f"{name}: {l.get('path')}: '{key}' present with the right type", ok, f"{key}={value!r}")
        check(f"{name}: {l.get('path')}: known status", l.get("status") in STATUSES, l.get("status"))


# --- The examples plus a malformed drawing, curved (the default) -------------------------------
inputs = os.path.join(root, "in")
for n in example_names:
    os.makedirs(inputs, exist_ok=True)
    shutil.copy(os.path.join(examples, n), os.path.join(inputs, n))
malformed = write(os.path.join(inputs, "sub", "malformed.svg"), SVG.format('<path d="M 10 10 L 20 x"/>'))
out = os.path.join(root, "out")
r, _ = run("batch", inputs, "-o", out, "--jobs", "2")
check("main run: exit 1 (one drawing failed)", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
report = read_report(os.path.join(out, "report.jsonl"))
expected_paths = sorted([os.path.join(inputs, n) for n in example_names] + [malformed])
check("main run: one line per drawing, in sorted order", [l["path"] for l in report] == expected_paths,
      [l.get("path") for l in report])
check_schema("main run", report)
first = by_path(report)
for n in example_names:
    l = first.get(os.path.join(inputs, n), {})
    check(f"main run: {n} ok", l.get("status") == "ok", l)
    msh = os.path.join(out, n[:-4] + ".msh")
    check(f"main run: {n}: mesh written under OUTDIR with the same name", os.path.exists(msh), msh)
    check(f"main run: {n}: certified by check (check_invalid 0)", l.get("check_invalid") == 0, l.get("check_invalid"))
    check(f"main run: {n}: curved figures present",
          all(isinstance(l.get(k), (int, float))
              for k in ("curved_triangles", "max_distance_rel", "fitted_edges", "straight_primary_edges"))
          and (l.get("curved_triangles") or 0) > 0, l)
    check(f"main run: {n}: time and peak memory measured",
          0 < l.get("seconds", 0) < 60 and 1 < l.get("peak_mb", 0) < 4000, (l.get("seconds"), l.get("peak_mb")))
    stats_path = os.path.join(out, n[:-4] + ".json")
    try:
        with open(stats_path) as f:
            stats = json.load(f)
        check(f"main run: {n}: triangles as in the statistics", stats["mesh"]["triangles"] == l.get("triangles"),
              (stats["mesh"]["triangles"], l.get("triangles")))
        check(f"main run: {n}: max AMIPS is the curved one", stats["curve"]["max_amips"] == l.get("max_amips"),
              (stats["curve"]["max_amips"], l.get("max_amips")))
        check(f"main run: {n}: straight primary edges as in the statistics",
              stats["curve"]["straight_primary_edges"] == l.get("straight_primary_edges"),
              (stats["curve"]["straight_primary_edges"], l.get("straight_primary_edges")))
    except (OSError, KeyError, json.JSONDecodeError) as e:
        check(f"main run: {n}: statistics readable", False, str(e))
bad = first.get(malformed, {})
check("main run: malformed drawing is invalid-input", bad.get("status") == "invalid-input", bad)
check("main run: its message names the file", "malformed.svg" in bad.get("message", ""), bad.get("message"))
check("main run: no mesh for it", not os.path.exists(os.path.join(out, "sub", "malformed.msh")))
progress = [l for l in r.stderr.splitlines() if l.startswith("[")]
check("main run: one progress line per drawing when stderr is not a terminal", len(progress) == len(expected_paths),
      r.stderr)

# --- Resumed run: everything finished is skipped, nothing rewritten; --force redoes it ----------
outputs = sorted(glob.glob(os.path.join(out, "*.msh")) + glob.glob(os.path.join(out, "*.json")))
mtimes = {p: os.stat(p).st_mtime_ns for p in outputs}
r, _ = run("batch", inputs, "-o", out, "--jobs", "2")
check("resume: exit 1 (the malformed drawing fails again)", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
second = by_path(read_report(os.path.join(out, "report.jsonl")))
check_schema("resume", list(second.values()))
for n in example_names:
    p = os.path.join(inputs, n)
    l = second.get(p, {})
    check(f"resume: {n} skipped", l.get("status") == "skipped", l)
    check(f"resume: {n}: figures read back",
          all(l.get(k) == first.get(p, {}).get(k) for k in ("triangles", "curved_triangles", "max_amips", "seconds",
                                                           "peak_mb", "check_invalid")), (l, first.get(p)))
check("resume: malformed drawing is tried again", second.get(malformed, {}).get("status") == "invalid-input")
check("resume: no output rewritten", {p: os.stat(p).st_mtime_ns for p in outputs} == mtimes)
r, _ = run("batch", inputs, "-o", out, "--jobs", "2", "--force")
forced = by_path(read_report(os.path.join(out, "report.jsonl")))
check("force: every example meshed again",
      all(forced.get(os.path.join(inputs, n), {}).get("status") == "ok" for n in example_names), forced)
check("force: meshes rewritten",
      all(os.stat(p).st_mtime_ns > mtimes[p] for p in outputs if p.endswith(".msh")), outputs)
# Other mesh options make the earlier meshes stale: not skipped.
r, _ = run("batch", os.path.join(inputs, example_names[0]), "-o", out, "--linear", "--report",
          os.path.join(root, "relinear.jsonl"))
l = read_report(os.path.join(root, "relinear.jsonl"))
check("options changed: redone, not skipped", [x.get("status") for x in l] == ["ok"], l)
check("options changed: --linear forwarded (no curved figures)",
      l and l[0].get("curved_triangles") is None and l[0].get("straight_primary_edges") is None, l)

# --- A drawing that takes too long: killed at the time limit ------------------------------------
rng = random.Random(7)
paths = []
for _ in range(3000):
    p = [f"{rng.uniform(0, 1000):.3f}" for _ in range(8)]
    paths.append(f'<path d="M {p[0]} {p[1]} C {p[2]} {p[3]} {p[4]} {p[5]} {p[6]} {p[7]}" fill="none" stroke="black"/>')
heavy = write(os.path.join(root, "heavy", "heavy.svg"),
              '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1000 1000">' + "".join(paths) + "</svg>")
r, wall = run("batch", heavy, "-o", os.path.join(root, "out-timeout"), "--timeout", "0.3")
l = read_report(os.path.join(root, "out-timeout", "report.jsonl"))
check("timeout: exit 1", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
check("timeout: status timeout", [x.get("status") for x in l] == ["timeout"], l)
check("timeout: killed at the limit", l and 0.3 <= l[0].get("seconds", 0) < 2.5, l)
check("timeout: the batch did not wait for the drawing", wall < 15, wall)
check("timeout: no mesh left", not os.path.exists(os.path.join(root, "out-timeout", "heavy.msh")))
check_schema("timeout", l)

# --- A memory limit too small for one drawing, enough for the others ----------------------------
# <use> nesting: ten copies of ten copies ... of a path of 50 cubics: half a million curves, some 600 MB.
cubics = "".join(f" C {i + 0.3} 1 {i + 0.6} 2 {i + 1} 0" for i in range(50))
defs = f'<path id="g0" d="M 0 0{cubics}" fill="none" stroke="black"/>'
for level in range(1, 5):
    defs += f'<g id="g{level}">' + "".join(f'<use href="#g{level - 1}" x="{k * 0.01}"/>' for k in range(10)) + "</g>"
hungry = write(os.path.join(root, "mem", "hungry.svg"), SVG.format(f"<defs>{defs}</defs><use href=\"#g4\"/>"))
mem_inputs = [hungry] + [os.path.join(inputs, n) for n in example_names]
r, _ = run("batch", *mem_inputs, "-o", os.path.join(root, "out-mem"), "--memory-limit", "0.1", "--timeout", "20",
           "--jobs", "2", "--linear")
l = by_path(read_report(os.path.join(root, "out-mem", "report.jsonl")))
check("memory: exit 1", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
check("memory: the hungry drawing runs out of memory (not ok, not a time-out)",
      l.get(hungry, {}).get("status") in ("out-of-memory", "crash"), l.get(hungry))
check("memory: the others are unaffected",
      all(l.get(p, {}).get("status") == "ok" for p in mem_inputs[1:]), [l.get(p, {}).get("status") for p in mem_inputs])
check_schema("memory", list(l.values()))

# --- Shards add up to the whole; folders mirror; default shard report names ---------------------
corpus = os.path.join(root, "corpus")
for sub in ("a", "b"):
    for n in example_names:
        os.makedirs(os.path.join(corpus, sub), exist_ok=True)
        shutil.copy(os.path.join(examples, n), os.path.join(corpus, sub, n))
write(os.path.join(corpus, "b", "broken.svg"), "this is not XML")
whole_out = os.path.join(root, "out-whole")
r, _ = run("batch", corpus, "-o", whole_out, "--linear", "--jobs", "2")
whole = read_report(os.path.join(whole_out, "report.jsonl"))
whole_count = 2 * len(example_names) + 1  # the examples in two folders and one broken file
check(f"whole: {whole_count} drawings", len(whole) == whole_count, [x.get("path") for x in whole])
check("whole: same names in two folders do not collide",
      all(os.path.exists(os.path.join(whole_out, sub, n[:-4] + ".msh")) for sub in ("a", "b") for n in example_names))
shard_out = os.path.join(root, "out-shards")
shards = []
for k in (1, 2, 3):
    extra = ["--report", os.path.join(root, f"shard-{k}.jsonl")] if k != 2 else []
    r, _ = run("batch", corpus, "-o", shard_out, "--linear", "--shard", f"{k}/3", *extra)
    check(f"shard {k}/3: exit code as its drawings say", r.returncode in (0, 1), f"exit {r.returncode}: {r.stderr}")
    shards.append(read_report(os.path.join(root, f"shard-{k}.jsonl") if k != 2 else
                              os.path.join(shard_out, "report-2-of-3.jsonl")))
all_paths = [x["path"] for x in whole]
for k, lines in enumerate(shards, 1):
    check(f"shard {k}/3: every third drawing of the sorted list",
          [x["path"] for x in lines] == [p for i, p in enumerate(all_paths) if i % 3 == k - 1], [x["path"] for x in lines])
union = [x["path"] for lines in shards for x in lines]
check("shards: add up exactly to the whole", sorted(union) == sorted(all_paths) and len(union) == len(set(union)), union)
check("shards: same statuses as the whole",
      {x["path"]: x["status"] for lines in shards for x in lines} == {x["path"]: x["status"] for x in whole})

# --- List files: comments, relative paths, duplicates; colliding names get a suffix -------------
lst = write(os.path.join(root, "lists", "drawings.txt"),
            "# two drawings of the same name, one twice\n"
            f"../corpus/a/{example_names[0]}\n\n"
            f"  ../corpus/b/{example_names[0]}   # the other folder\n"
            f"{os.path.join(corpus, 'a', example_names[0])}\n")
list_out = os.path.join(root, "out-list")
r, _ = run("batch", lst, os.path.join(corpus, "a", "..", "a", example_names[0]), "-o", list_out, "--linear")
l = read_report(os.path.join(list_out, "report.jsonl"))
check("list: exit 0", r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
check("list: each file once, relative to the list's folder",
      [x.get("path") for x in l] == [os.path.join(corpus, s, example_names[0]) for s in ("a", "b")], l)
meshes = sorted(os.listdir(list_out))
stem = example_names[0][:-4]
check("list: colliding names get distinct suffixed files",
      len([m for m in meshes if m.startswith(stem + "-") and m.endswith(".msh")]) == 2, meshes)
r, _ = run("batch", lst, "-o", list_out, "--linear")
check("list: suffixes are stable (second run skips)",
      [x.get("status") for x in read_report(os.path.join(list_out, "report.jsonl"))] == ["skipped", "skipped"])

# --- Mesh options are forwarded ------------------------------------------------------------------
coarse_out = os.path.join(root, "out-coarse")
r, _ = run("batch", os.path.join(corpus, "a"), "-o", coarse_out, "--linear", "-l", "0.3")
coarse = by_path(read_report(os.path.join(coarse_out, "report.jsonl")))
fine = by_path(whole)
check("forwarding: -l 0.3 gives fewer triangles than the default",
      all((coarse.get(p, {}).get("triangles") or 1e9) < (fine[p].get("triangles") or 0) for p in coarse) and coarse,
      [(coarse[p].get("triangles"), fine.get(p, {}).get("triangles")) for p in coarse])

first_drawing = os.path.join(inputs, example_names[0])
nofeat_out = os.path.join(root, "out-no-features")
r, _ = run("batch", first_drawing, "-o", nofeat_out, "--no-features")
nofeat = read_report(os.path.join(nofeat_out, "report.jsonl"))
check("forwarding: --no-features (a flag) leaves no curved triangle where the default curves some",
      [x.get("status") for x in nofeat] == ["ok"] and nofeat[0].get("curved_triangles") == 0
      and (first.get(first_drawing, {}).get("curved_triangles") or 0) > 0,
      (nofeat, first.get(first_drawing)))

icon = os.path.join(inputs, "stroked-icon.svg")
painted_out = os.path.join(root, "out-painted")
r, _ = run("batch", icon, "-o", painted_out, "--linear", "--domain", "painted", "--regions")
painted = read_report(os.path.join(painted_out, "report.jsonl"))
painted_stats = {}
if painted and painted[0].get("status") == "ok":
    with open(os.path.join(painted_out, "stroked-icon.json")) as f:
        painted_stats = json.load(f)
check("forwarding: --domain painted and --regions reach the child (the strokes' areas meshed and tagged)",
      [x.get("status") for x in painted] == ["ok"]
      and painted_stats.get("domain", {}).get("name") == "painted"
      and any(str(x.get("name", "")).endswith(".stroke") for x in painted_stats.get("regions", [])),
      (painted, painted_stats.get("domain"), r.stderr[-500:]))

# --- curvemesh report ----------------------------------------------------------------------------
html = os.path.join(root, "report.html")
r, _ = run("report", os.path.join(out, "report.jsonl"), "--html", html)
check("report: exit 0", r.returncode == 0, r.stderr)
total = len(expected_paths)
check("report: success rate", f"success rate: {total - 1} of {total}" in r.stdout, r.stdout)
check("report: counts by status", "invalid-input 1" in r.stdout and f"ok {total - 1}" in r.stdout, r.stdout)
check("report: distributions", "median" in r.stdout and "p90" in r.stdout and "p99" in r.stdout, r.stdout)
check("report: slowest and failures", "slowest" in r.stdout and "failures by cause" in r.stdout
      and malformed in r.stdout, r.stdout)
try:
    with open(html) as f:
        page = f.read()
except OSError:
    page = ""
check("report --html: written with histograms", page.count("<svg") >= 2, page[:300])
check("report --html: self-contained", "http://" not in page and "https://" not in page and "<script" not in page
      and " src=" not in page, [w for w in ("http://", "https://", "<script", " src=") if w in page])
check("report --html: lists the failure", "malformed.svg" in page)
r, _ = run("report", *[os.path.join(root, f"shard-{k}.jsonl") for k in (1, 3)],
           os.path.join(shard_out, "report-2-of-3.jsonl"))
check("report: shards together", r.returncode == 0 and f"drawings: {whole_count}" in r.stdout, r.stdout + r.stderr)
r, _ = run("report", write(os.path.join(root, "bad.jsonl"), '{"path": "x.svg"}\n'))
check("report: a malformed report is refused (exit 1)", r.returncode == 1 and "bad.jsonl:1" in r.stderr, r.stderr)

# --- A batch stopped from outside (a scheduler's time limit or scancel, a node going down) ----------
# The examples plus the heavy drawing, named to come last and meshed one at a time, so that the
# examples are done when it runs.
killed_in = os.path.join(root, "killed-in")
os.makedirs(killed_in)
for n in example_names:
    shutil.copy(os.path.join(examples, n), os.path.join(killed_in, n))
shutil.copy(heavy, os.path.join(killed_in, "zz-heavy.svg"))
killed_heavy = os.path.join(killed_in, "zz-heavy.svg")


def children_of(pid):
    found = []
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                cmdline = f.read().split(b"\0")
        except (OSError, ValueError):
            continue
        if entry.isdigit() and int(stat.rsplit(")", 1)[1].split()[1]) == pid:
            found.append((int(entry), [a.decode(errors="replace") for a in cmdline]))
    return found


def start_until_heavy(out_dir, *extra):
    """Starts a batch over killed_in; returns it and the pid of the child meshing the heavy drawing."""
    p = subprocess.Popen([binary, "batch", killed_in, "-o", out_dir, "--jobs", "1", *extra],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and p.poll() is None:
        mesh = [c for c, argv in children_of(p.pid) if "mesh" in argv and killed_heavy in argv]
        if mesh:
            time.sleep(0.3)  # into the meshing, past the start
            return p, mesh[0]
        time.sleep(0.05)
    p.kill()
    p.communicate()
    check("killed: the heavy drawing's child started", False, "no child within 60 s")
    return None, None


def alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def whole_lines(path):
    with open(path) as f:
        text = f.read()
    lines = text.splitlines()
    try:
        parsed = [json.loads(l) for l in lines if l.strip()]
    except json.JSONDecodeError:
        parsed = None
    return text.endswith("\n") or not text, parsed


# Slurm signals every process of a job, the children too, in no set order: the child's death must
# not be taken for the drawing's failure.
killed_out = os.path.join(root, "out-killed")
p, child = start_until_heavy(killed_out)
if p:
    os.kill(child, 15)
    time.sleep(0.1)
    os.kill(p.pid, 15)
    _, err = p.communicate(timeout=60)
    check("SIGTERM to the job: the batch dies of SIGTERM", p.returncode == -15, f"exit {p.returncode}: {err}")
    check("SIGTERM to the job: says it was interrupted", "interrupted" in err, err)
    ended, lines = whole_lines(os.path.join(killed_out, "report.jsonl"))
    check("SIGTERM to the job: the report is whole lines", ended and lines is not None, lines)
    lines = by_path(lines or [])
    check("SIGTERM to the job: the finished drawings are in the report",
          all(lines.get(os.path.join(killed_in, n), {}).get("status") == "ok" for n in example_names), lines)
    check("SIGTERM to the job: no line for the drawing it stopped (unfinished, not failed)",
          killed_heavy not in lines, lines.get(killed_heavy))
    check("SIGTERM to the job: no mesh or statistics of it",
          not any(os.path.exists(os.path.join(killed_out, "zz-heavy" + e)) for e in (".msh", ".json")))
    check("SIGTERM to the job: no temporary left", not glob.glob(os.path.join(killed_out, "*.tmp.*")),
          os.listdir(killed_out))

# Someone else (an out-of-memory helper, say) stops the child alone: that drawing crashed, the
# batch goes on.
alone_out = os.path.join(root, "out-child-alone")
p, child = start_until_heavy(alone_out)
if p:
    os.kill(child, 15)
    _, err = p.communicate(timeout=60)
    check("SIGTERM to the child alone: the batch finishes (exit 1)", p.returncode == 1, f"exit {p.returncode}: {err}")
    l = by_path(read_report(os.path.join(alone_out, "report.jsonl"))).get(killed_heavy, {})
    check("SIGTERM to the child alone: the drawing crashed", l.get("status") == "crash"
          and "SIGTERM" in l.get("message", ""), l)

# SIGKILL (a scheduler after its grace time, the out-of-memory killer): the children go too, the
# report written so far is whole lines, and the next run removes the temporaries and completes.
sigkill_out = os.path.join(root, "out-sigkill")
p, child = start_until_heavy(sigkill_out)
if p:
    p.kill()
    p.communicate(timeout=60)
    deadline = time.monotonic() + 10
    while alive(child) and time.monotonic() < deadline:
        time.sleep(0.05)
    check("SIGKILL: the child meshing a drawing dies with the batch", not alive(child), child)
    report_path = os.path.join(sigkill_out, "report.jsonl")
    ended, lines = whole_lines(report_path)
    check("SIGKILL: the report written so far is whole lines", ended and lines is not None
          and {l["path"] for l in lines} == {os.path.join(killed_in, n) for n in example_names}, lines)
    r, _ = run("report", report_path)
    check("SIGKILL: curvemesh report reads it", r.returncode == 0 and f"drawings: {len(example_names)}" in r.stdout,
          r.stdout + r.stderr)
    # What a process killed between writing and renaming leaves, ours and another shard's.
    ours = [os.path.join(sigkill_out, n) for n in ("zz-heavy.msh.tmp.4242", "zz-heavy.json.tmp.77",
                                                   "report.jsonl.tmp.4243", "zz-heavy.msh.tmp.k3j9x0q2m1ab",
                                                   "report.jsonl.tmp.0a1b2c3d4e5f")]
    theirs = [os.path.join(sigkill_out, n) for n in ("other.msh.tmp.4242", "other.msh.tmp.k3j9x0q2m1ab",
                                                     "zz-heavy.msh.tmp.X-1", "zz-heavy.msh.tmp.")]
    for t in ours + theirs:
        write(t, "half a file")
    r, _ = run("batch", killed_in, "-o", sigkill_out, "--jobs", "1", "--timeout", "0.5")
    l = by_path(read_report(report_path))
    check("SIGKILL, run again: the finished drawings are skipped",
          all(l.get(os.path.join(killed_in, n), {}).get("status") == "skipped" for n in example_names), l)
    check("SIGKILL, run again: the stopped drawing is redone", l.get(killed_heavy, {}).get("status") == "timeout",
          l.get(killed_heavy))
    check("SIGKILL, run again: its stale temporaries and the report's are removed",
          not any(os.path.exists(t) for t in ours), [t for t in ours if os.path.exists(t)])
    check("SIGKILL, run again: files that are not this run's temporaries stay",
          all(os.path.exists(t) for t in theirs), theirs)

# --- A report cut short --------------------------------------------------------------------------
# A report whose last line was being written when its batch died (a node failure on a shared file
# system can cut it anywhere): that line is left out, with a warning; a bad line elsewhere is an error.
good = [json.dumps(l) for l in read_report(os.path.join(out, "report.jsonl"))]
cut = write(os.path.join(root, "cut.jsonl"), "\n".join(good[:-1]) + "\n" + good[-1][:40])
r, _ = run("report", cut)
check("cut-short last line: report succeeds", r.returncode == 0, r.stderr)
check("cut-short last line: left out, and said so",
      f"drawings: {len(good) - 1} " in r.stdout and "cut short" in r.stdout and "cut.jsonl:" in r.stderr,
      r.stdout + r.stderr)
r, _ = run("report", write(os.path.join(root, "unterminated.jsonl"), "\n".join(good)))
check("a whole last line without its newline counts", r.returncode == 0 and f"drawings: {len(good)} " in r.stdout,
      r.stdout + r.stderr)
r, _ = run("report", write(os.path.join(root, "cut-middle.jsonl"), good[0][:40] + "\n" + "\n".join(good[1:]) + "\n"))
check("a cut line before the last is an error (exit 1)", r.returncode == 1 and "cut-middle.jsonl:1" in r.stderr,
      r.stderr)
r, _ = run("report", write(os.path.join(root, "garbage-end.jsonl"), "\n".join(good) + "\n{garbage\n"))
check("a bad last line that ends in a newline is an error (exit 1)", r.returncode == 1, r.stderr)

# --- Hostile file systems and inputs ---------------------------------------------------------------
hostile = os.path.join(root, "hostile")
example0 = os.path.join(examples, example_names[0])
example1 = os.path.join(examples, example_names[1])


def read_bytes(path):
    try:
        with open(path, "rb") as f:
            return f.read()
    except OSError:
        return None


def run_bounded(name, *args, timeout=30, cwd=None):
    """run(), with a hang reported as a failed check instead of ending the test."""
    try:
        return run(*args, timeout=timeout, cwd=cwd)
    except subprocess.TimeoutExpired:
        check(f"{name}: ends within {timeout} s", False, "it hung")
        return None, timeout


# A link planted where the report goes (OUTDIR is often shared): refused, the file it points at
# untouched, nothing meshed.
victim = write(os.path.join(hostile, "victim.txt"), "not a report\n")
link_out = os.path.join(hostile, "out-link")
os.makedirs(link_out)
os.symlink(victim, os.path.join(link_out, "report.jsonl"))
r, _ = run_bounded("report is a link", "batch", example0, "-o", link_out, "--linear")
if r:
    check("report is a link: exit 1", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
    check("report is a link: the message names it", os.path.join(link_out, "report.jsonl") in r.stderr, r.stderr)
check("report is a link: the file it points at is unchanged", read_bytes(victim) == b"not a report\n",
      read_bytes(victim))
check("report is a link: nothing meshed", not glob.glob(os.path.join(link_out, "*.msh")), os.listdir(link_out))

# A FIFO planted there: without a reader an open for writing would wait forever.
fifo_out = os.path.join(hostile, "out-fifo")
os.makedirs(fifo_out)
os.mkfifo(os.path.join(fifo_out, "report.jsonl"))
r, wall = run_bounded("report is a FIFO", "batch", example0, "-o", fifo_out, "--linear")
if r:
    check("report is a FIFO: exit 1", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
    check("report is a FIFO: promptly", wall < 10, wall)
    check("report is a FIFO: the message names it", "report.jsonl" in r.stderr and "FIFO" in r.stderr, r.stderr)

# An output that is an input: refused (usage) before anything is written, not even OUTDIR.
drawing = os.path.join(hostile, "clash", "a.svg")
os.makedirs(os.path.dirname(drawing))
shutil.copy(example0, drawing)
original = read_bytes(drawing)
clash_out = os.path.join(hostile, "out-clash")
r, _ = run("batch", drawing, "-o", clash_out, "--report", drawing)
check("--report is the drawing: exit 2", r.returncode == 2, f"exit {r.returncode}: {r.stderr}")
check("--report is the drawing: the message says so", "refusing to write over an input" in r.stderr, r.stderr)
check("--report is the drawing: the drawing is unchanged", read_bytes(drawing) == original)
check("--report is the drawing: nothing written", not os.path.exists(clash_out))
os.symlink(drawing, os.path.join(hostile, "clash", "link.jsonl"))
r, _ = run("batch", drawing, "-o", clash_out, "--report", os.path.join(hostile, "clash", "link.jsonl"))
check("--report is a link to the drawing: exit 2", r.returncode == 2 and read_bytes(drawing) == original,
      f"exit {r.returncode}: {r.stderr}")
clash_list = write(os.path.join(hostile, "clash", "list.txt"), "a.svg\n")
r, _ = run("batch", clash_list, "-o", clash_out, "--report", clash_list)
check("--report is the list file: exit 2, the list unchanged",
      r.returncode == 2 and read_bytes(clash_list) == b"a.svg\n", f"exit {r.returncode}: {r.stderr}")
# A listed drawing named a.json, meshed into its own folder: its statistics would be written over it.
shutil.copy(example0, os.path.join(hostile, "clash", "b.json"))
json_list = write(os.path.join(hostile, "clash", "json-list.txt"), "b.json\n")
r, _ = run("batch", json_list, "-o", os.path.join(hostile, "clash"), "--report", os.path.join(hostile, "r.jsonl"))
check("statistics over the drawing: exit 2, the drawing unchanged",
      r.returncode == 2 and read_bytes(os.path.join(hostile, "clash", "b.json")) == original,
      f"exit {r.returncode}: {r.stderr}")
r, _ = run("batch", drawing, "-o", clash_out, "--report", os.path.join(clash_out, "a.json"))
check("--report is a drawing's statistics: exit 2, two outputs named", r.returncode == 2
      and "name the same file" in r.stderr and not os.path.exists(clash_out), f"exit {r.returncode}: {r.stderr}")

# Resume compares the drawing file, not its time alone: another a.svg meets the same a.msh.
resume_out = os.path.join(hostile, "out-resume")
first_a = os.path.join(hostile, "dir1", "a.svg")
other_a = os.path.join(hostile, "dir2", "a.svg")
for path, source in ((first_a, example0), (other_a, example1)):
    os.makedirs(os.path.dirname(path))
    shutil.copy(source, path)
    os.utime(path, ns=(1_000_000_000_000_000_000, 1_000_000_000_000_000_000))  # older than any mesh
r, _ = run("batch", first_a, "-o", resume_out, "--linear")
one = read_report(os.path.join(resume_out, "report.jsonl"))
try:
    with open(os.path.join(resume_out, "a.json")) as f:
        record = json.load(f).get("batch", {}).get("input", {})
except (OSError, json.JSONDecodeError):
    record = {}
st = os.stat(first_a)
check("resume: the record names the drawing file (path, size, time)",
      record == {"path": os.path.realpath(first_a), "size": st.st_size, "mtime_ns": st.st_mtime_ns}, record)
r, _ = run("batch", other_a, "-o", resume_out, "--linear")
two = read_report(os.path.join(resume_out, "report.jsonl"))
r, _ = run("batch", other_a, "-o", os.path.join(hostile, "out-resume-direct"), "--linear")
direct = read_report(os.path.join(hostile, "out-resume-direct", "report.jsonl"))
check("resume: another a.svg is meshed, not skipped", [l.get("status") for l in two] == ["ok"], two)
check("resume: the mesh is the other drawing's",
      two and direct and one and two[0].get("triangles") == direct[0].get("triangles") != one[0].get("triangles"),
      (one, two, direct))
# The same path, another content copied over with the old time kept (cp -p, rsync -t).
shutil.copy(example0, other_a)
os.utime(other_a, ns=(1_000_000_000_000_000_000, 1_000_000_000_000_000_000))
r, _ = run("batch", other_a, "-o", resume_out, "--linear")
three = read_report(os.path.join(resume_out, "report.jsonl"))
check("resume: a drawing replaced with its time kept is meshed again",
      [l.get("status") for l in three] == ["ok"] and three[0].get("triangles") == one[0].get("triangles"), three)
r, _ = run("batch", other_a, "-o", resume_out, "--linear")
check("resume: the same file again is skipped",
      [l.get("status") for l in read_report(os.path.join(resume_out, "report.jsonl"))] == ["skipped"])

# Names that look like options are files: a drawing called -dash.svg, and list lines that would be
# options to a child (they are relative to the list's folder, so given as the list's own name).
dash_dir = os.path.join(hostile, "dash")
os.makedirs(dash_dir)
shutil.copy(example0, os.path.join(dash_dir, "-dash.svg"))
for k, (name, args) in enumerate((("given as ./-dash.svg", ["./-dash.svg"]), ("in the folder .", ["."]),
                                  ("in a folder", [dash_dir]))):
    dash_out = os.path.join(hostile, f"out-dash-{k}")
    r, _ = run("batch", *args, "-o", dash_out, "--linear", cwd=dash_dir)
    l = read_report(os.path.join(dash_out, "report.jsonl"))
    check(f"-dash.svg {name}: meshed ok", r.returncode == 0 and [x.get("status") for x in l] == ["ok"],
          f"exit {r.returncode}: {r.stderr} {l}")
    check(f"-dash.svg {name}: its mesh written", os.path.exists(os.path.join(dash_out, "-dash.msh")))
planted_svg, planted_msh = os.path.join(hostile, "planted.svg"), os.path.join(hostile, "planted.msh")
options_dir = os.path.join(hostile, "options")
write(os.path.join(options_dir, "list.txt"), f"--svg={planted_svg}\n-o{planted_msh}\n")
options_out = os.path.join(hostile, "out-options")
r, _ = run("batch", "list.txt", "-o", options_out, "--linear", cwd=options_dir)
l = read_report(os.path.join(options_out, "report.jsonl"))
check("option-like list lines: exit 1", r.returncode == 1, f"exit {r.returncode}: {r.stderr}")
check("option-like list lines: each an invalid-input, a file that cannot be opened",
      len(l) == 2 and all(x.get("status") == "invalid-input" and x.get("path", "?") in x.get("message", "")
                          and any(w in x.get("message", "").lower() for w in ("no such file", "cannot open"))
                          for x in l), l)
check("option-like list lines: nothing written where they point",
      not os.path.exists(planted_svg) and not os.path.exists(planted_msh))

# Control characters in file names: the report stays JSON Lines that no terminal obeys, and so does
# batch's own output. ESC (a colour, a title), DEL, C1 characters (NEL; CSI is a C1 ESC [) and, in
# the malformed drawing's name (its message repeats it), a byte that is not UTF-8.
ctl_dir = os.path.join(hostile, "ctl").encode()
os.makedirs(ctl_dir)
good_name = b"ctl-\x1b[31m-\x7f-\xc2\x85.svg"
bad_name = b"bad-\x1b]0;title\x07-\xc2\x9b2J-\xfe.svg"
shutil.copy(example0, os.path.join(ctl_dir, good_name))
with open(os.path.join(ctl_dir, bad_name), "w") as f:
    f.write(SVG.format('<path d="M 10 10 L 20 x"/>'))
ctl_out = os.path.join(hostile, "out-ctl")
ctl_report = os.path.join(ctl_out, "report.jsonl")
for attempt in ("first run", "second run"):
    r = subprocess.run([binary, "batch", ctl_dir, "-o", ctl_out, "--linear"], capture_output=True, timeout=120)
    check(f"control characters, {attempt}: exit 1 (the malformed drawing)", r.returncode == 1,
          f"exit {r.returncode}: {r.stderr!r}")
    raw = read_bytes(ctl_report) or b""
    lines = raw.split(b"\n")
    check(f"control characters, {attempt}: two lines", len(lines) == 3 and lines[2] == b"", raw)
    parsed = []
    for line in lines[:2]:
        check(f"control characters, {attempt}: no raw control byte in a line",
              not any(b < 0x20 or b == 0x7f for b in line) and not any(
                  line[i] == 0xc2 and 0x80 <= line[i + 1] <= 0x9f for i in range(len(line) - 1)), line)
        try:
            parsed.append(json.loads(line.decode("utf-8", errors="strict")))
        except (UnicodeDecodeError, json.JSONDecodeError) as e:
            check(f"control characters, {attempt}: a line is UTF-8 JSON", False, f"{e}: {line!r}")
    statuses = {p.get("path", "").split("/")[-1][:3]: p.get("status") for p in parsed}
    check(f"control characters, {attempt}: statuses",
          statuses == {"bad": "invalid-input", "ctl": "ok" if attempt == "first run" else "skipped"}, parsed)
    check(f"control characters, {attempt}: the characters kept, escaped, the bad byte replaced",
          any(p.get("path", "").endswith("ctl-\x1b[31m-\x7f-\x85.svg") for p in parsed)
          and any(p.get("path", "").endswith("bad-\x1b]0;title\x07-\x9b2J-\ufffd.svg")
                  # The message is the child's, which prints the name escaped.
                  and "title\\x07-\\u009b2J-\\xfe.svg" in p.get("message", "") for p in parsed), parsed)
    check(f"control characters, {attempt}: batch prints no raw ESC, BEL or C1 on stderr",
          b"\x1b" not in r.stderr and b"\x07" not in r.stderr and b"\xc2\x9b" not in r.stderr
          and b"\xc2\x85" not in r.stderr, r.stderr)
r, _ = run("report", ctl_report)
check("control characters: curvemesh report reads the report", r.returncode == 0, r.stderr)

# --- Usage errors and help ------------------------------------------------------------------------
usage = {"shard out of range": [inputs, "--shard", "4/3"], "shard not K/N": [inputs, "--shard", "x"],
         "no such input": [os.path.join(root, "missing.svg")], "no jobs": [inputs, "--jobs", "0"]}
for name, args in usage.items():
    r, _ = run("batch", *args, "-o", os.path.join(root, "out-usage"))
    check(f"usage: {name}: exit 2", r.returncode == 2, f"exit {r.returncode}: {r.stderr}")
r, _ = run("batch", inputs)
check("usage: no -o: exit 2", r.returncode == 2, f"exit {r.returncode}")
# A list of drawings that is a FIFO nobody writes to, or a device that never ends: refused at once.
list_fifo = os.path.join(root, "list.fifo")
os.mkfifo(list_fifo)
for name in (list_fifo, "/dev/zero"):
    r, _ = run("batch", name, "-o", os.path.join(root, "out-nonregular"))
    check(f"a list that is {name}: exit 1, not a regular file", r.returncode == 1 and "not a regular file" in r.stderr,
          f"exit {r.returncode}: {r.stderr}")
r, _ = run("batch", "--help")
check("batch --help explains every option", r.returncode == 0 and all(
    o in r.stdout for o in ("--jobs", "--timeout", "--memory-limit", "--report", "--force", "--shard", "--linear",
                            "--domain", "--regions", "--strokes", "--edge-length", "--mu", "--epsilon", "--min-angle", "--max-iterations", "--msh-version")),
      r.stdout)
r, _ = run("report", "--help")
check("report --help", r.returncode == 0 and "--html" in r.stdout, r.stdout)

finish()
