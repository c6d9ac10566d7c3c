// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CoverRefinement.h
 * @brief The R-buffer criterion of paper §4.2.5 and the refinement of paper §4.3 Steps 3 and
 * 5: after the global subdivision (IntervalSubdivision.h), patches that are partly hidden in
 * some hemisphere, or whose visible part there is disconnected, are split until their images
 * match the R-buffers or the limits are reached; the spherical cover is then built over the
 * refined patch list.
 *
 * Data flow, one way: IntervalSubdivision -> CoverRefinement -> SphericalCover::Build over
 * Patches(). The refinement fills the R-buffers of its receivers itself (projection fill,
 * paper §4.3 Step 2, on the cover's grid) and reads them at sample resolution:
 *
 *  - Step 3, hidden part: "By comparing polar projection of T_j with its image, if any, in the
 *    R buffer, determine if T_j is fully visible, fully hidden or partially visible to P_i."
 *    The polar projection of Q_j is RBuffer::UnoccludedProjectedSolidAngles (the projected
 *    solid angle of the samples the unoccluded Q_j covers); its image is the projected solid
 *    angle of the samples whose nearest surface is Q_j. Both are sums over the same samples
 *    with the same weights, so their difference is the hidden part up to the samples on Q_j's
 *    edges, and the cell rounding (a cell goes wholly to one source) does not enter: for a
 *    source a few cells wide that rounding alone moves the cell count by tens of per cent.
 *    Q_j is partially visible when its image covers at least MinimumVisibleCells cells'
 *    worth; it is "hidden substantially" when the hidden part exceeds HiddenFraction of its
 *    projection and MinimumHiddenCells cells' worth (a hidden sliver thinner than a cell cannot
 *    change which cells h_ij holds).
 *  - Step 3, connectedness: the image of Q_j is labelled into connected regions of samples
 *    (8-neighbours, wrapping in phi, the first sample row joined around the pole); Q_j is
 *    disconnected when two or more regions each hold at least a cell's worth of samples
 *    (fragments smaller than a cell are edge rounding, and a cell could not hold them).
 *  - A split is ternary along the longer 3-D direction (SplitInThree, §4.3 note 3) and obeys
 *    the limits of the subdivision (§4.3 note 2): not beyond MaxLevel, and only while Q_j
 *    projects from P_i to more than about one cell (its box's diagonal exceeds the cell angle
 *    times its distance).
 *
 * The receiver side follows from the symmetry of the cover (§3.3: every characteristic point
 * is a candidate for every other point's hemisphere). A floor patch half under a block is a
 * source in the hemispheres of the ceiling's and the walls' points, where the block hides the
 * half under it: Step 3 splits it there, and its pieces then receive light separately. No
 * receiver test of its own is needed for occlusion.
 *
 * Step 5 ("Modify Q by suitably replacing all subdivided patches which are not completely
 * hidden") and note 4 ("all patches completely hidden from the point do not get subdivided"):
 * a patch fully hidden from P_i, or whose image is under MinimumVisibleCells, never asks to be
 * split from P_i. A split patch is replaced in Q by all three pieces, including a piece that
 * is hidden from every point that saw its parent: Q is also the list of receivers, a hidden
 * piece still receives light (the floor under a block, seeing the block's inside) and SPEC
 * §4.2 requires the patches of each surface to tile its parameter domain.
 *
 * Iteration: after each round of splits, only the hemispheres that can change are analysed
 * again: those of the new pieces and those in which a split patch was visible (a patch hidden
 * from P_i has hidden pieces). The rounds end when no patch asks to be split; every round
 * deepens by one level, so there are at most MaxLevel + 1 rounds.
 *
 * Receiver side (before Step 3, RefinementSettings::SplitEnclosureBoundaries). A patch part of
 * which lies inside a closed solid, or under a surface turned away from it, is not
 * characterised by its centre for receiving light (§4.2.4; §4.2.5 "full visibility ...
 * depends on being not hidden by any other patch"): the floor under a bottomless block sees
 * only the block's inside, the ceiling above the light (hanging 0.5 mm below it) only the
 * light's back, while the rest of the same patch sees the room. A characteristic point on one
 * side of such an enclosure boundary gives the whole patch its row, which is the largest
 * reciprocity error of the Cornell box (a floor patch straddling a block's footprint with its
 * centre under the block takes nothing from the block's front although a third of it sees the
 * front at F ~ 0.2; 9.5% on floor / short_block_front). A point is enclosed when the first
 * surface met along its normal, and along the four directions 45 degrees from it, is met from
 * its back side (a one-sided surface; two-sided ones have no back): inside a closed solid
 * every direction meets a back side, whereas a point that sees some back side through an
 * opening (into a teapot through its lid gap) is not enclosed. A patch is split (SplitInThree,
 * reason RBuffer) while among a ProbesPerSide x ProbesPerSide grid of its points (the centres of
 * equal parameter cells) some are enclosed and some are not, up to MaxLevel; only the patches along
 * the boundaries are split, and the pieces wholly inside keep a row that sees nothing but the
 * solid's inside (correctly: they receive no light). The Step 3 analysis from the source side finds
 * the same patches (the floor patch is partly hidden in the ceiling's hemispheres) but needs every
 * hemisphere filled once per level, where the probes cost a few rays per patch (Embree, on the
 * ray fill's tessellation of the scene's surfaces). Probes find a boundary crossing a patch
 * unless it clips a corner between them (an error of that corner's area only).
 *
 * An enclosure boundary is also a contact line: a block's faces rise from it, and next to it
 * what a floor point receives from the face changes fast (from half its hemisphere at the
 * line to a tenth a patch width away). One point per 61 mm x 20 mm floor patch there misses
 * that variation by about 1% of the floor / block-face exchange even once the straddling
 * patches are split fine (measured: the same 1.2 to 1.4% at 4 and 6 extra levels, with the
 * block faces' side converged within 0.2% and the floor's hemispheres within 0.2% of a 64 x 256
 * grid). The probes therefore also cover EnclosureMargin patch widths around the patch: a
 * patch is split while a boundary passes within that distance, so the pieces shrink towards
 * the boundary like the variation they have to follow.
 *
 * Receiver side, horizons (RefinementSettings::SplitHorizons, after the enclosure boundaries).
 * Where the tangent plane of a nearby surface cuts a patch, part of the patch sees that
 * surface's front and part of it does not: the form factor from a point of the patch to the
 * surface grows from zero at the plane, with a kink there, and the characteristic point gives
 * the whole patch its own side's value. In the Cornell box the tall block's top (y = 330) is
 * seen from the red wall above y = 330 only, and the red wall's row of 61 mm x 21 mm patches
 * spanning 305..366 has its centres 5 mm above the plane: they see the top at about half the
 * mean over their patches (red_wall / tall_block_top 1.4% apart; 0.2% when every red wall patch
 * is replaced by 3 x 3 points). Beyond the kink the form factor bends over on the scale of the
 * distance to the surface, so that the next rows' centres overestimate it: splitting the
 * straddling row alone overshoots to 1.1% (measured), and the rows within a patch width of the
 * plane have to follow, as the EnclosureMargin rule does for enclosure boundaries. A patch is
 * split (SplitInThree, reason RBuffer; the longer direction) while some patch Q_j of another
 * surface (group) is within HorizonReach patch sizes (box diagonals) of its characteristic point,
 * lies in front of it (Q_j's centre above its tangent plane), and Q_j's tangent plane at its
 * centre cuts the patch's surface over the patch and EnclosureMargin patch widths around it (5 x 5
 * points, within the surface as for the probes, reach both sides of the plane by more than 2% of
 * the patch's size; a surface meeting it along an edge, a wall on the floor, does not cut it).
 * The reach is relative to the patch size because the kink's effect on a patch's mean is second
 * order in size / distance: pieces stop splitting once they are small against their distance to
 * the surface. Occlusion is not tested (a hidden horizon costs a few needless splits, never
 * accuracy). The tests are box and plane tests over the current patch list, one round per level:
 * no rays, no hemispheres. Cornell box at its settings: 5828 -> 6588 points, every pair with
 * min(F) >= 0.01 within 0.91% (BenchmarkCoverRefinement). Only planar surfaces (control points
 * within 1% of the net's size from one plane) are horizon sources: a curved surface's horizon,
 * seen from a point, is where its own tangent plane passes through the point, which moves over
 * the surface, so the tangent plane at one of its patches marks no kink; with curved sources the
 * teapot's close curved surfaces (body, lid, spout, handle) split one another, 33111 points in the
 * teapot room instead of 13461 (BenchmarkCoverRefinement --patches-only --hemispheres 0).
 *
 * Hemisphere interpolation (§3.4, §4.3 Step 5, note 5) is not used: the paper interpolates to
 * avoid "expensive" hemisphere computations, but here a hemisphere is one R-buffer fill (the
 * same cost as the analysis that decides the split), the interpolated rows of Fig. 7 are
 * approximations that break the cover's exactness (every covered cell once, rows summing to
 * one in a closed scene) exactly where refinement happens (at occlusion boundaries, where
 * neighbouring hemispheres differ most), and the cover is built over the refined list anyway.
 *
 * The result does not depend on the thread count: receivers are analysed independently and
 * their split requests merged in receiver order; the patch list is kept in a fixed order.
 */
#ifndef SPHCOVER_COVERREFINEMENT_H
#define SPHCOVER_COVERREFINEMENT_H

#include "cover/SphericalCover.h"
#include "math/ParallelFor.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <cstddef>
#include <string>
#include <vector>

namespace sphcover
{

struct RefinementSettings
{
  /// The grid, samples and fill options of the R-buffers: those of the cover to be built. The
  /// refinement always fills by projection (it needs the unoccluded projections); Fill is
  /// ignored.
  SphericalCoverOptions Cover;
  /// Deepest level of a patch (as SubdivisionSettings::MaxLevel).
  int MaxLevel = 5;
  /// Split Q_j when more than this fraction of its projection in H_i is hidden...
  double HiddenFraction = 0.1;
  /// ... and the hidden part is more than this many cells (of the size where Q_j is seen).
  double MinimumHiddenCells = 1.0;
  /// Q_j counts as fully hidden from P_i when its image is smaller than this many cells.
  double MinimumVisibleCells = 0.5;
  /// Split Q_j when its image in H_i is disconnected.
  bool SplitDisconnected = true;
  /// Receiver side: split patches across enclosure boundaries first (see the file comment).
  bool SplitEnclosureBoundaries = true;
  /// Probe points per side of a patch for the enclosure test, in [2, 16].
  int ProbesPerSide = 5;
  /// The probes also cover this many patch widths around the patch (in [0, 4]; see the file
  /// comment); the horizon test covers the same margin.
  double EnclosureMargin = 1.0;
  /// Receiver side: split patches across the visibility horizons of nearby surfaces (see the
  /// file comment).
  bool SplitHorizons = true;
  /// A surface counts as nearby when it comes within this many patch sizes (box diagonals) of
  /// the patch's characteristic point, in (0, 8].
  double HorizonReach = 2.0;
  /// Step 3 from the source side: analyse the hemispheres (rounds of R-buffer fills of every
  /// affected receiver; the costly part). Off: the receiver side alone.
  bool AnalyseHemispheres = true;

  /// Empty if the settings are usable, else what is wrong with them.
  std::string Problem() const;
};

struct RefinementStatistics
{
  std::size_t InputPatches = 0;
  std::size_t OutputPatches = 0;
  /// Rounds of analysis and splitting (the last one splits nothing).
  int Rounds = 0;
  /// R-buffers filled and analysed (hemispheres computed), over all rounds.
  std::size_t RowsAnalysed = 0;
  /// Patches split, and among them those only a disconnected image asked to split.
  std::size_t Splits = 0;
  std::size_t DisconnectedSplits = 0;
  /// (receiver, source) pairs that asked for a split the limits refused.
  std::size_t LimitedRequests = 0;
  /// Splits of the receiver side (enclosure boundaries), included in Splits.
  std::size_t EnclosureSplits = 0;
  /// Enclosure probes cast (rays).
  std::size_t Probes = 0;
  /// Splits across horizons (receiver side), included in Splits.
  std::size_t HorizonSplits = 0;
};

class CoverRefinement
{
public:
  /**
   * `patches` is the patch list Q (e.g. IntervalSubdivision::Patches()); `scene` holds their
   * surfaces (pieces are cut from the original surfaces) and must outlive the object. Throws
   * std::invalid_argument for unusable settings or a patch whose surface is not in the scene.
   */
  CoverRefinement(const Scene& scene,
    std::vector<Patch> patches,
    const RefinementSettings& settings);

  /**
   * Refines to the fixed point. Returns false if `progress` returned false (abort); Patches()
   * are then those after the last complete round (a valid tiling, not fully refined).
   */
  bool Run(const ProgressCallback& progress = nullptr,
    const ParallelFor& parallelFor = SequentialFor);

  /**
   * Where the enclosure probes of a patch may lie when its margin reaches beyond it: by default
   * its surface's unit square. A caller whose scene surfaces are pieces of larger surfaces (the
   * cover filter, whose input cells are the subdivision's patches) gives, per scene surface,
   * the rectangle of its own parameters that the whole larger surface spans (probes then reach
   * into the neighbouring pieces: the polynomial of a piece continues the surface it was cut
   * from), and the group (larger surface) of each, whose hits near a probe are its own
   * surface's. Empty vectors: the defaults. Throws std::invalid_argument for wrong sizes.
   */
  void SetProbeExtents(std::vector<UVRect> extents, std::vector<int> groups);

  /// The refined patch list, ordered by surface, then by v, then by u of their domains (as
  /// IntervalSubdivision::Patches()).
  std::vector<Patch> Patches() const;

  const RefinementStatistics& Statistics() const { return this->Stats; }

private:
  /// The receiver side: splits the patches across enclosure boundaries (file comment).
  bool SplitAcrossEnclosures(const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressShare);
  /// The receiver side: splits the patches across nearby surfaces' horizons (file comment),
  /// reporting progress from progressStart to progressEnd.
  bool SplitAcrossHorizons(const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressStart,
    double progressEnd);
  /// Whether leaf `k` of the current list has a nearby surface's horizon across it.
  bool SeesHorizonAcross(std::size_t k) const;
  /// Step 3 from the source side (file comment), from progressStart to 1.
  bool AnalyseHemispheres(const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressStart);

  struct Analysis;
  /// Fills and analyses the R-buffer of leaf `receiver` of `current`.
  void Analyse(std::size_t receiver,
    const std::vector<Patch>& current,
    const class RBufferFiller& filler,
    class RBuffer& buffer,
    Analysis& result) const;

  UVRect ProbeExtent(int surface) const;
  int GroupOf(int surface) const;

  const Scene& Environment;
  RefinementSettings Settings;
  std::vector<UVRect> ProbeExtents;
  std::vector<int> ProbeGroups;
  /// Per surface of the scene: whether it is planar (a horizon source).
  std::vector<char> PlanarSurfaces;
  /// Every patch ever made (a split appends its three pieces).
  std::vector<Patch> Nodes;
  /// The current patch list Q: indices into Nodes, a split piece in its parent's place.
  std::vector<int> Leaves;
  /// Per node: the nodes visible in its hemisphere at its last analysis (ascending), and
  /// whether it has been analysed since the list last changed around it.
  std::vector<std::vector<int>> VisibleNodes;
  std::vector<bool> Analysed;
  RefinementStatistics Stats;
};

} // namespace sphcover

#endif
