"""Numbers from linear EXR images, read with Blender (bpy + its numpy; no other packages).

    blender -b --factory-startup --python Data/reference/exr_stats.py -- stats A.exr [--rect X0 Y0 X1 Y1]
    blender -b --factory-startup --python Data/reference/exr_stats.py -- expect A.exr --mean R G B --tol T
    blender -b --factory-startup --python Data/reference/exr_stats.py -- compare A.exr B.exr [--block 16]

stats: per-channel mean, standard deviation, min and max over the image or over the pixel
rectangle [X0, X1) x [Y0, Y1) (x to the right, y down from the top row, as in the file).

expect: like stats, then checks that the image mean of every channel is within --tol
(relative; absolute where the expected value is 0) of --mean R G B; exits 1 if not.

compare: means over BLOCK x BLOCK pixel blocks of both images (same size, a multiple of
BLOCK), and the block-RMS relative error of A against B:

    e = sqrt( mean over blocks b and channels c of ((A_bc - B_bc) / B_bc)^2 )

over the blocks and channels where B_bc > 1e-3 * mean_c(B), the image mean of channel c
(blocks that see next to nothing are left out), and per channel the same RMS and the
normalised block RMS difference sqrt(mean_b (A_bc - B_bc)^2) / mean_b(B_bc). For two renders of one scene with different seeds at n samples per pixel, e / sqrt(2)
estimates the relative noise of one block mean at n spp; it falls as 1 / sqrt(spp).
Also printed: the relative difference of the image means per channel and the largest
block relative error.
"""

import argparse
import sys

import bpy
import numpy as np


def load(path):
    """Linear RGB as float64, shape (height, width, 3), row 0 = top of the image."""
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"  # no colour conversion: the file's numbers
    w, h = img.size
    if w == 0 or h == 0:
        sys.exit("exr_stats.py: error: %s: cannot read the image" % path)
    px = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    bpy.data.images.remove(img)
    # Blender's pixel buffer starts at the bottom row.
    return px.reshape(h, w, 4)[::-1, :, :3].astype(np.float64)


def block_means(a, block):
    h, w, _ = a.shape
    if h % block or w % block:
        sys.exit("exr_stats.py: error: image %dx%d is not a multiple of the block %d"
                 % (w, h, block))
    return a.reshape(h // block, block, w // block, block, 3).mean(axis=(1, 3))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="exr_stats.py")
    sub = ap.add_subparsers(dest="cmd", required=True)
    s = sub.add_parser("stats")
    s.add_argument("image")
    s.add_argument("--rect", type=int, nargs=4, metavar=("X0", "Y0", "X1", "Y1"))
    x = sub.add_parser("expect")
    x.add_argument("image")
    x.add_argument("--mean", type=float, nargs=3, required=True, metavar=("R", "G", "B"))
    x.add_argument("--tol", type=float, required=True)
    c = sub.add_parser("compare")
    c.add_argument("a")
    c.add_argument("b")
    c.add_argument("--block", type=int, default=16)
    args = ap.parse_args(argv)

    np.set_printoptions(precision=6, suppress=False)
    if args.cmd in ("stats", "expect"):
        a = load(args.image)
        h, w, _ = a.shape
        if getattr(args, "rect", None):
            x0, y0, x1, y1 = args.rect
            a = a[y0:y1, x0:x1]
        flat = a.reshape(-1, 3)
        print("image %s  %dx%d  pixels %d" % (args.image, w, h, flat.shape[0]))
        print("mean  ", flat.mean(axis=0))
        print("std   ", flat.std(axis=0))
        print("min   ", flat.min(axis=0))
        print("max   ", flat.max(axis=0))
        if args.cmd == "expect":
            want = np.array(args.mean)
            got = flat.mean(axis=0)
            dev = np.where(want != 0, got / np.where(want != 0, want, 1) - 1, got)
            ok = bool(np.all(np.abs(dev) <= args.tol))
            print("expect %s, deviation %s (tolerance %g): %s"
                  % (want, dev, args.tol, "ok" if ok else "FAIL"))
            sys.exit(0 if ok else 1)
    else:
        a = load(args.a)
        b = load(args.b)
        if a.shape != b.shape:
            sys.exit("exr_stats.py: error: sizes differ: %s vs %s" % (a.shape, b.shape))
        ba = block_means(a, args.block)
        bb = block_means(b, args.block)
        mask = bb > 1e-3 * bb.reshape(-1, 3).mean(axis=0)
        rel = np.where(mask, (ba - bb) / np.where(mask, bb, 1.0), 0.0)
        e = float(np.sqrt(np.sum(rel ** 2) / mask.sum()))
        print("compare %s against %s, %dx%d blocks, %d of %d block-channels used"
              % (args.a, args.b, args.block, args.block, int(mask.sum()), mask.size))
        print("block-RMS relative error  %.6f" % e)
        print("largest block rel. error  %.6f" % float(np.abs(rel).max()))
        per = [float(np.sqrt(np.sum(rel[..., c] ** 2) / mask[..., c].sum())) for c in range(3)]
        print("  per channel (R, G, B)   ", np.array(per))
        nrms = np.sqrt(((ba - bb) ** 2).reshape(-1, 3).mean(axis=0)) / bb.reshape(-1, 3).mean(axis=0)
        print("normalised block RMS diff.", nrms)
        print("image mean A              ", a.reshape(-1, 3).mean(axis=0))
        print("image mean B              ", b.reshape(-1, 3).mean(axis=0))
        print("image mean rel. difference", a.reshape(-1, 3).mean(axis=0) / b.reshape(-1, 3).mean(axis=0) - 1)


if __name__ == "__main__":
    main()
