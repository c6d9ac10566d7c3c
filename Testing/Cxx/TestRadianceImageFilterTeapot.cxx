// SPDX-License-Identifier: BSD-3-Clause
// vtkRadianceImageFilter on non-diffuse surfaces (paper §5.3.1), regression image
// (Data/Baseline, vtkImageDifference on the tone-mapped RGB, ImageRegression.h's thresholds): the
// teapot room (a mirror wall of k_s = 0.9, a phong teapot) through its scene camera, 96 x 72,
// 2 samples per pixel, from a coarse solution (MaxLevel 2, a 16 x 64 hemisphere grid). The
// mirror must show the room (its emission and diffuse part are zero, so without the
// directional part it would be black) and the teapot its highlights. Also asserted: the mirror
// wall's mean radiance is a sizeable share of the rest of the image's.
#include "RenderTestPipeline.h"

#include <vtkDataArray.h>

#include <iostream>

int TestRadianceImageFilterTeapot(int argc, char* argv[])
{
  RenderTestPipeline::Pipeline pipeline("teapot_room.scene", 2);
  pipeline.Render->SetCameraName("corner");
  pipeline.Render->SetWidth(96);
  pipeline.Render->SetHeight(72);
  pipeline.Render->SetSamplesPerPixel(2);
  pipeline.Render->Update();
  vtkImageData* image = pipeline.Render->GetOutput();
  std::cout << pipeline.Propagation->GetOutput()->GetNumberOfPoints() << " points, "
            << pipeline.Propagation->GetShots() << " shots\n";
  vtkDataArray* radiance = image->GetPointData()->GetArray("Radiance");
  vtkDataArray* surface = image->GetPointData()->GetArray("SurfaceId");
  if (!radiance || !surface)
  {
    std::cerr << "the render has no Radiance or SurfaceId\n";
    return EXIT_FAILURE;
  }
  // mirror_wall is the scene's third surface (index 2).
  double mirror = 0.0;
  double rest = 0.0;
  vtkIdType mirrorPixels = 0;
  vtkIdType restPixels = 0;
  for (vtkIdType p = 0; p < radiance->GetNumberOfTuples(); ++p)
  {
    const double luminance =
      radiance->GetComponent(p, 0) + radiance->GetComponent(p, 1) + radiance->GetComponent(p, 2);
    if (surface->GetComponent(p, 0) == 2)
    {
      mirror += luminance;
      ++mirrorPixels;
    }
    else if (surface->GetComponent(p, 0) >= 0)
    {
      rest += luminance;
      ++restPixels;
    }
  }
  if (mirrorPixels < 100 || restPixels < 100)
  {
    std::cerr << "the camera sees " << mirrorPixels << " mirror pixels and " << restPixels
              << " others; the view is not the one the test expects\n";
    return EXIT_FAILURE;
  }
  const double ratio = (mirror / mirrorPixels) / (rest / restPixels);
  std::cout << "mirror wall mean radiance / the other surfaces' = " << ratio << "\n";
  if (ratio < 0.3)
  {
    std::cerr << "the mirror wall is too dark (" << ratio << " of the rest): it does not show "
              << "the room\n";
    return EXIT_FAILURE;
  }
  return RenderTestPipeline::MatchesBaseline(image, argc, argv) ? EXIT_SUCCESS : EXIT_FAILURE;
}
