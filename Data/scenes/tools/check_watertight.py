#!/usr/bin/env python3
"""Check that a set of Bezier patches forms a closed (watertight), consistently oriented surface.

    python3 check_watertight.py FILE.bpt|FILE.scene [--tol 1e-9] [--samples 33]

Every boundary curve of every patch is either degenerate (all its control points coincide,
e.g. the poles of sphere.bpt) or must coincide with exactly one boundary curve of another
patch: same control points, in the same or the reverse order (within --tol). The curves are
also sampled and the largest distance between matched curves is reported.

Orientation: walking each patch's boundary counter-clockwise (seen from the front, i.e. with
dP/du x dP/dv toward the viewer) -- v=0 with u increasing, u=1 with v increasing, v=1 with u
decreasing, u=0 with v decreasing -- two patches that are consistently oriented traverse
their shared curve in OPPOSITE directions.

Exit status 0 if closed and consistently oriented, 1 otherwise.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from scenegeom import dist, load_scene, read_bpt  # noqa: E402

# side -> does the counter-clockwise walk go along increasing parameter?
CCW_FORWARD = {"v0": True, "u1": True, "v1": False, "u0": False}


def bezier_curve(ctrl, t):
    pts = [list(p) for p in ctrl]
    n = len(pts)
    for r in range(1, n):
        for i in range(n - r):
            pts[i] = [(1 - t) * a + t * b for a, b in zip(pts[i], pts[i + 1])]
    return pts[0]


def same(a, b, tol):
    return len(a) == len(b) and all(dist(p, q) <= tol for p, q in zip(a, b))


def check(patches, tol=1e-9, samples=33, verbose=True):
    edges = []  # (patch index, side, control points)
    n_degenerate = 0
    for k, p in enumerate(patches):
        for side in ("v0", "u1", "v1", "u0"):
            ctrl = p.boundary(side)
            if all(dist(q, ctrl[0]) <= tol for q in ctrl):
                n_degenerate += 1
                continue
            edges.append((k, side, ctrl))
    ok = True
    max_gap = 0.0
    pairs = 0
    for a in range(len(edges)):
        ka, sa, ca = edges[a]
        matches = []
        for b in range(len(edges)):
            if b == a:
                continue
            kb, sb, cb = edges[b]
            if same(ca, cb, tol):
                matches.append((b, False))
            elif same(ca, list(reversed(cb)), tol):
                matches.append((b, True))
        if len(matches) != 1:
            ok = False
            if verbose:
                print("patch %d side %s: %d matching curves (expected 1)" % (ka, sa, len(matches)))
            continue
        b, reversed_ = matches[0]
        if b < a:
            continue
        pairs += 1
        kb, sb, cb = edges[b]
        # sampled distance between the two curves
        for i in range(samples):
            t = i / (samples - 1)
            pa = bezier_curve(ca, t)
            pb = bezier_curve(cb, 1 - t if reversed_ else t)
            max_gap = max(max_gap, dist(pa, pb))
        # orientation: directions of the ccw walks along the shared curve
        dir_a = CCW_FORWARD[sa]
        dir_b = CCW_FORWARD[sb] != reversed_  # expressed in a's parameter direction
        if dir_a == dir_b:
            ok = False
            if verbose:
                print("patches %d (%s) and %d (%s) share a curve but are oriented inconsistently"
                      % (ka, sa, kb, sb))
    if verbose:
        print("%d patches, %d shared boundary curves, %d degenerate (collapsed) boundary curves, "
              "largest sampled gap %.3g" % (len(patches), pairs, n_degenerate, max_gap))
        print("CLOSED and consistently oriented" if ok else "NOT closed / not consistently oriented")
    return ok, pairs, n_degenerate, max_gap


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("--tol", type=float, default=1e-9)
    ap.add_argument("--samples", type=int, default=33)
    args = ap.parse_args()
    if args.file.endswith(".bpt"):
        patches = read_bpt(args.file)
    else:
        patches = [p for _, _, p in load_scene(args.file)[1]]
    ok, _, _, _ = check(patches, args.tol, args.samples)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
