// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ExchangeBalance.h
 * @brief Per-entry factors that make the light exchange of a point-sampled spherical cover
 * conserve energy while every hemisphere keeps its covered measure.
 *
 * The exchange of the cover. Entry e = (i, j) of row i (the region h_ij of H_i, paper §3.3)
 * carries the throughput G_ij = A_i Omega_ij (W per unit radiance): a shot of radiance dL by
 * Q_j delivers A_i Omega_ij dL to P_i (LightPropagation). Row i sums to the point's covered
 * throughput r_i = A_i Omega_i (Omega_i = CoveredProjectedSolidAngle, pi inside a closed scene),
 * and that is what makes the white furnace exact: a uniform radiance L arriving over h_i1..h_in
 * gives the irradiance pi L. What Q_j's shot delivers, however, is the column sum
 * sum_i A_i Omega_ij, while what Q_j sends into the scene is its own row sum r_j: the two are
 * equal only if the cover is reciprocal (A_i Omega_ij = A_j Omega_ji, paper §3.3's
 * "form factor" reciprocity). A cover sampled at characteristic points is not: the
 * hemisphere of P_i is taken at one point of patch i, cells are won by votes, and a
 * partially occluded pair can be seen one way only (the Cornell box with a front wall: 8.8% of
 * the throughput in entries whose reverse is null). The equilibrium then creates or destroys
 * light: 0.84% of the emitted power in that closed box (Data/scenes/cornell_box_closed.scene,
 * BenchmarkLightPropagation --refine 3 --balance 0).
 *
 * The balance. Factors f_ij = x_i y_j (one per receiver, one per source) such that the balanced
 * throughput G'_ij = x_i G_ij y_j has
 *   - row sums r_i: each hemisphere still gathers exactly its covered measure (the furnace stays
 *     exact, and an open scene's openings stay what the cover says);
 *   - column sums r_j: each source delivers exactly what its own hemisphere sends into the
 *     scene, so a diffuse shot of power pi A_j dL into a closed scene arrives in full, and the
 *     equilibrium balances emission and absorption.
 * This is matrix scaling to prescribed marginals (Sinkhorn-Knopp): alternately x_i = r_i /
 * sum_j G_ij y_j and y_j = r_j / sum_i x_i G_ij, until no y changes by more than Tolerance
 * (relative); the last step is a row step, so rows are exact and columns within the tolerance.
 * The factors touch only the entries that exist: regions keep their cells (what a point sees
 * through which cells, used for directional reflection and the renderer), only the measure
 * with which the radiance arriving through them counts in the irradiance and the power is
 * scaled (LightPropagation: the radiance itself is not, so that mirrors pass on what they see).
 * They are fixed before the first shot, so the propagation stays linear: order independence is kept
 * (unlike a per-shot rescaling of what each shot delivers, which was rejected for that reason,
 * LightPropagation).
 *
 * Why the marginals and not the pairs: a symmetric G' cannot keep one-sided entries (h_ij
 * without h_ji), and dropping them leaves holes where a point sees a source. The marginals are
 * what energy conservation needs for Lambertian sources; a non-diffuse shooter, whose radiance
 * differs from region to region, is balanced only up to how its radiance varies along its
 * column: closed scenes with mirrors keep a few tenths of a percent (LightPropagation).
 *
 * Sources that see nothing (r_j = 0) but are seen get the target 0, so y_j = 0: in a closed
 * scene these are points buried under an object (the Cornell floor under the blocks), whose
 * exitant radiance is their emission only, and the receivers' x_i give the measure they saw to
 * the rest of their rows. Receivers that see nothing have an empty row. Points that see but are
 * never seen (an empty column) cannot deliver their target, so the marginals cannot be met
 * exactly; the iteration then settles into a fixed cycle and stops as Stalled() (closed Cornell
 * box: 19 iterations, column residual 1.3e-6). The furnaces converge in 6 to 15 iterations.
 * After MaximumIterations without either, the factors are used as they are (rows exact) and
 * neither Converged() nor Stalled() is set.
 *
 * Cost: O(entries) per iteration, sequential in a fixed order (deterministic).
 */
#ifndef SPHCOVER_EXCHANGEBALANCE_H
#define SPHCOVER_EXCHANGEBALANCE_H

#include "math/ParallelFor.h"

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
  /// Balances the exchange of `cover`. Progress is the iteration count over MaximumIterations;
  /// returning false from `progress` stops early (Aborted()).
  explicit ExchangeBalance(const SphericalCover& cover,
    const ExchangeBalanceSettings& settings = {},
    const ProgressCallback& progress = nullptr);

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
