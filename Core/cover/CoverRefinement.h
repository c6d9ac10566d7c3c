// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CoverRefinement.h
 * @brief The refinement of paper §4.3 Steps 3 and 5 (criterion §4.2.5): after the global
 * subdivision (IntervalSubdivision.h), patches that are partly hidden in some hemisphere, or
 * whose visible part there is disconnected, are split until their images match the R-buffers
 * or the limits are reached; the spherical cover is then built over the refined list.
 *
 * Data flow, one way: IntervalSubdivision -> CoverRefinement -> SphericalCover::Build over
 * Patches(). Run() applies, in this order, each when its setting is on:
 *  1. the receiver side, enclosure boundaries (EnclosureSplit.h): rounds, each probing the
 *     leaves not yet probed and splitting in place those that straddle a boundary (the leaves
 *     of splitting each recursively, depth first), one level per round;
 *  2. the receiver side, horizons (HorizonSplit.h): rounds over the current list, one level
 *     per round;
 *  3. Step 3 from the source side (HiddenPartAnalysis.h): rounds of projection fills of the
 *     hemispheres that can change (those of new pieces and those in which a split patch was
 *     visible), then Step 5: "Modify Q by suitably replacing all subdivided patches which are
 *     not completely hidden": a split patch is replaced by all three pieces, in its place (Q
 *     is also the list of receivers, and the patches of a surface must tile its domain).
 * The rounds end when no patch asks to be split; each deepens by one level, so there are at
 * most MaxLevel + 1 of each. Hemisphere interpolation (§3.4, note 5) is not used: a hemisphere
 * costs one fill, as much as the analysis that decides the split.
 *
 * The result does not depend on the thread count: receivers are analysed independently, their
 * split requests merged in receiver order, and the patch list is kept in a fixed order.
 * Measurements and the variants tried: Documentation/notes/cover-refinement.md.
 */
#ifndef SPHCOVER_COVERREFINEMENT_H
#define SPHCOVER_COVERREFINEMENT_H

#include "cover/RefinementSettings.h"
#include "cover/SphericalCover.h"
#include "math/ParallelFor.h"
#include "math/RankShare.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <cstddef>
#include <string>
#include <vector>

namespace sphcover
{

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

  /**
   * Under MPI: the ranks probe the leaves of each round of Steps 1 and 2 and analyse the
   * hemispheres of each round of Step 3 in turn and join their verdicts (RankShare.h), so
   * every rank refines alike, to the serial result bit for bit. Run is then collective, and
   * throws RankShare::PeerFailure when another rank failed.
   */
  void SetRankShare(RankShare share) { this->Share = std::move(share); }

  /// The refined patch list, ordered by surface, then by v, then by u of their domains (as
  /// IntervalSubdivision::Patches()).
  std::vector<Patch> Patches() const;

  const RefinementStatistics& Statistics() const { return this->Stats; }

private:
  /// Step 1 (file comment), progress from 0 to progressShare.
  bool SplitAcrossEnclosures(const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressShare);
  /// Step 2, progress from progressStart to progressEnd.
  bool SplitAcrossHorizons(const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressStart,
    double progressEnd);
  /// Step 3 and 5 in rounds, progress from progressStart to 1.
  bool AnalyseHemispheres(const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressStart);
  /// One round of Step 3: analyses the leaves not analysed since the list changed around them
  /// and marks the leaves to split; false on abort.
  bool AnalyseRound(const HemisphereGrid& grid,
    const ProgressCallback& progress,
    const ParallelFor& parallelFor,
    double progressStart,
    std::vector<char>& hidden,
    std::vector<char>& disconnected);
  /// Under MPI: every rank's verdicts of a round (`myVerdicts`: the nodes this rank analysed
  /// and their visible nodes, already merged here with the flags and `limited`) merged on
  /// every rank; `ok` false when this rank failed (it then only takes part in the join).
  void JoinVerdicts(std::vector<char>& myVerdicts,
    bool ok,
    std::vector<char>& hidden,
    std::vector<char>& disconnected,
    std::size_t& limited);
  /// Step 5: replaces the marked leaves by their pieces and marks for analysis the
  /// hemispheres in which a split patch was visible; false when nothing was split.
  bool ReplaceSplitPatches(const std::vector<char>& hidden, const std::vector<char>& disconnected);
  /// Replaces every leaf k with split[k] set by its three pieces (SplitInThree, new nodes), in
  /// its place: Steps 1, 2 and 5 split alike.
  void SplitLeaves(const std::vector<char>& split);
  /// Appends a new node (a piece of a split) and returns its index.
  int AddNode(Patch piece);

  const Scene& Environment;
  RefinementSettings Settings;
  ProbeExtents Extents;
  /// Every patch ever made (a split appends its three pieces).
  std::vector<Patch> Nodes;
  /// The current patch list Q: indices into Nodes, a split piece in its parent's place.
  std::vector<int> Leaves;
  /// Per node: the nodes visible in its hemisphere at its last analysis (ascending), and
  /// whether it has been analysed since the list last changed around it.
  std::vector<std::vector<int>> VisibleNodes;
  std::vector<bool> Analysed;
  RefinementStatistics Stats;
  RankShare Share;
};

} // namespace sphcover

#endif
