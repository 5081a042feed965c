#!/usr/bin/env python3
"""scripts/slurm-batch, the collection on a Slurm cluster.

usage: slurm_test.py CURVEMESH_BINARY EXAMPLES_DIR --script
       slurm_test.py CURVEMESH_BINARY EXAMPLES_DIR --cluster

--script (no Slurm needed): usage errors (exit 2), --help, and the job scripts --dry-run prints,
run by hand task after task and then the report job: the merged report equals a plain batch's.

--cluster: a real one-node Slurm (tests/tools/slurm_local.py: munged, slurmctld and slurmd as
root, 127.0.0.1 only, in a temporary folder). The examples plus a broken drawing through a 2-task
array: the merged report equals a local `curvemesh batch` of the same inputs (statuses and
triangles). Then a second submission with a drawing that takes a while: its task is cancelled
(scancel) while meshing it, which leaves whole report lines, no line, mesh or temporary for the
stopped drawing and no crash; submitting again meshes only that drawing and completes the run.
Last, scripts/slurm-compare on the same inputs (its own cluster): both runs agree. Exits 77 (ctest's skip) with the reason when Slurm cannot start here; the daemons are stopped by
their pids whatever happens.
"""
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "tools"))
from checks import check, finish  # noqa: E402

SKIP = 77
binary, examples, mode = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
slurm_batch = os.path.normpath(os.path.join(here, "..", "..", "scripts", "slurm-batch"))
tmp = tempfile.TemporaryDirectory(prefix="slurm-test-")
root = tmp.name
example_names = sorted(n for n in os.listdir(examples) if n.endswith(".svg"))


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


def read_lines(path):
    """The report's lines, and whether every one of them is whole JSON."""
    try:
        with open(path) as f:
            text = f.read()
        return [json.loads(l) for l in text.splitlines() if l.strip()], text.endswith("\n") or not text
    except (OSError, json.JSONDecodeError) as e:
        return [], False


def figures(lines):
    return {l["path"]: (l["status"], l["triangles"]) for l in lines}


def shard_lines(outdir, n):
    lines = []
    for k in range(1, n + 1):
        lines += read_lines(os.path.join(outdir, f"report-{k}-of-{n}.jsonl"))[0]
    return lines


def summary_head(text):
    """The lines of `curvemesh report` that do not depend on timings or on how many reports there were."""
    return [re.sub(r" \(from \d+ reports?\)$", "", l) for l in text.splitlines()
            if l.startswith(("drawings:", "success rate:", "by status:"))]


# The examples plus a broken drawing (invalid-input), all copied into one folder.
inputs = os.path.join(root, "in")
for n in example_names:
    os.makedirs(inputs, exist_ok=True)
    shutil.copy(os.path.join(examples, n), os.path.join(inputs, n))
write(os.path.join(inputs, "broken.svg"), '<svg xmlns="http://www.w3.org/2000/svg"><path d="M 1 1 L x"/></svg>')

# What a plain batch makes of them: the reference.
local_out = os.path.join(root, "local")
r = subprocess.run([binary, "batch", inputs, "-o", local_out, "--jobs", "2"], capture_output=True, text=True,
                   timeout=300)
local, _ = read_lines(os.path.join(local_out, "report.jsonl"))
check("local batch: the examples ok, the broken drawing invalid-input (exit 1)",
      r.returncode == 1 and sorted(l["status"] for l in local) == ["invalid-input"] + ["ok"] * len(example_names),
      r.stderr)
local_summary = summary_head(subprocess.run([binary, "report", os.path.join(local_out, "report.jsonl")],
                                            capture_output=True, text=True, timeout=60).stdout)


def slurm_batch_run(*args, env=None, timeout=120):
    return subprocess.run([slurm_batch, *args], capture_output=True, text=True, timeout=timeout, env=env,
                          stdin=subprocess.DEVNULL)


def script_checks():
    usage = {"no INPUT": ["-o", root, "--tasks", "2"], "no -o": [inputs, "--tasks", "2"],
             "no --tasks": [inputs, "-o", root], "--tasks 0": [inputs, "-o", root, "--tasks", "0"],
             "--tasks x": [inputs, "-o", root, "--tasks", "x"],
             "--cpus-per-task 0": [inputs, "-o", root, "--tasks", "2", "--cpus-per-task", "0"],
             "an input that is not there": [os.path.join(root, "missing.svg"), "-o", root, "--tasks", "2"],
             "--shard is the script's": [inputs, "-o", root, "--tasks", "2", "--linear", "--shard", "1/2"],
             "--jobs is the script's": [inputs, "-o", root, "--tasks", "2", "--jobs", "4"],
             "--report is the script's": [inputs, "-o", root, "--tasks", "2", "--report", "r.jsonl"],
             "a mesh option curvemesh refuses": [inputs, "-o", root, "--tasks", "2", "--min-angle", "-3"],
             "an option nobody knows": [inputs, "-o", root, "--tasks", "2", "--lenght", "3"]}
    for name, args in usage.items():
        r = slurm_batch_run(*args, "--curvemesh", binary, "--dry-run")
        check(f"usage: {name}: exit 2 with a message", r.returncode == 2 and "usage:" in r.stderr
              and not r.stdout, f"exit {r.returncode}: {r.stdout}{r.stderr}")
    r = slurm_batch_run("--help")
    check("--help explains every option", r.returncode == 0 and all(
        o in r.stdout for o in ("--output-dir", "--tasks", "--cpus-per-task", "--time-per-task", "--mem-per-task",
                                "--partition", "--sbatch-option", "--job-name", "--curvemesh", "--dry-run",
                                "afterany", "singleton", "report-K-of-N.jsonl")), r.stdout)
    env = dict(os.environ, PATH="/nonexistent")
    r = slurm_batch_run(inputs, "-o", os.path.join(root, "no-sbatch"), "--tasks", "2", "--curvemesh", binary, env=env)
    check("no sbatch on PATH: exit 1, says so", r.returncode == 1 and "sbatch" in r.stderr, r.stderr)
    check("no sbatch on PATH: nothing created", not os.path.exists(os.path.join(root, "no-sbatch")))

    # --dry-run: the two job scripts, run here by hand as Slurm would run them.
    out = os.path.join(root, "dry")
    r = slurm_batch_run(inputs, "-o", out, "--tasks", "3", "--cpus-per-task", "2", "--time-per-task", "1:00:00",
                        "--mem-per-task", "2G", "--partition", "short", "--sbatch-option=--account=geo",
                        "--curvemesh", binary, "--dry-run", "--timeout", "100")
    check("--dry-run: exit 0, nothing created", r.returncode == 0 and not os.path.exists(out), r.stderr)
    scripts = re.findall(r"<<'EOF'\n(.*?\n)EOF\n", r.stdout, re.S)
    check("--dry-run: two job scripts", len(scripts) == 2, r.stdout)
    if len(scripts) != 2:
        return
    array, report = scripts
    for option in ("--array=1-3", "--cpus-per-task=2", "--time=1:00:00", "--mem=2G", "--partition=short",
                   f"--output={out}/slurm/%A_%a.out", "--dependency=singleton"):
        check(f"--dry-run: the array asks for {option}", f"#SBATCH {option}\n" in array, array)
    check("--dry-run: the array runs batch with absolute paths, --jobs C, its shard and the options passed on",
          f"{binary} batch {inputs} -o {out} --jobs 2 --shard \"$SLURM_ARRAY_TASK_ID/3\" --timeout 100" in array, array)
    check("--dry-run: the report job waits for the array, however it ended",
          "--dependency=afterany:${array%%;*}" in r.stdout and "--account=geo" in r.stdout, r.stdout)
    check("--dry-run: the report job merges report-K-of-3.jsonl into report.html",
          "report-$k-of-3.jsonl" in report and f"--html {out}/report.html" in report, report)
    r = subprocess.run(["bash", "-n"], input=r.stdout, capture_output=True, text=True)
    check("--dry-run: its output is a shell script", r.returncode == 0, r.stderr)
    os.makedirs(os.path.join(out, "slurm"))
    for k in (1, 2, 3):
        t = subprocess.run(["bash", "-c", array], env=dict(os.environ, SLURM_ARRAY_TASK_ID=str(k)), cwd=out,
                           capture_output=True, text=True, timeout=300)
        check(f"by hand: task {k} runs its shard", t.returncode in (0, 1) and f"shard {k}/3" in t.stderr, t.stderr)
    t = subprocess.run(["bash", "-c", report], cwd=out, capture_output=True, text=True, timeout=60)
    check("by hand: the report job merges the shards", t.returncode == 0 and summary_head(t.stdout) == local_summary,
          (t.stdout, t.stderr, local_summary))
    check("by hand: report.html and report.txt", os.path.exists(os.path.join(out, "report.html"))
          and os.path.exists(os.path.join(out, "report.txt")))
    check("by hand: the shards' lines are the plain batch's (statuses, triangles)",
          figures(shard_lines(out, 3)) == figures(local), (figures(shard_lines(out, 3)), figures(local)))
    os.remove(os.path.join(out, "report-2-of-3.jsonl"))
    t = subprocess.run(["bash", "-c", report], cwd=out, capture_output=True, text=True, timeout=60)
    check("by hand: a task without a report is named", t.returncode == 0 and "task 2 wrote no report" in t.stderr,
          t.stderr)


def submit(slurm, *args):
    r = slurm.run([slurm_batch, *args, "--curvemesh", binary], check=False, timeout=120)
    array = re.search(r"^array job (\d+)", r.stdout, re.M)
    report = re.search(r"^report job (\d+)", r.stdout, re.M)
    check(f"submit {' '.join(args[-4:])}: two job ids printed", r.returncode == 0 and array and report,
          f"exit {r.returncode}: {r.stdout}{r.stderr}")
    return (array.group(1), report.group(1)) if array and report else (None, None)


def child_meshing(drawing):
    """The pid of a `curvemesh mesh` of `drawing` running on this machine, or None."""
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                argv = [a.decode(errors="replace") for a in f.read().split(b"\0")]
        except OSError:
            continue
        # Batch passes the drawing after "--", so that no file name is read as an option.
        if len(argv) > 2 and argv[1] == "mesh" and "--" in argv and drawing in argv[argv.index("--") + 1:]:
            return int(entry)
    return None


def cluster_checks(slurm):
    # --- The examples and a broken drawing in 2 tasks ------------------------------------------------
    out = os.path.join(root, "slurm-out")
    start = time.monotonic()
    array, report = submit(slurm, inputs, "-o", out, "--tasks", "2")
    if not array:
        return
    done = slurm.wait([array, report], 150)
    check("first submission: done within 150 s", done, slurm.queued([array, report]))
    print(f"first submission: {time.monotonic() - start:.1f} s from sbatch to the merged report")
    broken_task = sorted(os.path.join(inputs, n) for n in os.listdir(inputs)).index(
        os.path.join(inputs, "broken.svg")) % 2 + 1
    check("first submission: each task ends as its batch did (FAILED: a drawing failed in it)",
          [slurm.state(f"{array}_{k}") for k in (1, 2)] ==
          ["FAILED" if k == broken_task else "COMPLETED" for k in (1, 2)],
          [slurm.state(f"{array}_{k}") for k in (1, 2)])
    check("first submission: the report job completed", slurm.state(report) == "COMPLETED",
          (slurm.state(report), slurm.logs("slurmctld")))
    lines = shard_lines(out, 2)
    check("first submission: the shards' lines equal the local batch's (statuses, triangles)",
          figures(lines) == figures(local), (figures(lines), figures(local)))
    try:
        with open(os.path.join(out, "report.txt")) as f:
            merged = f.read()
    except OSError as e:
        merged = str(e)
    check("first submission: the merged report's summary equals the local one's",
          summary_head(merged) == local_summary, (merged, local_summary))
    check("first submission: report.html lists the broken drawing",
          os.path.exists(os.path.join(out, "report.html"))
          and "broken.svg" in open(os.path.join(out, "report.html")).read())
    check("first submission: each task's log under OUTDIR/slurm",
          all(os.path.exists(os.path.join(out, "slurm", f"{array}_{k}.out")) for k in (1, 2)),
          os.listdir(os.path.join(out, "slurm")))
    check("first submission: the meshes are there",
          all(os.path.exists(os.path.join(out, n[:-4] + ".msh")) for n in example_names), os.listdir(out))

    # --- A task cancelled while it meshes; submitting again completes the run -----------------------
    # A drawing of random crossing cubics that takes some seconds; named to be the last of task 2's.
    inputs2 = os.path.join(root, "in2")
    for n in example_names:
        os.makedirs(inputs2, exist_ok=True)
        shutil.copy(os.path.join(examples, n), os.path.join(inputs2, n))
    rng = random.Random(7)
    paths = []
    for _ in range(300):
        p = [f"{rng.uniform(0, 1000):.3f}" for _ in range(8)]
        paths.append(f'<path d="M {p[0]} {p[1]} C {p[2]} {p[3]} {p[4]} {p[5]} {p[6]} {p[7]}" fill="none" stroke="black"/>')
    slow = write(os.path.join(inputs2, "zz-slow.svg"),
                 '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1000 1000">' + "".join(paths) + "</svg>")
    all2 = sorted([os.path.join(inputs2, n) for n in example_names] + [slow])
    task_of_slow = all2.index(slow) % 2 + 1
    out2 = os.path.join(root, "slurm-out2")
    array, report = submit(slurm, inputs2, "-o", out2, "--tasks", "2")
    if not array:
        return
    deadline = time.monotonic() + 90
    child = None
    while time.monotonic() < deadline and child is None:
        child = child_meshing(slow)
        time.sleep(0.05)
    check("cancel: the slow drawing is being meshed", child is not None, slurm.queued([array, report]))
    if child is None:
        return
    time.sleep(0.5)
    task = f"{array}_{task_of_slow}"
    slurm.run(["scancel", task], check=False)
    check("cancel: done within 60 s", slurm.wait([array, report], 60), slurm.queued([array, report]))
    check("cancel: the task was cancelled", (slurm.state(task) or "").startswith("CANCELLED"), slurm.state(task))
    check("cancel: the report job ran all the same", slurm.state(report) == "COMPLETED", slurm.state(report))
    lines, whole = read_lines(os.path.join(out2, f"report-{task_of_slow}-of-2.jsonl"))
    check("cancel: the cancelled task's report is whole lines", whole and lines, lines)
    check("cancel: no line for the drawing it stopped, no crash",
          slow not in figures(lines) and all(l["status"] == "ok" for l in lines), lines)
    check("cancel: the task's other drawings are in it",
          {l["path"] for l in lines} == {p for i, p in enumerate(all2) if i % 2 == task_of_slow - 1 and p != slow},
          lines)
    check("cancel: no mesh, statistics or temporary of the stopped drawing",
          not [f for f in os.listdir(out2) if f.startswith("zz-slow")], os.listdir(out2))
    check("cancel: the merged report has the other drawings",
          summary_head(open(os.path.join(out2, "report.txt")).read())[:1] == [
              f"drawings: {len(example_names)}"] if os.path.exists(os.path.join(out2, "report.txt"))
          else False, os.listdir(out2))
    meshes = {p: os.stat(p).st_mtime_ns for p in (os.path.join(out2, n[:-4] + ".msh") for n in example_names)
              if os.path.exists(p)}
    check("cancel: the examples' meshes stay", len(meshes) == len(example_names), meshes)
    array, report = submit(slurm, inputs2, "-o", out2, "--tasks", "2")
    if not array:
        return
    check("again: done within 120 s", slurm.wait([array, report], 120), slurm.queued([array, report]))
    lines = shard_lines(out2, 2)
    statuses = {l["path"]: l["status"] for l in lines}
    check("again: the stopped drawing is meshed now", statuses.get(slow) == "ok", statuses)
    check("again: the others are skipped, not meshed again",
          all(statuses.get(p) == "skipped" for p in all2 if p != slow)
          and {p: os.stat(p).st_mtime_ns for p in meshes} == meshes, statuses)
    with open(os.path.join(out2, "report.txt")) as f:
        text = f.read()
    check("again: the merged report is complete",
          f"drawings: {len(all2)} (from 2 reports)" in text and f"success rate: {len(all2)} of {len(all2)}" in text,
          text)


if mode == "--script":
    script_checks()
elif mode == "--cluster":
    from slurm_local import LocalSlurm, Unavailable  # noqa: E402

    # ctest's time-out or Ctrl-C: stop the daemons on the way out (the finally below).
    for s in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(s, lambda signum, frame: sys.exit(f"stopped by signal {signum}"))
    started = time.monotonic()
    try:
        with LocalSlurm() as slurm:
            print(f"one-node Slurm up in {time.monotonic() - started:.1f} s ({slurm.root})")
            try:
                cluster_checks(slurm)
            except BaseException:
                for name in ("slurmctld", "slurmd"):
                    print(slurm.logs(name))
                raise
    except Unavailable as e:
        print(f"SKIP: Slurm cannot run here: {e}")
        sys.exit(SKIP)
    print(f"{time.monotonic() - started:.1f} s with the cluster, stopping included")
    # scripts/slurm-compare (docs/measurements/batch-and-slurm.md) on the same inputs, with a cluster of its own.
    compare = os.path.normpath(os.path.join(here, "..", "..", "scripts", "slurm-compare"))
    r = subprocess.run([compare, inputs, "--tasks", "2", "--jobs", "2", "--curvemesh", binary], capture_output=True,
                       text=True, timeout=240, stdin=subprocess.DEVNULL)
    check("slurm-compare: the plain and the Slurm run agree (exit 0)", r.returncode == 0
          and "same report" in r.stdout and "Slurm's own:" in r.stdout, f"exit {r.returncode}: {r.stdout}{r.stderr}")
    print(r.stdout)
else:
    sys.exit(f"usage: {sys.argv[0]} CURVEMESH EXAMPLES --script|--cluster")
finish()
