"""Compares a screenshot (PNG) with its baseline by VTK's image comparison (vtkTesting, the
machinery of vtkRegressionTestImage: vtkImageDifference, which forgives a pixel matching a
neighbour within a small tolerance, then a threshold on the summed error).

Threshold 10, VTK's default for vtkRegressionTestImage, as the C++ image tests of this
repository use: it absorbs anti-aliasing and driver differences of a few edge pixels, not a
changed colour or a moved object. On failure the difference and test images are written to
the temporary folder (vtkTesting's -T) for inspection.

usage: CompareScreenshot.py SCREENSHOT.png BASELINE.png TEMP_DIR"""
import os
import sys

from vtkmodules.vtkTestingRendering import vtkTesting

THRESHOLD = 10.0

screenshot, baseline, temporary = sys.argv[1:4]
if not os.path.isfile(screenshot):
    print(f"FAILED: no screenshot {screenshot}")
    sys.exit(1)
os.makedirs(temporary, exist_ok=True)
testing = vtkTesting()
for argument in ("-V", os.path.abspath(baseline), "-T", os.path.abspath(temporary)):
    testing.AddArgument(argument)
result = testing.RegressionTest(screenshot, THRESHOLD)
if result != vtkTesting.PASSED:
    print(f"FAILED: {screenshot} differs from {baseline} beyond threshold {THRESHOLD}; "
          f"difference images in {temporary}")
sys.exit(0 if result == vtkTesting.PASSED else 1)
