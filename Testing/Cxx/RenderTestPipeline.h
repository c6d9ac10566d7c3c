// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RenderTestPipeline.h
 * @brief Test helpers for vtkRadianceImageFilter: the whole pipeline reader -> subdivision ->
 * cover -> propagation -> render for a scene at test-sized settings, and the regression
 * comparison of the tone-mapped `RGB` with a baseline image (ImageRegression.h).
 */
#ifndef SPHCOVER_RENDERTESTPIPELINE_H
#define SPHCOVER_RENDERTESTPIPELINE_H

#include "vtkIntervalSubdivisionFilter.h"
#include "vtkLightPropagationFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkRadianceImageFilter.h"
#include "vtkSphericalCoverFilter.h"

#include "ImageRegression.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

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
 * (ImageRegression::Check: every level counted, no shift, no averaging, error threshold 0.05;
 * the rendered image written under -T; its 1 % brighter, shifted and patched versions must fail).
 */
inline bool MatchesBaseline(vtkImageData* image, int argc, char* argv[])
{
  vtkNew<vtkImageData> rgb;
  rgb->SetExtent(image->GetExtent());
  rgb->GetPointData()->SetScalars(image->GetPointData()->GetArray("RGB"));
  return ImageRegression::Check(rgb, argc, argv);
}
}

#endif
