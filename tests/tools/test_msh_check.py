#!/usr/bin/python3
"""Self-test of msh_check.py on hand-written meshes whose verdict is known."""
import json
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
checker = os.path.join(here, "msh_check.py")
tmp = tempfile.TemporaryDirectory()
failures = 0


def check(name, condition, detail=""):
    global failures
    if not condition:
        failures += 1
        print(f"FAIL {name}: {detail}")


def run(name, text):
    path = os.path.join(tmp.name, name + ".msh")
    with open(path, "w") as f:
        f.write(text)
    r = subprocess.run([sys.executable, checker, path, "--json"], capture_output=True, text=True, timeout=120)
    try:
        return r.returncode, json.loads(r.stdout)
    except json.JSONDecodeError:
        return r.returncode, {"stdout": r.stdout, "stderr": r.stderr}


def msh22(nodes, triangles, lines=(), kind=2, line_kind=1):
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "3",
           '1 1 "primary"', '1 3 "boundary"', '2 4 "domain"', "$EndPhysicalNames", "$Nodes", str(len(nodes))]
    out += [f"{i + 1} {x} {y} 0" for i, (x, y) in enumerate(nodes)]
    out += ["$EndNodes", "$Elements", str(len(lines) + len(triangles))]
    k = 1
    for phys, tags in lines:
        out.append(f"{k} {line_kind} 2 {phys} {phys} " + " ".join(map(str, tags)))
        k += 1
    for t in triangles:
        out.append(f"{k} {kind} 2 4 1 " + " ".join(map(str, t)))
        k += 1
    return "\n".join(out + ["$EndElements"]) + "\n"


def msh41(nodes, triangles, kind=2):
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", "1", '2 4 "domain"', "$EndPhysicalNames",
           "$Entities", "0 0 1 0", "1 0 0 0 1 1 0 1 4 0", "$EndEntities",
           "$Nodes", f"1 {len(nodes)} 1 {len(nodes)}", f"2 1 0 {len(nodes)}"]
    out += [str(i + 1) for i in range(len(nodes))]
    out += [f"{x} {y} 0" for x, y in nodes]
    out += ["$EndNodes", "$Elements", f"1 {len(triangles)} 1 {len(triangles)}", f"2 1 {kind} {len(triangles)}"]
    out += [f"{k + 1} " + " ".join(map(str, t)) for k, t in enumerate(triangles)]
    return "\n".join(out + ["$EndElements"]) + "\n"


square = [(0, 0), (1, 0), (1, 1), (0, 1)]
boundary = [(3, (1, 2)), (3, (2, 3)), (3, (3, 4)), (3, (4, 1)), (1, (1, 3))]
for version, text in (("2.2", msh22(square, [(1, 2, 3), (1, 3, 4)], boundary)), ("4.1", msh41(square, [(1, 2, 3), (1, 3, 4)]))):
    rc, r = run("square" + version, text)
    check(f"square {version}: valid", rc == 0 and r.get("valid"), r)
    check(f"square {version}: 2 triangles", r.get("triangles") == 2, r)
    check(f"square {version}: min angle 45", abs(r.get("min_angle_deg", 0) - 45) < 1e-9, r)
    # Right isosceles: ‖J‖² = 1 + 5/3 = 8/3, det J = 2/√3, so E = 4/√3.
    check(f"square {version}: AMIPS 4/sqrt(3)", abs(r.get("max_amips", 0) - 4 / 3 ** 0.5) < 1e-12, r)
    check(f"square {version}: mean edge", abs(r.get("mean_edge_length", 0) - (4 + 2 ** 0.5) / 5) < 1e-12, r)
rc, r = run("square-lines", msh22(square, [(1, 2, 3), (1, 3, 4)], boundary))
check("line groups counted by name", r.get("lines") == {"boundary": 4, "primary": 1}, r)

rc, r = run("clockwise", msh22(square, [(1, 3, 2), (1, 3, 4)]))
check("clockwise: exit 1", rc == 1, r)
check("clockwise: 1 inverted", r.get("inverted") == 1, r)

rc, r = run("collinear", msh22([(0, 0), (1, 1), (2, 2)], [(1, 2, 3)]))
check("collinear: degenerate", rc == 1 and r.get("degenerate") == 1, r)

# The doubles a reader parses decide, not the decimal text. (0, 0), (1, 1), (3, 3.0000000000000001)
# is thin but counter-clockwise as written, yet the last coordinate reads as the double 3.0: flat
# for Gmsh and for every other reader, so flat for the checker (Gmsh agrees: Jacobian 0).
rc, r = run("decimal-thin", msh22([(0, 0), (1, 1), ("3", "3.0000000000000001")], [(1, 2, 3)]))
check("doubles decide: flat when read", rc == 1 and r.get("degenerate") == 1 and r.get("gmsh_min_jacobian") == 0, r)
# Tiny is not flat: (0, 0), (1, 0), (2, 1e-300) is counter-clockwise in doubles, and the exact
# test says so (Gmsh's own analysis may round it to zero, hence only the exact counts here).
rc, r = run("tiny-but-positive", msh22([(0, 0), (1, 0), ("2", "1e-300")], [(1, 2, 3)]))
check("doubles decide: tiny positive area is valid in the exact test", r.get("inverted") == 0 and r.get("degenerate") == 0, r)
rc, r = run("decimal-inverted", msh22([(0, 0), ("1", "1e-17"), ("2", "0")], [(1, 2, 3)]))
check("doubles decide: clockwise by 1e-17 is inverted", rc == 1 and r.get("inverted") == 1, r)

rc, r = run("stray-line", msh22(square, [(1, 2, 3), (1, 3, 4)], [(1, (2, 4))]))
check("line not on an edge: invalid", rc == 1 and r.get("lines_not_on_edges") == 1, r)

rc, r = run("truncated", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n$EndNodes\n")
check("truncated: exit 1 without traceback", rc == 1 and "unreadable" in json.dumps(r) and "Traceback" not in json.dumps(r), r)

# A 10-node triangle in Gmsh's order: corners, two nodes per edge (0-1, 1-2, 2-0), centre.
p3 = [(0, 0), (3, 0), (0, 3), (1, 0), (2, 0), (2, 1), (1, 2), (0, 2), (0, 1), (1, 1)]
rc, r = run("p3", msh41(p3, [tuple(range(1, 11))], kind=21))
check("10-node triangle: valid", rc == 0 and r.get("triangles") == 1, r)

# ---- Curved triangles: det J must be proved positive on the whole element. ----
import math  # noqa: E402

sys.path.insert(0, here)
import msh_check  # noqa: E402

# The checker's node order is Gmsh's (reference coordinates of the 6- and 10-node triangles).
try:
    import gmsh
    gmsh.initialize()
    for etype, order in ((9, 2), (21, 3)):
        ref = gmsh.model.mesh.getElementProperties(etype)[4]
        ours = [float(c) for node in msh_check.reference_nodes(order) for c in node]
        check(f"type {etype}: node order is Gmsh's", len(ref) == len(ours) and max(abs(a - b) for a, b in zip(ref, ours)) < 1e-15,
              (list(ref), ours))
    gmsh.finalize()
except ImportError as e:
    check("python3-gmsh available", False, e)


def curved(name, nodes, kind, expect_valid, **expect):
    """One curved triangle (nodes in Gmsh's order, all of them its own) in both file versions."""
    for version, text in (("2.2", msh22(nodes, [tuple(range(1, len(nodes) + 1))], kind=kind)),
                          ("4.1", msh41(nodes, [tuple(range(1, len(nodes) + 1))], kind=kind))):
        rc, r = run(f"{name}-{version}", text)
        label = f"{name} {version}"
        check(f"{label}: corners counter-clockwise", r.get("inverted") == 0 and r.get("degenerate") == 0, r)
        check(f"{label}: one curved triangle", r.get("curved") == 1, r)
        if expect_valid:
            check(f"{label}: valid", rc == 0 and r.get("valid") and r.get("curved_invalid") == 0, r)
        else:
            check(f"{label}: INVALID", rc == 1 and r.get("curved_invalid") == 1, r)
        for key, value in expect.items():
            got = r.get(key)
            ok = value(got) if callable(value) else got == value
            check(f"{label}: {key}", ok, r)


c30, s30 = math.cos(math.pi / 6), math.sin(math.pi / 6)
for order, kind in ((3, 21), (2, 9)):
    P = f"P{order}"
    if order == 3:
        straight = [(0, 0), (3, 0), (0, 3), (1, 0), (2, 0), (2, 1), (1, 2), (0, 2), (0, 1), (1, 1)]
        # Edge 1→2 on the unit circle about corner 0, nodes at 30° and 60°.
        arc = [(0, 0), (1, 0), (0, 1), (1 / 3, 0), (2 / 3, 0), (c30, s30), (s30, c30), (0, 2 / 3), (0, 1 / 3), (1 / 3, 1 / 3)]
        # The first node of edge 0→1 pushed beyond the opposite side (x + y = 3): still three
        # counter-clockwise corners, but the element folds over itself.
        fold = [(0, 0), (3, 0), (0, 3), (2, 4), (2, 0), (2, 1), (1, 2), (0, 2), (0, 1), (1, 1)]
        # That node only lifted to (1, 5/8): the Bernstein coefficients of det J are not all positive,
        # but det J is (min det J / straight det J ≈ 0.023, on edge η = 0 near ξ = 0.42).
        border = [(0, 0), (3, 0), (0, 3), (1, 0.625), (2, 0), (2, 1), (1, 2), (0, 2), (0, 1), (1, 1)]
        # Edge 0→1 the cubic with control points (0,0), (0,9), (18,0), (27,0): it leaves corner 0
        # along edge 2→0, so det J = 0 exactly there (nodes at t = 1/3, 2/3: (5,4), (16,2)).
        cusp = [(0, 0), (27, 0), (0, 27), (5, 4), (16, 2), (18, 9), (9, 18), (0, 18), (0, 9), (9, 9)]
    else:
        straight = [(0, 0), (2, 0), (0, 2), (1, 0), (1, 1), (0, 1)]
        arc = [(0, 0), (1, 0), (0, 1), (0.5, 0), (math.sqrt(0.5), math.sqrt(0.5)), (0, 0.5)]
        fold = [(0, 0), (2, 0), (0, 2), (1, 3), (1, 1), (0, 1)]
        # All three edge nodes moved: some coefficients negative, det J positive.
        border = [(0, 0), (4, 0), (0, 4), (2.5, 2), (3.5, 1.75), (-0.25, 2.5)]
        # Edge 0→1 the quadratic with control points (0,0), (0,2), (4,0): tangent to edge 2→0.
        cusp = [(0, 0), (4, 0), (0, 4), (1, 1), (2, 2), (0, 2)]
    curved(f"{P} straight", straight, kind, True, min_scaled_jacobian=lambda v: v is not None and abs(v - 1) < 1e-12,
           curved_subdivided=0)
    curved(f"{P} circle arc", arc, kind, True, curved_subdivided=0)
    curved(f"{P} folded by an edge node", fold, kind, False, curved_not_positive=1,
           min_scaled_jacobian=lambda v: v is not None and v < 0)
    # Gmsh's own analysis must agree that the borderline element is valid, and subdivision must
    # have been needed to prove it.
    curved(f"{P} borderline", border, kind, True, curved_subdivided=1,
           gmsh_min_jacobian_ratio=lambda v: v is not None and v > 0,
           min_scaled_jacobian=lambda v: v is not None and 0 < v < 0.2)
    curved(f"{P} det J = 0 at a corner", cusp, kind, False, curved_not_positive=1, min_scaled_jacobian=0.0)

# The energy of a curved element, against the derivatives of its map taken by hand: a cubic map
# (which the 10-node and, for its quadratic part, the 6-node element reproduce exactly), its
# AMIPS energy from the equilateral triangle at the 28 points (j/6, k/6), the largest.
def cubic_map(xi, eta, order):
    x = 2 * xi + 0.5 * eta + 0.3 * xi * eta + (0.2 * xi ** 3 - 0.1 * eta ** 2 * xi if order == 3 else 0)
    y = 1.7 * eta + 0.2 * xi + 0.25 * xi ** 2 + (0.15 * eta ** 3 if order == 3 else 0)
    dx = (2 + 0.3 * eta + (0.6 * xi ** 2 - 0.1 * eta ** 2 if order == 3 else 0),
          0.5 + 0.3 * xi - (0.2 * eta * xi if order == 3 else 0))
    dy = (0.2 + 0.5 * xi, 1.7 + (0.45 * eta ** 2 if order == 3 else 0))
    return (x, y), dx, dy


for order, kind in ((3, 21), (2, 9)):
    ref = msh_check.reference_nodes(order)
    nodes = [msh_check.Fraction(v) for xi, eta in ref for v in cubic_map(float(xi), float(eta), order)[0]]
    nodes = list(zip(nodes[0::2], nodes[1::2]))
    by_hand = 0.0
    for j in range(7):
        for k in range(7 - j):
            _, (xu, xv), (yu, yv) = cubic_map(j / 6, k / 6, order)
            u, v = (xu, yu), (xv, yv)  # the columns of J: d/dξ, d/dη
            det = u[0] * v[1] - u[1] * v[0]
            f = (2 * v[0] - u[0], 2 * v[1] - u[1])
            by_hand = max(by_hand, (3 * (u[0] ** 2 + u[1] ** 2) + f[0] ** 2 + f[1] ** 2) / (2 * math.sqrt(3) * det))
    got = msh_check.curved_amips(kind, nodes)
    check(f"P{order}: curved AMIPS is the map's", abs(got - by_hand) < 1e-9 * by_hand, (got, by_hand))
    rc, r = run(f"amips-P{order}", msh41([(float(x), float(y)) for x, y in nodes], [tuple(range(1, len(nodes) + 1))],
                                          kind=kind))
    check(f"P{order}: max_element_amips reported", abs(r.get("max_element_amips", 0) - by_hand) < 1e-6 * by_hand, r)
# A straight element's energy is its triangle's, curved or not: equilateral 2.
eq = [(0, 0), (1, 0), (0.5, math.sqrt(3) / 2)]
rc, r = run("equilateral", msh41(eq, [(1, 2, 3)]))
check("equilateral: max_element_amips 2", abs(r.get("max_element_amips", 0) - 2) < 1e-12, r)

# The decision itself on polynomials given by their Bernstein coefficients (degree 2):
# (λ0 − 2λ1)² + λ2 (λ0 + λ1 + λ2), times 2, is ≥ 0 and vanishes only at λ = (2/3, 1/3, 0), which no
# subdivision corner reaches: undecided at the depth limit (reported as invalid). Lifted by a
# small constant it is positive, and provably so after a few subdivisions.
touching = {(2, 0, 0): 2, (1, 1, 0): -4, (0, 2, 0): 8, (1, 0, 1): 1, (0, 1, 1): 1, (0, 0, 2): 2}
verdict, _ = msh_check.certify_positive(touching, 2)
check("double zero inside an edge: undecided", verdict == "undecided", verdict)
verdict, splits = msh_check.certify_positive({k: 64 * v + 1 for k, v in touching.items()}, 2)
check("the same lifted by 1/64: positive after subdivision", verdict == "positive" and splits > 0, (verdict, splits))
verdict, _ = msh_check.certify_positive({k: 64 * v - 1 for k, v in touching.items()}, 2)
check("the same lowered by 1/64: not positive", verdict == "not positive", verdict)


def lagrange_mesh(corners, triangles, order, share=True):
    """Nodes and 1-based element node lists of triangles with straight edges of the given order,
    edge nodes shared by neighbours (or each triangle's own when share is False), and the edge
    nodes by corner pair (from the lower tag)."""
    nodes, elements, edge_tags = list(corners), [], {}
    for t in triangles:
        en = list(t)
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(a, b), max(a, b))
            if not share or key not in edge_tags:
                (x0, y0), (x1, y1) = corners[key[0] - 1], corners[key[1] - 1]
                tags = []
                for s in range(1, order):
                    nodes.append((x0 + (x1 - x0) * s // order, y0 + (y1 - y0) * s // order))
                    tags.append(len(nodes))
                edge_tags[key] = tags
            en += edge_tags[key] if a == key[0] else edge_tags[key][::-1]
        if order == 3:
            nodes.append(tuple(sum(corners[c - 1][i] for c in t) // 3 for i in range(2)))
            en.append(len(nodes))
        elements.append(tuple(en))
    return nodes, elements, edge_tags


square6 = [(0, 0), (6, 0), (6, 6), (0, 6)]
for order, kind, line_kind in ((3, 21, 26), (2, 9, 8)):
    P = f"P{order}"
    for share in (True, False):
        nodes, elements, edge_tags = lagrange_mesh(square6, [(1, 2, 3), (1, 3, 4)], order, share)
        what = "shared" if share else "duplicated"
        for version, text in (("2.2", msh22(nodes, elements, kind=kind)), ("4.1", msh41(nodes, elements, kind=kind))):
            rc, r = run(f"{P}-square-{what}-{version}", text)
            if share:
                check(f"{P} square, shared edge nodes, {version}: valid", rc == 0 and r.get("edges_not_shared") == 0, r)
            else:
                check(f"{P} square, duplicated edge nodes, {version}: edge nodes not shared", rc == 1 and r.get("edges_not_shared") == 1
                      and "edge nodes not shared" in " ".join(r.get("problems", [])), r)
    # Boundary lines with interior nodes: must run along a triangle edge node for node.
    nodes, elements, edge_tags = lagrange_mesh(square6, [(1, 2, 3), (1, 3, 4)], order)
    good = [(3, (a, b, *edge_tags[(min(a, b), max(a, b))][:: 1 if a < b else -1])) for a, b in ((1, 2), (2, 3), (3, 4), (4, 1))]
    rc, r = run(f"{P}-lines", msh22(nodes, elements, good, kind=kind, line_kind=line_kind))
    check(f"{P} boundary lines on edges: valid", rc == 0 and r.get("lines_not_on_edges") == 0 and r.get("lines") == {"boundary": 4}, r)
    a, b, *inner = good[0][1]
    bad = good[1:] + [(3, (b, a, *inner))]  # interior nodes listed from the wrong end (or the only one, off by a tag)
    if order == 2:
        bad[-1] = (3, (a, b, inner[0] + 1))
    rc, r = run(f"{P}-lines-bad", msh22(nodes, elements, bad, kind=kind, line_kind=line_kind))
    check(f"{P} boundary line not matching an edge's nodes: invalid", rc == 1 and r.get("lines_not_on_edges") == 1, r)

# Meshes written by Gmsh itself: a disk, curved to order 3 and 2, in both file versions.
try:
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("disk")
    gmsh.model.occ.addDisk(0, 0, 0, 1, 1)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.3)
    gmsh.model.mesh.generate(2)
    written = []
    for order in (3, 2):
        gmsh.model.mesh.setOrder(order)
        for version in (4.1, 2.2):
            gmsh.option.setNumber("Mesh.MshFileVersion", version)
            path = os.path.join(tmp.name, f"gmsh-disk-P{order}-{version}.msh")
            gmsh.write(path)
            written.append((order, version, path))
    gmsh.finalize()
    for order, version, path in written:
        r = subprocess.run([sys.executable, checker, path, "--json"], capture_output=True, text=True, timeout=300)
        try:
            rep = json.loads(r.stdout)
        except json.JSONDecodeError:
            rep = {"stdout": r.stdout, "stderr": r.stderr}
        label = f"Gmsh's P{order} disk {version}"
        check(f"{label}: valid", r.returncode == 0 and rep.get("valid"), rep)
        check(f"{label}: all triangles curved and certified", rep.get("curved") == rep.get("triangles") > 10
              and rep.get("curved_invalid") == 0, rep)
        check(f"{label}: boundary lines on edges", rep.get("lines_not_on_edges") == 0 and sum(rep.get("lines", {}).values()) > 5, rep)
except ImportError as e:
    check("python3-gmsh available", False, e)

print(f"{'all checks passed' if failures == 0 else f'{failures} checks failed'}")
sys.exit(1 if failures else 0)
