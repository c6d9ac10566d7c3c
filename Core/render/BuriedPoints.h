// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BuriedPoints.h
 * @brief The characteristic points that no visible point can take after: those inside a closed
 * object or under a surface lying on theirs (the floor under a block, the ceiling above a lamp
 * hung just below it), which see the back sides of what encloses them in nearly every direction.
 *
 * Their illumination is real (next to nothing) but it is not characteristic of the visible part
 * of their surface (paper §4.2.4: P_i must be characteristic of the area it stands for): the
 * interpolation of paper §5.3.2 across the contact line would spread their darkness over a
 * patch's width of visible floor. CharacteristicPointInterpolator::SetExcludedPoints leaves
 * them out of every stencil.
 *
 * Test: from the point (the centre of its patch's domain on its surface, offset by
 * 1e-6 of the patch's size along the normal), BuriedRayCount cosine-distributed rays over the
 * hemisphere (a fixed Hammersley set: deterministic); the point is buried when more than
 * BuriedBackSideFraction of them first meet a back side. A point whose rays escape (an open
 * scene) or meet front sides is never buried. A surface none of whose points would be kept
 * keeps them all. Cost: O(points x BuriedRayCount x log triangles), far below the cover's.
 */
#ifndef SPHCOVER_BURIEDPOINTS_H
#define SPHCOVER_BURIEDPOINTS_H

#include "subdivision/CharacteristicPointInterpolator.h"

#include <vector>

namespace sphcover
{

class RayCaster;
struct Patch;

constexpr int BuriedRayCount = 64;
constexpr double BuriedBackSideFraction = 0.5;

/**
 * Per characteristic point of `interpolator`, whether it is buried (see the file comment).
 * `patches` tile the surfaces (Patch::SurfaceIndex, Domain) and `caster` casts them (the same
 * list, in order: RayCastPatches(patches)). `passedBack` (per patch; empty: none) marks the
 * patches whose back side is their reversed copy's front at the same place (the sides of a
 * two-sided surface): a ray meeting such a back side meets that front.
 */
std::vector<bool> BuriedPoints(const CharacteristicPointInterpolator& interpolator,
  const std::vector<Patch>& patches,
  const RayCaster& caster,
  const std::vector<char>& passedBack = {});

/// The same, with a caster of its own for `patches`.
std::vector<bool> BuriedPoints(const CharacteristicPointInterpolator& interpolator,
  const std::vector<Patch>& patches);

} // namespace sphcover

#endif
