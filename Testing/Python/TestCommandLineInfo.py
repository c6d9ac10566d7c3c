"""`sphcover info` prints the summary of every shipped scene: surfaces, patch degrees,
materials, cameras, bounds, settings; it agrees with facts of the Cornell box and the teapot."""
import subprocess
import sys

sphcover, data = sys.argv[1:3]
failures = []


def info(path):
    run = subprocess.run([sphcover, "info", path], capture_output=True, text=True, timeout=120)
    if run.returncode != 0:
        failures.append(f"{path}: exit {run.returncode}: {run.stderr.strip()}")
    return run.stdout


for scene in ["cornell_box", "cornell_box_meshes", "teapot_room", "furnace_box", "furnace_sphere",
              "howell_parallel", "howell_perpendicular"]:
    out = info(f"{data}/scenes/{scene}.scene")
    for heading in ["Surfaces:", "Materials:", "Cameras:", "Bounds:", "Settings:"]:
        if heading not in out:
            failures.append(f"{scene}: summary lacks '{heading}'")

cornell = info(f"{data}/scenes/cornell_box.scene")
if "Bounds: (0, 0, 0) to (556, 548.8, 559.2)" not in cornell:
    failures.append("cornell_box: wrong bounds line")
if "emission (18.387, 10.9873, 2.75357)" not in cornell:
    failures.append("cornell_box: lamp emission not shown")

teapot = info(f"{data}/models/teapot.bpt")
if "32x(3,3)" not in teapot or "Bounds: (-3, -2, 0) to (3.525, 2, 3.15)" not in teapot:
    failures.append("teapot.bpt: wrong degrees or bounds")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
