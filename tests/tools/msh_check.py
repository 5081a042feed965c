#!/usr/bin/python3
"""Certifies a 2D triangle mesh in a Gmsh .msh file, independently of the code that wrote it.

Reads ASCII .msh 4.1 and 2.2 with its own parser and decides the orientation of every triangle
in exact rational arithmetic on the coordinates every reader of the file obtains: each decimal
in the text parsed to the nearest double (as Gmsh, meshio and ParaView do), then taken exactly as
a fraction, so no rounding in the test can hide an inverted or flat triangle. Triangles must be
counter-clockwise. Line elements must lie on triangle edges. Then Gmsh (python3-gmsh) and meshio
(python3-meshio) must both read the file and see the same triangles, and Gmsh's Jacobian and the
inverse gradient error of its quality analysis must be positive. (Gmsh measures planar elements
relative to their own normal, so a clockwise triangle looks valid to it: orientation is decided
by the exact test alone.)

Usage: msh_check.py FILE.msh [--json]. Exit 0 when valid, 1 when invalid or unreadable.
"""
import argparse
import json
import math
import sys
from fractions import Fraction

TRIANGLES = {2: 3, 9: 6, 21: 10}  # element type -> node count (corners first)
LINES = {1: 2, 8: 3, 26: 4}
POINTS = {15: 1}
NODE_COUNT = {**TRIANGLES, **LINES, **POINTS}


class MeshError(Exception):
    pass


def sections(text):
    """Maps section name -> list of its lines (without the $ markers)."""
    out, name, body = {}, None, []
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("$End"):
            if name is None or s[4:] != name:
                raise MeshError(f"unexpected {s}")
            out[name] = body
            name, body = None, []
        elif s.startswith("$"):
            if name is not None:
                raise MeshError(f"section ${name} is not closed before {s}")
            name = s[1:]
        elif name is not None:
            body.append(s)
    if name is not None:
        raise MeshError(f"section ${name} is not closed")
    return out


class Tokens:
    def __init__(self, lines, what):
        self.words = " ".join(lines).split()
        self.i = 0
        self.what = what

    def next(self):
        if self.i >= len(self.words):
            raise MeshError(f"${self.what} ends too early")
        self.i += 1
        return self.words[self.i - 1]

    def int(self):
        w = self.next()
        try:
            return int(w)
        except ValueError:
            raise MeshError(f"${self.what}: expected an integer, found {w!r}")


def coordinate(word):
    # The decimal text itself is not what readers compute with: a triangle that is positive in the
    # doubles can be flat or inverted in the decimals by a fraction of an ulp, and vice versa.
    try:
        value = float(word)
    except ValueError:
        raise MeshError(f"coordinate {word!r} is not a number")
    if not math.isfinite(value):
        raise MeshError(f"coordinate {word!r} is not a finite number")
    return Fraction(value)


def parse(text):
    """Returns (nodes {tag: (Fraction x, Fraction y)}, elements [(type, nodes, physical)], names)."""
    sec = sections(text)
    if "MeshFormat" not in sec:
        raise MeshError("no $MeshFormat")
    fmt = sec["MeshFormat"][0].split()
    version, binary = fmt[0], fmt[1] if len(fmt) > 1 else "0"
    if binary != "0":
        raise MeshError("binary .msh files are not supported")
    names = {}
    if "PhysicalNames" in sec:
        t = Tokens(sec["PhysicalNames"], "PhysicalNames")
        for _ in range(t.int()):
            dim, tag = t.int(), t.int()
            name = t.next()
            while not name.endswith('"') or len(name) < 2:
                name += " " + t.next()
            names[(dim, tag)] = name.strip('"')
    nodes, elements = {}, []
    for required in ("Nodes", "Elements"):
        if required not in sec:
            raise MeshError(f"no ${required}")

    def add_node(tag, x, y, z):
        if tag in nodes:
            raise MeshError(f"node {tag} defined twice")
        if coordinate(z) != 0:
            raise MeshError(f"node {tag} has z = {z}: not a 2D mesh")
        nodes[tag] = (coordinate(x), coordinate(y))

    if version.startswith("2"):
        t = Tokens(sec["Nodes"], "Nodes")
        for _ in range(t.int()):
            add_node(t.int(), t.next(), t.next(), t.next())
        t = Tokens(sec["Elements"], "Elements")
        for _ in range(t.int()):
            _, etype, ntags = t.int(), t.int(), t.int()
            tags = [t.int() for _ in range(ntags)]
            if etype not in NODE_COUNT:
                raise MeshError(f"element type {etype} is not a 2D triangle, line or point")
            elements.append((etype, [t.int() for _ in range(NODE_COUNT[etype])], tags[0] if tags else 0))
    elif version.startswith("4.1"):
        entity_physical = {}
        if "Entities" in sec:
            t = Tokens(sec["Entities"], "Entities")
            counts = [t.int() for _ in range(4)]
            for dim, count in enumerate(counts):
                for _ in range(count):
                    tag = t.int()
                    for _ in range(3 if dim == 0 else 6):
                        t.next()
                    phys = [t.int() for _ in range(t.int())]
                    entity_physical[(dim, tag)] = phys[0] if phys else 0
                    if dim > 0:
                        for _ in range(t.int()):
                            t.int()
        t = Tokens(sec["Nodes"], "Nodes")
        blocks, _, _, _ = t.int(), t.int(), t.int(), t.int()
        for _ in range(blocks):
            _, _, parametric, count = t.int(), t.int(), t.int(), t.int()
            tags = [t.int() for _ in range(count)]
            for tag in tags:
                x, y, z = t.next(), t.next(), t.next()
                if parametric:
                    raise MeshError("parametric nodes are not supported")
                add_node(tag, x, y, z)
        t = Tokens(sec["Elements"], "Elements")
        blocks, _, _, _ = t.int(), t.int(), t.int(), t.int()
        for _ in range(blocks):
            dim, entity, etype, count = t.int(), t.int(), t.int(), t.int()
            if etype not in NODE_COUNT:
                raise MeshError(f"element type {etype} is not a 2D triangle, line or point")
            phys = entity_physical.get((dim, entity), 0)
            for _ in range(count):
                t.int()
                elements.append((etype, [t.int() for _ in range(NODE_COUNT[etype])], phys))
    else:
        raise MeshError(f"unsupported .msh version {version}")
    for etype, en, _ in elements:
        for n in en:
            if n not in nodes:
                raise MeshError(f"element refers to missing node {n}")
    return nodes, elements, names


def amips(a, b, c):
    e1 = (b[0] - a[0], b[1] - a[1])
    e2 = (c[0] - a[0], c[1] - a[1])
    det = e1[0] * e2[1] - e1[1] * e2[0]
    if det <= 0:
        return math.inf
    f = (2 * e2[0] - e1[0], 2 * e2[1] - e1[1])
    return (3 * (e1[0] ** 2 + e1[1] ** 2) + f[0] ** 2 + f[1] ** 2) / (2 * math.sqrt(3) * det)


def min_angle(a, b, c):
    def angle(p, q, r):
        u = (q[0] - p[0], q[1] - p[1])
        v = (r[0] - p[0], r[1] - p[1])
        return math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1])
    return min(angle(a, b, c), angle(b, c, a), angle(c, a, b))


def check_with_readers(path, triangles, report):
    try:
        import meshio
        m = meshio.read(path)
        count = sum(len(c.data) for c in m.cells if c.type in ("triangle", "triangle6", "triangle10"))
        report["meshio_triangles"] = count
        if count != triangles:
            report["problems"].append(f"meshio reads {count} triangles, not {triangles}")
    except Exception as e:  # any failure of the reader is a finding, not a crash
        report["problems"].append(f"meshio cannot read the file: {e}")
    try:
        import gmsh
        gmsh.initialize()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.open(path)
            types, tags, _ = gmsh.model.mesh.getElements(2)
            all_tags = [int(x) for ts in tags for x in ts]
            report["gmsh_triangles"] = len(all_tags)
            if len(all_tags) != triangles:
                report["problems"].append(f"Gmsh reads {len(all_tags)} triangles, not {triangles}")
            # Jacobian determinants at the element centres, by Gmsh's own element maps.
            dets = []
            for etype in types:
                _, jd, _ = gmsh.model.mesh.getJacobians(int(etype), [1 / 3, 1 / 3, 0])
                dets.extend(jd)
            if dets:
                report["gmsh_min_jacobian"] = float(min(dets))
                if min(dets) <= 0:
                    report["problems"].append(f"Gmsh finds a non-positive Jacobian ({min(dets):g})")
            # Gmsh's mesh quality analysis: the inverse gradient error measure is positive for
            # valid elements.
            gmsh.plugin.setNumber("AnalyseMeshQuality", "IGEMeasure", 1)
            gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 0)
            gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
            gmsh.plugin.setNumber("AnalyseMeshQuality", "DimensionOfElements", 2)
            gmsh.plugin.run("AnalyseMeshQuality")
            for view in gmsh.view.getTags():
                _, _, data, _, _ = gmsh.view.getModelData(view, 0)
                if data:
                    ige = min(d[0] for d in data)
                    report["gmsh_min_ige"] = float(ige)
                    if ige <= 0:
                        report["problems"].append(f"Gmsh's quality analysis finds a non-positive element ({ige:g})")
        finally:
            gmsh.finalize()
    except Exception as e:
        report["problems"].append(f"Gmsh cannot read the file: {e}")


def check(path, readers=True):
    report = {"file": path, "problems": []}
    try:
        with open(path, "r", encoding="ascii") as f:
            text = f.read()
        nodes, elements, names = parse(text)
    except (OSError, UnicodeDecodeError, MeshError, IndexError) as e:
        report["problems"].append(f"unreadable: {e}")
        report["valid"] = False
        return report
    tris = [en[:3] for etype, en, _ in elements if etype in TRIANGLES]
    inverted = degenerate = 0
    seen, duplicates, edges = set(), 0, set()
    min_a, max_e, sum_e = math.pi, 0.0, 0.0
    for a, b, c in tris:
        (ax, ay), (bx, by), (cx, cy) = nodes[a], nodes[b], nodes[c]
        det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)  # exact
        if det < 0:
            inverted += 1
        elif det == 0:
            degenerate += 1
        key = frozenset((a, b, c))
        duplicates += key in seen
        seen.add(key)
        for u, v in ((a, b), (b, c), (c, a)):
            edges.add((min(u, v), max(u, v)))
        fa, fb, fc = ((float(x), float(y)) for x, y in (nodes[a], nodes[b], nodes[c]))
        e = amips(fa, fb, fc)
        max_e, sum_e = max(max_e, e), sum_e + e
        min_a = min(min_a, min_angle(fa, fb, fc))
    lines, not_on_edges = {}, 0
    for etype, en, phys in elements:
        if etype in LINES:
            name = names.get((1, phys), str(phys))
            lines[name] = lines.get(name, 0) + 1
            if (min(en[0], en[1]), max(en[0], en[1])) not in edges:
                not_on_edges += 1
    used = {n for _, en, _ in elements for n in en}
    total_length = sum(math.dist([float(c) for c in nodes[u]], [float(c) for c in nodes[v]]) for u, v in edges)
    report.update(
        nodes=len(nodes), triangles=len(tris), edges=len(edges), inverted=inverted, degenerate=degenerate,
        duplicate_triangles=duplicates, unused_nodes=len(nodes) - len(used & nodes.keys()),
        min_angle_deg=math.degrees(min_a) if tris else 0.0, max_amips=max_e,
        mean_amips=sum_e / len(tris) if tris else 0.0,
        mean_edge_length=total_length / len(edges) if edges else 0.0, lines=lines,
        lines_not_on_edges=not_on_edges,
        physical_surfaces=sorted(n for (d, _), n in names.items() if d == 2))
    if not tris:
        report["problems"].append("no triangles")
    if inverted:
        report["problems"].append(f"{inverted} inverted (clockwise) triangles")
    if degenerate:
        report["problems"].append(f"{degenerate} degenerate (flat) triangles")
    if duplicates:
        report["problems"].append(f"{duplicates} duplicate triangles")
    if not_on_edges:
        report["problems"].append(f"{not_on_edges} line elements are not triangle edges")
    if readers and tris:
        check_with_readers(path, len(tris), report)
    report["valid"] = not report["problems"]
    return report


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("mesh")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a report")
    p.add_argument("--no-readers", action="store_true", help="skip the Gmsh and meshio reads")
    args = p.parse_args()
    report = check(args.mesh, readers=not args.no_readers)
    if args.json:
        print(json.dumps(report))
    else:
        for k, v in report.items():
            if k not in ("problems", "valid"):
                print(f"{k}: {v}")
        print("OK" if report["valid"] else "INVALID: " + "; ".join(report["problems"]))
    return 0 if report["valid"] else 1


if __name__ == "__main__":
    sys.exit(main())
