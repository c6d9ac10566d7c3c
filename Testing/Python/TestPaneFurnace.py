"""Panes (paper §5.4) in the whole pipeline: the white furnace of Data/scenes/furnace_pane.scene
(the unit cube, albedo a = (0.3, 0.6, 0.8) and Le = 1 everywhere, cut by a full pane at
x = 0.5 and a half pane at x = 0.25, each with reflectance + transmittance = a and Le = 1 on
both sides) solved and rendered by `sphcover render` from a camera looking through both panes.
The radiance arriving anywhere from any direction is Le / (1 - a): every surface's mean
irradiance in the report is pi Le / (1 - a), and every pixel, the panes' own radiance plus what
they let through, shows Le / (1 - a).

Measured 2026-12-04 (Documentation/notes/panes-and-textures.md), 96 x 96, 4 spp: the surfaces'
mean irradiance within 0.08 %, the image mean within 0.04 %, 9214 of 9216 pixels within 0.5 %;
the other two pixels are 5 % dark (a sample whose ray, through both panes, slips through the
seam where the wall behind meets its neighbour). Asserted: surfaces within 0.5 %, the image
mean within 0.2 %, 99.5 % of the pixels within 0.5 %."""
import json
import os
import subprocess
import sys
import tempfile

sphcover, data = sys.argv[1:3]
sys.path.insert(0, os.path.join(data, "reference"))
import compare_sphcover  # noqa: E402
import numpy as np  # noqa: E402

folder = tempfile.mkdtemp()
exr = os.path.join(folder, "furnace_pane.exr")
report = os.path.join(folder, "furnace_pane.json")
run = subprocess.run([sphcover, "render", os.path.join(data, "scenes", "furnace_pane.scene"),
                      "-o", exr, "--size", "96x96", "--report", report, "--quiet"],
                     capture_output=True, text=True, timeout=1800)
if run.returncode != 0:
    sys.exit(f"FAILED: render: {run.stderr.strip()}")
albedo = np.array([0.3, 0.6, 0.8])
expected = 1.0 / (1.0 - albedo)
failures = []
with open(report) as f:
    surfaces = json.load(f)["surfaces"]
worst_surface = max(np.abs(np.array(s["mean_irradiance"]) / (np.pi * expected) - 1).max() for s in surfaces)
print(f"surfaces' mean irradiance: worst {100 * worst_surface:.3f} % from pi Le / (1 - a)")
if len(surfaces) != 8 or worst_surface > 0.005:
    failures.append("a surface's mean irradiance is more than 0.5 % off (or surfaces are missing)")
image = compare_sphcover.read_exr(exr)
relative = image / expected - 1
mean = relative.mean(axis=(0, 1))
within = (np.abs(relative).max(axis=2) <= 0.005).mean()
print(f"image: mean {100 * mean} %, {100 * within:.2f} % of the pixels within 0.5 %, "
      f"worst {100 * np.abs(relative).max():.2f} %")
if np.abs(mean).max() > 0.002:
    failures.append("the image mean is more than 0.2 % off")
if within < 0.995:
    failures.append("fewer than 99.5 % of the pixels within 0.5 %")
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
