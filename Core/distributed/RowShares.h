// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RowShares.h
 * @brief The spherical cover in shares of rows, for a solve distributed over K processes
 * (ranks): the rows H_i are independent (paper §4.3: one R-buffer per characteristic point), so
 * the ranks build the rows of different receivers apart, and the cover they make is joined, or
 * kept in its shares, each rank propagating over its own rows (SharedPropagation.h).
 *
 * A share is a SphericalCover of every patch (every area and pane transmittance) whose rows are
 * empty but for those of its receivers: RowsOf cuts it out of a whole cover, BuildRowsOf builds
 * it, JoinRows joins shares back into a cover, the one way a cover is assembled from parts.
 * Every row of a share is the whole cover's row bit for bit, so the shares of every receiver
 * join into the cover SphericalCover::Build gives, bit for bit, whatever the receivers of each.
 * RowBlockBytes.h turns a share into bytes and back.
 *
 * Which receivers a rank takes is the caller's choice: share.MyItems (one by one round the
 * ranks: every rank gets a K-th of every surface, which evens out the work without an estimate,
 * the light propagation's share) or consecutive ranges of about equal estimated cost
 * (EstimateRowCosts, PartitionRows) dealt round the ranks, when the cover is gathered.
 */
#ifndef SPHCOVER_ROWSHARES_H
#define SPHCOVER_ROWSHARES_H

#include "cover/CandidateCulling.h"
#include "cover/SphericalCover.h"
#include "math/ParallelFor.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace sphcover
{

struct Patch;
class RankShare;
class RayCaster;

/// The cover's shares of rows (see the file comment); a friend of SphericalCover.
class RowShares
{
public:
  using Arrays = SphericalCover::Arrays;

  /**
   * An estimate of the work of each receiver's row, for splitting rows among processes by work
   * rather than by count: a fixed part per row plus the number of other patches whose control
   * net reaches above the tangent plane of P_i (paper §4.2.2's hemispherical containment,
   * bounded by the control net's box instead of Bernstein ranges), the candidates a fill
   * considers. The fixed part is 1 for the projection fill, whose work is its candidates'
   * projections, and 2N for the ray fill, whose rays through the cells cost about as much per
   * row as 2N candidates (fitted to the teapot room's rows timed on two ranks,
   * Documentation/notes/distributed-solve.md). O(N^2) box tests, about a thousandth of a build.
   */
  static std::vector<double> EstimateRowCosts(const std::vector<Patch>& patches,
    const SphericalCoverOptions& options);
  /**
   * Boundaries b_0 = 0 <= b_1 <= ... <= b_parts = costs.size() of `parts` consecutive receiver
   * ranges [b_k, b_k+1) of about equal summed cost: range k ends at the first receiver whose
   * running cost reaches (k+1)/parts of the total. Throws std::invalid_argument for parts = 0.
   */
  static std::vector<std::size_t> PartitionRows(const std::vector<double>& costs,
    std::size_t parts);
  /// The receivers of ranges `ranges` (ascending) of PartitionRows' `bounds`, ascending.
  static std::vector<std::size_t> ReceiversOfRanges(const std::vector<std::size_t>& bounds,
    const std::vector<std::size_t>& ranges);

  /**
   * A copy of `cover` that keeps the rows of `receivers` (ascending, each once) and empties the
   * others (their areas and the panes' transmittances stay): the share one rank of a
   * distributed propagation holds. The copy's entries are the kept rows' entries in receiver
   * order (KeptEntries). Throws std::invalid_argument for a receiver out of range or out of
   * order.
   */
  static SphericalCover RowsOf(const SphericalCover& cover,
    const std::vector<std::size_t>& receivers);
  /**
   * Replaces `cover` with the rows of `receivers` (ascending, each once) of the cover
   * Build(patches, options) gives, the others empty: Build's RowsOf(receivers) bit for bit, but
   * for two things a share cannot know alone: its entries carry measures of their own only when
   * one of its rows is measured (KeepCellMeasures, when another share's is), and Culling()
   * counts its rows only. How a rank of a distributed build makes its share without the whole
   * cover ever meeting on one. False, with the cover cleared, when `progress` returned false
   * (it counts the kept rows). Throws as Build does, and std::invalid_argument as RowsOf.
   */
  static bool BuildRowsOf(SphericalCover& cover,
    const std::vector<Patch>& patches,
    const SphericalCoverOptions& options,
    const std::vector<std::size_t>& receivers,
    const ParallelFor& parallelFor = SequentialFor,
    const ProgressCallback& progress = nullptr,
    std::shared_ptr<const RayCaster> rays = nullptr);
  /// Gives every entry of `cover` its cells' measure when it has no measures of its own, as
  /// Build gives the rows before its first measured one: a share whose rows are not measured,
  /// of a cover some of whose rows are (SphericalCover.h, "Measured regions").
  static void KeepCellMeasures(SphericalCover& cover);
  /**
   * Replaces `cover` with the join of shares of one cover (RowsOf's or BuildRowsOf's, exported):
   * receiver i's row is the one share's whose row i is not empty (or empty). With the shares of
   * every receiver it is the whole cover Build gives, bit for bit (a share without measures of
   * its own gets its cells' measures when another share has some, as Build's rows before its
   * first measured row). `options` and `culling` become Options() and Culling(). Returns an
   * explanation (and leaves the cover empty) when there is no share, a share is inconsistent
   * (as SphericalCover::ImportArrays), the shares differ in their grid, patches or areas, or
   * two hold the same row.
   */
  static std::string JoinRows(SphericalCover& cover,
    std::vector<Arrays> shares,
    const SphericalCoverOptions& options,
    const CullingStatistics& culling);

  /// The indices of the entries of `receivers`' rows of `cover` in receiver order: entry e of
  /// RowsOf(cover, receivers) is entry KeptEntries(cover, receivers)[e] of `cover`.
  static std::vector<std::size_t> KeptEntries(const SphericalCover& cover,
    const std::vector<std::size_t>& receivers);
  /// The first receiver whose row is not empty though another rank owns it (RankShare::Owns),
  /// or PatchCount() when there is none, as for RowsOf(cover, share.MyItems(PatchCount())).
  static std::size_t FirstForeignRow(const SphericalCover& cover, const RankShare& share);

private:
  /// Appends row `receiver` of `cover` (its entries, their strips and per-entry values) to
  /// `to`, the entries' first strips counted in `to`.
  static void AppendRowTo(const SphericalCover& cover, std::size_t receiver, Arrays& to);
};

} // namespace sphcover

#endif
