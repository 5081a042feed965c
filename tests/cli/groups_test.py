#!/usr/bin/env python3
"""The physical groups a solver selects by, read back with Gmsh's Python API and meshio (readers
that share nothing with curvemesh): one line group per drawn element named by its id (else
TAG#INDEX), a side two shapes share in both; "border" holding exactly the border of the meshed
domain; region ids and names the same with --domain box and filled; no id used by both lines and
triangles, in 4.1 and 2.2; node tags 1..N without a gap for every order and domain (dolfinx's
gmshio needs it, and reads the files when it is installed); --msh-boundary-only with each border
line once, in one group; the --stats groups as Gmsh counts them.

usage: groups_test.py CURVEMESH_BINARY EXAMPLES_DIR
"""
import contextlib
import io
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checks import check, finish  # noqa: E402

binary, examples = sys.argv[1], sys.argv[2]
tmp = tempfile.TemporaryDirectory()
try:
    import gmsh
    import meshio
except ImportError as e:  # the Debian packages python3-gmsh and python3-meshio
    print(f"groups_test: {e}", file=sys.stderr)
    sys.exit(1)

# Two squares sharing a side (ids), a stroked circle inside the left one (no id: circle#INDEX), and a
# box 0..100 x 0..60 around them.
SHARED = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 60">
  <rect id="left" x="10" y="10" width="40" height="40" fill="#ff0000"/>
  <rect id="right" x="50" y="10" width="40" height="40" fill="#0000ff"/>
  <circle cx="30" cy="30" r="8" fill="none" stroke="black"/>
</svg>
"""
shared_svg = os.path.join(tmp.name, "shared.svg")
with open(shared_svg, "w") as f:
    f.write(SHARED)


def mesh(name, source, *extra):
    out = os.path.join(tmp.name, name)
    r = subprocess.run([binary, "mesh", source, "-o", out + ".msh", "--stats", out + ".json", "-q", *extra],
                       capture_output=True, text=True, timeout=300)
    check(f"{name}: meshed", r.returncode == 0, r.stderr[-500:])
    stats = {}
    if r.returncode == 0:
        with open(out + ".json") as f:
            stats = json.load(f)
    return out + ".msh", stats


class Groups:
    """What Gmsh reads from a .msh: per (dim, id) the name and the elements (node tag tuples), the
    node tags, and the nodes' coordinates."""

    def __init__(self, path):
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        self.node_tags = sorted(int(t) for t in tags)
        self.xy = {int(t): (coords[3 * i], coords[3 * i + 1]) for i, t in enumerate(tags)}
        self.names, self.elements = {}, {}
        for dim, tag in gmsh.model.getPhysicalGroups():
            self.names[(dim, tag)] = gmsh.model.getPhysicalName(dim, tag)
            elements = []
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                types, _, nodes = gmsh.model.mesh.getElements(dim, entity)
                for t, n in zip(types, nodes):
                    size = gmsh.model.mesh.getElementProperties(t)[3]
                    elements += [tuple(int(x) for x in n[i:i + size]) for i in range(0, len(n), size)]
            self.elements[(dim, tag)] = elements
        self.triangles = [e for (d, _), es in self.elements.items() if d == 2 for e in es]
        gmsh.finalize()

    def id_of(self, dim, name):
        found = [t for (d, t), n in self.names.items() if d == dim and n == name]
        return found[0] if len(found) == 1 else None

    def length(self, dim_tag):
        """The group's length, its lines taken straight between their nodes (exact for straight
        lines)."""
        total = 0
        for e in self.elements[dim_tag]:
            ordered = [e[0], *e[2:], e[1]]  # Gmsh's order: ends first, then the inner nodes
            total += sum(math.dist(self.xy[a], self.xy[b]) for a, b in zip(ordered, ordered[1:]))
        return total

    def border_edges(self):
        """The edges (corner node pairs) on exactly one triangle."""
        count = {}
        for t in self.triangles:
            for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                key = (min(a, b), max(a, b))
                count[key] = count.get(key, 0) + 1
        return {k for k, c in count.items() if c == 1}


def edge(line):
    return (min(line[0], line[1]), max(line[0], line[1]))


# --- each drawn element's group, a shared side in both, the border -------------------------------
# The order's flag and its name in the checks.
ORDERS = {"linear": ["--linear"], "curved": [], "quadratic": ["--order", "2"]}
for kind, order in ORDERS.items():
    for domain in ("box", "filled"):
        name = f"shared-{kind}-{domain}"
        path, stats = mesh(name, shared_svg, "--regions", "--domain", domain, *order)
        g = Groups(path)
        left, right, circle = g.id_of(1, "left"), g.id_of(1, "right"), g.id_of(1, "circle#3")
        check(f"{name}: one line group per drawn element, named by id or TAG#INDEX",
              None not in (left, right, circle), sorted(g.names.values()))
        if None in (left, right, circle):
            continue
        check(f"{name}: each square's group is its whole outline, the shared side included",
              abs(g.length((1, left)) - 160) < 1e-9 and abs(g.length((1, right)) - 160) < 1e-9,
              (g.length((1, left)), g.length((1, right))))
        shared = {edge(e) for e in g.elements[(1, left)]} & {edge(e) for e in g.elements[(1, right)]}
        check(f"{name}: the shared side is in both groups", abs(sum(
            math.dist(g.xy[a], g.xy[b]) for a, b in shared) - 40) < 1e-9, len(shared))
        border = g.id_of(1, "border")
        border_edges = {edge(e) for e in g.elements.get((1, border), [])}
        check(f"{name}: 'border' holds every edge on one triangle and no other",
              border is not None and border_edges == g.border_edges(), len(border_edges))
        # The border's length: the box's sides (0..100 x 0..60 grown by the margin), or the squares'
        # outline together (80 x 40).
        xs = [p[0] for p in g.xy.values()]
        ys = [p[1] for p in g.xy.values()]
        want = 2 * (max(xs) - min(xs) + max(ys) - min(ys)) if domain == "box" else 240
        check(f"{name}: the border is exactly the domain's outline", border is not None and
              abs(g.length((1, border)) - want) < 1e-9 * want, (g.length((1, border)) if border else None, want))
        lines = {t for d, t in g.names if d == 1}
        surfaces = {t for d, t in g.names if d == 2}
        check(f"{name}: no id is both a line group's and a region's", not lines & surfaces, (lines, surfaces))
        counted = {(s["dim"], s["id"]): (s["name"], s.get("lines", s.get("triangles")))
                   for s in stats.get("groups", [])}
        check(f"{name}: --stats lists the groups Gmsh reads, with their counts",
              counted == {k: (g.names[k], len(g.elements[k])) for k in g.names}, (counted, g.names))
        if domain == "box":
            box_regions = {n: t for (d, t), n in g.names.items() if d == 2}
        else:
            filled_regions = {n: t for (d, t), n in g.names.items() if d == 2}
    check(f"shared-{kind}: region ids the same with --domain box and filled",
          filled_regions and all(box_regions.get(n) == t for n, t in filled_regions.items())
          and "background" not in filled_regions, (box_regions, filled_regions))

# --- an example without ids, both versions: disjoint ids, contiguous node tags ---------------------
overlapping = os.path.join(examples, "overlapping-shapes.svg")
for version in ("4.1", "2.2"):
    for kind, order in ORDERS.items():
        for domain in ("box", "filled", "evenodd"):
            name = f"overlapping-{version}-{kind}-{domain}"
            path, stats = mesh(name, overlapping, "--regions", "--domain", domain, "--msh-version", version, *order)
            g = Groups(path)
            check(f"{name}: node tags are 1..N without a gap", g.node_tags == list(range(1, len(g.node_tags) + 1)),
                  g.node_tags[:5])
            with contextlib.redirect_stdout(io.StringIO()):
                m = meshio.read(path)
            used = {}
            for block, physical in zip(m.cells, m.cell_data["gmsh:physical"]):
                used.setdefault(1 if block.type.startswith("line") else 2, set()).update(int(p) for p in physical)
            check(f"{name}: meshio finds no id on both lines and triangles", not used.get(1, set()) & used.get(2, set()),
                  used)
            check(f"{name}: every element group is named TAG#INDEX", all(
                n.split("#")[0] in ("rect", "circle", "ellipse", "polygon") for (d, t), n in g.names.items()
                if d == 1 and t >= 6), g.names)

# --- --msh-boundary-only: the border, each line once, in one group ---------------------------------
for version in ("4.1", "2.2"):
    name = f"boundary-only-{version}"
    full, _ = mesh(name + "-full", shared_svg, "--linear", "--regions", "--domain", "filled", "--msh-version", version)
    path, _ = mesh(name, shared_svg, "--linear", "--regions", "--domain", "filled", "--msh-version", version,
                   "--msh-boundary-only")
    g, whole = Groups(path), Groups(full)
    lines = [edge(e) for (d, _), es in g.elements.items() if d == 1 for e in es]
    check(f"{name}: each border edge once, nothing else", sorted(lines) == sorted(g.border_edges()),
          (len(lines), len(g.border_edges())))
    check(f"{name}: the same triangles and nodes as without it",
          sorted(g.triangles) == sorted(whole.triangles) and g.xy == whole.xy)
    check(f"{name}: lines in the drawn elements' groups",
          {n for (d, _), n in g.names.items() if d == 1} == {"left", "right"}, g.names)
    if version == "4.1":
        with open(path) as f:
            text = f.read()
        entities = text.split("$Entities\n")[1].split("$EndEntities")[0].splitlines()
        curves = int(entities[0].split()[1])
        check(f"{name}: every curve entity has one physical tag (deal.II refuses more)",
              all(line.split()[7] == "1" for line in entities[1:1 + curves]), entities[:4])

# --- dolfinx reads the files, when installed ---------------------------------------------------------
try:
    with contextlib.redirect_stderr(io.StringIO()):
        from dolfinx.io import gmshio
        from mpi4py import MPI
except Exception as e:  # noqa: BLE001 (dolfinx is optional: a missing or broken install skips this)
    print(f"groups_test: dolfinx not checked: {e!r}")
    gmshio = None
if gmshio is not None:
    for kind, order in ORDERS.items():
        name = f"dolfinx-{kind}"
        path, stats = mesh(name, overlapping, "--regions", "--domain", "filled", *order)
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        try:
            domain, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, MPI.COMM_SELF, 0, gdim=2)
            cells = domain.topology.index_map(2).size_local
            check(f"{name}: dolfinx's gmshio reads it, every triangle tagged",
                  cells == stats["domain"]["triangles"] and len(cell_tags.values) == cells, cells)
        except Exception as e:  # noqa: BLE001
            check(f"{name}: dolfinx's gmshio reads it", False, repr(e)[-300:])
        gmsh.finalize()

finish()
