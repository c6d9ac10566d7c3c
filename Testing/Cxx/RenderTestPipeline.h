// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RenderTestPipeline.h
 * @brief Test helpers for vtkRadianceImageFilter: the whole pipeline reader -> subdivision ->
 * cover -> propagation -> render for a scene at test-sized settings, and the regression
 * comparison of the tone-mapped `RGB` with a baseline image (vtkTesting, vtkImageDifference).
 */
#ifndef SPHCOVER_RENDERTESTPIPELINE_H
#define SPHCOVER_RENDERTESTPIPELINE_H

#include "vtkIntervalSubdivisionFilter.h"
#include "vtkLightPropagationFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkRadianceImageFilter.h"
#include "vtkSphericalCoverFilter.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTesting.h>
#include <vtkTrivialProducer.h>

#include <string>

namespace RenderTestPipeline
{
struct Pipeline
{
  vtkNew<vtkPatchSceneReader> Reader;
  vtkNew<vtkIntervalSubdivisionFilter> Subdivision;
  vtkNew<vtkSphericalCoverFilter> Cover;
  vtkNew<vtkLightPropagationFilter> Propagation;
  vtkNew<vtkRadianceImageFilter> Render;

  /// `scene` is a file name under Data/scenes; coarse hemispheres keep the test in seconds.
  Pipeline(const std::string& scene, int maxLevel, int thetaBins = 16, int phiBins = 64)
  {
    this->Reader->SetFileName((std::string(SPHCOVER_DATA_DIR "/scenes/") + scene).c_str());
    this->Subdivision->SetInputConnection(this->Reader->GetOutputPort());
    this->Subdivision->SetMaxLevel(maxLevel);
    this->Subdivision->SetThetaBins(thetaBins);
    this->Subdivision->SetPhiBins(phiBins);
    this->Cover->SetInputConnection(this->Subdivision->GetOutputPort(0));
    this->Cover->SetThetaBins(thetaBins);
    this->Cover->SetPhiBins(phiBins);
    this->Propagation->SetInputConnection(this->Cover->GetOutputPort(0));
    this->Render->SetInputConnection(0, this->Propagation->GetOutputPort(0));
    this->Render->SetPatchesConnection(this->Subdivision->GetOutputPort(0));
  }
};

/**
 * Compares the tone-mapped RGB of `image` with the baseline given by -V on the command line
 * (vtkTesting::RegressionTest: vtkImageDifference, the failing image written under -T).
 * Threshold: vtkImageDifference's summed error of the worst-matching alignment; 10 is VTK's
 * customary threshold for software-rendered images (the render is deterministic, so a change
 * in the method shows as a much larger difference).
 */
inline bool MatchesBaseline(vtkImageData* image, int argc, char* argv[], double threshold = 10.0)
{
  vtkNew<vtkImageData> rgb;
  rgb->SetExtent(image->GetExtent());
  rgb->GetPointData()->SetScalars(image->GetPointData()->GetArray("RGB"));
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(rgb);
  vtkNew<vtkTesting> testing;
  for (int k = 0; k < argc; ++k)
  {
    testing->AddArgument(argv[k]);
  }
  return testing->RegressionTest(producer, threshold) == vtkTesting::PASSED;
}
}

#endif
