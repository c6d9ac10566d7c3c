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
  if (patches.size() != emission.size())
  {
    throw std::invalid_argument("BrightEmitters: the emission of " +
      std::to_string(emission.size()) + " patches for " + std::to_string(patches.size()));
  }
  double area = 0.0;
  double emitted = 0.0;
  int surfaces = 0;
  for (size_t k = 0; k < patches.size(); ++k)
  {
    area += patches[k].Area;
    emitted += patches[k].Area * (emission[k].x + emission[k].y + emission[k].z);
    surfaces = std::max(surfaces, patches[k].SurfaceIndex + 1);
  }
  std::vector<bool> bright(static_cast<size_t>(surfaces), false);
  if (!(area > 0.0) || !(emitted > 0.0))
  {
    return bright;
  }
  const double threshold = contrast * emitted / area;
  for (size_t k = 0; k < patches.size(); ++k)
  {
    if (patches[k].SurfaceIndex >= 0 && emission[k].x + emission[k].y + emission[k].z > threshold)
    {
      bright[static_cast<size_t>(patches[k].SurfaceIndex)] = true;
    }
  }
  return bright;
}

} // namespace sphcover
