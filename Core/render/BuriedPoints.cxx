// SPDX-License-Identifier: BSD-3-Clause
#include "render/BuriedPoints.h"

#include "cover/RayCastFill.h"
#include "geometry/RayCaster.h"
#include "math/Constants.h"
#include "math/RadicalInverse.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sphcover
{

namespace
{
/// Whether most rays from (surface, u, v) of patch `patch` first meet back sides.
bool IsBuried(const Patch& patch,
  double u,
  double v,
  const RayCaster& caster,
  const std::vector<char>& passedBack)
{
  // The point in the patch's own parameters (its Geometry is reparametrised to [0,1]^2).
  const UVRect& d = patch.Domain;
  const double lu = std::clamp((u - d.U0) / (d.U1 - d.U0), 0.0, 1.0);
  const double lv = std::clamp((v - d.V0) / (d.V1 - d.V0), 0.0, 1.0);
  const glm::dvec3 normal = patch.Geometry.Normal(lu, lv);
  const glm::dvec3 origin = patch.Geometry.Evaluate(lu, lv) + 1e-6 * patch.Geometry.Size() * normal;
  const glm::dvec3 helper =
    std::fabs(normal.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  const glm::dvec3 tangent = glm::normalize(glm::cross(helper, normal));
  const glm::dvec3 bitangent = glm::cross(normal, tangent);
  int backSides = 0;
  for (int k = 0; k < BuriedRayCount; ++k)
  {
    // Cosine-distributed (Malley's method on the Hammersley point).
    const double r = std::sqrt((k + 0.5) / BuriedRayCount);
    const double phi = TwoPi * RadicalInverse(static_cast<unsigned>(k));
    const glm::dvec3 direction = r * std::cos(phi) * tangent + r * std::sin(phi) * bitangent +
      std::sqrt(std::max(0.0, 1.0 - r * r)) * normal;
    std::size_t hitPatch = 0;
    double distance = 0.0;
    bool front = true;
    if (caster.FirstHit(origin, direction, 0.0, hitPatch, distance, front) && !front &&
      (passedBack.empty() || !passedBack[hitPatch]))
    {
      ++backSides;
    }
  }
  return backSides > BuriedBackSideFraction * BuriedRayCount;
}
}

std::vector<bool> BuriedPoints(const CharacteristicPointInterpolator& interpolator,
  const std::vector<Patch>& patches,
  const RayCaster& caster,
  const std::vector<char>& passedBack)
{
  // The patch under each characteristic point (the patches tile the surfaces).
  const CharacteristicPointInterpolator patchLayout =
    CharacteristicPointInterpolator::OfPatches(patches);
  std::vector<bool> buried(interpolator.PointCount(), false);
  std::vector<std::size_t> kept(interpolator.SurfaceCount(), 0);
  for (std::size_t p = 0; p < interpolator.PointCount(); ++p)
  {
    const int surface = interpolator.SurfaceOf(p);
    const UVRect& domain = interpolator.Domain(p);
    const std::ptrdiff_t patch =
      patchLayout.ContainingPoint(surface, domain.CenterU(), domain.CenterV());
    buried[p] = patch >= 0 &&
      IsBuried(patches[static_cast<size_t>(patch)],
        domain.CenterU(),
        domain.CenterV(),
        caster,
        passedBack);
    kept[static_cast<size_t>(surface)] += buried[p] ? 0 : 1;
  }
  for (std::size_t p = 0; p < buried.size(); ++p)
  {
    // A surface all buried keeps its points: something must stand for it.
    if (kept[static_cast<size_t>(interpolator.SurfaceOf(p))] == 0)
    {
      buried[p] = false;
    }
  }
  return buried;
}

std::vector<bool> BuriedPoints(const CharacteristicPointInterpolator& interpolator,
  const std::vector<Patch>& patches)
{
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  return BuriedPoints(interpolator, patches, caster);
}

} // namespace sphcover
