"""Compares screenshots (PNG) with their baselines by VTK's image comparison, vtkImageDifference
(the filter behind vtkRegressionTestImage and vtkTesting::RegressionTest).

vtkImageDifference compares each pixel with the baseline's pixel and its neighbours (a shift
of one pixel is forgiven, which absorbs anti-aliasing and driver differences along edges) and
counts a pixel as wrong by how much its summed difference |dR| + |dG| + |dB| exceeds a pixel
threshold; the thresholded error adds these up over the image. Thresholds:
- pixel threshold 30 (of 765): stricter than vtkTesting's fixed 105, which forgives up to
  about 35 levels per band and so misses a dim scene turning a little brighter (the steps of
  example 2 between 100 shots and equilibrium differ by at most 68);
- error threshold 10, VTK's default for vtkRegressionTestImage.
Identical renders give 0; on failure the difference image is written to TEMP_DIR.

usage: CompareScreenshot.py TEMP_DIR SCREENSHOT.png BASELINE.png [SCREENSHOT.png BASELINE.png ...]"""
import os
import sys

from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

PIXEL_THRESHOLD = 30
ERROR_THRESHOLD = 10.0

temporary, *pairs = sys.argv[1:]
if not pairs or len(pairs) % 2:
    sys.exit("usage: CompareScreenshot.py TEMP_DIR SCREENSHOT.png BASELINE.png [...]")
os.makedirs(temporary, exist_ok=True)


def read(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return reader


failed = 0
for screenshot, baseline in zip(pairs[0::2], pairs[1::2]):
    if not os.path.isfile(screenshot) or not os.path.isfile(baseline):
        print(f"FAILED: missing {screenshot if not os.path.isfile(screenshot) else baseline}")
        failed += 1
        continue
    test, valid = read(screenshot), read(baseline)
    if test.GetOutput().GetDimensions() != valid.GetOutput().GetDimensions():
        print(f"FAILED: {screenshot} is {test.GetOutput().GetDimensions()}, its baseline "
              f"{baseline} {valid.GetOutput().GetDimensions()}")
        failed += 1
        continue
    difference = vtkImageDifference()
    difference.SetInputConnection(test.GetOutputPort())
    difference.SetImageConnection(valid.GetOutputPort())
    difference.SetThreshold(PIXEL_THRESHOLD)
    difference.Update()
    error = difference.GetThresholdedError()
    print(f"{os.path.basename(screenshot)}: thresholded error {error:.3f} "
          f"(threshold {ERROR_THRESHOLD})")
    if error > ERROR_THRESHOLD:
        path = os.path.join(temporary, "difference_" + os.path.basename(screenshot))
        writer = vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(difference.GetOutputPort())
        writer.Write()
        print(f"FAILED: {screenshot} differs from {baseline}; difference image {path}")
        failed += 1
sys.exit(1 if failed else 0)
