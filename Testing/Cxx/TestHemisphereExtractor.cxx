// SPDX-License-Identifier: BSD-3-Clause
// vtkHemisphereExtractor (Documentation/Pipeline.md#inspection-filters), facts:
// - for every characteristic point of the Cornell box (MaxLevel 2), the image's Source is the
//   cover's row (SphericalCover::ExpandRow), SurfaceId and SurfaceNameId are the source's, the
//   cells with a source sum to the point's CoveredProjectedSolidAngle and all cells to pi (1e-12);
// - the image's geometry (extent, spacing, origin) and its WHOLE_EXTENT published before the
//   data pass, following the cover's bins when they change;
// - the 3-D mesh: one cell per (theta, phi) cell, points on the sphere of radius Radius (the
//   automatic radius is 5% of the bounding-box diagonal), none behind the tangent plane, each
//   cell in the direction of its own (theta, phi) cell in the frame (T, N x T, N), facing out;
// - in the closed furnace box every cell of every point has a source;
// - bad PointId, negative Radius and an input without a cover: one clear error each.
#include "FailureExpectation.h"
#include "HemisphereTestScenes.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "math/Constants.h"

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkInformation.h>
#include <vtkPoints.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
using sphcover::Pi;

int Fail(const std::string& what)
{
  std::cerr << "FAILED: " << what << "\n";
  return 1;
}

/// Image facts for one point: Source against ExpandRow, SurfaceId, measures.
int CheckImage(vtkHemisphereExtractor* extractor,
  vtkPolyData* coverPoints,
  const sphcover::SphericalCover& cover,
  vtkIdType point)
{
  int failures = 0;
  vtkImageData* image = extractor->GetImageOutput();
  const sphcover::HemisphereGrid& grid = cover.Grid();
  const std::string where = "point " + std::to_string(point);
  int extent[6];
  image->GetExtent(extent);
  double spacing[3];
  image->GetSpacing(spacing);
  double origin[3];
  image->GetOrigin(origin);
  if (extent[0] != 0 || extent[1] != grid.PhiBins() || extent[2] != 0 ||
    extent[3] != grid.ThetaBins() || extent[4] != 0 || extent[5] != 0 ||
    std::fabs(spacing[0] - 2 * Pi / grid.PhiBins()) > 1e-15 ||
    std::fabs(spacing[1] - 0.5 * Pi / grid.ThetaBins()) > 1e-15 || origin[0] != 0.0 ||
    origin[1] != 0.0 || origin[2] != 0.0)
  {
    return Fail(where + ": image extent, spacing or origin");
  }
  vtkDataArray* source = image->GetCellData()->GetArray("Source");
  vtkDataArray* surface = image->GetCellData()->GetArray("SurfaceId");
  vtkDataArray* measure = image->GetCellData()->GetArray("ProjectedSolidAngle");
  if (!source || !surface || !measure || source->GetNumberOfTuples() != grid.CellCount())
  {
    return Fail(where + ": image cell arrays Source, SurfaceId, ProjectedSolidAngle");
  }
  const std::vector<int32_t> row = cover.ExpandRow(static_cast<size_t>(point));
  vtkDataArray* surfaceOfPatch = coverPoints->GetPointData()->GetArray("SurfaceId");
  vtkDataArray* name = image->GetCellData()->GetArray("SurfaceNameId");
  vtkDataArray* nameOfPatch = coverPoints->GetPointData()->GetArray("SurfaceNameId");
  if (!name || !nameOfPatch)
  {
    return Fail(where + ": SurfaceNameId");
  }
  double covered = 0.0;
  double total = 0.0;
  int mismatches = 0;
  for (vtkIdType cell = 0; cell < grid.CellCount(); ++cell)
  {
    const int j = static_cast<int>(source->GetComponent(cell, 0));
    mismatches += j != row[static_cast<size_t>(cell)];
    const int expectedSurface = j < 0 ? -1 : static_cast<int>(surfaceOfPatch->GetComponent(j, 0));
    mismatches += static_cast<int>(surface->GetComponent(cell, 0)) != expectedSurface;
    const int expectedName = j < 0 ? -1 : static_cast<int>(nameOfPatch->GetComponent(j, 0));
    mismatches += static_cast<int>(name->GetComponent(cell, 0)) != expectedName;
    total += measure->GetComponent(cell, 0);
    covered += j >= 0 ? measure->GetComponent(cell, 0) : 0.0;
  }
  if (mismatches)
  {
    failures += Fail(where + ": " + std::to_string(mismatches) +
      " cells differ from the cover's row or the source's surface");
  }
  const double expected =
    coverPoints->GetPointData()->GetArray("CoveredProjectedSolidAngle")->GetComponent(point, 0);
  if (std::fabs(covered - expected) > 1e-12 || std::fabs(total - Pi) > 1e-12)
  {
    std::cerr << "  covered " << covered << " vs " << expected << ", total " << total << "\n";
    failures += Fail(where + ": projected solid angles");
  }
  return failures;
}

/// Mesh facts: radius, tangent plane, cell count, orientation and direction of every cell.
int CheckMesh(vtkHemisphereExtractor* extractor,
  vtkPolyData* coverPoints,
  const sphcover::HemisphereGrid& grid,
  vtkIdType point,
  double radius)
{
  int failures = 0;
  vtkPolyData* mesh = extractor->GetMeshOutput();
  if (mesh->GetNumberOfCells() != grid.CellCount())
  {
    return Fail("mesh: " + std::to_string(mesh->GetNumberOfCells()) + " cells instead of " +
      std::to_string(grid.CellCount()));
  }
  double p[3];
  coverPoints->GetPoint(point, p);
  double n[3];
  double t[3];
  coverPoints->GetPointData()->GetArray("Normals")->GetTuple(point, n);
  coverPoints->GetPointData()->GetArray("Tangents")->GetTuple(point, t);
  // The frame written out here, independently of the filter: B = N x T.
  const double b[3] = {
    n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]
  };
  const double eps = 1e-9 * radius;
  int off = 0;
  for (vtkIdType k = 0; k < mesh->GetNumberOfPoints(); ++k)
  {
    double x[3];
    mesh->GetPoint(k, x);
    const double d[3] = { x[0] - p[0], x[1] - p[1], x[2] - p[2] };
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    off += std::fabs(length - radius) > eps || n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < -eps;
  }
  if (off)
  {
    failures += Fail("mesh: " + std::to_string(off) +
      " points off the sphere of radius Radius or behind the tangent plane");
  }
  int misplaced = 0;
  int inward = 0;
  for (vtkIdType cell = 0; cell < mesh->GetNumberOfCells(); ++cell)
  {
    vtkPoints* corners = mesh->GetCell(cell)->GetPoints();
    double c[3] = { 0, 0, 0 };
    const int count = static_cast<int>(corners->GetNumberOfPoints());
    for (int k = 0; k < count; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        c[a] += corners->GetPoint(k)[a] / count - p[a] / count;
      }
    }
    const glm::dvec3 local(c[0] * t[0] + c[1] * t[1] + c[2] * t[2],
      c[0] * b[0] + c[1] * b[1] + c[2] * b[2],
      c[0] * n[0] + c[1] * n[1] + c[2] * n[2]);
    misplaced += grid.CellOfLocalDirection(local) != cell;
    double q[3][3];
    for (int k = 0; k < 3; ++k)
    {
      corners->GetPoint(k, q[k]);
    }
    const double u[3] = { q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2] };
    const double v[3] = { q[2][0] - q[0][0], q[2][1] - q[0][1], q[2][2] - q[0][2] };
    const double w[3] = {
      u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]
    };
    inward += w[0] * c[0] + w[1] * c[1] + w[2] * c[2] <= 0.0;
  }
  if (misplaced || inward)
  {
    failures += Fail("mesh: " + std::to_string(misplaced) +
      " cells not in the direction of their (theta, phi) cell, " + std::to_string(inward) +
      " facing inwards");
  }
  return failures;
}

bool WholeExtentIs(vtkHemisphereExtractor* extractor, int phiBins, int thetaBins)
{
  extractor->UpdateInformation();
  int extent[6];
  extractor->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  return extent[0] == 0 && extent[1] == phiBins && extent[2] == 0 && extent[3] == thetaBins &&
    extent[4] == 0 && extent[5] == 0;
}
}

int TestHemisphereExtractor(int, char*[])
{
  int failures = 0;

  // The Cornell box: every point.
  {
    HemisphereTestScenes::Pipeline pipeline(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene", 2);
    // Published before any data pass (the cover has not run yet): the default 32 x 128 grid
    // (the scene has no settings block).
    if (!WholeExtentIs(pipeline.Extractor, 128, 32))
    {
      failures += Fail("WHOLE_EXTENT before the first update");
    }
    pipeline.Extractor->Update();
    vtkPolyData* points = pipeline.CoverPoints();
    sphcover::SphericalCover cover;
    const std::string problem = vtkSphericalCoverArrays::Load(points, cover);
    if (!problem.empty())
    {
      return Fail("cannot load the cover: " + problem);
    }
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      pipeline.Extractor->SetPointId(i);
      pipeline.Extractor->Update();
      failures += CheckImage(pipeline.Extractor, points, cover, i);
    }
    std::cout << points->GetNumberOfPoints() << " hemispheres of the Cornell box checked\n";

    // The mesh, automatic radius and a given one.
    pipeline.Extractor->SetPointId(7);
    pipeline.Extractor->Update();
    const double automatic = 0.05 * points->GetLength();
    failures += CheckMesh(pipeline.Extractor, points, cover.Grid(), 7, automatic);
    pipeline.Extractor->SetRadius(33.0);
    pipeline.Extractor->Update();
    failures += CheckMesh(pipeline.Extractor, points, cover.Grid(), 7, 33.0);

    // Errors.
    pipeline.Extractor->SetPointId(points->GetNumberOfPoints());
    failures += FailureExpectation::Check(pipeline.Extractor,
      { "PointId " + std::to_string(points->GetNumberOfPoints()), "out of range" },
      "PointId past the end");
    pipeline.Extractor->SetPointId(-1);
    failures += FailureExpectation::Check(
      pipeline.Extractor, { "PointId -1", "out of range" }, "negative PointId");
    pipeline.Extractor->SetPointId(0);
    pipeline.Extractor->SetRadius(-1.0);
    failures +=
      FailureExpectation::Check(pipeline.Extractor, { "Radius must be >= 0" }, "negative Radius");
    // The subdivision's characteristic points: the right kind of dataset, but no cover.
    vtkNew<vtkHemisphereExtractor> bare;
    bare->SetInputConnection(pipeline.Subdivision->GetOutputPort(1));
    failures += FailureExpectation::Check(bare, { "no spherical cover" }, "input without a cover");
  }

  // The closed furnace box: nothing is missing from any hemisphere; the published extent
  // follows the cover's bins.
  {
    HemisphereTestScenes::Pipeline pipeline(SPHCOVER_DATA_DIR "/scenes/furnace_box.scene", 2);
    pipeline.Cover->SetThetaBins(16);
    pipeline.Cover->SetPhiBins(48);
    if (!WholeExtentIs(pipeline.Extractor, 48, 16))
    {
      failures += Fail("WHOLE_EXTENT with 16 x 48 bins");
    }
    pipeline.Extractor->Update();
    vtkPolyData* points = pipeline.CoverPoints();
    int empty = 0;
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      pipeline.Extractor->SetPointId(i);
      pipeline.Extractor->Update();
      vtkDataArray* source =
        pipeline.Extractor->GetImageOutput()->GetCellData()->GetArray("Source");
      for (vtkIdType cell = 0; cell < source->GetNumberOfTuples(); ++cell)
      {
        empty += source->GetComponent(cell, 0) < 0;
      }
      if (pipeline.Extractor->GetMeshOutput()->GetNumberOfCells() != 16 * 48)
      {
        failures += Fail("furnace box: mesh cell count");
      }
    }
    if (empty || points->GetNumberOfPoints() == 0)
    {
      failures += Fail("furnace box: " + std::to_string(empty) + " cells without a source");
    }
    std::cout << points->GetNumberOfPoints() << " hemispheres of the furnace box full\n";
    pipeline.Cover->SetThetaBins(8);
    if (!WholeExtentIs(pipeline.Extractor, 48, 8))
    {
      failures += Fail("WHOLE_EXTENT does not follow the cover's ThetaBins");
    }
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
