// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file HemisphereInterpolation.h
 * @brief Which hemispheres are interpolated from their neighbours instead of computed (paper
 * §3.4, "the neighbours of H_i are likely to be very similar", and §4.3 Step 5 note 5: "the
 * hemispherical tessellation is interpolated ... The hemispherical tessellation computation is
 * expensive and this way it is avoided whenever possible").
 *
 * The plan: per characteristic point P_i either nothing (H_i is computed: a key) or its donors,
 * the keys whose hemispheres give H_i: its neighbours across the edges of its patch on the same
 * surface (the patches containing the points just beyond each edge at the centre's other
 * parameter, as CharacteristicPointInterpolator finds them), the paper's "(u0, v0) ... (u1, v1)"
 * around P_i, taken in pairs that bracket it (left and right, below and above). A point is
 * interpolated when
 *  - it has at least one such pair: what changes from one donor to the other changes across P_i;
 *  - every donor is near and alike: its normal within MaxNormalAngleDegrees of P_i's (the
 *    interpolation is in one (theta, phi) space: a flat surface) and its point within
 *    MaxDonorDistance x the patch's Size() (a much larger neighbour sees from elsewhere);
 *  - no donor is itself interpolated (an error cannot travel).
 * Points are taken in patch order (by surface, then v, then u): a point that qualifies is
 * interpolated and its donors become keys. On a uniform layout this is a checkerboard: half the
 * points are interpolated, from four neighbours (two along an edge). The plan depends on the
 * patches alone, never on threads or ranks.
 *
 * How H_i is made from its pairs is RayCastFiller::FillFromDonors: each pair whose donors are
 * alike (MaxDifference) is interpolated row by row (InterpolateHemispheres, below); a cell
 * where the pairs agree takes their source without a ray, the others are cast; with no pair
 * alike, H_i is computed. Measurements: Documentation/notes/interpolated-hemispheres.md.
 * Complexity: O(points) (per point four bucket lookups).
 */
#ifndef SPHCOVER_HEMISPHEREINTERPOLATION_H
#define SPHCOVER_HEMISPHEREINTERPOLATION_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphcover
{

struct Patch;

struct HemisphereInterpolationOptions
{
  /// Interpolate hemispheres at all (off, the default: every hemisphere is computed; why it is
  /// not on: Documentation/notes/interpolated-hemispheres.md).
  bool Enabled = false;
  /// A donor's normal at most this far from the receiver's, in degrees (a fraction of a cell:
  /// the donors' cells are the receiver's directions).
  double MaxNormalAngleDegrees = 0.5;
  /// A donor's point at most this many times the receiver patch's Size() (its bounding box
  /// diagonal) away: a neighbour of the same size is about 0.7 of it away, one three times
  /// larger about 1.4.
  double MaxDonorDistance = 1.0;
  /// Donors too different to interpolate between: the cells where they show different
  /// surfaces (or one of them nothing) measure more than this fraction of the hemisphere
  /// (projected solid angle). Then the hemisphere is computed.
  double MaxDifference = 0.1;
  /// In the cells of an interpolated hemisphere where the donors differ, cast every sample of
  /// the cells at a change of surface as a computed hemisphere does (true), or their centres
  /// only (false: such cells are decided by their centre ray alone).
  bool SampleBoundaryCells = true;
};

/**
 * Paper §3.4's row-by-row interpolation of two hemispheres on one grid (the same frames): the
 * cells of H at `t` in [0, 1] from H_a (t = 0) to H_b (t = 1), each given by its cells' sources
 * (RBuffer::NoSource where none) and R. Row by row, the runs of one source (strips, and the
 * runs of no source) of a and b are matched in order (the longest common subsequence of their
 * sources); a matched strip's ends are interpolated linearly, as is its R. Between two matched
 * strips, what only a has (a strip disappearing on the way to b, Fig. 7) takes a share of the
 * interpolated gap that shrinks as (1 - t) times its length in a, what only b has a share that
 * grows as t times its length in b, a's before b's, each in its own order. A cell takes the
 * strip that holds its centre. The phi seam is a fixed end of every row.
 */
void InterpolateHemispheres(int thetaBins,
  int phiBins,
  const int32_t* sourcesA,
  const float* depthsA,
  const int32_t* sourcesB,
  const float* depthsB,
  double t,
  int32_t* sources,
  float* depths);

class HemisphereInterpolationPlan
{
public:
  HemisphereInterpolationPlan() = default;
  /// The plan for `patches` (see the file comment); every point computed when disabled.
  HemisphereInterpolationPlan(const std::vector<Patch>& patches,
    const HemisphereInterpolationOptions& options);

  std::size_t PointCount() const { return this->Offsets.empty() ? 0 : this->Offsets.size() - 1; }
  bool IsInterpolated(std::size_t point) const
  {
    return !this->Offsets.empty() && this->Offsets[point + 1] > this->Offsets[point];
  }
  /// The donors of `point`, [DonorsBegin, DonorsEnd), ascending; none for a key.
  const uint32_t* DonorsBegin(std::size_t point) const
  {
    return this->DonorList.data() + this->Offsets[point];
  }
  const uint32_t* DonorsEnd(std::size_t point) const
  {
    return this->DonorList.data() + this->Offsets[point + 1];
  }
  std::size_t InterpolatedCount() const { return this->Interpolated; }
  /// No donor on that side.
  static constexpr uint32_t None = 0xffffffffu;
  /// The donors of `point` that bracket it along u (axis 0: left, right) or v (axis 1: below,
  /// above); None where that pair is not complete.
  uint32_t PairDonor(std::size_t point, int axis, int side) const
  {
    return this->Pairs[point * 4 + static_cast<std::size_t>(axis * 2 + side)];
  }

private:
  std::vector<uint32_t> Pairs;
  std::vector<uint32_t> Offsets;
  std::vector<uint32_t> DonorList;
  std::size_t Interpolated = 0;
};

} // namespace sphcover

#endif
