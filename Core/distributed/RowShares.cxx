// SPDX-License-Identifier: BSD-3-Clause
#include "distributed/RowShares.h"

#include "math/IntervalVector.h"
#include "math/RankShare.h"
#include "subdivision/Patch.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphcover
{

namespace
{
/// Whether `arrays` were built on the grid and with the fill of `options`.
bool SameGridAndFill(const SphericalCover::Arrays& arrays, const SphericalCoverOptions& options)
{
  return arrays.ThetaBins == options.ThetaBins && arrays.PhiBins == options.PhiBins &&
    arrays.SamplesTheta == options.SamplesTheta && arrays.SamplesPhi == options.SamplesPhi &&
    arrays.Fill == static_cast<int>(options.Fill);
}

/// Throws std::invalid_argument (in `caller`'s name) unless `receivers` are ascending, each
/// once, and below n.
void CheckReceivers(const std::vector<std::size_t>& receivers, std::size_t n, const char* caller)
{
  for (std::size_t k = 0; k < receivers.size(); ++k)
  {
    if (receivers[k] >= n || (k > 0 && receivers[k] <= receivers[k - 1]))
    {
      throw std::invalid_argument(std::string(caller) + ": receiver " +
        std::to_string(receivers[k]) + " of " + std::to_string(n) +
        (receivers[k] >= n ? "" : ", not after the previous one"));
    }
  }
}
}

std::vector<double> RowShares::EstimateRowCosts(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options)
{
  const size_t count = patches.size();
  const double fixed =
    options.Fill == RBufferFill::RayCasting ? 2.0 * static_cast<double>(count) : 1.0;
  std::vector<double> costs(count, fixed);
  for (size_t i = 0; i < count; ++i)
  {
    const glm::dvec3& point = patches[i].Point;
    const glm::dvec3& normal = patches[i].Normal;
    size_t candidates = 0;
    for (size_t j = 0; j < count; ++j)
    {
      // The largest height N_i . (Q - P_i) over the box of Q_j's control net, per axis the
      // larger of the box's two ends.
      const IntervalVec3& box = patches[j].Geometry.Bounds();
      double height = 0.0;
      for (int axis = 0; axis < 3; ++axis)
      {
        height += std::max(normal[axis] * (box[axis].Lower() - point[axis]),
          normal[axis] * (box[axis].Upper() - point[axis]));
      }
      candidates += j != i && height > 0.0 ? 1 : 0;
    }
    costs[i] += static_cast<double>(candidates);
  }
  return costs;
}

std::vector<std::size_t> RowShares::PartitionRows(const std::vector<double>& costs,
  std::size_t parts)
{
  if (parts == 0)
  {
    throw std::invalid_argument("RowShares::PartitionRows: no part");
  }
  const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
  std::vector<std::size_t> bounds(parts + 1, costs.size());
  bounds[0] = 0;
  double running = 0.0;
  size_t part = 1;
  for (size_t i = 0; i < costs.size() && part < parts; ++i)
  {
    running += costs[i];
    // Several parts may end at one receiver (fewer receivers than parts): they stay empty.
    while (part < parts && running >= total * static_cast<double>(part) / parts)
    {
      bounds[part++] = i + 1;
    }
  }
  return bounds;
}

std::vector<std::size_t> RowShares::ReceiversOfRanges(const std::vector<std::size_t>& bounds,
  const std::vector<std::size_t>& ranges)
{
  std::vector<std::size_t> receivers;
  for (const std::size_t range : ranges)
  {
    for (std::size_t i = bounds.at(range); i < bounds.at(range + 1); ++i)
    {
      receivers.push_back(i);
    }
  }
  return receivers;
}

void RowShares::AppendRowTo(const SphericalCover& cover, std::size_t receiver, Arrays& to)
{
  const std::size_t begin = cover.RowOffsets[receiver];
  const std::size_t end = cover.RowOffsets[receiver + 1];
  if (begin == end)
  {
    return;
  }
  // The row's strips are consecutive: its first entry's first to its last entry's end.
  const std::size_t stripBegin = cover.Entries[begin].FirstStrip;
  const std::size_t stripEnd = cover.StripEnd(end - 1);
  const std::size_t keptStrips = to.Strips.size();
  for (std::size_t e = begin; e < end; ++e)
  {
    SphericalCover::Entry entry = cover.Entries[e];
    entry.FirstStrip = static_cast<uint32_t>(entry.FirstStrip - stripBegin + keptStrips);
    to.Entries.push_back(entry);
  }
  auto append = [](auto& into, const auto& from, std::size_t b, std::size_t e, std::size_t width)
  {
    if (!from.empty())
    {
      into.insert(into.end(),
        from.begin() + static_cast<std::ptrdiff_t>(b * width),
        from.begin() + static_cast<std::ptrdiff_t>(e * width));
    }
  };
  append(to.Unoccluded, cover.Unoccluded, begin, end, 1);
  append(to.Strips, cover.Strips, stripBegin, stripEnd, 1);
  append(to.StripDepths, cover.StripDepths, stripBegin, stripEnd, 1);
  append(to.Measures, cover.Measures, begin, end, 1);
  append(to.Layers, cover.Layers, begin, end, 1);
  append(to.Filters, cover.Filters, begin, end, 3);
}

SphericalCover RowShares::RowsOf(const SphericalCover& cover,
  const std::vector<std::size_t>& receivers)
{
  const std::size_t n = cover.PatchCount();
  CheckReceivers(receivers, n, "RowShares::RowsOf");
  Arrays kept = SphericalCover::EmptyArrays(cover.BuildOptions, cover.UnoccludedKnown);
  kept.RowOffsets.assign(n + 1, 0);
  std::size_t next = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (next < receivers.size() && receivers[next] == i)
    {
      ++next;
      AppendRowTo(cover, i, kept);
    }
    kept.RowOffsets[i + 1] = kept.Entries.size();
  }
  kept.Areas = cover.Areas;
  kept.Transmittances = cover.Transmittances;
  const std::string problem = SphericalCover::CheckArrays(kept);
  if (!problem.empty())
  {
    throw std::logic_error("RowShares::RowsOf: " + problem);
  }
  SphericalCover rows;
  rows.Adopt(std::move(kept), cover.BuildOptions);
  rows.CullingCounts = cover.CullingCounts;
  rows.PaneLimitCounts = cover.PaneLimitCounts;
  return rows;
}

bool RowShares::BuildRowsOf(SphericalCover& cover,
  const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  const std::vector<std::size_t>& receivers,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  std::shared_ptr<const RayCaster> rays)
{
  CheckReceivers(receivers, patches.size(), "RowShares::BuildRowsOf");
  if (!cover.BuildRows(patches, options, receivers, parallelFor, progress, std::move(rays)))
  {
    return false;
  }
  // BuildRows put the rows one after the other: each moves to its receiver, the others empty,
  // and every patch gets its area (a source's, read by the propagation).
  const std::size_t n = patches.size();
  std::vector<uint64_t> offsets(n + 1, 0);
  for (std::size_t k = 0; k < receivers.size(); ++k)
  {
    offsets[receivers[k] + 1] = cover.RowOffsets[k + 1] - cover.RowOffsets[k];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  cover.RowOffsets = std::move(offsets);
  cover.Areas.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    cover.Areas[i] = patches[i].Area;
  }
  cover.BuildColumns();
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

void RowShares::KeepCellMeasures(SphericalCover& cover)
{
  if (!cover.Measures.empty())
  {
    return;
  }
  std::vector<float> measures(cover.Entries.size());
  for (std::size_t e = 0; e < measures.size(); ++e)
  {
    measures[e] = static_cast<float>(cover.CellsMeasure(e));
  }
  cover.Measures = std::move(measures);
}

std::string RowShares::JoinRows(SphericalCover& cover,
  std::vector<Arrays> shares,
  const SphericalCoverOptions& options,
  const CullingStatistics& culling)
{
  cover.Clear();
  if (shares.empty())
  {
    return "no share of rows";
  }
  // Each share checked on its own (as ImportArrays), then against the first and the options.
  std::vector<SphericalCover> covers(shares.size());
  bool measured = false;
  for (std::size_t s = 0; s < shares.size(); ++s)
  {
    const std::string name = "share " + std::to_string(s) + ": ";
    if (!SameGridAndFill(shares[s], options))
    {
      return name + "its grid or fill is not the cover's";
    }
    const std::string problem = covers[s].ImportArrays(std::move(shares[s]));
    if (!problem.empty())
    {
      return name + problem;
    }
    // The join reads the shares' rows alone: their columns go at once, so that at most one
    // share's are held (the gathered build joins K shares of the whole cover).
    covers[s].Columns = std::vector<SphericalCover::ColumnEntry>();
    covers[s].ColumnOffsets = std::vector<uint64_t>();
    const SphericalCover& first = covers.front();
    if (covers[s].Areas != first.Areas || covers[s].Transmittances != first.Transmittances ||
      covers[s].UnoccludedKnown != first.UnoccludedKnown)
    {
      return name + "its patches or their areas are not share 0's";
    }
    measured = measured || covers[s].HasMeasures();
  }
  shares.clear();
  const std::size_t n = covers.front().PatchCount();
  Arrays joined = SphericalCover::EmptyArrays(options, covers.front().UnoccludedKnown);
  joined.RowOffsets.reserve(n + 1);
  // Reserved whole: grown by doubling, the joined arrays would hold up to twice their size.
  std::size_t entries = 0;
  std::size_t strips = 0;
  for (SphericalCover& share : covers)
  {
    if (measured)
    {
      KeepCellMeasures(share);
    }
    entries += share.EntryCount();
    strips += share.StripCount();
  }
  joined.Entries.reserve(entries);
  joined.Unoccluded.reserve(entries);
  joined.Strips.reserve(strips);
  joined.StripDepths.reserve(strips);
  joined.Measures.reserve(measured ? entries : 0);
  joined.Layers.reserve(covers.front().HasPanes() ? entries : 0);
  joined.Filters.reserve(covers.front().HasPanes() ? 3 * entries : 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::size_t holder = covers.size();
    for (std::size_t s = 0; s < covers.size(); ++s)
    {
      if (covers[s].EntryEnd(i) == covers[s].EntryBegin(i))
      {
        continue;
      }
      if (holder < covers.size())
      {
        return "receiver " + std::to_string(i) + "'s row is in share " + std::to_string(holder) +
          " and in share " + std::to_string(s);
      }
      holder = s;
    }
    if (holder < covers.size())
    {
      AppendRowTo(covers[holder], i, joined);
      if (joined.Strips.size() > std::numeric_limits<uint32_t>::max())
      {
        return "the shares hold more than 2^32 - 1 strips";
      }
    }
    joined.RowOffsets.push_back(joined.Entries.size());
  }
  joined.Areas = covers.front().Areas;
  joined.Transmittances = covers.front().Transmittances;
  // Each share counted what its own rows dropped behind panes.
  PaneLimitDrops paneLimit;
  for (const SphericalCover& share : covers)
  {
    paneLimit += share.PaneLimitCounts;
  }
  covers.clear();
  const std::string problem = SphericalCover::CheckArrays(joined);
  if (!problem.empty())
  {
    return problem;
  }
  cover.Adopt(std::move(joined), options);
  cover.CullingCounts = culling;
  cover.PaneLimitCounts = paneLimit;
  return std::string();
}

std::vector<std::size_t> RowShares::KeptEntries(const SphericalCover& cover,
  const std::vector<std::size_t>& receivers)
{
  std::vector<std::size_t> entries;
  for (const std::size_t i : receivers)
  {
    for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
    {
      entries.push_back(e);
    }
  }
  return entries;
}

std::size_t RowShares::FirstForeignRow(const SphericalCover& cover, const RankShare& share)
{
  for (std::size_t i = 0; i < cover.PatchCount(); ++i)
  {
    if (!share.Owns(i) && cover.EntryEnd(i) > cover.EntryBegin(i))
    {
      return i;
    }
  }
  return cover.PatchCount();
}

} // namespace sphcover
