// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RefinementSettings.h
 * @brief The settings of the cover refinement (paper §4.2.5, §4.3 Steps 3 and 5; see
 * CoverRefinement.h) that its criteria share, and the probe extents and surface groups of the
 * receiver-side criteria.
 */
#ifndef SPHCOVER_REFINEMENTSETTINGS_H
#define SPHCOVER_REFINEMENTSETTINGS_H

#include "cover/SphericalCover.h"
#include "math/UVRect.h"

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
  /// Receiver side: split patches across enclosure boundaries first (EnclosureSplit.h).
  bool SplitEnclosureBoundaries = true;
  /// Probe points per side of a patch for the enclosure test, in [2, 16].
  int ProbesPerSide = 5;
  /// The probes also cover this many patch widths around the patch (in [0, 4]); the horizon
  /// test covers the same margin.
  double EnclosureMargin = 1.0;
  /// Receiver side: split patches across the visibility horizons of nearby surfaces
  /// (HorizonSplit.h).
  bool SplitHorizons = true;
  /// A surface counts as nearby when it comes within this many patch sizes (box diagonals) of
  /// the patch's characteristic point, in (0, 8].
  double HorizonReach = 2.0;
  /// Step 3 from the source side: analyse the hemispheres (rounds of R-buffer fills of every
  /// affected receiver; the costly part, HiddenPartAnalysis.h). Off: the receiver side alone.
  bool AnalyseHemispheres = true;

  /// Empty if the settings are usable, else what is wrong with them.
  std::string Problem() const;
};

/// Where the receiver-side tests of a patch may look beyond it, per scene surface (see
/// CoverRefinement::SetProbeExtents): the rectangle of its parameters that its larger surface
/// spans (empty: the unit square), and its group, the larger surface (empty: itself).
struct ProbeExtents
{
  std::vector<UVRect> Extents;
  std::vector<int> Groups;

  UVRect Extent(int surface) const
  {
    return this->Extents.empty() ? UVRect::Unit() : this->Extents[static_cast<size_t>(surface)];
  }
  int Group(int surface) const
  {
    return this->Groups.empty() ? surface : this->Groups[static_cast<size_t>(surface)];
  }
};

} // namespace sphcover

#endif
