"""Two-sided surfaces in the whole pipeline: the white furnace of
Data/scenes/furnace_two_sided.scene (the unit cube, rho 0.5 and Le 1 everywhere, holding a
"two_sided" plate of the same material at z = 0.5) solved and rendered by `sphcover render`
from the scene's camera, which lies under the plate and looks up at its back side. Both sides of
the plate emit, receive and reflect, so the radiance is Le / (1 - rho) = 2 everywhere: every
surface's mean exitant radiance in the report, the plate's back side and every pixel of the
image; the emitted power, pi Le (6 + 2 x 0.36) W, is all absorbed.

Measured 2026-12-06, 64 x 64, 4 spp: every surface 1.99999, imbalance 9.9e-6, every pixel
within 1e-5. Before two-sided surfaces had a hemisphere on each side (the plate's back side hid
the walls behind it and emitted nothing) the floor's mean was 1.764, the ceiling's 1.971, the
other walls' 1.905, the plate's 1.986, the imbalance 10.2 % and the back side of the plate 0.7 %
off in the image. Asserted: surfaces within 0.5 %, imbalance under 0.5 %, every pixel within
0.5 %."""
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
exr = os.path.join(folder, "furnace_two_sided.exr")
report = os.path.join(folder, "furnace_two_sided.json")
run = subprocess.run([sphcover, "render", os.path.join(data, "scenes", "furnace_two_sided.scene"),
                      "-o", exr, "--size", "64x64", "--report", report, "--quiet"],
                     capture_output=True, text=True, timeout=1800)
if run.returncode != 0:
    sys.exit(f"FAILED: render: {run.stderr.strip()}")
expected = 2.0
failures = []
with open(report) as f:
    solution = json.load(f)
surfaces = solution["surfaces"]
for s in surfaces:
    print(f"{s['name']}: area {s['area']:.4f}, mean exitant radiance {s['mean_exitant_radiance'][0]:.5f}")
worst_surface = max(np.abs(np.array(s["mean_exitant_radiance"]) / expected - 1).max() for s in surfaces)
if len(surfaces) != 7 or worst_surface > 0.005:
    failures.append("a surface's mean exitant radiance is more than 0.5 % off 2 (or surfaces are missing)")
energy = solution["energy"]
print(f"emitted {energy['emitted_w'][0]:.5f} W, absorbed {energy['absorbed_w'][0]:.5f} W, "
      f"imbalance {energy['relative_imbalance']:.2e}")
if abs(energy["emitted_w"][0] / (np.pi * (6 + 2 * 0.36)) - 1) > 1e-9:
    failures.append("the plate does not emit from both sides")
if energy["relative_imbalance"] > 0.005:
    failures.append("the energy imbalance is 0.5 % or more")
image = compare_sphcover.read_exr(exr)
relative = image / expected - 1
height, width = image.shape[:2]
centre = np.abs(relative[height // 2, width // 2]).max()
print(f"image: the plate's back side at the centre {100 * centre:.4f} % off, "
      f"worst pixel {100 * np.abs(relative).max():.4f} %")
if centre > 0.005:
    failures.append("the plate's back side seen by the camera is more than 0.5 % off 2")
if np.abs(relative).max() > 0.005:
    failures.append("a pixel is more than 0.5 % off 2")
for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
