// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file HiddenPartAnalysis.h
 * @brief Paper §4.2.5 / §4.3 Step 3 for one hemisphere H_i: which sources Q_j are partly
 * hidden from P_i, or seen in disconnected pieces, and so ask to be split.
 *
 * "By comparing polar projection of T_j with its image, if any, in the R buffer, determine if
 * T_j is fully visible, fully hidden or partially visible to P_i." The polar projection of Q_j
 * is RBuffer::UnoccludedProjectedSolidAngles; its image the projected solid angle of the
 * samples whose nearest surface is Q_j (same samples, same weights: the cell rounding does not
 * enter). Q_j is visible when its image covers MinimumVisibleCells cells' worth (note 4: a
 * hidden patch is never split from P_i), hidden substantially when the hidden part exceeds
 * HiddenFraction of its projection and MinimumHiddenCells cells' worth, and disconnected when
 * two or more of its image's regions (8-neighbour samples, wrapping in phi, the first row
 * joined around the pole) each hold a cell's worth. A split request obeys §4.3 note 2: below
 * MaxLevel, and only while Q_j's box diagonal exceeds the cell angle times its distance.
 *
 * Input: the receiver's index in the current patch list, a projection filler over that list
 * and an R-buffer of the cover's grid. Output: HemisphereAnalysis. O(samples + visible
 * sources x log); one analyser per thread (it keeps per-source working arrays).
 */
#ifndef SPHCOVER_HIDDENPARTANALYSIS_H
#define SPHCOVER_HIDDENPARTANALYSIS_H

#include "cover/RBuffer.h"
#include "cover/RefinementSettings.h"
#include "subdivision/Patch.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphcover
{

/// What the analysis of one hemisphere H_i found (sources as indices into the current list).
struct HemisphereAnalysis
{
  /// Sources visible in H_i (image of at least one sample), ascending.
  std::vector<uint32_t> Visible;
  /// Sources to split because substantially hidden, and (not already there) because their
  /// image is disconnected; both within the limits.
  std::vector<uint32_t> Hidden;
  std::vector<uint32_t> Disconnected;
  /// Sources that asked for a split the limits refused.
  std::size_t Limited = 0;
};

class HiddenPartAnalyser
{
public:
  /// `settings` must outlive the analyser.
  explicit HiddenPartAnalyser(const RefinementSettings& settings);

  /// Fills the R-buffer of `receiver` of `current` with `filler` and analyses it.
  void Analyse(std::size_t receiver,
    const std::vector<Patch>& current,
    const RBufferFiller& filler,
    RBuffer& buffer,
    HemisphereAnalysis& result);

private:
  /// Labels the image of every source into regions of samples and sums its measure and
  /// samples; lists the visible sources.
  void LabelImages(const RBuffer& buffer, HemisphereAnalysis& result);
  /// Union-find over the samples (path halving; union by index, so that the labelling
  /// depends on nothing but the R-buffer).
  int32_t Find(int32_t x);
  void Join(int32_t a, int32_t b);

  const RefinementSettings& Settings;
  /// Per source (one slot per patch, left zero between receivers).
  std::vector<double> VisibleMeasure;
  std::vector<uint32_t> VisibleSamples;
  std::vector<uint32_t> LargeRegions;
  /// Per sample: the union-find parents and the regions' sizes.
  std::vector<int32_t> Parent;
  std::vector<uint32_t> RegionSamples;
};

} // namespace sphcover

#endif
