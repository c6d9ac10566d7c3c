// SPDX-License-Identifier: BSD-3-Clause
#include "propagation/ExchangeBalance.h"

#include "cover/SphericalCover.h"

#include <algorithm>
#include <cmath>

namespace sphcover
{

ExchangeBalance::ExchangeBalance(const SphericalCover& cover,
  const ExchangeBalanceSettings& settings,
  const ProgressCallback& progress)
{
  const std::size_t n = cover.PatchCount();
  const std::size_t entries = cover.EntryCount();
  // G_ij = A_i Omega_ij by entry (row order) and in column order, and the targets r_i.
  std::vector<double> rowThroughput(entries);
  std::vector<double> columnThroughput(entries);
  std::vector<double> target(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
    {
      rowThroughput[e] = cover.PatchArea(i) * cover.ProjectedSolidAngle(e);
      target[i] += rowThroughput[e];
    }
  }
  for (std::size_t k = 0; k < entries; ++k)
  {
    columnThroughput[k] = rowThroughput[cover.ColumnAt(k).EntryIndex];
  }

  std::vector<double> x(n, 1.0);
  std::vector<double> y(n, 1.0);
  // Column sums of x_i G_ij y_j against r_j, over the sources that are seen (r_j = 0 gives
  // y_j = 0, see the header); also updates y when asked (the column step).
  const auto columnStep = [&](bool update)
  {
    double residual = 0.0;
    double largestChange = 0.0;
    for (std::size_t j = 0; j < n; ++j)
    {
      if (cover.ColumnBegin(j) == cover.ColumnEnd(j))
      {
        continue;
      }
      double sum = 0.0;
      for (std::size_t k = cover.ColumnBegin(j); k < cover.ColumnEnd(j); ++k)
      {
        sum += x[cover.ColumnAt(k).Receiver] * columnThroughput[k];
      }
      if (!(sum > 0.0))
      {
        continue;
      }
      residual =
        std::max(residual, std::fabs(sum * y[j] - target[j]) / std::max(target[j], sum * y[j]));
      if (update)
      {
        const double next = target[j] / sum;
        largestChange = std::max(largestChange, std::fabs(next - y[j]) / std::max(next, y[j]));
        y[j] = next;
      }
    }
    return update ? largestChange : residual;
  };
  const auto rowStep = [&]
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      double sum = 0.0;
      for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
      {
        sum += rowThroughput[e] * y[cover.EntryAt(e).Source];
      }
      x[i] = sum > 0.0 ? target[i] / sum : 1.0;
    }
  };

  this->InitialResidual = columnStep(false);
  // The change of every iteration, to tell a slow convergence from a stall.
  std::vector<double> changes;
  while (this->IterationCount < settings.MaximumIterations)
  {
    rowStep();
    const double change = columnStep(true);
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
  rowStep();
  this->Residual = columnStep(false);
  this->Factors.resize(entries);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
    {
      this->Factors[e] = x[i] * y[cover.EntryAt(e).Source];
    }
  }
  if (progress)
  {
    progress(1.0);
  }
}

} // namespace sphcover
