// SPDX-License-Identifier: BSD-3-Clause
#include "propagation/ExchangeBalance.h"

#include "cover/SphericalCover.h"

#include <algorithm>
#include <cmath>

namespace sphcover
{
namespace
{

/// The matrix scaling of the balance (see the header): the throughputs G_ij = A_i Omega_ij by
/// entry (row order) and in column order, the targets r_i, and the factors x (rows), y (columns).
class MatrixScaling
{
public:
  explicit MatrixScaling(const SphericalCover& cover)
    : Cover(cover)
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
  }

  /// Column sums of x_i G_ij y_j against r_j, over the sources that are seen (r_j = 0 gives
  /// y_j = 0, see the header): the largest relative residual, or with `update` the column step
  /// (y_j = r_j / sum) and its largest relative change.
  double ColumnStep(bool update)
  {
    const SphericalCover& cover = this->Cover;
    std::vector<double>& x = this->X;
    std::vector<double>& y = this->Y;
    double residual = 0.0;
    double largestChange = 0.0;
    for (std::size_t j = 0; j < cover.PatchCount(); ++j)
    {
      if (cover.ColumnBegin(j) == cover.ColumnEnd(j))
      {
        continue;
      }
      double sum = 0.0;
      for (std::size_t k = cover.ColumnBegin(j); k < cover.ColumnEnd(j); ++k)
      {
        sum += x[cover.ColumnAt(k).Receiver] * this->ColumnThroughput[k];
      }
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
    return update ? largestChange : residual;
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
  const ProgressCallback& progress)
{
  MatrixScaling scaling(cover);
  this->InitialResidual = scaling.ColumnStep(false);
  // The change of every iteration, to tell a slow convergence from a stall.
  std::vector<double> changes;
  while (this->IterationCount < settings.MaximumIterations)
  {
    scaling.RowStep();
    const double change = scaling.ColumnStep(true);
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
    if (progress &&
      !progress(static_cast<double>(this->IterationCount) /
        static_cast<double>(settings.MaximumIterations)))
    {
      this->WasAborted = true;
      return;
    }
  }
  // A row step last: each hemisphere gathers exactly its covered measure.
  scaling.RowStep();
  this->Residual = scaling.ColumnStep(false);
  this->Factors = scaling.EntryFactors();
  if (progress)
  {
    progress(1.0);
  }
}

} // namespace sphcover
