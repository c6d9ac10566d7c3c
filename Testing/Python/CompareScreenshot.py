"""Compares screenshots (PNG) with their baselines by VTK's image comparison, vtkImageDifference,
with the thresholds of the C++ image tests (Testing/Cxx/ImageRegression.h; README, "Writing a
regression image test for your own scene"):

- pixel threshold 0: every level of every channel counts (vtkImageDifference's default, 105,
  and vtkTesting's, forgive up to 105 levels per channel: a 10 % brighter image gives 0);
- no shift, no averaging: a pixel is compared with the same pixel of the baseline only;
- both images padded by 2 black pixels: vtkImageDifference skips a 2-pixel border;
- error threshold 0.05 (the thresholded error is the sum of |difference| / (3 * 255) over pixels
  and channels): measured between runs of these screenshots (Mesa's llvmpipe under Xvfb) 0.000;
  0.05 is room for another platform's last-bit rounding, 40 times below the smallest mutation.

Then the mutations: each screenshot 1 % brighter, shifted right by one pixel and with a 2 x 2
patch at its centre changed by 128 levels must FAIL against its baseline (a comparison loosened
again fails the test). On failure the screenshot's difference image is written to TEMP_DIR.

usage: CompareScreenshot.py TEMP_DIR SCREENSHOT.png BASELINE.png [SCREENSHOT.png BASELINE.png ...]
       CompareScreenshot.py --self-test BASELINE.png [...]   (each baseline against itself and
       its mutations; no screenshot needed)"""
import os
import sys

import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkImagingCore import vtkImageConstantPad, vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

PIXEL_THRESHOLD = 0
ALLOW_SHIFT = False
AVERAGING = False
ERROR_THRESHOLD = 0.05


def read(path):
    """The PNG at path as an (height, width, 3) uint8 array."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)
    if pixels.shape[2] < 3:
        pixels = numpy.repeat(pixels[:, :, :1], 3, axis=2)
    return numpy.ascontiguousarray(pixels[:, :, :3])


def to_vtk(pixels):
    height, width, _ = pixels.shape
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    image.GetPointData().SetScalars(numpy_to_vtk(pixels.reshape(-1, 3), deep=1))
    pad = vtkImageConstantPad()
    pad.SetInputData(image)
    pad.SetConstant(0)
    pad.SetOutputWholeExtent(-2, width + 1, -2, height + 1, 0, 0)
    pad.Update()
    return pad.GetOutput()


def compare(test, baseline):
    """(thresholded error, vtkImageDifference) of two (height, width, 3) uint8 arrays."""
    difference = vtkImageDifference()
    difference.SetInputData(to_vtk(test))
    difference.SetImageData(to_vtk(baseline))
    difference.SetThreshold(PIXEL_THRESHOLD)
    difference.SetAllowShift(ALLOW_SHIFT)
    difference.SetAveraging(AVERAGING)
    difference.Update()
    return difference.GetThresholdedError(), difference


def mutations(pixels):
    brighter = numpy.minimum(255, numpy.rint(pixels * 1.01)).astype(numpy.uint8)
    shifted = pixels.copy()
    shifted[:, 1:] = pixels[:, :-1]
    patched = pixels.copy()
    y, x = pixels.shape[0] // 2, pixels.shape[1] // 2
    patched[y:y + 2, x:x + 2] = (patched[y:y + 2, x:x + 2].astype(int) + 128) % 256
    return [("1 % brighter", brighter), ("shifted right by one pixel", shifted),
            ("a 2 x 2 patch changed", patched)]


def mutations_fail(name, pixels, baseline):
    """True when every mutation of pixels fails against baseline (each printed)."""
    good = True
    for what, mutated in mutations(pixels):
        error, _ = compare(mutated, baseline)
        fails = error > ERROR_THRESHOLD
        print(f"  mutation '{what}': thresholded error {error:.3f}: "
              f"{'fails, as it must' if fails else 'PASSES'}")
        if not fails:
            print(f"FAILED: the comparison does not see {name} {what}: it has been loosened")
            good = False
    return good


def self_test(baselines):
    failed = 0
    for path in baselines:
        baseline = read(path)
        error, _ = compare(baseline, baseline)
        print(f"{os.path.basename(path)}: against itself {error:.3f}")
        if error != 0.0:
            print(f"FAILED: {path} does not match itself")
            failed += 1
        if not mutations_fail(path, baseline, baseline):
            failed += 1
    return failed


def compare_pairs(temporary, pairs):
    os.makedirs(temporary, exist_ok=True)
    failed = 0
    for screenshot, baseline_path in zip(pairs[0::2], pairs[1::2]):
        if not os.path.isfile(screenshot) or not os.path.isfile(baseline_path):
            missing = baseline_path if os.path.isfile(screenshot) else screenshot
            print(f"FAILED: missing {missing}")
            failed += 1
            continue
        test, baseline = read(screenshot), read(baseline_path)
        if test.shape != baseline.shape:
            print(f"FAILED: {screenshot} is {test.shape[1]} x {test.shape[0]}, its baseline "
                  f"{baseline_path} {baseline.shape[1]} x {baseline.shape[0]}")
            failed += 1
            continue
        error, difference = compare(test, baseline)
        print(f"{os.path.basename(screenshot)}: thresholded error {error:.3f} (pixel threshold "
              f"{PIXEL_THRESHOLD}, no shift, no averaging, error threshold {ERROR_THRESHOLD})")
        if error > ERROR_THRESHOLD:
            path = os.path.join(temporary, "difference_" + os.path.basename(screenshot))
            writer = vtkPNGWriter()
            writer.SetFileName(path)
            writer.SetInputConnection(difference.GetOutputPort())
            writer.Write()
            print(f"FAILED: {screenshot} differs from {baseline_path}; difference image {path}")
            failed += 1
        if not mutations_fail(screenshot, test, baseline):
            failed += 1
    return failed


if __name__ == "__main__":
    arguments = sys.argv[1:]
    if arguments[:1] == ["--self-test"] and len(arguments) > 1:
        sys.exit(1 if self_test(arguments[1:]) else 0)
    if len(arguments) < 3 or len(arguments) % 2 == 0:
        sys.exit(__doc__)
    sys.exit(1 if compare_pairs(arguments[0], arguments[1:]) else 0)
