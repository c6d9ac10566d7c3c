#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes Data/brdf/clay.brdf.csv, the example tabulated BRDF (format: Data/scenes/FORMAT.md,
section "BRDF tables").

A back-scattering "clay": f = rho / pi * (1 + beta sin(theta_in) sin(theta_out) cos(delta_phi)),
rho = (0.75, 0.55, 0.35), beta = 0.8. Light is reflected preferably back toward where it came
from (delta_phi = 0) at grazing angles, as rough dusty surfaces do. The function is reciprocal,
non-negative (beta <= 1) and its directional albedo is exactly rho for every direction: the
cos(delta_phi) term integrates to zero over the azimuth, and on the table's grid (delta_phi in
steps of 15 degrees, symmetric about 90) so does its piecewise-linear interpolation. That
makes it the "tabulated BRDF of known constant albedo" of the white-furnace tests.

Run from anywhere: python3 Data/brdf/tools/make_clay_table.py
"""
import math
import os

RHO = (0.75, 0.55, 0.35)
BETA = 0.8
THETAS = range(0, 91, 10)
DELTA_PHIS = range(0, 181, 15)


def main():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "clay.brdf.csv")
    lines = [
        "# Back-scattering clay: f = rho/pi (1 + 0.8 sin(ti) sin(to) cos(dphi)),",
        "# rho = 0.75 0.55 0.35 (its albedo, the same for every direction).",
        "# Written by Data/brdf/tools/make_clay_table.py. Angles in degrees, f in 1/sr.",
        "theta_in,theta_out,delta_phi,r,g,b",
    ]
    for ti in THETAS:
        for to in THETAS:
            for dp in DELTA_PHIS:
                shape = 1.0 + BETA * math.sin(math.radians(ti)) * math.sin(math.radians(to)) * \
                    math.cos(math.radians(dp))
                values = ",".join("%.9g" % (rho / math.pi * shape) for rho in RHO)
                lines.append("%d,%d,%d,%s" % (ti, to, dp, values))
    with open(path + ".tmp", "w") as out:
        out.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
