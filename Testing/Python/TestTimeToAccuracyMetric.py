"""The metric of the time-to-accuracy benchmark (Testing/Benchmarks/time_to_accuracy.py, issue 16):
the relative RMS over lit blocks of the luminance block means, and the Cycles time at equal
error. On the committed Cycles reference (Data/reference/cornell_box_cycles.exr, read with
vtkOpenEXRReader):
  - the reference against itself is 0 on both grids, at 512 x 512 and box-downsampled to
    256 x 256 (a block mean is the same area mean at either resolution);
  - the reference scaled by 1.01 is 1 % on both grids; scaled by 1.02 on one half of the image's
    columns and by 0.98 on the other, 2 % (every block's relative error is +-2 %);
  - changing R and B so that the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B stays is 0 (the
    metric is of luminance, not of the channels), while scaling G alone by 1.01 is not;
  - a block darker than DARK_FRACTION of the mean is left out, however wrong the image there;
and on the interpolation: between (1 s, 4 %), (4 s, 2 %), (16 s, 1 %), 2 % takes 4 s and
sqrt(2) % takes 8 s (log-log), 8 % takes 0.25 s and 0.5 % 64 s (error ~ time^-1/2 beyond).
"""
import math
import os
import sys

import numpy as np

data = sys.argv[1]
sys.path.insert(0, os.path.join(os.path.dirname(data), "Testing", "Benchmarks"))
import time_to_accuracy as tta  # noqa: E402

failures = []


def expect(label, got, want, tolerance=1e-12):
    print(f"{label}: {got!r} (expected {want!r})")
    if got is None or not abs(got - want) <= tolerance:
        failures.append(f"{label}: {got!r}, expected {want!r}")


reference = tta.compare_sphcover.read_exr(os.path.join(data, "reference",
                                                       "cornell_box_cycles.exr"))
if reference.shape != (512, 512, 3):
    failures.append(f"the reference is {reference.shape}, not 512 x 512 x 3")
half = tta.downsample(reference, 2)

for grid in tta.GRIDS:
    expect(f"reference vs itself, {grid} blocks", tta.luminance_block_error(
        reference, reference, grid)[0], 0.0)
    expect(f"downsampled reference vs reference, {grid} blocks", tta.luminance_block_error(
        half, reference, grid)[0], 0.0, 1e-6)
    expect(f"1.01 x reference, {grid} blocks", tta.luminance_block_error(
        1.01 * reference, reference, grid)[0], 0.01)
    halves = reference.copy()
    halves[:, :256] *= 1.02
    halves[:, 256:] *= 0.98
    expect(f"+-2 % halves, {grid} blocks", tta.luminance_block_error(
        halves, reference, grid)[0], 0.02)

    same_y = reference.copy()
    delta = 0.1 * reference[..., 0]
    same_y[..., 0] += delta
    same_y[..., 2] -= delta * tta.LUMINANCE[0] / tta.LUMINANCE[2]
    expect(f"R and B changed at constant Y, {grid} blocks",
           tta.luminance_block_error(same_y, reference, grid)[0], 0.0, 1e-9)
    green = reference.copy()
    green[..., 1] *= 1.01
    error = tta.luminance_block_error(green, reference, grid)[0]
    print(f"G x 1.01, {grid} blocks: {error}")
    if not 0.001 < error < 0.01:
        failures.append(f"G x 1.01 gives {error}, not between 0.1 % and 1 %")

# errors_against downsamples the reference to a 256 x 256 image's resolution.
errors = tta.errors_against(1.01 * half, reference)
for grid in tta.GRIDS:
    expect(f"errors_against at 256 x 256, {grid} blocks", errors[grid], 0.01, 1e-9)

# A dark block (below DARK_FRACTION of the mean) is skipped, a lit one is not.
flat = np.ones((64, 64, 3))
flat[:4, :4] = 1e-6
wrong = flat.copy()
wrong[:4, :4] = 1.0
error, lit = tta.luminance_block_error(wrong, flat, 16)
expect("a wrong dark block", error, 0.0)
if lit != 255:
    failures.append(f"{lit} lit blocks, expected 255 of 256")
wrong[60:, 60:] *= 1.16
expect("one lit block 16 % off of 255", tta.luminance_block_error(wrong, flat, 16)[0],
       0.16 / math.sqrt(255))

curve = [(1.0, 0.04), (4.0, 0.02), (16.0, 0.01)]
for error, seconds, how in [(0.02, 4.0, "interpolated"), (0.02 / math.sqrt(2), 8.0,
                            "interpolated"), (0.08, 0.25, "extrapolated below"),
                            (0.005, 64.0, "extrapolated above")]:
    got, got_how = tta.equal_error_time(curve, error)
    expect(f"Cycles time at {100 * error:.3f} %", got, seconds, 1e-9)
    if got_how != how:
        failures.append(f"at {error}: {got_how}, expected {how}")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
