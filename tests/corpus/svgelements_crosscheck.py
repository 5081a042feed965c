#!/usr/bin/python3
"""Cross-checks curvemesh's SVG reader against an independent parser, svgelements (Debian's
python3-svgelements), on a fixed list of openclipart drawings.

For each file, both readers give the drawn geometry; they agree when, up to a uniform scale and
translation (svgelements maps the root viewBox to the root's width/height, we keep viewBox
units), the bounding box's aspect ratio and the total curve length divided by the bounding-box
diagonal are both within --tolerance (relative). What is compared: every rendered shape (path,
rect, circle, ellipse, line, polyline, polygon) whatever its fill and stroke, not display:none,
not visibility:hidden, <use> instances included, defs/symbol contents only through <use>.
Isolated points (a lone moveto, a path within ε_m of a point) count in our box as lone movetos
count in svgelements'. Text is left out of ours: svgelements reads <text> but has no glyphs for it.

usage: svgelements_crosscheck.py --curvemesh BUILD/curvemesh [--list FILE] [--root DIR]
                                 [--jobs 2] [--min-agree 0.98] [--json-out FILE]
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

# 16-point Gauss–Legendre on [0, 1].
_X, _W = np.polynomial.legendre.leggauss(16)
GL_X, GL_W = (_X + 1) / 2, _W / 2


def cubic_lengths(p, pieces=8):
    """Arc lengths of n cubics, p of shape (n, 4, 2): composite Gauss–Legendre."""
    total = np.zeros(len(p))
    for k in range(pieces):
        t = (k + GL_X) / pieces  # (16,)
        s = 1 - t
        d = 3 * ((s * s)[None, :, None] * (p[:, 1] - p[:, 0])[:, None, :]
                 + (2 * s * t)[None, :, None] * (p[:, 2] - p[:, 1])[:, None, :]
                 + (t * t)[None, :, None] * (p[:, 3] - p[:, 2])[:, None, :])
        total += (np.linalg.norm(d, axis=2) * GL_W[None, :]).sum(axis=1) / pieces
    return total


def cubic_bbox(p):
    """Tight bounding box of n cubics by dense sampling plus the endpoints (error ~1e-7 relative)."""
    t = np.linspace(0, 1, 257)
    s = 1 - t
    pts = ((s ** 3)[None, :, None] * p[:, 0][:, None] + (3 * s * s * t)[None, :, None] * p[:, 1][:, None]
           + (3 * s * t * t)[None, :, None] * p[:, 2][:, None] + (t ** 3)[None, :, None] * p[:, 3][:, None])
    pts = pts.reshape(-1, 2)
    return pts.min(axis=0), pts.max(axis=0)


def ours(binary, path, tmp):
    out = os.path.join(tmp, os.path.basename(path) + ".json")
    r = subprocess.run([binary, "features", path, "-o", out], capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        return {"error": r.stderr.strip().splitlines()[0] if r.stderr.strip() else f"exit {r.returncode}"}
    data = json.load(open(out))
    os.remove(out)
    # curvemesh draws text as its glyphs' outlines, which svgelements does not have
    text = {i for i, s in enumerate(data["sources"]) if s["tag"] == "text"}
    data["curves"] = [c for c in data["curves"] if c["source"] not in text]
    data["points"] = [q for q, s in zip(data["points"], data.get("point_sources", [])) if s not in text]
    if not data["curves"]:
        return {"length": 0.0, "min": None, "max": None, "warnings": data["warnings"]}
    p = np.array([c["p"] for c in data["curves"]], dtype=float).reshape(-1, 4, 2)
    lo, hi = cubic_bbox(p)
    if data["points"]:  # isolated points (lone movetos, tiny paths) count in the box
        pts = np.array(data["points"], dtype=float)
        lo, hi = np.minimum(lo, pts.min(axis=0)), np.maximum(hi, pts.max(axis=0))
    return {"length": float(cubic_lengths(p).sum()), "min": lo.tolist(), "max": hi.tolist(),
            "warnings": data["warnings"]}


def theirs(path):
    """svgelements' geometry: its parse of shapes, path data and arcs in each element's own
    coordinates, and its composed transform (viewport included), applied here. (Reifying instead
    would let svgelements re-express an arc under a skew as another arc, which it gets wrong.)"""
    import svgelements as se
    svg = se.SVG.parse(path, reify=False)
    cubics, points, length = [], [], 0.0
    for e in svg.elements():
        if not isinstance(e, se.Shape) or e.values.get("visibility") in ("hidden", "collapse"):
            continue
        m = e.transform
        a, b, c, d, tx, ty = m.a, m.b, m.c, m.d, m.e, m.f

        def mapped(q):
            return (a * q[0] + c * q[1] + tx, b * q[0] + d * q[1] + ty)

        for seg in se.Path(e):
            if isinstance(seg, se.Move):
                if seg.end is not None:
                    points.append(mapped(seg.end))  # a lone moveto still counts in the box
                continue
            if seg.start is None or seg.end is None:
                continue
            if isinstance(seg, (se.Line, se.Close)):
                p0, p1 = mapped(seg.start), mapped(seg.end)
                length += math.dist(p0, p1)
                points += [p0, p1]
            elif isinstance(seg, se.CubicBezier):
                cubics.append([mapped(seg.start), mapped(seg.control1), mapped(seg.control2), mapped(seg.end)])
            elif isinstance(seg, se.QuadraticBezier):
                q0, q1, q2 = mapped(seg.start), mapped(seg.control), mapped(seg.end)
                cubics.append([q0, tuple(q0[i] + 2 / 3 * (q1[i] - q0[i]) for i in range(2)),
                               tuple(q2[i] + 2 / 3 * (q1[i] - q2[i]) for i in range(2)), q2])
            elif isinstance(seg, se.Arc):
                # svgelements' own evaluation of the arc, densely sampled, then mapped.
                n = 256
                pts = [mapped(seg.point(k / n)) for k in range(n + 1)]
                length += sum(math.dist(pts[k], pts[k + 1]) for k in range(n))
                points += pts
    lo, hi = [math.inf, math.inf], [-math.inf, -math.inf]
    if cubics:
        p = np.array(cubics, dtype=float)
        length += float(cubic_lengths(p).sum())
        clo, chi = cubic_bbox(p)
        lo, hi = [min(lo[i], clo[i]) for i in range(2)], [max(hi[i], chi[i]) for i in range(2)]
    for q in points:
        lo, hi = [min(lo[i], q[i]) for i in range(2)], [max(hi[i], q[i]) for i in range(2)]
    if lo[0] == math.inf:
        return {"length": 0.0, "min": None, "max": None}
    return {"length": length, "min": lo, "max": hi}


def measures(r):
    """Scale-free measures: aspect ratio and length / diagonal."""
    if r.get("min") is None:
        return None
    w, h = r["max"][0] - r["min"][0], r["max"][1] - r["min"][1]
    diag = math.hypot(w, h)
    if diag == 0:
        return None
    return {"aspect": w / h if h > 0 else math.inf, "length_per_diag": r["length"] / diag}


def relative(a, b):
    if a == b:
        return 0.0
    if math.isinf(a) or math.isinf(b):
        return math.inf
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def hints(path):
    text = open(path, encoding="utf-8", errors="replace").read()
    found = [k for k in ("<use", "<text", "clipPath", "<mask", "<pattern", "<marker", "<switch", "<symbol",
                         "preserveAspectRatio", "<!ENTITY", "<style", "display:none", "display=\"none\"")
             if k in text]
    if text.count("<svg") > 1:
        found.append("nested <svg>")
    return found


def check(args_path):
    binary, root, rel, tolerance = args_path
    path = os.path.join(root, rel)
    with tempfile.TemporaryDirectory() as tmp:
        a = ours(binary, path, tmp)
    if "error" in a:
        return {"file": rel, "status": "refused", "detail": a["error"]}
    try:
        b = theirs(path)
    except Exception as exc:  # the independent parser failed: counted, never hidden
        return {"file": rel, "status": "svgelements-failed", "detail": f"{type(exc).__name__}: {exc}"}
    ma, mb = measures(a), measures(b)
    if ma is None or mb is None:
        same = ma is None and mb is None
        return {"file": rel, "status": "agree" if same else "differ",
                "detail": "" if same else f"empty geometry: ours {ma}, svgelements {mb}"}
    da, dl = relative(ma["aspect"], mb["aspect"]), relative(ma["length_per_diag"], mb["length_per_diag"])
    ok = da <= tolerance and dl <= tolerance
    return {"file": rel, "status": "agree" if ok else "differ", "aspect": [ma["aspect"], mb["aspect"]],
            "length_per_diag": [ma["length_per_diag"], mb["length_per_diag"]], "rel_aspect": da,
            "rel_length": dl, "detail": "" if ok else ", ".join(hints(path))}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--curvemesh", required=True)
    parser.add_argument("--list", default=os.path.join(here, "crosscheck-files.txt"))
    parser.add_argument("--root", default="/usr/share/openclipart/svg")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--tolerance", type=float, default=2e-3)
    parser.add_argument("--min-agree", type=float, default=0.98)
    parser.add_argument("--json-out")
    args = parser.parse_args()

    files = [l.strip() for l in open(args.list) if l.strip() and not l.startswith("#")]
    missing = [f for f in files if not os.path.exists(os.path.join(args.root, f))]
    if missing:
        print(f"{len(missing)} listed files are missing under {args.root} (is openclipart-svg installed?)")
        return 2
    binary = os.path.abspath(args.curvemesh)
    with concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(check, [(binary, args.root, f, args.tolerance) for f in files]))

    for r in results:
        if r["status"] == "differ" and "aspect" in r:
            print(f"DIFFER {r['file']}: aspect {r['aspect'][0]:.6g} vs {r['aspect'][1]:.6g} "
                  f"(rel {r['rel_aspect']:.2e}), length/diag {r['length_per_diag'][0]:.6g} vs "
                  f"{r['length_per_diag'][1]:.6g} (rel {r['rel_length']:.2e}); uses: {r['detail']}")
        elif r["status"] != "agree":
            print(f"{r['status'].upper()} {r['file']}: {r['detail']}")
    agree = sum(r["status"] == "agree" for r in results)
    refused = sum(r["status"] == "refused" for r in results)
    failed = sum(r["status"] == "svgelements-failed" for r in results)
    share = agree / len(results)
    print(f"{agree}/{len(results)} files agree ({100 * share:.1f} %); curvemesh refused {refused}, "
          f"svgelements failed on {failed} (both counted as disagreements)")
    if args.json_out:
        with open(args.json_out, "w") as f:
            json.dump(results, f, indent=1)
    print(f"{1 if share >= args.min_agree else 0} passed, {0 if share >= args.min_agree else 1} failed")
    return 0 if share >= args.min_agree else 1


if __name__ == "__main__":
    sys.exit(main())
