// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SharedPropagation.h
 * @brief The light propagation of paper §5 shared among the K processes (ranks) of a solve:
 * each rank propagates over the rows of its own receivers, i with i mod K = the rank
 * (RankShare::MyItems), which are all the rows its cover holds (RowShares::RowsOf). The serial
 * LightPropagation runs unchanged; this drives it through its batch hook
 * (LightPropagation::BatchHook), which joins the scan before every batch and the batch's
 * non-diffuse shots.
 *
 * Receivers dealt round the ranks one by one give each rank about a K-th of every surface
 * (neighbouring patches cost alike), so the ranks' work is balanced without an estimate, and so
 * are the non-diffuse shooters of each batch, whose owners reflect them at the same time. Every
 * batch, the ranks agree on its shooters (from every rank's candidates, chosen as the serial
 * scan chooses), their owners send what they shoot (the unshot radiance, with the scan; for the
 * non-diffuse shooters, all in one exchange, their reflected radiance toward the regions and the
 * fallback and view cells the other ranks' receivers read) and each rank updates its own receivers
 * in column order. So every owned patch's state, and each result of an owned patch (Irradiance,
 * ExitantRadiance, Brightness, the incident radiances of its row), is the serial one bit for
 * bit; the history's shooters and powers are serial's, its sums over the ranks (UnshotEnergy,
 * ReceiverUpdates) equal up to the order of addition. Communication per batch: see
 * SharedPropagation.cxx and Documentation/notes/distributed-solve.md.
 */
#ifndef SPHCOVER_SHAREDPROPAGATION_H
#define SPHCOVER_SHAREDPROPAGATION_H

#include "math/RankShare.h"
#include "propagation/LightPropagation.h"

namespace sphcover
{

/**
 * Shares `propagation` among the ranks of `share` (see the file comment); a share of one rank
 * leaves it serial. Call after the constructor and SetExchangeFactors (whose factors are then
 * the kept rows'); collective (the ranks exchange the keys of their non-diffuse rows once).
 * Run is then collective and BrightestFirst only, Shoot is refused, Energy and LampIrradiance
 * are collective, the other results are of owned patches only (LightPropagation::Owns). Throws
 * std::invalid_argument for a row of another rank's receiver that is not empty,
 * RankShare::PeerFailure when another rank failed.
 */
void SharePropagation(LightPropagation& propagation, RankShare share);

} // namespace sphcover

#endif
