#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes Data/brdf/ggx_r050.brdf.csv: Blender Cycles' Glossy BSDF (distribution GGX, roughness
0.5, colour (0.8, 0.6, 0.4)) tabulated in the format of Data/scenes/FORMAT.md ("BRDF tables"),
so that SphericalCover and Cycles render the same glossy lobe (issue 39 item 3; the Cycles side:
Data/reference/render_cycles.py, which renders a table naming this origin with the Glossy BSDF
itself).

The BRDF is what Cycles 3.4.1 (Debian's blender 3.4.1, whose kernel sources are installed under
/usr/share/blender/scripts/addons/cycles/source/kernel) evaluates for that node:

- svm/closure.h, case CLOSURE_BSDF_MICROFACET_GGX_ID: alpha_x = alpha_y = roughness^2 (the
  node's Roughness is squared), no Fresnel (`extra = NULL`), the closure's weight is the node's
  Color; the node's "GGX" is the single-scattering CLOSURE_BSDF_MICROFACET_GGX_ID ("Multiscatter
  GGX" is a separate choice, CLOSURE_BSDF_MICROFACET_MULTI_GGX_ID).
- closure/bsdf_microfacet.h, bsdf_microfacet_ggx_eval_reflect (isotropic branch): Walter et al.
  2007 eq. 20 with eq. 33 and 34,
      f cos(theta_in) = F G D / (4 cos(theta_out)),  F = 1 (reflection_color without Fresnel),
      D = alpha^2 / (pi cos^4(theta_m) (alpha^2 + tan^2(theta_m))^2),  m = normalize(in + out),
      G = G1(in) G1(out),  G1(v) = 2 / (1 + sqrt(1 + alpha^2 tan^2(theta_v)))
  (the uncorrelated Smith form), and 0 unless both cosines are > 0.
So f = colour x D G1(in) G1(out) / (4 cos(theta_in) cos(theta_out)): reciprocal, isotropic, and
single-scattering, so it loses energy (directional albedo 0.916 x colour at normal incidence,
0.83 at 70 degrees: the GGX tail beyond the horizon and G). FORMAT.md's directions point away
from the surface on both sides, delta_phi = 180 the mirror side; Cycles' I and omega_in are the
same two directions.

The grid: theta_in and theta_out every 2.5 degrees (0 ... 90), delta_phi every 10 degrees on
[0, 110] and every 2.5 degrees on [120, 180], where the lobe is: 37 x 37 x 37 = 50,653 points.
At theta = 90 the value is Cycles' 0 (both cosines must be > 0). Trilinear interpolation of this
grid (BrdfTable) reflects a uniform light within 0.1 % of the exact lobe's albedo up to 85
degrees, and the L1 error of the interpolated lobe (the integral of |f_table - f| cos dw over the
exact albedo) is at most 0.36 % for theta_out up to 60 degrees, 1.1 % at 80 and 1.4 % at 85
(`--check` prints these figures).

    python3 Data/brdf/tools/make_ggx_table.py [--check | --albedo THETA_OUT_DEG [ROUGHNESS]]

Plain python3, no third-party packages; render_cycles.py imports `origin_line`/`parse_origin`/
`ggx` from here to check that a table is still this lobe before it renders the node instead.
"""
import bisect
import math
import os
import sys

ROUGHNESS = 0.5
COLOUR = (0.8, 0.6, 0.4)
THETAS = [2.5 * k for k in range(37)]
DELTA_PHIS = [10.0 * k for k in range(12)] + [120.0 + 2.5 * k for k in range(25)]
FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "ggx_r050.brdf.csv")

# The machine-readable origin, a comment line of the table (render_cycles.py reads it).
ORIGIN_PREFIX = "# origin: cycles-glossy-ggx"


def origin_line(roughness, colour):
    return "%s roughness=%g color=%g,%g,%g" % ((ORIGIN_PREFIX, roughness) + tuple(colour))


def parse_origin(line):
    """(roughness, colour) of an origin line, or None when `line` is not one; ValueError when
    it is one but malformed."""
    if not line.startswith(ORIGIN_PREFIX):
        return None
    fields = dict(part.split("=", 1) for part in line[len(ORIGIN_PREFIX):].split())
    if set(fields) != {"roughness", "color"}:
        raise ValueError("expected roughness=R color=R,G,B in %r" % line)
    colour = tuple(float(c) for c in fields["color"].split(","))
    if len(colour) != 3:
        raise ValueError("expected three colour values in %r" % line)
    return float(fields["roughness"]), colour


def ggx(theta_in, theta_out, delta_phi, roughness):
    """Cycles 3.4's GGX lobe without its colour, f in 1/sr (angles in radians; see the file
    comment); 0 unless both directions are above the surface."""
    ci, co = math.cos(theta_in), math.cos(theta_out)
    if not (ci > 1e-12 and co > 1e-12):
        return 0.0
    alpha2 = (roughness * roughness) ** 2
    si, so = math.sin(theta_in), math.sin(theta_out)
    # in = (si, 0, ci), out = (so cos dphi, so sin dphi, co); m = (in + out) / |in + out|
    hx, hy, hz = si + so * math.cos(delta_phi), so * math.sin(delta_phi), ci + co
    cos_m2 = hz * hz / (hx * hx + hy * hy + hz * hz)
    # D = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2) = alpha^2 / (pi (cos^2 (alpha^2 - 1) + 1)^2)
    d = alpha2 / (math.pi * (cos_m2 * (alpha2 - 1.0) + 1.0) ** 2)

    def g1(c):
        return 2.0 / (1.0 + math.sqrt(1.0 + alpha2 * (1.0 - c * c) / (c * c)))

    return d * g1(ci) * g1(co) / (4.0 * ci * co)


def table_rows(roughness, colour):
    for ti in THETAS:
        for to in THETAS:
            for dp in DELTA_PHIS:
                lobe = ggx(math.radians(ti), math.radians(to), math.radians(dp), roughness)
                yield ti, to, dp, tuple(c * lobe for c in colour)


def write(path):
    lines = [
        "# Blender Cycles 3.4 Glossy BSDF, distribution GGX (single scattering, no Fresnel),",
        "# roughness %g (alpha = %g), colour %g %g %g: f = colour D G1(in) G1(out) / (4 cos cos)."
        % ((ROUGHNESS, ROUGHNESS ** 2) + COLOUR),
        "# Written by Data/brdf/tools/make_ggx_table.py. Angles in degrees, f in 1/sr.",
        origin_line(ROUGHNESS, COLOUR),
        "theta_in,theta_out,delta_phi,r,g,b",
    ]
    for ti, to, dp, rgb in table_rows(ROUGHNESS, COLOUR):
        lines.append("%g,%g,%g,%s" % (ti, to, dp, ",".join("%.7g" % v for v in rgb)))
    with open(path + ".tmp", "w", newline="\n") as out:
        out.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)


def trilinear(values, ti, to, dp):
    """The table's interpolation (BrdfTable::Evaluate): trilinear on the grid, degrees."""
    def locate(grid, x):
        k = min(max(bisect.bisect_right(grid, x) - 1, 0), len(grid) - 2)
        return k, min(max((x - grid[k]) / (grid[k + 1] - grid[k]), 0.0), 1.0)

    (a, ta), (b, tb), (c, tc) = locate(THETAS, ti), locate(THETAS, to), locate(DELTA_PHIS, dp)
    total = 0.0
    for da, wa in ((0, 1 - ta), (1, ta)):
        for db, wb in ((0, 1 - tb), (1, tb)):
            for dc, wc in ((0, 1 - tc), (1, tc)):
                total += wa * wb * wc * values[(a + da, b + db, c + dc)]
    return total


def check():
    """Prints, per theta_out, the exact lobe's albedo, the table's relative albedo error and
    the L1 error of the interpolated lobe (midpoint rule in sin^2(theta_in) and delta_phi)."""
    values = {}
    for a, ti in enumerate(THETAS):
        for b, to in enumerate(THETAS):
            for c, dp in enumerate(DELTA_PHIS):
                values[(a, b, c)] = ggx(math.radians(ti), math.radians(to), math.radians(dp),
                                        ROUGHNESS)
    n_s, n_phi = 120, 240
    for to in (0, 20, 40, 60, 70, 80, 85):
        exact = table = l1 = 0.0
        for i in range(n_s):
            ti = math.asin(math.sqrt((i + 0.5) / n_s))
            for j in range(n_phi):
                dp = (j + 0.5) * math.pi / n_phi
                e = ggx(ti, math.radians(to), dp, ROUGHNESS)
                t = trilinear(values, math.degrees(ti), to, math.degrees(dp))
                exact, table, l1 = exact + e, table + t, l1 + abs(t - e)
        scale = math.pi / (n_s * n_phi)
        print("theta_out %2d: albedo %.4f (x colour), table %+.2f %%, L1 error %.2f %%"
              % (to, exact * scale, 100 * (table / exact - 1), 100 * l1 / exact))


def albedo(theta_out_deg, roughness, steps=400):
    """The exact lobe's directional albedo (without its colour) at theta_out, by the midpoint
    rule in sin^2(theta_in) and delta_phi on steps x 2 steps points: what a glossy floor shows
    under a uniform incident radiance of 1 (Data/reference/check_units.sh, check 7)."""
    total = 0.0
    for i in range(steps):
        ti = math.asin(math.sqrt((i + 0.5) / steps))
        for j in range(2 * steps):
            total += ggx(ti, math.radians(theta_out_deg), (j + 0.5) * math.pi / (2 * steps),
                         roughness)
    return total * math.pi / (2 * steps * steps)


def main():
    if "--check" in sys.argv[1:]:
        check()
        return
    if sys.argv[1:2] == ["--albedo"]:
        roughness = float(sys.argv[3]) if len(sys.argv) > 3 else ROUGHNESS
        a = albedo(float(sys.argv[2]), roughness)
        print(" ".join("%.6f" % (c * a) for c in COLOUR))
        return
    write(FILE)
    print("wrote", os.path.normpath(FILE))


if __name__ == "__main__":
    main()
