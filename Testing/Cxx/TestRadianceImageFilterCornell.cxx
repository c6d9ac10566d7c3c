// SPDX-License-Identifier: BSD-3-Clause
// vtkRadianceImageFilter, regression image (Data/Baseline, vtkImageDifference on the
// tone-mapped RGB with the thresholds of ImageRegression.h, its mutations failing): the Cornell
// box through its scene camera, 128 x 128, 4 samples per pixel, from a coarse solution (MaxLevel 2,
// a 16 x 64 hemisphere grid). The lamp, the red and green walls' colour bleeding onto the white
// ones and the blocks' shading must appear where the room puts them.
#include "RenderTestPipeline.h"

#include <iostream>

int TestRadianceImageFilterCornell(int argc, char* argv[])
{
  RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 2);
  pipeline.Render->SetCameraName("main");
  pipeline.Render->SetWidth(128);
  pipeline.Render->SetHeight(128);
  pipeline.Render->SetSamplesPerPixel(4);
  pipeline.Render->Update();
  std::cout << pipeline.Propagation->GetOutput()->GetNumberOfPoints() << " points, "
            << pipeline.Propagation->GetShots() << " shots\n";
  return RenderTestPipeline::MatchesBaseline(pipeline.Render->GetOutput(), argc, argv)
    ? EXIT_SUCCESS
    : EXIT_FAILURE;
}
