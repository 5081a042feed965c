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


def msh22(nodes, triangles, lines=(), kind=2):
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", "3",
           '1 1 "primary"', '1 3 "boundary"', '2 4 "domain"', "$EndPhysicalNames", "$Nodes", str(len(nodes))]
    out += [f"{i + 1} {x} {y} 0" for i, (x, y) in enumerate(nodes)]
    out += ["$EndNodes", "$Elements", str(len(lines) + len(triangles))]
    k = 1
    for phys, (a, b) in lines:
        out.append(f"{k} 1 2 {phys} {phys} {a} {b}")
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

print(f"{'all checks passed' if failures == 0 else f'{failures} checks failed'}")
sys.exit(1 if failures else 0)
