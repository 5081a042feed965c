#!/usr/bin/env python3
"""curvemesh's meshes in a real solver: FEniCSx (Debian's python3-dolfinx) solves Poisson's
equation on a disc drawn as a <circle> and on an ellipse drawn as an <ellipse>, meshed with
`--domain filled` at three sizes, and the L2 error against a manufactured solution that vanishes
on the true curve converges at the rate the geometry allows (the slope fitted to the three sizes): with cubic geometry and P3 at least
3.7, with quadratic geometry and P2 at least 2.7, and with straight triangles (`--order 1`) P2
stalls below 2.2 (the polygon is h² off the curve). Order 3 arrives through the .msh and the gmsh
API (dolfinx.io.gmshio.model_to_mesh), orders 1 and 2 through `--xdmf` (XDMFFile.read_mesh).
The region cell tags and one element's facet tags arrive in dolfinx with the areas and lengths
`--stats` reports (facet tags through XDMF: dolfinx's gmsh route keeps one tag per facet, the
smallest, which is the line's kind).

usage: fenicsx_test.py CURVEMESH_BINARY
"""
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import ufl
from dolfinx import fem, io
from mpi4py import MPI
from petsc4py import PETSc

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cli"))
from checks import check, finish  # noqa: E402

binary = sys.argv[1]
tmp = tempfile.TemporaryDirectory()
SIZES = [0.05, 0.025, 0.0125]  # -l: the target edge length relative to the drawing's diagonal

# (name, SVG element, the curve's implicit function phi: phi = 0 on it, > 0 inside).
SHAPES = [
    ("circle", '<circle id="disc" cx="0" cy="0" r="1" fill="black"/>', lambda x, y: 1 - x * x - y * y),
    ("ellipse", '<ellipse id="oval" cx="0" cy="0" rx="1.5" ry="0.8" fill="black"/>',
     lambda x, y: 1 - x * x / 2.25 - y * y / 0.64),
]


def svg_file(name, element):
    path = os.path.join(tmp.name, f"{name}.svg")
    with open(path, "w") as f:
        f.write(f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="-2 -2 4 4">{element}</svg>\n')
    return path


def mesh_file(svg, order, size, suffix, *extra):
    out = os.path.join(tmp.name, f"{os.path.basename(svg)[:-4]}-o{order}-l{size}")
    args = [binary, "mesh", svg, "-q", "--domain", "filled", "--order", str(order), "-l", str(size),
            "-o", out + ".msh", "--stats", out + ".json", *extra]
    if suffix == ".xdmf":
        args += ["--xdmf", out + ".xdmf"]
    run = subprocess.run(args, capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"{' '.join(args)}: {run.stderr}")
    with open(out + ".json") as f:
        return out + suffix, json.load(f)


def read_msh(path):
    """The mesh, cell tags and facet tags as dolfinx makes them from Gmsh's model of the file."""
    import gmsh
    from dolfinx.io import gmshio
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.open(path)
        return gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=2)
    finally:
        gmsh.finalize()


def read_xdmf(path):
    with io.XDMFFile(MPI.COMM_WORLD, path, "r") as f:
        mesh = f.read_mesh(name="mesh")
        cells = f.read_meshtags(mesh, name="cell_tags")
        mesh.topology.create_connectivity(1, 2)
        facets = f.read_meshtags(mesh, name="facet_tags")
    return mesh, cells, facets


def l2_error(mesh, degree, phi):
    """Solves -Δu = f, u = 0 on the mesh's boundary, for u = phi·exp(x + y/2) (0 on the true curve),
    and returns the L2 error over the mesh, integrated with a quadrature exact enough."""
    x = ufl.SpatialCoordinate(mesh)
    u_exact = phi(x[0], x[1]) * ufl.exp(x[0] + x[1] / 2)
    V = fem.FunctionSpace(mesh, ("Lagrange", degree))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    f = -ufl.div(ufl.grad(u_exact))
    mesh.topology.create_connectivity(1, 2)
    from dolfinx.mesh import exterior_facet_indices
    boundary = fem.locate_dofs_topological(V, 1, exterior_facet_indices(mesh.topology))
    bc = fem.dirichletbc(PETSc.ScalarType(0), boundary, V)
    problem = fem.petsc.LinearProblem(ufl.inner(ufl.grad(u), ufl.grad(v)) * ufl.dx, f * v * ufl.dx, bcs=[bc],
                                      petsc_options={"ksp_type": "preonly", "pc_type": "lu"})
    uh = problem.solve()
    dx = ufl.dx(metadata={"quadrature_degree": 2 * degree + 6})
    return math.sqrt(fem.assemble_scalar(fem.form((uh - u_exact) ** 2 * dx)))


def rates(errors, triangles):
    """The L2 rates between successive sizes, h taken as 1/sqrt(triangles)."""
    return [math.log(errors[i] / errors[i + 1]) / (0.5 * math.log(triangles[i + 1] / triangles[i]))
            for i in range(len(errors) - 1)]


def fitted_rate(errors, triangles):
    """The rate of the three sizes together: the least-squares slope of log(error) against log(h),
    h = 1/sqrt(triangles) (the meshes are adaptive: one step alone is noisy)."""
    h = np.log(np.array(triangles, dtype=float)) * -0.5
    return float(np.polyfit(h, np.log(np.array(errors)), 1)[0])


def study(name, element, phi, order, degree, suffix):
    svg = svg_file(name, element)
    errors, triangles = [], []
    for size in SIZES:
        path, stats = mesh_file(svg, order, size, suffix)
        mesh = (read_msh(path) if suffix == ".msh" else read_xdmf(path))[0]
        triangles.append(mesh.topology.index_map(2).size_local)
        errors.append(l2_error(mesh, degree, phi))
    r, fitted = rates(errors, triangles), fitted_rate(errors, triangles)
    print(f"{name}: order {order} geometry, P{degree}: triangles {triangles}, L2 errors "
          f"{', '.join(f'{e:.3g}' for e in errors)}, rates {', '.join(f'{x:.2f}' for x in r)}, fitted {fitted:.2f}")
    return fitted


TWO_SHAPES = ('<rect id="plate" x="-1.8" y="-1.5" width="3.6" height="3" fill="gray"/>'
              '<circle id="disc" cx="0.3" cy="0" r="1" fill="red"/>')


def measure(mesh, tags, dim, tag):
    """The area (dim 2) or length (dim 1: the facets inside the mesh and on its border) that
    dolfinx integrates over the entities with this tag."""
    one = fem.Constant(mesh, PETSc.ScalarType(1))
    if dim == 2:
        return fem.assemble_scalar(fem.form(one * ufl.dx(domain=mesh, subdomain_data=tags, subdomain_id=tag)))
    inside = ufl.dS(domain=mesh, subdomain_data=tags, subdomain_id=tag)
    border = ufl.ds(domain=mesh, subdomain_data=tags, subdomain_id=tag)
    return fem.assemble_scalar(fem.form(one("+") * inside + one * border))


def check_tags(order, suffix):
    """Regions as cell tags, and (through XDMF) the disc's outline, inside the mesh, as facet tags:
    what dolfinx integrates over them is what --stats says."""
    svg = svg_file("two", TWO_SHAPES)
    path, stats = mesh_file(svg, order, 0.05, suffix, "--regions")
    mesh, cells, facets = read_msh(path) if suffix == ".msh" else read_xdmf(path)
    groups = {(g["dim"], g["name"]): g for g in stats["groups"]}
    for name in ["plate", "disc"]:
        g = groups[(2, name)]
        area = measure(mesh, cells, 2, g["id"])
        check(f"order {order}{suffix}: region {name} arrives as cell tag {g['id']} with --stats' area",
              abs(area - g["area"]) <= 1e-9 * g["area"], f"{area} vs {g['area']}")
    if suffix == ".xdmf":
        g = groups[(1, "disc")]
        length = measure(mesh, facets, 1, g["id"])
        check(f"order {order}: the disc's outline arrives as facet tag {g['id']} with --stats' length",
              abs(length - g["length"]) <= 1e-9 * g["length"], f"{length} vs {g['length']}")
        check(f"order {order}: the outline is a circle's (2 pi r to 1e-6)", abs(length - 2 * math.pi) < 1e-6 * 2 * math.pi
              or order == 1, length)


def main():
    check_tags(3, ".msh")
    check_tags(2, ".xdmf")
    check_tags(1, ".xdmf")
    for name, element, phi in SHAPES:
        r3 = study(name, element, phi, 3, 3, ".msh")
        check(f"{name}: cubic geometry, P3 converges at rate >= 3.7", r3 >= 3.7, f"rate {r3}")
        r2 = study(name, element, phi, 2, 2, ".xdmf")
        check(f"{name}: quadratic geometry, P2 converges at rate >= 2.7", r2 >= 2.7, f"rate {r2}")
        r1 = study(name, element, phi, 1, 2, ".xdmf")
        check(f"{name}: straight triangles stall P2 below rate 2.2", r1 < 2.2, f"rate {r1}")
    finish()


if __name__ == "__main__":
    main()
