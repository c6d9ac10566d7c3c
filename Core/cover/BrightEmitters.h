// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BrightEmitters.h
 * @brief Which surfaces' regions the spherical cover measures on the source
 * (SphericalCoverOptions::MeasuredSurfaces): the lamps of a scene.
 *
 * A region's cells measure it to about a boundary cell; what that costs in a receiver's
 * irradiance is the boundary's share of the region times the contrast between the region's
 * radiance and its neighbours' (a wall next to a wall of the same radiance loses nothing when
 * a cell goes to one or the other). The contrast is largest, and the regions smallest, for
 * emitters that are a small part of the scene: a surface is a bright emitter when its emitted
 * radiance (the sum of its bands) exceeds Contrast times the area-weighted mean emitted radiance
 * of all patches. A white furnace, where everything emits alike, has none (its cells' measures
 * are exact in every row's sum, which is all an even radiance sees); a Cornell box's lamp, 3 %
 * of its area, is one.
 */
#ifndef SPHCOVER_BRIGHTEMITTERS_H
#define SPHCOVER_BRIGHTEMITTERS_H

#include <glm/vec3.hpp>

#include <vector>

namespace sphcover
{
struct Patch;

/// Per surface (indexed by Patch::SurfaceIndex, up to the largest) whether it is a bright
/// emitter; `emission` is each patch's emitted radiance (W m^-2 sr^-1 per band). Throws
/// std::invalid_argument when the sizes differ.
std::vector<bool> BrightEmitters(const std::vector<Patch>& patches,
  const std::vector<glm::dvec3>& emission,
  double contrast = 2.0);

/// The same from each patch's surface index (negative: none), area and emitted radiance, for a
/// stage that holds them as arrays (the propagation's points). Throws std::invalid_argument
/// when the sizes differ.
std::vector<bool> BrightEmitters(const std::vector<int>& surfaceOfPatch,
  const std::vector<double>& area,
  const std::vector<glm::dvec3>& emission,
  double contrast = 2.0);

} // namespace sphcover

#endif
