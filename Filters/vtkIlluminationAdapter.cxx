// SPDX-License-Identifier: BSD-3-Clause
#include "vtkIlluminationAdapter.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <exception>

namespace names = vtkSphericalCoverArrayNames;

bool vtkIlluminationAdapter::Read(vtkPolyData* points,
  Illumination& illumination,
  std::string& error)
{
  vtkPointData* pd = points->GetPointData();
  vtkDataArray* radiosity = pd->GetArray(names::Radiosity);
  vtkDataArray* surfaceId = pd->GetArray(names::SurfaceId);
  vtkDataArray* uvRange = pd->GetArray(names::UVRange);
  vtkDataArray* twoSided = pd->GetArray(names::TwoSided);
  if (!radiosity || radiosity->GetNumberOfComponents() != 3)
  {
    error = std::string("the input has no point array Radiosity (3 components); connect the "
                        "illuminated cover points (vtkLightPropagationFilter's output 0), not ") +
      (points->GetNumberOfPoints() == 0 ? "an empty dataset" : "points without illumination");
    return false;
  }
  if (!surfaceId || !uvRange || uvRange->GetNumberOfComponents() != 4)
  {
    error = "the input lacks the point arrays SurfaceId and UVRange (4 components) that place "
            "each characteristic point on its surface";
    return false;
  }
  const vtkIdType count = points->GetNumberOfPoints();
  std::vector<int> surfaceOfPoint(static_cast<size_t>(count));
  std::vector<sphcover::UVRect> domainOfPoint(static_cast<size_t>(count));
  illumination.ExitantRadiance.assign(static_cast<size_t>(count), glm::dvec3(0.0));
  illumination.TwoSidedSurface.clear();
  for (vtkIdType i = 0; i < count; ++i)
  {
    const size_t k = static_cast<size_t>(i);
    surfaceOfPoint[k] = static_cast<int>(surfaceId->GetComponent(i, 0));
    double r[4];
    uvRange->GetTuple(i, r);
    domainOfPoint[k] = sphcover::UVRect{ r[0], r[1], r[2], r[3] };
    radiosity->GetTuple(i, &illumination.ExitantRadiance[k][0]);
    if (surfaceOfPoint[k] >= 0)
    {
      const size_t s = static_cast<size_t>(surfaceOfPoint[k]);
      illumination.TwoSidedSurface.resize(std::max(illumination.TwoSidedSurface.size(), s + 1));
      illumination.TwoSidedSurface[s] = twoSided && twoSided->GetComponent(i, 0) != 0.0;
    }
  }
  try
  {
    illumination.Interpolator =
      sphcover::CharacteristicPointInterpolator(surfaceOfPoint, domainOfPoint);
  }
  catch (const std::exception& e)
  {
    error = e.what();
    return false;
  }
  return true;
}
