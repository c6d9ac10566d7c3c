// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file IntervalSubdivision.h
 * @brief The environment-dependent subdivision of paper §4.3: the patch list Q and its
 * characteristic points, split until every pair of patches satisfies the criteria of §4.2
 * within tolerance (SubdivisionCriteria.h) or the limits are reached.
 *
 * Q starts as the surfaces of the scene (§4.3: "Initially, Q is set to be equal to S"). The
 * engine then sweeps over Q: for every receiver patch Q_i (characteristic point P_i at its
 * parametric centre, Step 0) and every candidate source Q_j it evaluates the criteria by range
 * estimates over the whole patches. A source that straddles the horizon of P_i, has a
 * silhouette, or is not spherical enough around P_i is split (Step 2); a receiver that P_i does
 * not characterise for light from P_j is split (Step 2, characterisability). Splits are
 * ternary, along u or v, whichever keeps the pieces square in 3-D (§4.3 note 3), and are exact
 * (de Casteljau on the original surface). Sweeps repeat until no patch needs a split; a later
 * sweep re-examines only pairs with a new patch, since the others have not changed.
 *
 * Limits (§4.3 note 2): no patch goes deeper than MaxLevel, and no patch is split once it
 * projects, from the point that asks, to about one (theta,phi) cell of the cover's grid, or
 * once its box's diagonal is at most MinPatchSize times the scene's. MaxLevel counts splits per
 * surface, so alone it gives a small block face as many points as a large wall; the size limit
 * spends them where the surfaces are large. A
 * budget (MaximumPatches, MemoryLimitBytes, MaximumPairTests) stops a subdivision that would
 * grow beyond them with an error before the sweep's splits, or the sweep, are made.
 *
 * The pairwise work is culled by a bounding-volume hierarchy of the patches' interval boxes
 * (§4.1): a group of patches whose box lies below the tangent plane of P_i is classified as
 * a whole, and old receivers visit only the groups that hold new patches.
 *
 * The R-buffer criterion of §4.2.5 (visibility, hiding by other patches) belongs to the
 * spherical cover stage. The result does not depend on the number of threads: the split
 * requests of a sweep are merged by criterion priority, not by arrival order.
 *
 * Complexity: the pair tests (SubdivisionStatistics::PairTests, at most N^2 per sweep for N
 * patches, far fewer after the hierarchy's culling), each a few range bounds of
 * SubdivisionCriteria.h; memory O(patches made), with their derivative nets.
 */
#ifndef SPHCOVER_INTERVALSUBDIVISION_H
#define SPHCOVER_INTERVALSUBDIVISION_H

#include "math/ParallelFor.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"
#include "subdivision/SubdivisionCriteria.h"

#include <array>
#include <atomic>
#include <cstddef>
#include <vector>

namespace sphcover
{

struct SubdivisionStatistics
{
  /// Pairs (receiver point, source patch) whose criteria were evaluated by range estimates.
  std::size_t PairTests = 0;
  /// Sweeps over the patch list until no split was needed (none when MaxLevel allows no split).
  int Sweeps = 0;
  /// Splits performed, by reason (indexed by SplitReason).
  std::array<std::size_t, 6> Splits{};
  /// Pairs not evaluated because neither patch may be split any more (MaxLevel, or both
  /// already project to about one cell from the other's point).
  std::size_t LimitedPairs = 0;
};

class IntervalSubdivision
{
public:
  IntervalSubdivision(const Scene& scene, const SubdivisionSettings& settings);

  /**
   * Subdivides to the fixed point. Returns false if `progress` returned false (abort); the
   * patches are then those of the last complete sweep. Throws std::invalid_argument for
   * unusable settings (SubdivisionSettings::Problem()), std::length_error when a sweep would
   * make more patches than MaximumPatches or hold more than MemoryLimitBytes, or when the pair
   * tests (predicted for the next sweep from the share of its candidate pairs the last sweep
   * tested, or made so far) would exceed MaximumPairTests.
   */
  bool Run(const ProgressCallback& progress = nullptr,
    const ParallelFor& parallelFor = SequentialFor);

  /// The final patches Q, ordered by surface, then by v, then by u of their domains.
  std::vector<Patch> Patches() const;

  const SubdivisionStatistics& Statistics() const { return this->Stats; }

  /// The view of a final patch that the criteria use (material kind and sidedness applied).
  PatchView ViewOfPatch(const Patch& patch) const;

private:
  /// Splits a patch in three along u or v (whichever direction is longer in 3-D).
  void Split(int node, SplitReason reason);
  /// One sweep's pair tests (paper §4.3 Step 2): fills `requested` (INT_MAX: no split) and the
  /// pairs tested and left by the limits; false if `progress` asked to abort.
  bool ExaminePairs(std::vector<std::atomic<int>>& requested,
    std::size_t& pairTests,
    std::size_t& limited,
    const ProgressCallback& progress,
    const ParallelFor& parallelFor) const;
  /// Splits the requested leaves and makes the next patch list; false if nothing was split.
  bool ApplySplits(const std::vector<std::atomic<int>>& requested);
  /// Throws std::length_error when the requested splits would exceed the budget.
  void CheckBudget(const std::vector<std::atomic<int>>& requested) const;
  /// Throws std::length_error when the pair tests so far plus `sweepPairTests` (predicted or
  /// made in this sweep) exceed MaximumPairTests.
  void CheckCost(double sweepPairTests, const char* verb) const;

  const Scene& Environment;
  SubdivisionSettings Settings;
  /// Every patch ever made (a split appends its three pieces).
  std::vector<Patch> Nodes;
  /// The current patch list Q: indices into Nodes.
  std::vector<int> Leaves;
  /// Whether each leaf was made in the last sweep (its pairs still need examining).
  std::vector<bool> LeafIsNew;
  /// Bytes held by Nodes (the budget's measure).
  std::size_t NodeBytes = 0;
  /// Diagonal of the box of all surfaces (MinPatchSize's unit).
  double SceneDiagonal = 0.0;
  SubdivisionStatistics Stats;
};

} // namespace sphcover

#endif
