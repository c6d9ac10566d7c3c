// SPDX-License-Identifier: BSD-3-Clause
#include "propagation/SolutionFigures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphcover
{
double RelativeImbalance(const glm::dvec3& emitted, const glm::dvec3& absorbed)
{
  double imbalance = 0.0;
  for (int band = 0; band < 3; ++band)
  {
    if (emitted[band] > 0.0)
    {
      imbalance = std::max(imbalance, std::fabs(emitted[band] - absorbed[band]) / emitted[band]);
    }
  }
  return imbalance;
}

namespace
{

/// std::invalid_argument unless every point has a surface in [0, SurfaceCount).
void CheckSurfaces(const PointIllumination& illumination)
{
  const int groups = illumination.SurfaceCount;
  for (std::size_t k = 0; k < illumination.SurfaceOfPoint.size(); ++k)
  {
    const int g = illumination.SurfaceOfPoint[k];
    if (g < 0 || g >= groups)
    {
      throw std::invalid_argument("solution figures: point " + std::to_string(k) + " has surface " +
        std::to_string(g) + ", not one of the " + std::to_string(groups));
    }
  }
}

} // namespace

CoverFigures ComputeCoverFigures(const SphericalCover& cover, const PointIllumination& illumination)
{
  if (cover.PatchCount() != illumination.SurfaceOfPoint.size())
  {
    throw std::invalid_argument("solution figures: " + std::to_string(cover.PatchCount()) +
      " points in the cover, but " + std::to_string(illumination.SurfaceOfPoint.size()) +
      " surfaces");
  }
  CheckSurfaces(illumination);
  CoverFigures figures;
  figures.FormFactors = cover.FormFactors(illumination.SurfaceOfPoint, illumination.SurfaceCount);
  figures.CharacteristicPoints = cover.PatchCount();
  figures.Strips = cover.StripCount();
  return figures;
}

SolutionFigures ComputeSolutionFigures(const SphericalCover& cover,
  const PointIllumination& illumination)
{
  return ComputeSolutionFigures(ComputeCoverFigures(cover, illumination), illumination);
}

SolutionFigures ComputeSolutionFigures(const CoverFigures& cover,
  const PointIllumination& illumination)
{
  const std::size_t points = illumination.SurfaceOfPoint.size();
  if (illumination.Area.size() != points || illumination.Irradiance.size() != points ||
    illumination.ExitantRadiance.size() != points || cover.CharacteristicPoints != points)
  {
    throw std::invalid_argument("solution figures: " + std::to_string(cover.CharacteristicPoints) +
      " points in the cover, but " + std::to_string(points) + " surfaces, " +
      std::to_string(illumination.Area.size()) + " areas, " +
      std::to_string(illumination.Irradiance.size()) + " irradiances and " +
      std::to_string(illumination.ExitantRadiance.size()) + " radiances");
  }
  CheckSurfaces(illumination);
  const std::size_t count = static_cast<std::size_t>(std::max(0, illumination.SurfaceCount));
  SolutionFigures figures;
  figures.Surfaces.resize(count);
  for (std::size_t k = 0; k < points; ++k)
  {
    figures.Surfaces[static_cast<std::size_t>(illumination.SurfaceOfPoint[k])].Area +=
      illumination.Area[k];
  }
  // Means weighted by the points' share of their surface's area (the patches tile it).
  for (std::size_t k = 0; k < points; ++k)
  {
    SurfaceFigures& surface =
      figures.Surfaces[static_cast<std::size_t>(illumination.SurfaceOfPoint[k])];
    const double weight = illumination.Area[k] / surface.Area;
    for (int band = 0; band < 3; ++band)
    {
      surface.MeanIrradiance[band] += weight * illumination.Irradiance[k][band];
      surface.MeanExitantRadiance[band] += weight * illumination.ExitantRadiance[k][band];
    }
  }
  figures.FormFactors = cover.FormFactors;
  figures.Emitted = illumination.Emitted;
  figures.Absorbed = illumination.Absorbed;
  figures.RelativeImbalance = RelativeImbalance(illumination.Emitted, illumination.Absorbed);
  figures.CharacteristicPoints = points;
  figures.Strips = cover.Strips;
  return figures;
}
}
