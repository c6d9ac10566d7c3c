#!/usr/bin/env python3
"""Closed-form view (form) factors from Howell's catalogue, checked by numerical quadrature.

  C-11  parallel, coaxial, equal rectangles a x b at separation c
  C-14  perpendicular rectangles with a common edge of length l (plate A: l x w, plate B: l x h)
  C-41  parallel coaxial disks of radii r1 and r2 at separation h

Run:  python3 howell.py            (prints the values used in Data/scenes/README.md)
      python3 howell.py --quick    (skips the quadrature cross-check)

Plain python3, no third-party packages.
"""

import math
import sys


def f_parallel(a, b, c):
    """Howell C-11: F from one a x b rectangle to an identical, directly opposed one at distance c.

    X = a/c, Y = b/c
    F = 2/(pi X Y) * { ln sqrt[(1+X^2)(1+Y^2)/(1+X^2+Y^2)]
                       + X sqrt(1+Y^2) atan(X/sqrt(1+Y^2)) + Y sqrt(1+X^2) atan(Y/sqrt(1+X^2))
                       - X atan(X) - Y atan(Y) }
    """
    X, Y = a / c, b / c
    x1, y1 = 1 + X * X, 1 + Y * Y
    return 2.0 / (math.pi * X * Y) * (
        math.log(math.sqrt(x1 * y1 / (x1 + Y * Y)))
        + X * math.sqrt(y1) * math.atan(X / math.sqrt(y1))
        + Y * math.sqrt(x1) * math.atan(Y / math.sqrt(x1))
        - X * math.atan(X) - Y * math.atan(Y))


def f_perpendicular(l, w, h):
    """Howell C-14: F from plate A (l x w) to plate B (l x h), perpendicular, sharing the edge l.

    H = h/l, W = w/l
    F = 1/(pi W) * { W atan(1/W) + H atan(1/H) - sqrt(H^2+W^2) atan(1/sqrt(H^2+W^2))
          + 1/4 ln[ (1+W^2)(1+H^2)/(1+W^2+H^2)
                    * (W^2 (1+W^2+H^2) / ((1+W^2)(W^2+H^2)))^(W^2)
                    * (H^2 (1+H^2+W^2) / ((1+H^2)(H^2+W^2)))^(H^2) ] }
    """
    H, W = h / l, w / l
    H2, W2 = H * H, W * W
    s = math.sqrt(H2 + W2)
    log_term = (math.log((1 + W2) * (1 + H2) / (1 + W2 + H2))
                + W2 * math.log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2)))
                + H2 * math.log(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2))))
    return 1.0 / (math.pi * W) * (W * math.atan(1 / W) + H * math.atan(1 / H)
                                  - s * math.atan(1 / s) + 0.25 * log_term)


# --------------------------------------------------------------------------- quadrature check


def f_disks(r1, r2, h):
    """Howell C-41: F from a disk of radius r1 to a parallel, coaxial disk of radius r2 at
    distance h.

    R1 = r1/h, R2 = r2/h, X = 1 + (1 + R2^2) / R1^2
    F = 1/2 * { X - sqrt(X^2 - 4 (R2/R1)^2) }
    """
    R1, R2 = r1 / h, r2 / h
    X = 1 + (1 + R2 * R2) / (R1 * R1)
    return 0.5 * (X - math.sqrt(X * X - 4 * (R2 / R1) ** 2))


def disks_quadrature(r1, r2, h, n=24):
    """F_12 for C-41 by quadrature: by symmetry the inner integral over disk 2 depends on the
    radius rho of the point on disk 1 only; F_12 = (2 / r1^2) int_0^r1 rho F_d(rho) d rho with
    F_d(rho) = int_2 h^2 / (pi r^4) dA, integrated in polar coordinates (s, phi) on disk 2."""
    xs, ws = _gauss_legendre(n)
    total = 0.0
    for x, w in zip(xs, ws):
        rho = r1 * x
        fd = 0.0
        for y, v in zip(xs, ws):
            s_ = r2 * y
            for z, u in zip(xs, ws):
                phi = 2 * math.pi * z
                d2 = rho * rho + s_ * s_ - 2 * rho * s_ * math.cos(phi) + h * h
                fd += v * u * r2 * 2 * math.pi * s_ * h * h / (math.pi * d2 * d2)
        total += w * r1 * rho * fd
    return 2.0 * total / (r1 * r1)


def _gauss_legendre(n):
    """Nodes and weights on [0, 1] (Newton iteration on P_n)."""
    xs, ws = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-15:
                break
        xs.append(0.5 * (1 - x))
        ws.append(1.0 / ((1 - x * x) * dp * dp))
    return xs, ws


def _nodes(n, breaks):
    """Composite Gauss-Legendre nodes/weights on the intervals between consecutive breaks."""
    xs, ws = _gauss_legendre(n)
    out = []
    for a, b in zip(breaks[:-1], breaks[1:]):
        out += [(a + (b - a) * x, (b - a) * w) for x, w in zip(xs, ws)]
    return out


def graded(levels, ratio=0.35):
    """Breaks on [0, 1] refined geometrically toward 0 (for the common-edge singularity)."""
    return [0.0] + [ratio ** k for k in range(levels, -1, -1)]


def form_factor_quadrature(A, nA, B, nB, n=8, breaks1=(0.0, 1.0), breaks2=(0.0, 1.0)):
    """F_AB = 1/area(A) * int_A int_B cos cos / (pi r^2) for planar parallelograms
    A = (origin, edge1, edge2), B likewise, with unit normals nA, nB. Composite
    Gauss-Legendre on the given breaks of each parameter (same breaks for A and B)."""
    s_nodes, t_nodes = _nodes(n, list(breaks1)), _nodes(n, list(breaks2))

    def pts(P):
        o, e1, e2 = P
        area = math.sqrt(sum(c * c for c in _cross(e1, e2)))
        return [([o[0] + s * e1[0] + t * e2[0], o[1] + s * e1[1] + t * e2[1],
                  o[2] + s * e1[2] + t * e2[2]], ws_ * wt * area)
                for s, ws_ in s_nodes for t, wt in t_nodes], area

    pa, areaA = pts(A)
    pb, _ = pts(B)
    total = 0.0
    for x, wa in pa:
        acc = 0.0
        for y, wb in pb:
            d = [y[0] - x[0], y[1] - x[1], y[2] - x[2]]
            r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
            ca = (d[0] * nA[0] + d[1] * nA[1] + d[2] * nA[2])
            cb = -(d[0] * nB[0] + d[1] * nB[1] + d[2] * nB[2])
            if ca > 0 and cb > 0:
                acc += wb * ca * cb / (r2 * r2)
        total += wa * acc
    return total / (math.pi * areaA)


def perpendicular_quadrature(l, w, h, n=8, levels=14):
    """F_AB for C-14 by quadrature, with the integral along the common edge direction on B done
    in closed form (it carries the near-singularity of the integrand at the common edge).

    A = {(s, 0, t)}, s in [0, l], t in [0, w], normal +y; B = {(s', t', 0)}, t' in [0, h], normal +z.
    cos_A cos_B / (pi r^4)-kernel: t t' / (pi r^4), r^2 = (s - s')^2 + t^2 + t'^2, and
    int ds' / (D^2 + q^2)^2 = G(D), G(D) = D / (2 q^2 (D^2 + q^2)) + atan(D / q) / (2 q^3).
    """
    def G(D, q):
        return D / (2 * q * q * (D * D + q * q)) + math.atan(D / q) / (2 * q ** 3)

    s_nodes = _nodes(n, [0.0, 0.25 * l, 0.5 * l, 0.75 * l, l])
    t_nodes = _nodes(n, [w * b for b in graded(levels)])
    u_nodes = _nodes(n, [h * b for b in graded(levels)])
    total = 0.0
    for s, ws in s_nodes:
        for t, wt in t_nodes:
            for u, wu in u_nodes:
                q = math.sqrt(t * t + u * u)
                total += ws * wt * wu * t * u * (G(l - s, q) + G(s, q))
    return total / (math.pi * l * w)


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def main():
    quick = "--quick" in sys.argv
    print("Textbook checks:")
    print("  C-11 unit squares at distance 1:            F = %.6f  (tables: 0.19982)" % f_parallel(1, 1, 1))
    print("  C-14 unit squares sharing an edge:          F = %.6f  (tables: 0.20004)" % f_perpendicular(1, 1, 1))

    # howell_parallel.scene: A and B are 1 x 2 rectangles, separation 1
    a, b, c = 1.0, 2.0, 1.0
    fp = f_parallel(a, b, c)
    print("\nhowell_parallel.scene  (C-11, a = %g, b = %g, c = %g, X = a/c = %g, Y = b/c = %g)" % (a, b, c, a / c, b / c))
    print("  F_AB = F_BA = %.6f" % fp)
    print("  mean irradiance on B for Le = 1 on a black emitter A: pi * F_BA = %.6f W m^-2" % (math.pi * fp))

    # howell_perpendicular.scene: A = floor 1 x 2 (common edge 1, width 2), B = 1 x 1.5 wall
    l, w, h = 1.0, 2.0, 1.5
    fab = f_perpendicular(l, w, h)
    fba = f_perpendicular(l, h, w)
    print("\nhowell_perpendicular.scene  (C-14, common edge l = %g, A: l x w = %g x %g, B: l x h = %g x %g,"
          " W = w/l = %g, H = h/l = %g)" % (l, l, w, l, h, w / l, h / l))
    print("  F_AB = %.6f" % fab)
    print("  F_BA = %.6f   (reciprocity: A_A F_AB / A_B = %.6f)" % (fba, (l * w) * fab / (l * h)))
    print("  mean irradiance on B for Le = 1 on a black emitter A: pi * F_BA = %.6f W m^-2" % (math.pi * fba))

    # howell_disks.scene: disks of radii 1 (A) and 0.5 (B) at distance 0.8
    r1, r2, hd = 1.0, 0.5, 0.8
    print("\nhowell_disks.scene  (C-41, r1 = %g, r2 = %g, h = %g)" % (r1, r2, hd))
    print("  F_AB = %.6f" % f_disks(r1, r2, hd))
    print("  F_BA = %.6f" % f_disks(r2, r1, hd))
    print("  C-41 equal disks r = h: F = %.6f  (tables: 0.38197)" % f_disks(1, 1, 1))

    if quick:
        return
    print("\nQuadrature cross-check (composite Gauss-Legendre):")
    # Parallel: A in y = 0 facing +y, B in y = 1 facing -y.
    A = ([0, 0, 0], [1, 0, 0], [0, 0, 2])
    B = ([0, 1, 0], [1, 0, 0], [0, 0, 2])
    q = form_factor_quadrature(A, [0, 1, 0], B, [0, -1, 0], n=10)
    print("  parallel      F_AB quadrature %.6f  closed form %.6f  rel.diff %.1e" % (q, fp, abs(q - fp) / fp))
    # Perpendicular: A in y = 0 (x in [0,1], z in [0,2]) facing +y; B in z = 0 (x in [0,1],
    # y in [0,1.5]) facing +z; the x-integral on B in closed form, graded toward the common edge.
    q = perpendicular_quadrature(l, w, h)
    print("  perpendicular F_AB quadrature %.6f  closed form %.6f  rel.diff %.1e" % (q, fab, abs(q - fab) / fab))
    q = perpendicular_quadrature(l, h, w)
    print("  perpendicular F_BA quadrature %.6f  closed form %.6f  rel.diff %.1e" % (q, fba, abs(q - fba) / fba))
    for a1, a2 in ((r1, r2), (r2, r1)):
        q, f = disks_quadrature(a1, a2, hd), f_disks(a1, a2, hd)
        print("  disks r1 = %g r2 = %g: F quadrature %.6f  closed form %.6f  rel.diff %.1e" % (a1, a2, q, f, abs(q - f) / f))


if __name__ == "__main__":
    main()
