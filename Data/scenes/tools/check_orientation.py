#!/usr/bin/env python3
"""Print the front-side normal of every patch of a .scene (or of a .bpt file).

    python3 check_orientation.py SCENE_OR_BPT [--toward X,Y,Z] [--grid K]

For each patch: the surface entry and its name, the patch number inside the entry, the point
at the parametric centre, the unit normal dP/du x dP/dv there (after "transform" and "flip"),
and, with --toward, whether the front faces TOWARD the given point or AWAY from it.
With --grid K the normal is also evaluated on a K x K grid of interior points, and the
patch is reported MIXED if the sign relative to --toward changes across the patch.

Plain python3; reads only well-formed files (this is not the scene loader).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from scenegeom import dot, load_scene, norm, read_bpt, sub, unit  # noqa: E402


def fmt(v, digits=4):
    scale = max(abs(x) for x in v) or 1.0
    return "(" + ", ".join(("%." + str(digits) + "g") % (0.0 if abs(x) < 1e-12 * scale else x) for x in v) + ")"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("--toward", help="reference point X,Y,Z")
    ap.add_argument("--grid", type=int, default=0, help="also test a K x K grid of interior points")
    args = ap.parse_args()

    if args.file.endswith(".bpt"):
        patches = [(0, os.path.basename(args.file), p) for p in read_bpt(args.file)]
    else:
        _, patches = load_scene(args.file)
    ref = [float(x) for x in args.toward.split(",")] if args.toward else None

    counter = {}
    for entry, name, p in patches:
        k = counter.get(entry, 0)
        counter[entry] = k + 1
        c = p.eval(0.5, 0.5)
        n = p.normal(0.5, 0.5)
        line = "%-3d %-22s patch %-3d centre %-32s normal %-28s" % (entry, name, k, fmt(c), fmt(unit(n), 3))
        if norm(n) == 0:
            line += " ZERO NORMAL AT CENTRE"
        if ref is not None:
            signs = set()
            samples = [(0.5, 0.5)]
            if args.grid > 0:
                g = args.grid
                samples += [((i + 0.5) / g, (j + 0.5) / g) for i in range(g) for j in range(g)]
            for (u, v) in samples:
                nn = p.normal(u, v)
                if norm(nn) == 0:
                    continue
                signs.add(dot(nn, sub(ref, p.eval(u, v))) > 0)
            line += " " + ("MIXED" if len(signs) > 1 else ("TOWARD" if signs == {True} else "AWAY"))
        print(line)


if __name__ == "__main__":
    main()
