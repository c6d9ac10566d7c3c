// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ProjectionFill.h
 * @brief The R-buffer fill of paper §4.3 Step 2: "converting the boundary curves of T_j into
 * 3D polar coordinates and then seed filling the region in the R-buffer. Using R the distance
 * between P_i and P_j as the Z value paint this into the R buffer as one would do for the Z
 * buffer."
 *
 * For receiver i (frame of HemisphereFrame::OfPatch), per candidate source j:
 *
 * 1. Culling and pieces (paper §4.2.1, §4.2.2): a quadtree over Q_j's parameter square
 *    (depth RBufferFillOptions::MaxPieceDepth) drops rectangles below the tangent plane of P_i
 *    (CandidateCulling) or below the lowest sample row, and accepts as pieces rectangles that
 *    face P_i everywhere within a bounding cone of half-angle <= 45 degrees (a front-facing
 *    piece projects one to one). Rectangles turned away from P_i are no sources; with
 *    BackFacesOcclude they are projected as occluder pieces that leave their samples empty.
 * 2. Boundary: the four edges of a piece are mapped to unit directions from P_i and sampled
 *    adaptively into great-circle arcs (a straight 3-D edge needs a single arc).
 * 3. Region fill on the rows of sample directions by winding numbers on the sphere (nonzero
 *    rule), so the phi seam, the pole and the horizon need no special case.
 * 4. Depth test ("those (theta, phi) grid cells, which have larger R in the R buffer are
 *    replaced"): pieces carry rigorous depth ranges from RangeOfSquaredDistance and are
 *    painted nearest first; only where two sources' ranges overlap are the exact distances
 *    along the sample ray computed (Newton, RayPatchIntersection) and compared.
 * 5. Classification: RBuffer::Classify, with the representative sample's exact R by Newton.
 *    The unoccluded projected solid angle of every source (for paper §4.3 Step 3) comes from
 *    the same spans without the depth test.
 *
 * Complexity per receiver: O(candidate pieces x (boundary arcs x sample rows + covered
 * samples)), plus one Newton solve per sample where depth ranges overlap. No environment-wide
 * state (EnvironmentBytes() is 0); Fill() is thread-safe. The tolerances and special cases of
 * each step: Documentation/notes/projection-fill.md.
 */
#ifndef SPHCOVER_PROJECTIONFILL_H
#define SPHCOVER_PROJECTIONFILL_H

#include "cover/RBuffer.h"

#include <vector>

namespace sphcover
{

class ProjectionFiller : public RBufferFiller
{
public:
  ProjectionFiller(const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options);

  RBufferFill Kind() const override { return RBufferFill::Projection; }
  void Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics* culling) const override;
  std::size_t EnvironmentBytes() const override { return 0; }

private:
  const std::vector<Patch>& Patches;
  const HemisphereGrid& Grid;
  RBufferFillOptions Options;
  /// SurfaceIndex of every patch: the groups of the classification vote.
  std::vector<int32_t> SurfaceOfPatch;
};

} // namespace sphcover

#endif
