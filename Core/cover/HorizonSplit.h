// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file HorizonSplit.h
 * @brief The receiver side of the cover refinement, horizons: where the tangent plane of a
 * nearby planar surface cuts a patch, part of the patch sees that surface's front and part of
 * it does not; the form factor to the surface has a kink there that one characteristic point
 * cannot follow, so the patch is split (SplitInThree, reason RBuffer).
 *
 * A patch has a horizon across it when some patch Q_j of another surface group, on a planar
 * surface (control points within 1% of the net's size from one plane: a curved surface's
 * horizon moves with the point that sees it), is within HorizonReach patch sizes (box
 * diagonals) of its characteristic point, lies in front of it (Q_j's centre above its tangent
 * plane by 2% of its size), and Q_j's tangent plane at its centre cuts the patch's surface over
 * the patch and EnclosureMargin patch widths around it (5 x 5 points within ProbeExtents reach
 * both sides of the plane by more than 2% of the patch's size: a wall standing on the floor
 * does not cut it). Occlusion is not tested (a hidden horizon costs a few needless splits).
 *
 * Box and plane tests only: O(current patches) per tested patch, no rays. Thread-safe.
 */
#ifndef SPHCOVER_HORIZONSPLIT_H
#define SPHCOVER_HORIZONSPLIT_H

#include "cover/RefinementSettings.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vector>

namespace sphcover
{

class HorizonTest
{
public:
  /// Finds the planar surfaces of `scene`; all three arguments must outlive the test.
  HorizonTest(const Scene& scene, const ProbeExtents& extents, const RefinementSettings& settings);

  /// Whether `receiver` has a nearby surface's horizon across it, among the sources
  /// nodes[leaves[k]] (the current patch list).
  bool Across(const Patch& receiver,
    const std::vector<Patch>& nodes,
    const std::vector<int>& leaves) const;

private:
  const Scene& Environment;
  const ProbeExtents& Extents;
  const RefinementSettings& Settings;
  /// Per surface of the scene: whether it is planar (a horizon source).
  std::vector<char> PlanarSurfaces;
};

} // namespace sphcover

#endif
