// SPDX-License-Identifier: BSD-3-Clause
// vtkHemisphereExtractor, regression image (VTK-style baseline): the hemisphere of a
// characteristic point on the teapot room's floor in front of the teapot (between the teapot and
// the camera), as its (phi, theta) image (above) and as the 3-D hemisphere in the room (below),
// coloured by the named scene entry seen through each cell (SurfaceNameId: the teapot's 32
// Bezier surfaces are one entry, one colour): the teapot must take a large part of the
// hemisphere on the side facing it. The cover uses a 16 x 64 grid filled by ray casting, which
// keeps the test fast (the projection fill of the Bezier teapot at 32 x 128 takes seconds).
#include "HemisphereTestScenes.h"
#include "ImageRegression.h"

#include <vtkCellData.h>

#include <iostream>

int TestHemisphereExtractorTeapot(int argc, char* argv[])
{
  HemisphereTestScenes::Pipeline pipeline(SPHCOVER_DATA_DIR "/scenes/teapot_room.scene", 2);
  pipeline.Cover->SetThetaBins(16);
  pipeline.Cover->SetPhiBins(64);
  pipeline.Cover->SetFillMethodToRayCasting();
  pipeline.Cover->Update();
  const int floor = HemisphereTestScenes::SurfaceIdOf(pipeline.CoverPoints(), "floor");
  const double front[3] = { 0.0, 0.0, 4.0 };
  const vtkIdType point =
    HemisphereTestScenes::NearestPointOfSurface(pipeline.CoverPoints(), floor, front);
  if (point < 0)
  {
    std::cerr << "FAILED: no characteristic point on the floor\n";
    return EXIT_FAILURE;
  }
  pipeline.Extractor->SetPointId(point);
  pipeline.Extractor->SetRadius(1.0);
  pipeline.Extractor->Update();
  double p[3];
  pipeline.CoverPoints()->GetPoint(point, p);
  std::cout << "point " << point << " at (" << p[0] << ", " << p[1] << ", " << p[2] << ")\n";

  vtkNew<vtkRenderWindow> window;
  // The scene camera widened: the point lies just below its field of view.
  HemisphereTestScenes::RenderHemisphere(pipeline, window, 0.7, "SurfaceNameId");
  return ImageRegression::Check(window, argc, argv) ? EXIT_SUCCESS : EXIT_FAILURE;
}
