#!/usr/bin/python3
"""Independent check of feature processing on openclipart drawings, by brute force over the
JSON that `curvemesh features --processed` writes (nothing of the stage's own bookkeeping is
trusted):

  1. primary polylines never cross: no two primary edges intersect except at a shared endpoint;
  2. the μ rule (docs/method.md, "Feature processing"): two primary edges are at least μ apart, unless
     they belong to one input curve (or to the cubics of one arc, the curves' `arc`) and are joined
     along it by at most π/2·μ of polyline (around a closed arc, a circle, either way) without
     folding back (adjacent edges meet at least at the junction angle, others point the same
     way), or share an endpoint and meet there at an angle of at least the junction angle;
  3. every secondary segment lies within ε of the input curve it came from (5 points per segment
     against the curve sampled as a 2,000-point polyline).

Edges are compared all against all (numpy, in blocks). Files with more than --max-edges primary
edges are skipped to bound the time; the run fails if fewer than --min-files were checked.

usage: features_check.py --curvemesh BUILD/curvemesh [--list FILE] [--root DIR] [--jobs 2]
"""
import argparse
import concurrent.futures
import json
import os
import subprocess
import sys
import tempfile

import numpy as np


def cross2(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def point_segment_distance(p, a, b):
    ab = b - a
    len2 = (ab * ab).sum(-1)
    t = np.where(len2 > 0, ((p - a) * ab).sum(-1) / np.where(len2 > 0, len2, 1), 0.0)
    t = np.clip(t, 0, 1)
    return np.linalg.norm(p - (a + t[..., None] * ab), axis=-1)


def segment_distances(a, b, c, d):
    """Distances between segments a-b (shape (n,1,2)) and c-d (shape (1,m,2)); 0 when they cross."""
    d1, d2 = cross2(b - a, c - a), cross2(b - a, d - a)
    d3, d4 = cross2(d - c, a - c), cross2(d - c, b - c)
    crossing = (d1 * d2 < 0) & (d3 * d4 < 0)
    dist = np.minimum.reduce([point_segment_distance(a, c, d), point_segment_distance(b, c, d),
                              point_segment_distance(c, a, b), point_segment_distance(d, a, b)])
    return np.where(crossing, 0.0, dist), crossing


def check_file(args_path):
    binary, root, rel, max_edges = args_path
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "f.json")
        r = subprocess.run([binary, "features", os.path.join(root, rel), "-o", out, "--processed"],
                           capture_output=True, text=True, timeout=300)
        if r.returncode != 0:
            return {"file": rel, "status": "error", "detail": r.stderr.strip()[:300]}
        data = json.load(open(out))
    par = data["parameters"]
    mu, eps, junction = par["mu"], par["epsilon"], np.radians(par["junction_angle_deg"])
    tol = 1e-12 * par["d"]

    # Primary edges with their section and position in it.
    # The sections of one input curve follow each other in the JSON and share endpoints, and so do
    # those of the cubics one arc was cut into: chain them, so that the "joined by π/2·μ of
    # polyline" rule measures along the whole curve. A chain of an arc's cubics that ends where it
    # starts (a circle) is closed.
    arc_of = [c.get("arc", -1) for c in data["curves"]]
    a_list, b_list, sec, along = [], [], [], []
    chain, chain_end, chain_len, chain_arc = -1, None, 0.0, -1
    totals, closed, chain_start, chain_first = [], [], None, -1
    for s in data["sections"]:
        poly = s["polyline"]
        arc = arc_of[s["curve"]]
        same_curve = chain_end is not None and s["curve"] == chain_curve and poly[0] == chain_end
        same_arc = chain_end is not None and arc >= 0 and arc == chain_arc and poly[0] == chain_end
        if not (same_curve or same_arc):
            chain += 1
            chain_len, chain_start, chain_first = 0.0, poly[0], s["curve"]
            totals.append(0.0)
            closed.append(False)
        chain_curve, chain_end, chain_arc = s["curve"], poly[-1], arc
        closed[chain] = arc >= 0 and s["curve"] != chain_first and poly[-1] == chain_start
        for k in range(len(poly) - 1):
            length = float(np.hypot(poly[k + 1][0] - poly[k][0], poly[k + 1][1] - poly[k][1]))
            if s["kind"] == "primary":
                a_list.append(poly[k])
                b_list.append(poly[k + 1])
                sec.append(chain)
                along.append(chain_len)
            chain_len += length
        totals[chain] = chain_len
    n = len(a_list)
    if n > max_edges:
        return {"file": rel, "status": "skipped", "detail": f"{n} primary edges"}
    problems = []
    if n:
        A, B = np.array(a_list, float), np.array(b_list, float)
        sec, along = np.array(sec), np.array(along)
        chain_total, chain_closed = np.array(totals), np.array(closed, bool)
        edge_len = np.linalg.norm(B - A, axis=1)
        block = max(1, 4_000_000 // max(n, 1))
        for start in range(0, n, block):
            i = np.arange(start, min(n, start + block))
            dist, crossing = segment_distances(A[i][:, None], B[i][:, None], A[None], B[None])
            same = i[:, None] == np.arange(n)[None]
            # Joined along one section by at most π/2·μ of polyline (consecutive edges included);
            # around a closed chain, across its start too.
            first_end = np.minimum(along[i][:, None] + edge_len[i][:, None], along[None] + edge_len[None])
            second_start = np.maximum(along[i][:, None], along[None])
            gap = second_start - first_end
            second_end = np.maximum(along[i][:, None] + edge_len[i][:, None], along[None] + edge_len[None])
            first_start = np.minimum(along[i][:, None], along[None])
            across = chain_total[sec][None] - second_end + first_start
            gap = np.where(chain_closed[sec][None], np.minimum(gap, across), gap)
            consecutive = (sec[i][:, None] == sec[None]) & (gap <= 0.5 * np.pi * mu + tol)
            # ... unless the curve folds back between them: adjacent edges meeting at less than the
            # junction angle, or edges pointing in opposite directions.
            D = B - A
            dot = D[i] @ D.T
            norms = np.maximum(edge_len[i][:, None] * edge_len[None], 1e-300)
            joint_angle = np.arccos(np.clip(-dot / norms, -1.0, 1.0))
            adjacent = np.abs(gap) <= tol
            consecutive &= np.where(adjacent, joint_angle >= junction - 1e-9, dot > 0)
            # Shared endpoints and the angle between the edges there.
            ends_i = np.stack([A[i], B[i]], 1)          # (k, 2, 2)
            ends_j = np.stack([A, B], 1)                 # (n, 2, 2)
            shared = (ends_i[:, :, None, None, :] == ends_j[None, None, :, :, :]).all(-1)  # (k,2,n,2)
            shared_count = shared.sum((1, 3))
            angle_ok = np.zeros_like(same)
            one = shared_count == 1
            if one.any():
                ki, nj = np.nonzero(one)
                sh = shared[ki, :, nj, :]                # (m, 2, 2)
                ei, ej = np.argwhere(sh)[:, 1], np.argwhere(sh)[:, 2]
                p = ends_i[ki, ei]
                u = ends_i[ki, 1 - ei] - p
                v = ends_j[nj, 1 - ej] - p
                ang = np.arctan2(np.abs(cross2(u, v)), (u * v).sum(-1))
                angle_ok[ki, nj] = ang >= junction - 1e-12
            exempt = same | consecutive | (one & angle_ok)
            bad_cross = crossing & ~same
            bad_close = (dist < mu - tol) & ~exempt
            for x, y in zip(*np.nonzero(bad_cross | bad_close)):
                if i[x] < y:
                    kind = "cross" if bad_cross[x, y] else "closer than mu"
                    problems.append(f"primary edges {i[x]} and {y} {kind} (distance {dist[x, y]:.3g}, mu {mu:.3g})")
    # Secondary segments within ε of their input curve.
    t = np.linspace(0, 1, 2000)[:, None]
    for si, s in enumerate(data["segments"]):
        p = np.array(data["curves"][s["curve"]]["p"], float).reshape(4, 2)
        curve = ((1 - t) ** 3) * p[0] + 3 * t * (1 - t) ** 2 * p[1] + 3 * t * t * (1 - t) * p[2] + t ** 3 * p[3]
        a, b = np.array(s["a"], float), np.array(s["b"], float)
        for f in (0, 0.25, 0.5, 0.75, 1):
            q = a + f * (b - a)
            d = point_segment_distance(q[None], curve[:-1], curve[1:]).min()
            if d > eps + tol:
                problems.append(f"secondary segment {si} is {d:.3g} from its curve (epsilon {eps:.3g})")
                break
    return {"file": rel, "status": "ok" if not problems else "failed", "edges": n,
            "segments": len(data["segments"]), "detail": "; ".join(problems[:5])}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--curvemesh", required=True)
    parser.add_argument("--list", default=os.path.join(here, "crosscheck-files.txt"))
    parser.add_argument("--root", default="/usr/share/openclipart/svg")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--max-edges", type=int, default=6000)
    parser.add_argument("--min-files", type=int, default=100)
    args = parser.parse_args()
    files = [l.strip() for l in open(args.list) if l.strip() and not l.startswith("#")]
    binary = os.path.abspath(args.curvemesh)
    with concurrent.futures.ProcessPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(check_file, [(binary, args.root, f, args.max_edges) for f in files]))
    checked = [r for r in results if r["status"] in ("ok", "failed")]
    failed = [r for r in results if r["status"] in ("failed", "error")]
    for r in failed:
        print(f"{r['status'].upper()} {r['file']}: {r['detail']}")
    skipped = sum(r["status"] == "skipped" for r in results)
    edges = sum(r.get("edges", 0) for r in checked)
    segments = sum(r.get("segments", 0) for r in checked)
    print(f"checked {len(checked)} files ({edges} primary edges, {segments} secondary segments), "
          f"skipped {skipped} larger than {args.max_edges} primary edges; {len(failed)} failed")
    ok = not failed and len(checked) >= args.min_files
    print(f"{len(checked) - len(failed)} passed, {len(failed) + (0 if len(checked) >= args.min_files else 1)} failed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
