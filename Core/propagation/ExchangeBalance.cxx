// SPDX-License-Identifier: BSD-3-Clause
#include "propagation/ExchangeBalance.h"

#include "cover/SphericalCover.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace sphcover
{
namespace
{

/// Bits below a column's largest term (rounded up to a power of two, 2^e) that its fixed-point
/// sum keeps: each term's truncation costs less than 2^(e - 100), and 2^28 terms still fit the
/// 128 bits.
constexpr int FixedPointBits = 100;
__extension__ typedef unsigned __int128 FixedPoint; // GCC's and Clang's 128-bit integer

/// static_cast<FixedPoint>(x) for 0 <= x < 2^FixedPointBits, in two 64-bit conversions instead
/// of libgcc's 128-bit one (a tenth of the propagation's time on the Cornell box): x = hi 2^64 +
/// lo exactly (x and hi 2^64 are multiples of x's ulp, lo < 2^64 is representable), so the sum
/// of the parts' truncations is x's, bit for bit.
inline FixedPoint TruncateToFixedPoint(double x)
{
  const double twoTo64 = 18446744073709551616.0;
  const auto hi = static_cast<std::uint64_t>(x / twoTo64);
  const double lo = x - static_cast<double>(hi) * twoTo64;
  return (static_cast<FixedPoint>(hi) << 64) + static_cast<std::uint64_t>(lo);
}

/// The matrix scaling of the balance (see the header): the throughputs G_ij = A_i Omega_ij by
/// entry (row order) and in column order, the targets r_i, and the factors x (rows), y (columns).
/// Under a share the cover holds this rank's rows; x is known for them, y and r for every patch.
class MatrixScaling
{
public:
  MatrixScaling(const SphericalCover& cover, const RankShare& share)
    : Share(share)
    , Cover(cover)
    , RowThroughput(cover.EntryCount())
    , ColumnThroughput(cover.EntryCount())
    , Target(cover.PatchCount(), 0.0)
    , X(cover.PatchCount(), 1.0)
    , Y(cover.PatchCount(), 1.0)
  {
    for (std::size_t i = 0; i < cover.PatchCount(); ++i)
    {
      for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
      {
        // The balance is of the geometric cover (layer 0); what lies behind panes follows
        // their regions (EntryFactors).
        this->RowThroughput[e] =
          cover.Layer(e) == 0 ? cover.PatchArea(i) * cover.ProjectedSolidAngle(e) : 0.0;
        this->Target[i] += this->RowThroughput[e];
      }
    }
    for (std::size_t k = 0; k < cover.EntryCount(); ++k)
    {
      this->ColumnThroughput[k] = this->RowThroughput[cover.ColumnAt(k).EntryIndex];
    }
    if (share.Distributed())
    {
      // r_j is its row's: every rank needs every source's.
      this->Target = JoinOwnedItems(share, this->Target);
    }
  }

  /**
   * sum_i x_i G_ij of every column j over every rank's rows, the same whatever the order of
   * the terms or the ranks: each term is truncated to a multiple of 2^(e_j - FixedPointBits),
   * 2^e_j above the column's largest term, and the integers are added. False (after the joins,
   * so that no rank waits) when some rank's `stop` is true.
   */
  bool ExactColumnSums(std::vector<double>& sums, bool stop)
  {
    const SphericalCover& cover = this->Cover;
    const std::size_t n = cover.PatchCount();
    // The largest term of each column, and this rank's stop, joined: the maxima are the same
    // whatever the order.
    std::vector<double> largest(n + 1, 0.0);
    for (std::size_t j = 0; j < n; ++j)
    {
      for (std::size_t k = cover.ColumnBegin(j); k < cover.ColumnEnd(j); ++k)
      {
        largest[j] = std::max(largest[j], this->Term(k));
      }
    }
    largest[n] = stop ? 1.0 : 0.0;
    CombineOverRanks(this->Share, largest, [](double a, double b) { return std::max(a, b); });
    if (largest[n] != 0.0)
    {
      return false;
    }
    std::vector<int> exponent(n, 0);
    std::vector<FixedPoint> fixed(n, 0);
    for (std::size_t j = 0; j < n; ++j)
    {
      if (!std::isfinite(largest[j]))
      {
        continue; // an overflowed column: its sum is its largest term (below)
      }
      std::frexp(largest[j], &exponent[j]);
      // Powers of two: the products are exact (below 2^FixedPointBits), the truncation is not.
      // Two of them, as 2^(FixedPointBits - e) alone overflows for a column of subnormal terms.
      const int shift = FixedPointBits - exponent[j];
      const double scaleA = std::ldexp(1.0, shift / 2);
      const double scaleB = std::ldexp(1.0, shift - shift / 2);
      for (std::size_t k = cover.ColumnBegin(j); k < cover.ColumnEnd(j); ++k)
      {
        const double term = this->Term(k);
        if (term > 0.0)
        {
          fixed[j] += TruncateToFixedPoint(term * scaleA * scaleB);
        }
      }
    }
    CombineOverRanks(this->Share, fixed, [](FixedPoint a, FixedPoint b) { return a + b; });
    sums.resize(n);
    for (std::size_t j = 0; j < n; ++j)
    {
      sums[j] = std::isfinite(largest[j])
        ? std::ldexp(static_cast<double>(fixed[j]), exponent[j] - FixedPointBits)
        : largest[j];
    }
    return true;
  }

  /// Column sums of x_i G_ij y_j against r_j, over the sources that are seen (r_j = 0 gives
  /// y_j = 0, see the header): the largest relative residual, or with `update` the column step
  /// (y_j = r_j / sum) and its largest relative change. False when some rank's `stop` is true.
  bool ColumnStep(bool update, double& result, bool stop = false)
  {
    std::vector<double>& y = this->Y;
    std::vector<double> sums;
    if (!this->ExactColumnSums(sums, stop))
    {
      return false;
    }
    double residual = 0.0;
    double largestChange = 0.0;
    for (std::size_t j = 0; j < sums.size(); ++j)
    {
      const double sum = sums[j];
      if (!(sum > 0.0))
      {
        continue;
      }
      residual = std::max(
        residual, std::fabs(sum * y[j] - this->Target[j]) / std::max(this->Target[j], sum * y[j]));
      if (update)
      {
        const double next = this->Target[j] / sum;
        largestChange = std::max(largestChange, std::fabs(next - y[j]) / std::max(next, y[j]));
        y[j] = next;
      }
    }
    result = update ? largestChange : residual;
    return true;
  }

  /// x_i = r_i / sum_j G_ij y_j: every hemisphere gathers exactly its covered measure.
  void RowStep()
  {
    const SphericalCover& cover = this->Cover;
    for (std::size_t i = 0; i < cover.PatchCount(); ++i)
    {
      double sum = 0.0;
      for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
      {
        sum += this->RowThroughput[e] * this->Y[cover.EntryAt(e).Source];
      }
      this->X[i] = sum > 0.0 ? this->Target[i] / sum : 1.0;
    }
  }

  /// f_e = x_i y_j of every entry e = (i, j), by entry index.
  std::vector<double> EntryFactors() const
  {
    const SphericalCover& cover = this->Cover;
    std::vector<double> factors(cover.EntryCount());
    for (std::size_t i = 0; i < cover.PatchCount(); ++i)
    {
      // Regions seen through panes (SphericalCover.h, "Panes") count as the panes' regions in
      // front of them do, on average over the row: in a closed scene the layers behind then
      // keep the measure of the panes' regions (the white furnace with panes stays exact).
      double paneBalanced = 0.0;
      double pane = 0.0;
      for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
      {
        const std::size_t j = cover.EntryAt(e).Source;
        factors[e] = this->X[i] * this->Y[j];
        if (cover.Layer(e) == 0 && cover.PaneTransmittance(j) != glm::dvec3(0.0))
        {
          paneBalanced += factors[e] * cover.ProjectedSolidAngle(e);
          pane += cover.ProjectedSolidAngle(e);
        }
      }
      const double behind = pane > 0.0 ? paneBalanced / pane : 1.0;
      for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
      {
        if (cover.Layer(e) != 0)
        {
          factors[e] = behind;
        }
      }
    }
    return factors;
  }

private:
  /// x_i G_ij of the entry at column position k.
  double Term(std::size_t k) const
  {
    return this->X[this->Cover.ColumnAt(k).Receiver] * this->ColumnThroughput[k];
  }

  const RankShare& Share;
  const SphericalCover& Cover;
  std::vector<double> RowThroughput;
  std::vector<double> ColumnThroughput;
  std::vector<double> Target;
  std::vector<double> X;
  std::vector<double> Y;
};

} // namespace

ExchangeBalance::ExchangeBalance(const SphericalCover& cover,
  const ExchangeBalanceSettings& settings,
  const ProgressCallback& progress,
  const RankShare& share)
{
  if (share.Distributed())
  {
    // A rank holding another's row fails; the others learn it in the join, not by waiting.
    std::size_t foreign = 0;
    while (foreign < cover.PatchCount() &&
      (share.Owns(foreign) || cover.VisibleSourceCount(foreign) == 0))
    {
      ++foreign;
    }
    const bool own = foreign == cover.PatchCount();
    if (!share.EveryRankOk(own))
    {
      if (own)
      {
        throw RankShare::PeerFailure();
      }
      throw std::invalid_argument("ExchangeBalance: row " + std::to_string(foreign) +
        " is another rank's receiver's but not empty (RowShares::RowsOf)");
    }
  }
  MatrixScaling scaling(cover, share);
  scaling.ColumnStep(false, this->InitialResidual);
  // The change of every iteration, to tell a slow convergence from a stall.
  std::vector<double> changes;
  bool stop = false;
  while (this->IterationCount < settings.MaximumIterations)
  {
    scaling.RowStep();
    double change = 0.0;
    // A rank's stop reaches every rank in the next column step's join.
    if (!scaling.ColumnStep(true, change, stop))
    {
      this->WasAborted = true;
      return;
    }
    ++this->IterationCount;
    if (change <= settings.Tolerance)
    {
      this->HasConverged = true;
      break;
    }
    // Where the marginals cannot be met exactly (see the header), the iteration settles into a
    // fixed cycle whose change no longer falls: stop when it has not halved in StallWindow
    // iterations.
    changes.push_back(change);
    if (changes.size() > StallWindow && change > 0.5 * changes[changes.size() - 1 - StallWindow])
    {
      this->HasStalled = true;
      break;
    }
    stop = progress &&
      !progress(static_cast<double>(this->IterationCount) /
        static_cast<double>(settings.MaximumIterations));
  }
  // A row step last: each hemisphere gathers exactly its covered measure.
  scaling.RowStep();
  if (!scaling.ColumnStep(false, this->Residual, stop))
  {
    this->WasAborted = true;
    return;
  }
  this->Factors = scaling.EntryFactors();
  if (progress)
  {
    progress(1.0);
  }
}

} // namespace sphcover
