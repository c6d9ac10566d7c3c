"""An independent reference for the whole method (issue 6): the Cornell box rendered by the
pipeline (reader, subdivision, spherical cover, light propagation, vtkRadianceImageFilter)
agrees block-wise with the Blender Cycles path tracing of Data/reference/cornell_box_cycles.exr
(512 x 512, 2048 spp, block noise 0.17 %), read with vtkOpenEXRReader.

At the scene's settings (16 x 64 hemisphere grid, max_level 4, tolerance 0.02; the solve
takes ~8 s on an idle 2-core machine), rendered at 128 x 128 with 64 stratified samples per
pixel: its 4 x 4-pixel blocks cover the same regions as the reference's 16 x 16 blocks (block
means are area integrals: a 128 x 128 render with 1024 spp and a 512 x 512 one with 64 spp
differ by a block-RMS of 0.0026, against 0.082 to Cycles).

Measured (Data/reference/README.md, "SphericalCover vs Cycles"), with the exchange balance
(vtkLightPropagationFilter's BalanceExchanges, the default): block-RMS relative error
e = 0.0346 (R 0.0265, G 0.0358, B 0.0401); image means -0.09 %, -0.19 %, -0.17 % (balance
off: e = 0.0337, means -0.57 %, -0.57 %, -0.51 %). The error is
method error: interpolation across shadow and occlusion boundaries (the ceiling next to the
lamp, the floor at the blocks' bases) and a low bias of the walls of 1.2 to 2 % (0.3 to 1 %
when RBuffer::Classify diffuses its rounding error along the rows: the plain plurality vote
loses 1-2 % of the lamp's projected solid angle, Testing/Core/cover/TestCornellDirectLight.cxx).

2026-12-03: with the lamps' direct light and its first bounce taken from the patches' nodes
(vtkSphericalCoverFilter's DirectIrradianceNodes and DirectBounceRays,
Core/cover/DirectIrradiance.h) e = 0.0137, and the issue-16 metric
(Testing/Benchmarks/time_to_accuracy.py: relative RMS of luminance block means on a 16 x 16
and a 64 x 64 grid, here 8-px and 2-px blocks) 0.95 % and 1.76 % (the direct light alone at
the nodes: 1.12 % and 2.03 %; no nodes: 1.7 % and 3.0 %).

2026-12-03 (session 11): the cover's own version of that light is taken off the points'
values (vtkLightPropagationFilter's CoverLampIrradiance), so the nodes replace it at the points
too, and the scene's settings became a 16 x 64 grid at max_level 4: 0.83 % and 1.83 % (the
same settings without the replacement: 3.97 % and 6.29 %).

2026-12-07: the scene lost its settings block and is solved at the defaults (32 x 128,
max_level 5, the nodes 9 x 9 where the light is not bilinear, 3 x 3 elsewhere).

Asserted, with margins for changes of the method that are not regressions (~0.02 on the
block errors):
  - e < 0.06 and every e_c < 0.07;
  - the luminance block errors of the 16 x 16 and 64 x 64 grids below 0.95 % and 1.95 % (the
    direct light and its first bounce from the nodes, the cover's version of it taken off);
  - each image mean within 1 % of the reference's (the balance off misses it by half of that
    at coarser settings: -4.6 % at max_level 2 and a 16 x 64 grid).
Checked by hand: halving the emission (means -50 %), swapping the R and B bands of the red
wall's reflectance, or flipping the image (e ~ 59) fails it.
"""
import os
import sys

data = sys.argv[1]
sys.path.insert(0, os.path.join(data, "reference"))
sys.path.insert(0, os.path.join(os.path.dirname(data), "Testing", "Benchmarks"))
import compare_sphcover  # noqa: E402
import time_to_accuracy  # noqa: E402

failures = []
reference = compare_sphcover.read_exr(os.path.join(data, "reference", "cornell_box_cycles.exr"))
if reference.shape != (512, 512, 3):
    failures.append(f"reference: expected 512 x 512 RGB, got {reference.shape}")

image, facts = compare_sphcover.render(os.path.join(data, "scenes", "cornell_box.scene"),
                                       size=(128, 128), spp=64)
result = compare_sphcover.compare(image, reference, block=16)
print(compare_sphcover.report(result, facts))
print("block error map (RMS over channels, %, top row first):")
print(compare_sphcover.error_map_text(result))

luminance = time_to_accuracy.errors_against(image, reference)
print("luminance block errors (issue 16's metric): "
      + ", ".join(f"{grid} x {grid} blocks {100 * value:.2f} %" for grid, value in luminance.items()))
for grid, limit in ((16, 0.0095), (64, 0.0195)):
    if not luminance[grid] < limit:
        failures.append(f"luminance block error on {grid} x {grid} blocks "
                        f"{100 * luminance[grid]:.2f} % >= {100 * limit:.2f} %")
if not result["block_rms"] < 0.06:
    failures.append(f"block-RMS relative error {result['block_rms']:.4f} >= 0.06")
for name, value in zip("RGB", result["block_rms_channel"]):
    if not value < 0.07:
        failures.append(f"block-RMS relative error of {name} {value:.4f} >= 0.07")
for name, value in zip("RGB", result["mean_error_channel"]):
    if not abs(value) < 0.01:
        failures.append(f"image mean of {name} differs by {100 * value:+.2f} % (limit 1 %)")

for failure in failures:
    print("FAILED:", failure)
sys.exit(1 if failures else 0)
