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

SolutionFigures ComputeSolutionFigures(const SphericalCover& cover,
  const PointIllumination& illumination)
{
  const std::size_t points = illumination.SurfaceOfPoint.size();
  if (illumination.Area.size() != points || illumination.Irradiance.size() != points ||
    illumination.ExitantRadiance.size() != points || cover.PatchCount() != points)
  {
    throw std::invalid_argument("solution figures: " + std::to_string(cover.PatchCount()) +
      " points in the cover, but " + std::to_string(points) + " surfaces, " +
      std::to_string(illumination.Area.size()) + " areas, " +
      std::to_string(illumination.Irradiance.size()) + " irradiances and " +
      std::to_string(illumination.ExitantRadiance.size()) + " radiances");
  }
  const int groups = illumination.SurfaceCount;
  const std::size_t count = static_cast<std::size_t>(std::max(0, groups));
  SolutionFigures figures;
  figures.Surfaces.resize(count);
  for (std::size_t k = 0; k < points; ++k)
  {
    const int g = illumination.SurfaceOfPoint[k];
    if (g < 0 || g >= groups)
    {
      throw std::invalid_argument("solution figures: point " + std::to_string(k) + " has surface " +
        std::to_string(g) + ", not one of the " + std::to_string(groups));
    }
    figures.Surfaces[static_cast<std::size_t>(g)].Area += illumination.Area[k];
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
  figures.FormFactors = cover.FormFactors(illumination.SurfaceOfPoint, groups);
  figures.Emitted = illumination.Emitted;
  figures.Absorbed = illumination.Absorbed;
  figures.RelativeImbalance = RelativeImbalance(illumination.Emitted, illumination.Absorbed);
  figures.CharacteristicPoints = points;
  figures.Strips = cover.StripCount();
  return figures;
}
}
