"""`sphcover info` prints the summary of every shipped scene: surfaces, patch degrees,
materials, cameras, bounds, settings; it agrees with facts of the Cornell box, the teapot and the
textured floor."""
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
              "howell_parallel", "howell_perpendicular", "textured_floor"]:
    out = info(f"{data}/scenes/{scene}.scene")
    for heading in ["Surfaces:", "Materials:", "Cameras:", "Bounds:", "Settings:"]:
        if heading not in out:
            failures.append(f"{scene}: summary lacks '{heading}'")

cornell = info(f"{data}/scenes/cornell_box.scene")
if "Bounds: (0, 0, 0) to (556, 548.8, 559.2)" not in cornell:
    failures.append("cornell_box: wrong bounds line")
if "emission (18.387, 10.9873, 2.75357)" not in cornell:
    failures.append("cornell_box: lamp emission not shown")

# A texture is named with its size and encoding as read (paper §5.4).
textured = info(f"{data}/scenes/textured_floor.scene")
if "textures/ramp.png (16x16, srgb)" not in textured:
    failures.append("textured_floor: the floor's texture is not shown as read")

teapot = info(f"{data}/models/teapot.bpt")
if "32x(3,3)" not in teapot or "Bounds: (-3, -2, 0) to (3.525, 2, 3.15)" not in teapot:
    failures.append("teapot.bpt: wrong degrees or bounds")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
