// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file EnclosureSplit.h
 * @brief The receiver side of the cover refinement, enclosure boundaries (paper §4.2.4,
 * §4.2.5): a patch part of which lies inside a closed solid, or under a surface turned away
 * from it, is not characterised by its centre for receiving light, so it is split across the
 * boundary.
 *
 * A point is enclosed when the first surface met along its normal, and along the four
 * directions 45 degrees from it, is met from its back side (a one-sided surface): inside a
 * closed solid every direction meets a back side, a point seeing a back side through an
 * opening does not. A patch is split (SplitInThree, reason RBuffer) while among a grid of
 * probe points (ProbesPerSide per patch width, the centres of equal parameter cells, over the
 * patch and EnclosureMargin patch widths around it, within its surface's ProbeExtents) some
 * are enclosed and some are not, up to MaxLevel; the margin grades the pieces towards the
 * boundary, along which the received light varies fast.
 *
 * The probes are rays (RayCaster) against the scene's whole surfaces, from tNear = 1e-7 of the
 * scene's size, hits of the probe's own surface group within twice the tessellation tolerance
 * skipped. Cost: up to 5 rays per probe point, (ProbesPerSide (1 + 2 margin))^2 points per
 * tested patch. Thread-safe: Straddles() may run for several patches at once (CoverRefinement
 * splits in rounds, probing a round's patches in parallel and on several ranks).
 */
#ifndef SPHCOVER_ENCLOSURESPLIT_H
#define SPHCOVER_ENCLOSURESPLIT_H

#include "cover/RefinementSettings.h"
#include "geometry/RayCaster.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <cstddef>
#include <memory>
#include <vector>

namespace sphcover
{

class EnclosureSplitter
{
public:
  /// Casts against the surfaces of `scene`; all three arguments must outlive the splitter.
  EnclosureSplitter(const Scene& scene,
    const ProbeExtents& extents,
    const RefinementSettings& settings);

  /// Whether the scene has no surface (nothing to probe).
  bool Empty() const { return this->Rays == nullptr; }

  /**
   * Whether the patch straddles an enclosure boundary: some of its probe points are enclosed
   * and some not (it is to be split). Adds the probe rays cast to `probes`.
   */
  bool Straddles(const Patch& patch, std::size_t& probes) const;

private:
  /// The side of the first surface met along one ray: 1 back, 0 front or none, -1 undecided.
  int BackSideFirst(const Patch& patch,
    const glm::dvec3& origin,
    const glm::dvec3& direction,
    std::size_t& probes) const;
  /// 1 when the point at (u, v) of the patch (may lie around it) is enclosed, 0 when not, -1
  /// without a verdict.
  int Enclosed(const Patch& patch, double u, double v, std::size_t& probes) const;

  const Scene& Environment;
  const ProbeExtents& Extents;
  const RefinementSettings& Settings;
  std::unique_ptr<RayCaster> Rays;
  double TNear = 0.0;
  double OwnTolerance = 0.0;
};

} // namespace sphcover

#endif
