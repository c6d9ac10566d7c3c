// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RayCastFill.h
 * @brief The second R-buffer fill (Documentation/Pipeline.md#spherical-cover, paper §4.3 Step 2):
 * the sample rays of every cell are cast from P_i through the RayCaster's tessellation of the exact
 * patches, and the first front side hit is mapped back to its patch.
 *
 * Rays: origin P_i (a vertex of its own patch's tessellation, so a ray never starts inside one
 * of its triangles), the sample directions of HemisphereGrid in world coordinates, cast in
 * row-major sample order. A hit filter implements the visibility semantics of RBuffer.h: back
 * sides are skipped (traversal goes on behind them) unless BackFacesOcclude, and hits on the
 * receiver's own patch nearer than SelfExclusionFraction * Size() (all of them when
 * CountSelfVisibility is off) are P_i itself. A back side that occludes leaves its sample empty.
 * A sample is grazing when the exact normal at the hit's (u, v) meets the ray with
 * |cos| < GrazingCosine. With RefineHits, R is refined on the exact patch (RayCaster::Refine)
 * for the cells' representative samples only, when Classify asks for it; without, R is the
 * tessellation's. Fill() is O(samples x log triangles) and may run from several threads.
 */
#ifndef SPHCOVER_RAYCASTFILL_H
#define SPHCOVER_RAYCASTFILL_H

#include "cover/RBuffer.h"
#include "geometry/RayCaster.h"

#include <vector>

namespace sphcover
{

/// The caster's view of the patches (their geometry and surface; the patches must outlive it).
std::vector<RayCastPatch> RayCastPatches(const std::vector<Patch>& patches);
/// The caster's options among a fill's.
RayCasterOptions RayCastOptions(const RBufferFillOptions& options);

class RayCastFiller : public RBufferFiller
{
public:
  /// Throws what RayCaster throws (patches beyond MaxRayCastCoordinate, Embree failing).
  RayCastFiller(const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options);
  ~RayCastFiller() override;
  RayCastFiller(const RayCastFiller&) = delete;
  RayCastFiller& operator=(const RayCastFiller&) = delete;

  RBufferFill Kind() const override { return RBufferFill::RayCasting; }
  void Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics* culling) const override;
  std::size_t EnvironmentBytes() const override;

  /// The tessellation the samples are cast against.
  const RayCaster& Caster() const { return this->Rays; }

private:
  /// Casts the samples of `receiver`'s hemisphere into `buffer` (sources, grazing flags, the
  /// tessellation's depths) and keeps the hits' (u, v, t) for the refinement in Classify.
  void CastSamples(std::size_t receiver, const HemisphereFrame& frame, RBuffer& buffer) const;

  const std::vector<Patch>& Patches;
  const HemisphereGrid& Grid;
  RBufferFillOptions Options;
  std::vector<int32_t> SurfaceOfPatch;
  RayCaster Rays;
};

} // namespace sphcover

#endif
