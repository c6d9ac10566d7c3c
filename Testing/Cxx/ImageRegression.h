// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ImageRegression.h
 * @brief Regression image comparison that sees a 1 % change: vtkImageDifference with every
 * level counted, no shift, no averaging and an error threshold from the measured run-to-run
 * difference, plus the mutations that prove it (README, "Writing a regression image test for
 * your own scene").
 *
 * Why not vtkRegressionTestImage: vtkTesting::RegressionTest leaves vtkImageDifference at its
 * defaults, which forgive up to 105 levels per channel and pixel, any shift of up to two pixels
 * and 3x3 averaging before the error threshold (10) is applied. An image 10 % brighter, shifted
 * by one pixel or with a 2 x 2 hole passes with a thresholded error of 0. Our renders are
 * deterministic CPU renders (the radiance renderer, Mesa's llvmpipe under Xvfb): run after run
 * they are the same bytes, so nothing needs forgiving.
 *
 * The comparison (Tolerance):
 * - PixelThreshold 0: vtkImageDifference subtracts it from every channel's |difference|; 0
 *   counts every level (a 1 % brighter image changes most pixels by one level).
 * - AllowShift off, Averaging off: a pixel is compared with the same pixel of the baseline only.
 * - both images padded by 2 pixels of black first: vtkImageDifference skips a 2-pixel border,
 *   which would leave the image's edges unchecked.
 * - ErrorThreshold 0.05: the thresholded error is sum over pixels and channels of
 *   |difference| / (3 * 255), i.e. "whole pixels gone from black to white". Measured between
 *   runs on this platform: 0.000 for every test. 0.05 (38 levels in all, e.g. 13 pixels off by
 *   one level in each channel) leaves room for another compiler's or CPU's last-bit rounding
 *   and is 40 times below the smallest mutation below (2.0).
 *
 * The mutations (Mutations): the rendered image 1 % brighter, shifted right by one pixel, and
 * with a 2 x 2 patch at its centre changed by 128 levels per channel (thresholded error 2.0 at
 * any image content). Check() asserts each of them FAILS against the baseline, so a test whose
 * comparison is loosened again fails itself.
 */
#ifndef SPHCOVER_IMAGEREGRESSION_H
#define SPHCOVER_IMAGEREGRESSION_H

#include <vtkImageConstantPad.h>
#include <vtkImageData.h>
#include <vtkImageDifference.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace ImageRegression
{
/// vtkImageDifference's thresholds; the defaults are the project's policy (see the file comment).
struct Tolerance
{
  int PixelThreshold = 0;
  bool AllowShift = false;
  bool Averaging = false;
  double ErrorThreshold = 0.05;
};

struct Verdict
{
  bool Passed = false;
  double Error = 0.0;
  double ThresholdedError = 0.0;
  std::string Problem; ///< non-empty when the images cannot be compared at all
  vtkSmartPointer<vtkImageData> Difference;
};

/// An RGB unsigned char copy of `image`'s scalars (the first three components), its extent
/// starting at 0.
inline vtkSmartPointer<vtkImageData> RGB(vtkImageData* image)
{
  vtkSmartPointer<vtkImageData> rgb = vtkSmartPointer<vtkImageData>::New();
  int d[3];
  image->GetDimensions(d);
  rgb->SetExtent(0, d[0] - 1, 0, d[1] - 1, 0, d[2] - 1);
  rgb->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  vtkDataArray* in = image->GetPointData()->GetScalars();
  vtkUnsignedCharArray* out = vtkUnsignedCharArray::SafeDownCast(rgb->GetPointData()->GetScalars());
  for (vtkIdType p = 0; in && p < out->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int component = std::min(c, in->GetNumberOfComponents() - 1);
      out->SetValue(3 * p + c, static_cast<unsigned char>(in->GetComponent(p, component)));
    }
  }
  return rgb;
}

inline vtkSmartPointer<vtkImageData> Padded(vtkImageData* image)
{
  int extent[6];
  image->GetExtent(extent);
  vtkNew<vtkImageConstantPad> pad;
  pad->SetInputData(image);
  pad->SetConstant(0);
  pad->SetOutputWholeExtent(
    extent[0] - 2, extent[1] + 2, extent[2] - 2, extent[3] + 2, extent[4], extent[5]);
  pad->Update();
  vtkSmartPointer<vtkImageData> out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(pad->GetOutput());
  return out;
}

/// The comparison every regression image test of this project makes.
inline Verdict Compare(vtkImageData* test, vtkImageData* baseline, const Tolerance& tolerance = {})
{
  Verdict verdict;
  int a[3];
  int b[3];
  test->GetDimensions(a);
  baseline->GetDimensions(b);
  if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2])
  {
    verdict.Problem = "the image is " + std::to_string(a[0]) + " x " + std::to_string(a[1]) +
      ", its baseline " + std::to_string(b[0]) + " x " + std::to_string(b[1]);
    return verdict;
  }
  vtkSmartPointer<vtkImageData> t = Padded(RGB(test));
  vtkSmartPointer<vtkImageData> v = Padded(RGB(baseline));
  vtkNew<vtkImageDifference> difference;
  difference->SetInputData(t);
  difference->SetImageData(v);
  difference->SetThreshold(tolerance.PixelThreshold);
  difference->SetAllowShift(tolerance.AllowShift);
  difference->SetAveraging(tolerance.Averaging);
  difference->Update();
  verdict.Error = difference->GetError();
  verdict.ThresholdedError = difference->GetThresholdedError();
  verdict.Passed = verdict.ThresholdedError <= tolerance.ErrorThreshold;
  verdict.Difference = vtkSmartPointer<vtkImageData>::New();
  verdict.Difference->DeepCopy(difference->GetOutput());
  return verdict;
}

/// The window's pixels (back buffer, RGB), as vtkRegressionTestImage grabs them.
inline vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkSmartPointer<vtkImageData> image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

/// The mutations a regression image test must see, each a copy of `image` (RGB unsigned char).
inline vtkSmartPointer<vtkImageData> Mutated(vtkImageData* image,
  const std::function<void(unsigned char*, int, int)>& change)
{
  vtkSmartPointer<vtkImageData> copy = RGB(image);
  int d[3];
  copy->GetDimensions(d);
  change(static_cast<unsigned char*>(copy->GetScalarPointer()), d[0], d[1]);
  return copy;
}

inline std::vector<std::pair<std::string, vtkSmartPointer<vtkImageData>>> Mutations(
  vtkImageData* image)
{
  std::vector<std::pair<std::string, vtkSmartPointer<vtkImageData>>> mutations;
  mutations.emplace_back("1 % brighter",
    Mutated(image,
      [](unsigned char* p, int w, int h)
      {
        for (int k = 0; k < 3 * w * h; ++k)
        {
          p[k] = static_cast<unsigned char>(std::min(255.0, std::round(p[k] * 1.01)));
        }
      }));
  mutations.emplace_back("shifted right by one pixel",
    Mutated(image,
      [](unsigned char* p, int w, int h)
      {
        for (int y = 0; y < h; ++y)
        {
          unsigned char* row = p + 3 * w * y;
          std::memmove(row + 3, row, 3 * (w - 1));
        }
      }));
  mutations.emplace_back("a 2 x 2 patch changed",
    Mutated(image,
      [](unsigned char* p, int w, int h)
      {
        for (int y = h / 2; y < h / 2 + 2; ++y)
        {
          for (int x = w / 2; x < w / 2 + 2; ++x)
          {
            for (int c = 0; c < 3; ++c)
            {
              unsigned char& v = p[3 * (w * y + x) + c];
              v = static_cast<unsigned char>((v + 128) % 256);
            }
          }
        }
      }));
  return mutations;
}

/// The mutations of `image` compared with `baseline`: true when every one FAILS (printed).
inline bool MutationsFail(vtkImageData* image,
  vtkImageData* baseline,
  const Tolerance& tolerance = {})
{
  bool all = true;
  for (const auto& mutation : Mutations(image))
  {
    const Verdict verdict = Compare(mutation.second, baseline, tolerance);
    std::cout << "mutation '" << mutation.first << "': thresholded error "
              << verdict.ThresholdedError << " (threshold " << tolerance.ErrorThreshold
              << "): " << (verdict.Passed ? "PASSES" : "fails, as it must") << "\n";
    if (verdict.Passed)
    {
      std::cerr << "FAILED: the comparison does not see the rendered image " << mutation.first
                << " (thresholded error " << verdict.ThresholdedError
                << " <= " << tolerance.ErrorThreshold << "): it has been loosened\n";
      all = false;
    }
  }
  return all;
}

inline vtkSmartPointer<vtkImageData> ReadPNG(const std::string& path)
{
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    return nullptr;
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkImageData> image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(reader->GetOutput());
  return image;
}

inline void WritePNG(vtkImageData* image, const std::string& path)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

inline std::string Argument(int argc, char* argv[], const char* flag)
{
  for (int k = 0; k + 1 < argc; ++k)
  {
    if (std::strcmp(argv[k], flag) == 0)
    {
      return argv[k + 1];
    }
  }
  return {};
}

inline std::string BaseName(const std::string& path)
{
  const std::string::size_type slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/**
 * The regression image check of a test: `image` against the baseline given by -V, the rendered
 * image written under -T (the candidate baseline to review and copy to Data/Baseline), the
 * difference image next to it on failure, then the mutations of the rendered image, each of
 * which must fail. True when the image matches and every mutation fails.
 */
inline bool Check(vtkImageData* image, int argc, char* argv[], const Tolerance& tolerance = {})
{
  const std::string baselinePath = Argument(argc, argv, "-V");
  const std::string temporary = Argument(argc, argv, "-T");
  if (baselinePath.empty() || temporary.empty())
  {
    std::cerr << "FAILED: a regression image test needs -V BASELINE.png -T TEMPORARY_DIR\n";
    return false;
  }
  const std::string name = BaseName(baselinePath);
  vtkSmartPointer<vtkImageData> rgb = RGB(image);
  const std::string rendered = temporary + "/" + name;
  WritePNG(rgb, rendered);
  vtkSmartPointer<vtkImageData> baseline = ReadPNG(baselinePath);
  if (!baseline)
  {
    std::cerr << "FAILED: no baseline " << baselinePath << "; the rendered image is " << rendered
              << " (review it, then copy it there)\n";
    return false;
  }
  const Verdict verdict = Compare(rgb, baseline, tolerance);
  if (!verdict.Problem.empty())
  {
    std::cerr << "FAILED: " << verdict.Problem << " (" << rendered << ")\n";
    return false;
  }
  std::cout << name << ": thresholded error " << verdict.ThresholdedError << " (pixel threshold "
            << tolerance.PixelThreshold << ", no shift, no averaging, error threshold "
            << tolerance.ErrorThreshold << ")\n";
  std::cout << "<DartMeasurement name=\"ImageError\" type=\"numeric/double\">"
            << verdict.ThresholdedError << "</DartMeasurement>\n";
  bool passed = verdict.Passed;
  if (!passed)
  {
    const std::string difference = temporary + "/" + name.substr(0, name.size() - 4) + ".diff.png";
    WritePNG(verdict.Difference, difference);
    std::cerr << "FAILED: " << rendered << " differs from " << baselinePath
              << " (thresholded error " << verdict.ThresholdedError << " > "
              << tolerance.ErrorThreshold << "); difference image " << difference << "\n";
  }
  // The comparison must see a 1 % change of this very image.
  if (!MutationsFail(rgb, baseline, tolerance))
  {
    passed = false;
  }
  return passed;
}

/// Check() of what a render window shows.
inline bool Check(vtkRenderWindow* window, int argc, char* argv[], const Tolerance& tolerance = {})
{
  return Check(Capture(window), argc, argv, tolerance);
}
}

#endif
