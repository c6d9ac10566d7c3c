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
 * 1. Culling and pieces (paper §4.2.1, §4.2.2). A quadtree over Q_j's parameter square drops
 *    rectangles below the tangent plane of P_i (CandidateCulling) or wholly below the lowest
 *    sample row, and accepts a rectangle as a "piece" when it faces P_i everywhere and its
 *    bounding cone seen from P_i has a half-angle of at most 45 degrees. A front-facing piece
 *    projects one to one (no folds), and a 45-degree cone cannot hold both N_i and -N_i, which
 *    makes the pole test below unambiguous. Rectangles turned away from P_i are dropped as
 *    sources; with RBufferFillOptions::BackFacesOcclude (the default) they are split and
 *    projected alike as occluder pieces, which win the depth test like any piece but leave
 *    their samples empty. Rectangles on a silhouette (facing undecided) are split until their
 *    cone is below half a sample spacing; their centre's facing then decides which side P_i
 *    sees. Rectangles of the receiver's own patch that come within the self-exclusion radius of
 *    P_i are split until they lie inside it and dropped (RBuffer.h). Depth 16 at most.
 *
 * 2. Boundary (paper: "boundary curves ... into 3D polar coordinates"). The four edges of a
 *    piece, counter-clockwise in (u, v), are mapped to unit directions from P_i in the local
 *    frame and sampled adaptively into great-circle arcs: an edge interval is split until the
 *    directions at its quarter points lie within 1e-3 of a sample spacing (angle) of the arc
 *    between its ends and the arc spans at most 60 degrees. A straight 3D edge (every edge of
 *    a bilinear patch) projects onto a great circle, so it needs a single arc.
 *
 * 3. Region fill. The region is filled on the rows of sample directions (constant theta) by
 *    winding numbers computed on the sphere, so the phi seam, the pole and the horizon need no
 *    special case:
 *    - the crossings of every arc with every sample row's cone theta = theta_s are solved
 *      exactly (a quadratic along the chord of the arc), each with the sign of its crossing;
 *    - the winding number W at a sample (theta_s, phi) is W(N) plus the signed crossings met on
 *      the path from the pole N down the meridian phi = 0 to theta_s and then along the row to
 *      phi (winding differences are path independent). W(N) is the boundary's winding around
 *      the axis N (from its signed crossings of the half-plane phi = 0); a nonzero winding with
 *      a cone that does not contain N means the region holds -N instead, which lies below the
 *      horizon with the whole 45-degree cone, and the piece is skipped;
 *    - a sample is covered where W != 0 (nonzero rule). Parts of a piece below the horizon are
 *      clipped for free: no sample row lies there.
 *
 * 4. Depth test (paper: "those (theta, phi) grid cells, which have larger R in the R buffer
 *    are replaced"). Each piece carries a rigorous depth range [R_lo, R_hi] from
 *    sqrt(RangeOfSquaredDistance). Pieces are painted nearest range first; a sample already
 *    held by another source's piece keeps or changes hands by comparing the ranges, and only
 *    where the ranges overlap are both exact distances along the sample ray computed by
 *    Newton's method (RayPatchIntersection, started from the nearest of a 5 x 5 grid of the
 *    piece's directions) and compared; the exact value is then kept for that sample. A piece
 *    whose Newton solution falls outside it (a sample within the boundary tolerance) does not
 *    take the sample.
 *
 * 5. Classification: RBuffer::Classify, with the representative sample's exact R computed by
 *    Newton where the depth test did not need it. The unoccluded cell counts of every source
 *    (for paper §4.3 Step 3) come from the same spans, without the depth test.
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
