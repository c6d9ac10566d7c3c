// SPDX-License-Identifier: BSD-3-Clause
// Core's Bezier evaluation agrees with VTK's own vtkBezierQuadrilateral on the reader's output:
// every Utah teapot patch and random patches of degrees up to 7 (square and anisotropic), at
// random parametric points. Agreement to 1e-12 of the bounding box proves that the reader
// writes the control points in VTK's ordering and the degrees in HigherOrderDegrees.
#include "vtkSurfaceGridBuilder.h"

#include "geometry/BezierPatch.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"

#include <vtkBezierQuadrilateral.h>
#include <vtkCellType.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <random>

namespace
{
/// Largest distance between Core's and VTK's evaluation over `samples` random points of every
/// cell, relative to the diagonal of the scene's bounds.
double MaxRelativeDeviation(const sphcover::Scene& scene, int samples, std::mt19937_64& random)
{
  vtkNew<vtkUnstructuredGrid> grid;
  vtkSurfaceGridBuilder::Build(scene, grid);
  double bounds[6];
  grid->GetBounds(bounds);
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  vtkNew<vtkGenericCell> cell;
  std::vector<double> weights(256);
  double worst = 0.0;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const sphcover::BezierPatch& patch = scene.Surfaces[static_cast<size_t>(c)].Patch;
    grid->GetCell(c, cell);
    for (int s = 0; s < samples; ++s)
    {
      // Include the corners and edges, where an ordering error shows first.
      double pcoords[3] = { unit(random), unit(random), 0.0 };
      if (s < 4)
      {
        pcoords[0] = (s & 1) ? 1.0 : 0.0;
        pcoords[1] = (s & 2) ? 1.0 : 0.0;
      }
      int subId = 0;
      double vtkPoint[3];
      cell->EvaluateLocation(subId, pcoords, vtkPoint, weights.data());
      const glm::dvec3 corePoint = patch.Evaluate(pcoords[0], pcoords[1]);
      const double deviation = std::sqrt((vtkPoint[0] - corePoint.x) * (vtkPoint[0] - corePoint.x) +
        (vtkPoint[1] - corePoint.y) * (vtkPoint[1] - corePoint.y) +
        (vtkPoint[2] - corePoint.z) * (vtkPoint[2] - corePoint.z));
      worst = std::max(worst, deviation / diagonal);
    }
  }
  return worst;
}
}

int TestBezierQuadrilateralAgreement(int, char*[])
{
  std::mt19937_64 random(20261122);
  int failures = 0;

  const sphcover::Scene teapot = sphcover::LoadBptAsScene(SPHCOVER_DATA_DIR "/models/teapot.bpt");
  const double teapotDeviation = MaxRelativeDeviation(teapot, 64, random);
  std::cout << "teapot: 32 patches, max deviation / bbox diagonal = " << teapotDeviation << "\n";
  if (!(teapotDeviation < 1e-12))
  {
    std::cerr << "Teapot patches disagree with vtkBezierQuadrilateral\n";
    ++failures;
  }

  // Random control nets of many degree pairs, square and anisotropic.
  const int degreePairs[][2] = { { 2, 2 },
    { 3, 3 },
    { 2, 3 },
    { 3, 2 },
    { 4, 4 },
    { 5, 2 },
    { 1, 4 },
    { 4, 1 },
    { 6, 6 },
    { 7, 7 },
    { 7, 3 },
    { 2, 7 } };
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  sphcover::Scene randomScene;
  randomScene.SurfaceNames.push_back("random");
  randomScene.Materials.emplace_back();
  for (const auto& degrees : degreePairs)
  {
    const int m = degrees[0];
    const int n = degrees[1];
    std::vector<glm::dvec3> points;
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= m; ++i)
      {
        // A wavy sheet over the unit square, so the patch is not degenerate.
        points.emplace_back(double(i) / m + 0.2 * coordinate(random),
          double(j) / n + 0.2 * coordinate(random),
          0.5 * coordinate(random));
      }
    }
    randomScene.Surfaces.emplace_back(sphcover::BezierPatch(m, n, std::move(points)), 0, 0);
  }
  const double randomDeviation = MaxRelativeDeviation(randomScene, 64, random);
  std::cout << "random patches of degrees up to 7: max deviation / bbox diagonal = "
            << randomDeviation << "\n";
  if (!(randomDeviation < 1e-12))
  {
    std::cerr << "Random patches disagree with vtkBezierQuadrilateral\n";
    ++failures;
  }

  // The cell types are the contract of Documentation/Pipeline.md#reader.
  vtkNew<vtkUnstructuredGrid> grid;
  vtkSurfaceGridBuilder::Build(randomScene, grid);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    if (grid->GetCellType(c) != VTK_BEZIER_QUADRILATERAL)
    {
      std::cerr << "cell " << c << " is not a VTK_BEZIER_QUADRILATERAL\n";
      ++failures;
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
