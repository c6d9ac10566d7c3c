// SPDX-License-Identifier: BSD-3-Clause
#include "cover/BrightEmitters.h"

#include "subdivision/Patch.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sphcover
{

std::vector<bool> BrightEmitters(const std::vector<Patch>& patches,
  const std::vector<glm::dvec3>& emission,
  double contrast)
{
  std::vector<int> surfaces(patches.size());
  std::vector<double> areas(patches.size());
  for (size_t k = 0; k < patches.size(); ++k)
  {
    surfaces[k] = patches[k].SurfaceIndex;
    areas[k] = patches[k].Area;
  }
  return BrightEmitters(surfaces, areas, emission, contrast);
}

std::vector<bool> BrightEmitters(const std::vector<int>& surfaceOfPatch,
  const std::vector<double>& area,
  const std::vector<glm::dvec3>& emission,
  double contrast)
{
  if (surfaceOfPatch.size() != emission.size() || area.size() != emission.size())
  {
    throw std::invalid_argument("BrightEmitters: the emission of " +
      std::to_string(emission.size()) + " patches for " + std::to_string(surfaceOfPatch.size()) +
      " surface indices and " + std::to_string(area.size()) + " areas");
  }
  double totalArea = 0.0;
  double emitted = 0.0;
  int surfaces = 0;
  for (size_t k = 0; k < emission.size(); ++k)
  {
    totalArea += area[k];
    emitted += area[k] * (emission[k].x + emission[k].y + emission[k].z);
    surfaces = std::max(surfaces, surfaceOfPatch[k] + 1);
  }
  std::vector<bool> bright(static_cast<size_t>(surfaces), false);
  if (!(totalArea > 0.0) || !(emitted > 0.0))
  {
    return bright;
  }
  const double threshold = contrast * emitted / totalArea;
  for (size_t k = 0; k < emission.size(); ++k)
  {
    if (surfaceOfPatch[k] >= 0 && emission[k].x + emission[k].y + emission[k].z > threshold)
    {
      bright[static_cast<size_t>(surfaceOfPatch[k])] = true;
    }
  }
  return bright;
}

} // namespace sphcover
