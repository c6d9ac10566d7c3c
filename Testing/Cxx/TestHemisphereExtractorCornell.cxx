// SPDX-License-Identifier: BSD-3-Clause
// vtkHemisphereExtractor, regression image (VTK-style baseline): the hemisphere of the
// characteristic point at the centre of the Cornell box's floor, as its (phi, theta) image
// (above) and as the 3-D hemisphere in the room (below), coloured by the surface seen through
// each cell. The blocks, walls and the lamp must appear where the room puts them.
#include "HemisphereTestScenes.h"
#include "ImageRegression.h"

#include <vtkCellData.h>

#include <iostream>

int TestHemisphereExtractorCornell(int argc, char* argv[])
{
  HemisphereTestScenes::Pipeline pipeline(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene", 2);
  pipeline.Cover->Update();
  const int floor = HemisphereTestScenes::SurfaceIdOf(pipeline.CoverPoints(), "floor");
  const double centre[3] = { 278.0, 0.0, 279.6 };
  const vtkIdType point =
    HemisphereTestScenes::NearestPointOfSurface(pipeline.CoverPoints(), floor, centre);
  if (point < 0)
  {
    std::cerr << "FAILED: no characteristic point on the floor\n";
    return EXIT_FAILURE;
  }
  pipeline.Extractor->SetPointId(point);
  // A quarter of the room's height: large enough to read, small enough to stay below the blocks'
  // tops seen from the camera.
  pipeline.Extractor->SetRadius(120.0);
  pipeline.Extractor->Update();
  std::cout << "point " << point << ", " << pipeline.Extractor->GetImageOutput()->GetNumberOfCells()
            << " cells\n";

  vtkNew<vtkRenderWindow> window;
  HemisphereTestScenes::RenderHemisphere(pipeline, window, 1.0);
  return ImageRegression::Check(window, argc, argv) ? EXIT_SUCCESS : EXIT_FAILURE;
}
