#!/usr/bin/env python3
"""Outputs that cannot be turned against the user, checked from outside the process on files and
links the test plants itself: a link at the output is replaced, never written through; a FIFO or
a device is written in place (a write error such as /dev/full's is reported), a folder refused;
an output that is an input (by any name, through a hard or a symbolic link) or two outputs naming
one file are a usage error before anything is read or written; a failed run leaves none of its
outputs and no temporary; messages print an input's control characters escaped.

usage: outputs_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import json
import os
import re
import stat
import subprocess
import sys
import tempfile
import threading

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
SOURCE = os.path.join(examples, "overlapping-shapes.svg")


def path(name):
    return os.path.join(tmp.name, name)


def write(name, content):
    with open(path(name), "wb") as f:
        f.write(content if isinstance(content, bytes) else content.encode())
    return path(name)


def read(p):
    with open(p, "rb") as f:
        return f.read()


def run(*args, timeout=300):
    return subprocess.run([binary, *args], capture_output=True, timeout=timeout)


def leftovers(folder):
    """Temporaries a run left in `folder` (NAME.tmp.SUFFIX)."""
    return [n for n in os.listdir(folder) if ".tmp." in n]


def fresh_folder(name):
    folder = path(name)
    os.mkdir(folder)
    return folder


# A link planted at the output is replaced by the mesh; the file it pointed to is untouched.
folder = fresh_folder("link")
victim = write("victim.txt", "precious\n")
os.symlink(victim, os.path.join(folder, "out.msh"))
r = run("mesh", SOURCE, "-o", os.path.join(folder, "out.msh"), "-q")
out = os.path.join(folder, "out.msh")
check("a link at -o: exit 0", r.returncode == 0, r.stderr.decode()[-300:])
check("a link at -o: the link's target is untouched", read(victim) == b"precious\n")
check("a link at -o: replaced by a regular file holding the mesh",
      not os.path.islink(out) and read(out).startswith(b"$MeshFormat"))
check("a link at -o: no temporary left", leftovers(folder) == [], leftovers(folder))

# A dangling link planted at --stats: replaced, its target not created.
folder = fresh_folder("dangling")
target = path("dangling-target.json")
os.symlink(target, os.path.join(folder, "s.json"))
r = run("mesh", SOURCE, "-o", os.path.join(folder, "m.msh"), "--stats", os.path.join(folder, "s.json"), "-q")
check("a dangling link at --stats: exit 0", r.returncode == 0, r.stderr.decode()[-300:])
check("a dangling link at --stats: its target is not created", not os.path.exists(target))
check("a dangling link at --stats: replaced by the statistics",
      not os.path.islink(os.path.join(folder, "s.json")) and "mesh" in json.loads(read(os.path.join(folder, "s.json"))))

# A FIFO as the output: written in place (a reader on the other end gets the mesh), still a FIFO.
fifo = path("out.fifo")
os.mkfifo(fifo)
got = {}


def drain():
    with open(fifo, "rb") as f:
        got["bytes"] = f.read()


reader = threading.Thread(target=drain)
reader.start()
r = run("mesh", SOURCE, "-o", fifo, "-q", timeout=120)
reader.join(60)
check("a FIFO at -o: exit 0", r.returncode == 0, r.stderr.decode()[-300:])
check("a FIFO at -o: the reader gets the mesh", got.get("bytes", b"").startswith(b"$MeshFormat"))
check("a FIFO at -o: still a FIFO", stat.S_ISFIFO(os.lstat(fifo).st_mode))

# /dev/full: the write's error reported, exit 1, the device left as it is.
if os.path.exists("/dev/full"):
    r = run("mesh", SOURCE, "-o", "/dev/full", "-q")
    err = r.stderr.decode()
    check("-o /dev/full: exit 1", r.returncode == 1, err[-300:])
    check("-o /dev/full: says the device is full", "No space left on device" in err, err[-300:])
    check("-o /dev/full: still a character device", stat.S_ISCHR(os.lstat("/dev/full").st_mode))

# Device nodes of the test's own (root only): written in place, never replaced by a file.
if os.geteuid() == 0:
    null = path("null")
    os.mknod(null, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    r = run("mesh", SOURCE, "-o", null, "--stats", null + ".json", "-q")
    check("-o a null device: exit 0", r.returncode == 0, r.stderr.decode()[-300:])
    check("-o a null device: still a character device", stat.S_ISCHR(os.lstat(null).st_mode))
    link = path("null-link")
    os.symlink(null, link)
    r = run("mesh", SOURCE, "-o", link, "-q")
    check("-o a link (ours) to a null device: written through it, the link kept",
          r.returncode == 0 and os.path.islink(link) and stat.S_ISCHR(os.stat(link).st_mode), r.stderr.decode()[-300:])

# A folder as the output: refused, exit 1, nothing written.
folder = fresh_folder("as-output")
r = run("mesh", SOURCE, "-o", folder, "--svg", path("folder.svg"), "-q")
check("-o a folder: exit 1", r.returncode == 1, r.stderr.decode()[-300:])
check("-o a folder: says it is a folder", b"folder" in r.stderr, r.stderr.decode()[-300:])
check("-o a folder: the other output is not written", not os.path.exists(path("folder.svg")))

# An output that is the input, by any name: exit 2 before anything is read or written.
drawing = write("drawing.svg", read(SOURCE))
original = read(drawing)
os.link(drawing, path("hard.svg"))
os.symlink(drawing, path("soft.svg"))
for option in ("-o", "--svg", "--vtu", "--stats"):
    for name in (drawing, path("hard.svg"), path("soft.svg"), os.path.join(tmp.name, ".", "drawing.svg")):
        outputs = {"-o": path("clash.msh")}
        outputs[option] = name
        args = ["mesh", drawing, "-q"]
        for o, p in outputs.items():
            args += [o, p]
        r = run(*args)
        label = f"mesh {option} {os.path.basename(name)} over the input"
        check(f"{label}: exit 2", r.returncode == 2, r.stderr.decode()[-300:])
        check(f"{label}: says it would write over an input", b"refusing to write over an input" in r.stderr,
              r.stderr.decode()[-300:])
        check(f"{label}: the drawing is unchanged", read(drawing) == original)
        check(f"{label}: no other output written", not os.path.exists(path("clash.msh")))

for args in (["features", drawing, "-o", path("f.json"), "--svg", path("hard.svg")],
             ["solve", "inflate", drawing, "-o", path("i.vtu"), "--surface", path("soft.svg")],
             ["diffuse", drawing, "-o", path("d.png"), "--vtu", drawing],
             ["report", drawing, "--html", path("hard.svg")]):
    r = run(*args)
    label = " ".join(args[:2] if args[0] == "solve" else args[:1]) + " over the input"
    check(f"{label}: exit 2", r.returncode == 2, r.stderr.decode()[-300:])
    check(f"{label}: the drawing is unchanged", read(drawing) == original)
    check(f"{label}: nothing written", not any(os.path.exists(path(n)) for n in ("f.json", "i.vtu", "d.png")))

# Two outputs naming one file (by two spellings): exit 2.
r = run("mesh", SOURCE, "-o", path("twice.msh"), "--vtu", os.path.join(tmp.name, ".", "twice.msh"))
check("two outputs naming one file: exit 2", r.returncode == 2, r.stderr.decode()[-300:])
check("two outputs naming one file: nothing written", not os.path.exists(path("twice.msh")))

# A failed run removes every output it wrote; what was there before stays as it was.
folder = fresh_folder("all-or-nothing")
earlier = os.path.join(folder, "out.msh")
with open(earlier, "w") as f:
    f.write("an earlier run's mesh\n")
r = run("mesh", SOURCE, "-o", earlier, "--vtu", os.path.join(folder, "out.vtu"),
        "--stats", os.path.join(folder, "out.json"), "--svg", os.path.join(tmp.name, "missing", "x.svg"), "-q")
check("an unwritable --svg: exit 1", r.returncode == 1, r.stderr.decode()[-300:])
check("an unwritable --svg: names it", b"missing/x.svg" in r.stderr, r.stderr.decode()[-300:])
check("an unwritable --svg: no .vtu and no statistics left",
      sorted(os.listdir(folder)) == ["out.msh"], sorted(os.listdir(folder)))
check("an unwritable --svg: the earlier mesh is untouched", read(earlier) == b"an earlier run's mesh\n")
r = run("mesh", SOURCE, "-o", os.path.join(folder, "full.msh"), "--stats", "/dev/full", "-q")
check("--stats /dev/full: exit 1, and the mesh is not left", r.returncode == 1 and
      not os.path.exists(os.path.join(folder, "full.msh")), r.stderr.decode()[-300:])
check("failed runs leave no temporary", leftovers(folder) == [], leftovers(folder))

# A solve whose picture cannot be written leaves no VTU either.
r = run("solve", "inflate", SOURCE, "-o", path("inflate.vtu"), "--png", os.path.join(tmp.name, "missing", "p.png"))
check("solve with an unwritable --png: exit 1 and no VTU", r.returncode == 1 and not os.path.exists(path("inflate.vtu")),
      r.stderr.decode()[-300:])

# An element id with a quote and a line break: a region's name the .msh holds escaped, that Gmsh
# reads back; the VTU and the statistics as well.
quoted = write("quoted.svg", '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 8">'
                             '<path id="a&quot;b&#10;c\x1b[2J" d="M0 0 L10 0 L5 8 Z" fill="red"/></svg>')
r = run("mesh", quoted, "-o", path("quoted.msh"), "--regions", "--vtu", path("quoted.vtu"),
        "--stats", path("quoted.json"), "-q")
check("an id with a quote, a line break and ESC: exit 0", r.returncode == 0, r.stderr.decode()[-300:])
if r.returncode == 0:
    names = json.loads(read(path("quoted.json")))["regions"]
    check("the statistics hold the id as it is", any(n["name"] == 'a"b\nc\x1b[2J' for n in names), names)
    gmsh_reader = subprocess.run(
        [sys.executable, "-c",
         "import gmsh, sys; gmsh.initialize(); gmsh.option.setNumber('General.Terminal', 0); gmsh.open(sys.argv[1]);"
         "print([gmsh.model.getPhysicalName(d, t) for d, t in gmsh.model.getPhysicalGroups()])", path("quoted.msh")],
        capture_output=True, text=True, timeout=120)
    check("Gmsh reads the .msh and its escaped name", gmsh_reader.returncode == 0 and
          "a\\\\x22b\\\\x0ac\\\\x1b[2J" in gmsh_reader.stdout, gmsh_reader.stdout + gmsh_reader.stderr[-300:])

# A control character in a file name is printed escaped, never raw.
weird = write("esc\x1b]0;title\x07.svg", "<svg xmlns='http://www.w3.org/2000/svg'><path d='M0 0 L1 1'/>")
r = run("mesh", weird, "-o", path("weird.msh"))
check("a broken drawing with ESC and BEL in its name: exit 1", r.returncode == 1, r.stderr.decode()[-300:])
check("its message prints them escaped", b"\x1b" not in r.stderr and b"\x07" not in r.stderr and b"\\x1b" in r.stderr,
      r.stderr[-300:])

# --xdmf: the XML and its HDF5 file beside it, both or neither; order 3 refused before anything is
# read or written; the summary line names every file and counts what the files hold.
folder = fresh_folder("xdmf")
xdmf, h5, msh = (os.path.join(folder, n) for n in ("m.xdmf", "m.h5", "m.msh"))
r = run("mesh", SOURCE, "-o", msh, "--order", "1", "--domain", "filled", "--xdmf", xdmf)
check("--xdmf: exit 0", r.returncode == 0, r.stderr.decode()[-300:])
check("--xdmf: the XML names its HDF5 file beside it", b'Format="HDF">m.h5:/mesh/geometry<' in read(xdmf))
check("--xdmf: the HDF5 file", read(h5).startswith(b"\x89HDF\r\n\x1a\n"))
in_file = int(read(msh).split(b"$Elements\n")[1].split(b"\n")[0].split()[1])  # 4.1: blocks, elements, ...
triangles = [int(n) for n in re.findall(rb"(\d+) triangles of order 1, (\d+) lines", r.stdout)[0]]
check("the summary names every file written", r.stdout.decode().startswith(f"curvemesh: wrote {msh}, {xdmf}, {h5}: "),
      r.stdout)
check("the summary counts the triangles and lines written (--domain filled: fewer than meshed)",
      sum(triangles) == in_file, (triangles, in_file))
first = read(h5)
os.remove(h5)
r = run("mesh", SOURCE, "-o", msh, "--order", "1", "--domain", "filled", "--xdmf", xdmf, "-q")
check("--xdmf: the same HDF5 bytes for the same mesh", read(h5) == first)
for name in os.listdir(folder):
    os.remove(os.path.join(folder, name))
r = run("mesh", SOURCE, "-o", msh, "--xdmf", xdmf)
check("--xdmf with order 3: exit 2, saying what to do", r.returncode == 2 and b"--order 2 or 1" in r.stderr,
      r.stderr.decode()[-300:])
check("--xdmf with order 3: nothing written", os.listdir(folder) == [], os.listdir(folder))
r = run("mesh", SOURCE, "-o", msh, "--order", "1", "--xdmf", xdmf, "--stats", os.path.join(folder, "no", "s.json"))
check("--xdmf and an unwritable --stats: exit 1, neither XDMF file left",
      r.returncode == 1 and os.listdir(folder) == [], os.listdir(folder))
r = run("mesh", SOURCE, "-o", h5, "--order", "1", "--xdmf", xdmf)
check("-o naming --xdmf's HDF5 file: a usage error", r.returncode == 2 and os.listdir(folder) == [],
      r.stderr.decode()[-300:])

sys.exit(finish())
