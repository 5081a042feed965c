#!/usr/bin/python3
"""Certifies a 2D triangle mesh in a Gmsh .msh file, independently of the code that wrote it.

Reads ASCII .msh 4.1 and 2.2 with its own parser and decides the orientation of every triangle
in exact rational arithmetic on the coordinates every reader of the file obtains: each decimal
in the text parsed to the nearest double (as Gmsh, meshio and ParaView do), then taken exactly as
a fraction, so no rounding in the test can hide an inverted or flat triangle. Triangles must be
counter-clockwise. For curved triangles (6 and 10 nodes) the Jacobian determinant of the element
map must be proved positive on the whole closed element, exactly as well (Bernstein coefficients
with subdivision, see check_curved), and neighbours must share their edge nodes. Line elements
must be triangle edges, interior nodes included. Then Gmsh (python3-gmsh) and meshio
(python3-meshio) must both read the file and see the same triangles, and Gmsh's Jacobian and its
quality analysis (min J / max J over each element, inverse gradient error) must be positive.
(Gmsh measures planar elements relative to their own normal, so a clockwise triangle looks valid
to it: orientation is decided by the exact test alone.)
It also reports the largest energy of the elements as maps (`max_element_amips`: the conformal
AMIPS energy from the equilateral triangle, for a curved element the largest over the 28
barycentric points of denominator 6, in floats), for callers that bound the quality.

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


# ---------------------------------------------------------------------------------------------
# Exact validity of curved (6- and 10-node) triangles.
#
# The element maps the reference triangle (ξ, η) ∈ {ξ, η ≥ 0, ξ + η ≤ 1} to the plane by Lagrange
# interpolation of its n = 2 or 3 order nodes. Written in barycentric coordinates
# λ = (λ0, λ1, λ2) = (1 − ξ − η, ξ, η) the same polynomial is a Bézier triangle
#     x(λ) = Σ_{|α| = n} P_α B^n_α(λ),   B^n_α(λ) = n!/(α0! α1! α2!) λ0^α0 λ1^α1 λ2^α2,
# whose control points P follow from the nodes by one fixed rational linear map (the nodes sit at
# the domain points α/n, and the Lagrange and Bernstein bases span the same space). With
# e0, e1, e2 the unit multi-indices, ∂x/∂ξ = ∂x/∂λ1 − ∂x/∂λ0 and the derivative of a Bézier
# triangle along λa is n Σ_{|β| = n−1} P_{β+ea} B^{n−1}_β, so
#     det J = (n Σ_β U_β B^{n−1}_β) × (n Σ_γ V_γ B^{n−1}_γ),  U_β = P_{β+e1} − P_{β+e0}, V_γ = P_{γ+e2} − P_{γ+e0},
# and with B^m_β B^m_γ = C(β) C(γ) / C(β+γ) B^{2m}_{β+γ} (C the multinomial coefficient) det J is
# a Bernstein polynomial of degree 2(n − 1) with coefficients
#     D_δ = n² / C(δ) Σ_{β+γ=δ} C(β) C(γ) U_β × V_γ.
# The Bernstein basis is nonnegative and sums to one, so all D_δ > 0 proves det J > 0 on the
# closed triangle; the coefficients at the corners (δ = d e_a) are the values there, so a corner
# coefficient ≤ 0 proves the element invalid. Otherwise the triangle is split at its edge midpoints
# into four and each part re-expanded (de Casteljau / blossoming), which tightens the coefficients
# to the values quadratically, and the test repeats to a depth limit.
#
# All of this is done in integers: the coordinates of an element are doubles, so multiplying them
# by the largest power-of-two denominator among them makes them integers, and every rational
# constant below is cleared by a common positive factor. Positive factors common to all
# coefficients of a polynomial do not change its sign anywhere.

CURVED_ORDER = {9: 2, 21: 3}  # element type -> polynomial order
CERTIFY_DEPTH = 12  # subdivision levels; a part then spans 1/4096 of the reference edge


def multi_indices(d):
    """The barycentric multi-indices (α0, α1, α2) with α0 + α1 + α2 = d."""
    return [(d - j - k, j, k) for j in range(d + 1) for k in range(d + 1 - j)]


def multinomial(alpha):
    return math.factorial(sum(alpha)) // math.prod(math.factorial(a) for a in alpha)


def reference_nodes(order):
    """Reference (ξ, η) of the Lagrange nodes in Gmsh's order: the corners (0,0), (1,0), (0,1);
    then the interior nodes of edges 0→1, 1→2, 2→0, each starting from its first corner at steps
    of 1/order; then, for order 3, the centre (1/3, 1/3)."""
    corners = [(Fraction(0), Fraction(0)), (Fraction(1), Fraction(0)), (Fraction(0), Fraction(1))]
    out = list(corners)
    for a, b in ((0, 1), (1, 2), (2, 0)):
        for s in range(1, order):
            t = Fraction(s, order)
            out.append(tuple((1 - t) * corners[a][i] + t * corners[b][i] for i in range(2)))
    if order == 3:
        out.append((Fraction(1, 3), Fraction(1, 3)))
    return out


def bernstein(alpha, lam):
    return multinomial(alpha) * math.prod(l ** a for l, a in zip(lam, alpha))


def invert(matrix):
    """Exact inverse of a square matrix of Fractions (Gauss–Jordan)."""
    n = len(matrix)
    a = [list(row) + [Fraction(int(i == j)) for j in range(n)] for i, row in enumerate(matrix)]
    for c in range(n):
        pivot = next(r for r in range(c, n) if a[r][c] != 0)
        a[c], a[pivot] = a[pivot], a[c]
        a[c] = [v / a[c][c] for v in a[c]]
        for r in range(n):
            if r != c and a[r][c] != 0:
                f = a[r][c]
                a[r] = [v - f * w for v, w in zip(a[r], a[c])]
    return [row[n:] for row in a]


_maps = {}


def bezier_map(order):
    """(multi-indices, integer matrix T, positive scale s) with control point P_α = Σ_r T[α][r] x_r / s
    for the nodes x_r in Gmsh's order: the inverse of the matrix B^order_α(node r)."""
    if order not in _maps:
        alphas = multi_indices(order)
        nodes = reference_nodes(order)
        lam = [(1 - xi - eta, xi, eta) for xi, eta in nodes]
        inv = invert([[bernstein(alpha, l) for alpha in alphas] for l in lam])
        scale = math.lcm(*(v.denominator for row in inv for v in row))
        _maps[order] = (alphas, [[int(v * scale) for v in row] for row in inv], scale)
    return _maps[order]


def jacobian_bernstein(order, points):
    """Bernstein coefficients {δ: integer} of det J of the element with nodes `points` (Fractions, in
    Gmsh's order), each a common positive multiple of the true coefficient; and that multiple."""
    alphas, T, s = bezier_map(order)
    den = max(c.denominator for p in points for c in p)  # powers of two: the largest is their lcm
    ints = [(int(x * den), int(y * den)) for x, y in points]
    P = {alpha: (sum(t * x for t, (x, _) in zip(row, ints)), sum(t * y for t, (_, y) in zip(row, ints)))
         for alpha, row in zip(alphas, T)}  # s·den·(control point)
    m = order - 1
    e = ((1, 0, 0), (0, 1, 0), (0, 0, 1))

    def plus(a, b):
        return (a[0] + b[0], a[1] + b[1], a[2] + b[2])

    U = {b: (P[plus(b, e[1])][0] - P[plus(b, e[0])][0], P[plus(b, e[1])][1] - P[plus(b, e[0])][1]) for b in multi_indices(m)}
    V = {b: (P[plus(b, e[2])][0] - P[plus(b, e[0])][0], P[plus(b, e[2])][1] - P[plus(b, e[0])][1]) for b in multi_indices(m)}
    deltas = multi_indices(2 * m)
    common = math.lcm(*(multinomial(d) for d in deltas))
    sums = dict.fromkeys(deltas, 0)
    for b, u in U.items():
        for g, v in V.items():
            sums[plus(b, g)] += multinomial(b) * multinomial(g) * (u[0] * v[1] - u[1] * v[0])
    # True D_δ = order² sums_δ / (C(δ) (s·den)²); scaled here by common·(s·den)²/order².
    return {d: sums[d] * (common // multinomial(d)) for d in deltas}, Fraction(common * (s * den) ** 2, order ** 2)


def subdivide(coeffs, degree, triangle):
    """Coefficients of the same polynomial on the sub-triangle with the given vertices (integer
    barycentric triples, each summing to 2), all scaled by 2^degree: the blossom
    f(v0^i, v1^j, v2^k) by de Casteljau steps with v0, then v1, then v2."""
    def step(c, d, v):  # degree d -> d − 1, evaluating one argument of the blossom at v
        return {a: v[0] * c[(a[0] + 1, a[1], a[2])] + v[1] * c[(a[0], a[1] + 1, a[2])] + v[2] * c[(a[0], a[1], a[2] + 1)]
                for a in multi_indices(d - 1)}

    out = {}
    after_i = coeffs
    for i in range(degree + 1):
        if i:
            after_i = step(after_i, degree - i + 1, triangle[0])
        after_j = after_i
        for j in range(degree - i + 1):
            if j:
                after_j = step(after_j, degree - i - j + 1, triangle[1])
            c, d = after_j, degree - i - j
            while d:
                c, d = step(c, d, triangle[2]), d - 1
            out[(i, j, degree - i - j)] = c[(0, 0, 0)]
    return out


# The four halves-of-edges sub-triangles, vertices as barycentric triples times 2.
_CHILDREN = (((2, 0, 0), (1, 1, 0), (1, 0, 1)), ((1, 1, 0), (0, 2, 0), (0, 1, 1)),
             ((1, 0, 1), (0, 1, 1), (0, 0, 2)), ((0, 1, 1), (1, 0, 1), (1, 1, 0)))


def certify_positive(coeffs, degree, depth=CERTIFY_DEPTH):
    """'positive' when the Bernstein polynomial is proved > 0 on the closed triangle, 'not positive'
    when a value ≤ 0 is found at a (sub-)triangle corner, 'undecided' at the depth limit; and the
    number of subdivisions done. Depth first, stopping at the first decisive finding."""
    corners = ((degree, 0, 0), (0, degree, 0), (0, 0, degree))
    stack, splits = [(coeffs, 0)], 0
    while stack:
        c, level = stack.pop()
        if any(c[k] <= 0 for k in corners):
            return "not positive", splits
        if all(v > 0 for v in c.values()):
            continue
        if level == depth:
            return "undecided", splits
        splits += 1
        stack.extend((subdivide(c, degree, t), level + 1) for t in _CHILDREN)
    return "positive", splits


# Float statistics: det J sampled on the lattice of barycentric points with denominator 8.
_SAMPLES = [tuple(Fraction(a, 8) for a in alpha) for alpha in multi_indices(8)]
_sample_basis = {}


def sampled_minimum(coeffs, degree):
    """Minimum over the sample lattice of the polynomial with float coefficients {δ: value}."""
    if degree not in _sample_basis:
        _sample_basis[degree] = [[(d, float(bernstein(d, lam))) for d in multi_indices(degree)] for lam in _SAMPLES]
    return min(sum(coeffs[d] * b for d, b in row) for row in _sample_basis[degree])


def check_curved(etype, points):
    """(verdict, subdivisions, scaled Jacobian estimate) of one 6- or 10-node triangle: the verdict
    of certify_positive, and min det J / det J of the straight triangle through the corners (None
    when that triangle is not counter-clockwise)."""
    order = CURVED_ORDER[etype]
    coeffs, factor = jacobian_bernstein(order, points)
    verdict, splits = certify_positive(coeffs, 2 * (order - 1))
    (ax, ay), (bx, by), (cx, cy) = points[:3]
    straight = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)  # det J of the straight triangle
    scaled = None
    if straight > 0:
        unit = factor * straight  # coefficients are det J times `factor`
        scaled = sampled_minimum({d: float(Fraction(v) / unit) for d, v in coeffs.items()}, 2 * (order - 1))
    return verdict, splits, scaled


# The energy of a curved element: the conformal AMIPS energy of its map, measured from the
# equilateral triangle (as `amips` below for a straight one), at the 28 points of the barycentric
# lattice of denominator 6; the largest value, in floats. Infinite where det J ≤ 0.
_AMIPS_LATTICE = [tuple(Fraction(a, 6) for a in alpha) for alpha in multi_indices(6)]
_derivative_basis = {}


def curved_amips(etype, points):
    order = CURVED_ORDER[etype]
    alphas, T, s = bezier_map(order)
    xy = [(float(x), float(y)) for x, y in points]
    P = {alpha: (sum(t * x for t, (x, _) in zip(row, xy)) / s, sum(t * y for t, (_, y) in zip(row, xy)) / s)
         for alpha, row in zip(alphas, T)}  # the Bézier control points
    m = order - 1
    if m not in _derivative_basis:
        _derivative_basis[m] = [[(b, float(bernstein(b, lam))) for b in multi_indices(m)] for lam in _AMIPS_LATTICE]
    worst = 0.0
    for row in _derivative_basis[m]:
        # dx/dξ = order Σ B_β (P_β+e1 − P_β+e0), dx/dη = order Σ B_β (P_β+e2 − P_β+e0).
        u = [0.0, 0.0]
        v = [0.0, 0.0]
        for (b0, b1, b2), w in row:
            p0, p1, p2 = P[(b0 + 1, b1, b2)], P[(b0, b1 + 1, b2)], P[(b0, b1, b2 + 1)]
            for i in range(2):
                u[i] += order * w * (p1[i] - p0[i])
                v[i] += order * w * (p2[i] - p0[i])
        det = u[0] * v[1] - u[1] * v[0]
        if det <= 0:
            return math.inf
        f = (2 * v[0] - u[0], 2 * v[1] - u[1])
        worst = max(worst, (3 * (u[0] ** 2 + u[1] ** 2) + f[0] ** 2 + f[1] ** 2) / (2 * math.sqrt(3) * det))
    return worst


def oriented_edge(a, b, interior):
    """(key, interior node tags) of an edge between corner tags a and b whose interior nodes are
    listed from a to b, both read from the lower corner tag."""
    interior = list(interior)
    return ((a, b), interior) if a < b else ((b, a), interior[::-1])


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
            # Gmsh's mesh quality analysis, over the whole of each element (by its own Bézier
            # bounds): with JacobianDeterminant, Gmsh 4.8 makes a view "minJ/maxJ 2D" whose one
            # column per element holds min det J / max det J (maxJ / minJ when det J < 0 throughout,
            # and 0 when max det J = 0), so a value ≤ 0 means det J vanishes or changes sign on the
            # element; with IGEMeasure a view "IGE 2D" holding the inverse gradient error measure,
            # positive for valid elements.
            gmsh.plugin.setNumber("AnalyseMeshQuality", "JacobianDeterminant", 1)
            gmsh.plugin.setNumber("AnalyseMeshQuality", "IGEMeasure", 1)
            gmsh.plugin.setNumber("AnalyseMeshQuality", "CreateView", 1)
            gmsh.plugin.setNumber("AnalyseMeshQuality", "DimensionOfElements", 2)
            gmsh.plugin.run("AnalyseMeshQuality")
            for view in gmsh.view.getTags():
                name = gmsh.option.getString(f"View[{gmsh.view.getIndex(view)}].Name")
                _, _, data, _, _ = gmsh.view.getModelData(view, 0)
                if not data:
                    continue
                lowest = float(min(d[0] for d in data))
                if name.startswith("minJ/maxJ"):
                    report["gmsh_min_jacobian_ratio"] = lowest
                    if lowest <= 0:
                        report["problems"].append(f"Gmsh's quality analysis finds det J ≤ 0 in an element "
                                                  f"(min J / max J = {lowest:g})")
                elif name.startswith("IGE"):
                    report["gmsh_min_ige"] = lowest
                    if lowest <= 0:
                        report["problems"].append(f"Gmsh's quality analysis finds a non-positive element (IGE {lowest:g})")
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
    curved = [(etype, en) for etype, en, _ in elements if etype in CURVED_ORDER]
    inverted = degenerate = 0
    seen, duplicates, edges = set(), 0, set()
    min_a, max_e, sum_e = math.pi, 0.0, 0.0
    max_straight_e = 0.0  # over the 3-node triangles (the energy of the others is their map's, below)
    kinds = [etype for etype, _, _ in elements if etype in TRIANGLES]
    for (a, b, c), kind in zip(tris, kinds):
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
        if kind not in CURVED_ORDER:
            max_straight_e = max(max_straight_e, e)
        min_a = min(min_a, min_angle(fa, fb, fc))
    # Every edge with its interior nodes read from its lower corner tag: triangles that share an
    # edge must share these nodes too, or the mesh is not conforming (a crack, or an overlap, even
    # when duplicated nodes sit at the same positions).
    edge_nodes, unshared = {}, 0
    for etype, en, _ in elements:
        if etype in TRIANGLES:
            inner = CURVED_ORDER.get(etype, 1) - 1  # interior nodes per edge
            for k, (i, j) in enumerate(((0, 1), (1, 2), (2, 0))):
                key, interior = oriented_edge(en[i], en[j], en[3 + k * inner:3 + (k + 1) * inner])
                if edge_nodes.setdefault(key, interior) != interior:
                    unshared += 1
    # Line elements must be triangle edges, interior nodes included.
    lines, not_on_edges = {}, 0
    for etype, en, phys in elements:
        if etype in LINES:
            name = names.get((1, phys), str(phys))
            lines[name] = lines.get(name, 0) + 1
            key, interior = oriented_edge(en[0], en[1], en[2:])
            if edge_nodes.get(key) != interior:
                not_on_edges += 1
    # Curved triangles: exact positivity of det J on the whole element.
    not_positive = uncertified = subdivided = 0
    min_scaled, max_curved_e = math.inf, 0.0
    for etype, en in curved:
        verdict, splits, scaled = check_curved(etype, [nodes[n] for n in en])
        max_curved_e = max(max_curved_e, curved_amips(etype, [nodes[n] for n in en]))
        not_positive += verdict == "not positive"
        uncertified += verdict == "undecided"
        subdivided += splits > 0
        if scaled is not None:
            min_scaled = min(min_scaled, scaled)
    used = {n for _, en, _ in elements for n in en}
    total_length = sum(math.dist([float(c) for c in nodes[u]], [float(c) for c in nodes[v]]) for u, v in edges)
    report.update(
        nodes=len(nodes), triangles=len(tris), edges=len(edges), inverted=inverted, degenerate=degenerate,
        duplicate_triangles=duplicates, unused_nodes=len(nodes) - len(used & nodes.keys()),
        min_angle_deg=math.degrees(min_a) if tris else 0.0, max_amips=max_e,
        max_element_amips=max(max_curved_e, max_straight_e),
        mean_amips=sum_e / len(tris) if tris else 0.0,
        mean_edge_length=total_length / len(edges) if edges else 0.0, lines=lines,
        lines_not_on_edges=not_on_edges, edges_not_shared=unshared,
        curved=len(curved), curved_invalid=not_positive + uncertified, curved_not_positive=not_positive,
        curved_uncertified=uncertified, curved_subdivided=subdivided,
        min_scaled_jacobian=min_scaled if min_scaled < math.inf else None,
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
    if unshared:
        report["problems"].append(f"edge nodes not shared: {unshared} triangle edges use other nodes than their neighbour's")
    if not_positive:
        report["problems"].append(f"{not_positive} curved triangles have a Jacobian determinant ≤ 0 somewhere")
    if uncertified:
        report["problems"].append(f"{uncertified} curved triangles could not be certified (det J > 0 not proved "
                                  f"after {CERTIFY_DEPTH} subdivisions)")
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
