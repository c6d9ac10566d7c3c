// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ExchangeBalance.h
 * @brief Per-entry factors that make the light exchange of a point-sampled spherical cover
 * conserve energy while every hemisphere keeps its covered measure.
 *
 * Entry e = (i, j) of the cover (region h_ij of H_i, paper §3.3) carries the throughput
 * G_ij = A_i Omega_ij: a shot of radiance dL by Q_j delivers A_i Omega_ij dL to P_i. Row i sums
 * to the point's covered throughput r_i = A_i Omega_i (which keeps the white furnace exact), but
 * what Q_j delivers is its column sum, which equals what it sends, r_j, only where the cover is
 * reciprocal (A_i Omega_ij = A_j Omega_ji, §3.3); a cover sampled at characteristic points is
 * not, and its equilibrium then creates or destroys light.
 *
 * The balance: factors f_ij = x_i y_j such that x_i G_ij y_j has row sums r_i (each hemisphere
 * gathers its covered measure) and column sums r_j (each source delivers what its hemisphere
 * sends): matrix scaling to prescribed marginals (Sinkhorn-Knopp), row and column steps in turn
 * until no y_j changes by more than Tolerance (relative), a row step last (rows exact). The
 * factors scale only the measure with which the existing regions count in the irradiance and the
 * power (LightPropagation::SetExchangeFactors), not the regions or the radiance; fixed before the
 * first shot, they keep the propagation linear and order independent.
 *
 * Sources that see nothing but are seen (r_j = 0) get y_j = 0. Where the marginals cannot be met
 * (a point that sees but is never seen) the iteration settles into a cycle and stops as
 * Stalled(); after MaximumIterations without either, the factors are used as they are (rows
 * exact). Why the marginals and not the pairs, and the imbalances measured:
 * Documentation/notes/propagation.md.
 *
 * Cost: O(entries) per iteration. Deterministic whatever the order of the entries: a column
 * sum is summed exactly in fixed point (each term truncated to 2^-100 of the column's largest,
 * ExactColumnSums), so that the ranks of a distributed propagation, each holding the rows of its
 * receivers, get the factors of the whole cover bit for bit.
 *
 * Under a share (math/RankShare.h), collective: per iteration two joins of n values per rank
 * (the columns' largest terms, then their fixed-point sums).
 */
#ifndef SPHCOVER_EXCHANGEBALANCE_H
#define SPHCOVER_EXCHANGEBALANCE_H

#include "math/ParallelFor.h"
#include "math/RankShare.h"

#include <cstddef>
#include <vector>

namespace sphcover
{

class SphericalCover;

struct ExchangeBalanceSettings
{
  /// Stop when no source factor changes by more than this (relative) in an iteration.
  double Tolerance = 1e-10;
  std::size_t MaximumIterations = 200;
};

class ExchangeBalance
{
public:
  /// No factors (every f_ij = 1).
  ExchangeBalance() = default;
  /**
   * Balances the exchange of `cover`. Progress is the iteration count over MaximumIterations;
   * returning false from `progress` stops early (Aborted()). Under `share` the ranks balance
   * together, `cover` holding this rank's receivers' rows (RowShares::RowsOf of
   * share.MyItems, as SharePropagation): EntryFactors are then those of its
   * entries, equal to the whole cover's bit for bit, and a rank that stops stops every rank
   * (each is Aborted() after the same iteration). Collective under a share; throws
   * RankShare::PeerFailure when another rank failed, std::invalid_argument when `cover` holds
   * another rank's row.
   */
  explicit ExchangeBalance(const SphericalCover& cover,
    const ExchangeBalanceSettings& settings = {},
    const ProgressCallback& progress = nullptr,
    const RankShare& share = RankShare());

  /// f_e = x_i y_j of every entry of the cover, by entry index (empty: none computed).
  const std::vector<double>& EntryFactors() const { return this->Factors; }
  std::size_t Iterations() const { return this->IterationCount; }
  /// max over the sources that are seen of |c_j - r_j| / max(c_j, r_j), c_j the balanced column
  /// sum (relative, and 1 for a source seen but seeing nothing), for the final factors.
  double ColumnResidual() const { return this->Residual; }
  /// Whether the source factors settled within Tolerance.
  bool Converged() const { return this->HasConverged; }
  /// Whether the iteration stopped because its change no longer fell (not halved in 10
  /// iterations): the marginals cannot be met exactly, ColumnResidual() is as close as they get.
  bool Stalled() const { return this->HasStalled; }
  bool Aborted() const { return this->WasAborted; }
  /// ColumnResidual of the cover as built (every f = 1): how far from balanced it was.
  double InitialColumnResidual() const { return this->InitialResidual; }

private:
  std::vector<double> Factors;
  std::size_t IterationCount = 0;
  double Residual = 0.0;
  double InitialResidual = 0.0;
  static constexpr std::size_t StallWindow = 10;
  bool HasConverged = false;
  bool HasStalled = false;
  bool WasAborted = false;
};

} // namespace sphcover

#endif
