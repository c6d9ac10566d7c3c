// SPDX-License-Identifier: BSD-3-Clause
// The regression image comparison itself (ImageRegression.h), on every baseline of the C++ image
// tests given on the command line: a baseline matches itself with a thresholded error of 0, and
// its 1 % brighter, one-pixel-shifted and 2 x 2-patched versions FAIL. A mutation test: it fails
// when the comparison is loosened again (a per-pixel threshold, a shift allowed, averaging, a
// larger error threshold). For contrast it prints what vtkRegressionTestImage's comparison
// (vtkImageDifference's defaults, error threshold 10) makes of the same mutations: 0.
// Needs no X server: it reads PNG files only.
#include "ImageRegression.h"
#include "TestFailures.h"

#include <iostream>
#include <string>

int TestImageRegressionMutations(int argc, char* argv[])
{
  using TestFailures::Check;
  ImageRegression::Tolerance vtkDefaults;
  vtkDefaults.PixelThreshold = 105;
  vtkDefaults.AllowShift = true;
  vtkDefaults.Averaging = true;
  vtkDefaults.ErrorThreshold = 10.0;
  int baselines = 0;
  for (int k = 1; k < argc; ++k)
  {
    const std::string path = argv[k];
    vtkSmartPointer<vtkImageData> baseline = ImageRegression::ReadPNG(path);
    Check(baseline != nullptr, "read " + path);
    if (!baseline)
    {
      continue;
    }
    ++baselines;
    std::cout << ImageRegression::BaseName(path) << ":\n";
    const ImageRegression::Verdict self = ImageRegression::Compare(baseline, baseline);
    Check(self.Passed && self.ThresholdedError == 0.0, path + " matches itself with error 0");
    Check(ImageRegression::MutationsFail(baseline, baseline), path + ": every mutation fails");
    for (const auto& mutation : ImageRegression::Mutations(baseline))
    {
      const ImageRegression::Verdict loose =
        ImageRegression::Compare(mutation.second, baseline, vtkDefaults);
      std::cout << "  vtkRegressionTestImage's comparison of '" << mutation.first
                << "': thresholded error " << loose.ThresholdedError << "\n";
    }
  }
  Check(baselines > 0, "at least one baseline given");
  return TestFailures::ExitCode();
}
