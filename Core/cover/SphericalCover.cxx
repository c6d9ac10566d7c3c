// SPDX-License-Identifier: BSD-3-Clause
#include "cover/SphericalCover.h"

#include "cover/HemisphereInterpolation.h"
#include "cover/RayCastFill.h"
#include "math/Constants.h"
#include "math/IntervalVector.h"

#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace sphcover
{

static_assert(sizeof(SphericalCover::Strip) == 6, "a strip is three uint16");

double SphericalCover::MeasureOfStrips(const HemisphereGrid& grid,
  const SphericalCover::Strip* first,
  const SphericalCover::Strip* last)
{
  double sum = 0.0;
  for (const SphericalCover::Strip* strip = first; strip != last; ++strip)
  {
    sum += (strip->PhiEnd - strip->PhiBegin) * grid.CellMeasure(strip->Row);
  }
  return sum;
}
static_assert(sizeof(SphericalCover::Entry) == 8, "an entry is two uint32");

bool SphericalCover::Build(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  std::shared_ptr<const RayCaster> rays)
{
  std::vector<std::size_t> receivers(patches.size());
  std::iota(receivers.begin(), receivers.end(), std::size_t(0));
  if (!this->BuildRows(patches, options, receivers, parallelFor, progress, std::move(rays)))
  {
    return false;
  }
  this->BuildColumns();
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

void SphericalCover::BuildColumns()
{
  // Count, prefix sums, then fill in receiver order (receivers ascending per column).
  const size_t count = this->PatchCount();
  this->ColumnOffsets.assign(count + 1, 0);
  for (const Entry& entry : this->Entries)
  {
    ++this->ColumnOffsets[entry.Source + 1];
  }
  std::partial_sum(
    this->ColumnOffsets.begin(), this->ColumnOffsets.end(), this->ColumnOffsets.begin());
  this->Columns.resize(this->Entries.size());
  std::vector<uint64_t> cursor(this->ColumnOffsets.begin(), this->ColumnOffsets.end() - 1);
  for (size_t i = 0; i < count; ++i)
  {
    for (size_t e = this->EntryBegin(i); e < this->EntryEnd(i); ++e)
    {
      this->Columns[cursor[this->Entries[e].Source]++] = { static_cast<uint32_t>(i),
        static_cast<uint32_t>(e) };
    }
  }
}

std::size_t SphericalCover::StripEnd(std::size_t entry) const
{
  return entry + 1 < this->Entries.size() ? this->Entries[entry + 1].FirstStrip
                                          : this->Strips.size();
}

int CompareEntryKeys(uint32_t sourceA,
  unsigned layerA,
  const glm::vec3& filterA,
  uint32_t sourceB,
  unsigned layerB,
  const glm::vec3& filterB)
{
  if (sourceA != sourceB)
  {
    return sourceA < sourceB ? -1 : 1;
  }
  if (layerA != layerB)
  {
    return layerA < layerB ? -1 : 1;
  }
  for (int band = 0; band < 3; ++band)
  {
    if (filterA[band] != filterB[band])
    {
      return filterA[band] < filterB[band] ? -1 : 1;
    }
  }
  return 0;
}

std::ptrdiff_t SphericalCover::FindEntry(std::size_t receiver, std::size_t source) const
{
  const auto begin =
    this->Entries.begin() + static_cast<std::ptrdiff_t>(this->EntryBegin(receiver));
  const auto end = this->Entries.begin() + static_cast<std::ptrdiff_t>(this->EntryEnd(receiver));
  const auto found = std::lower_bound(
    begin, end, source, [](const Entry& e, std::size_t s) { return e.Source < s; });
  // The source's entries run by layer: the first is of layer 0 when Q_j is seen directly.
  if (found == end || found->Source != source ||
    this->Layer(static_cast<size_t>(found - this->Entries.begin())) != 0)
  {
    return -1;
  }
  return found - this->Entries.begin();
}

glm::dvec3 SphericalCover::Filter(std::size_t entry) const
{
  if (this->Filters.empty())
  {
    return glm::dvec3(1.0);
  }
  const float* f = &this->Filters[3 * entry];
  return glm::dvec3(f[0], f[1], f[2]);
}

glm::dvec3 SphericalCover::PaneTransmittance(std::size_t patch) const
{
  if (this->Transmittances.empty())
  {
    return glm::dvec3(0.0);
  }
  const float* t = &this->Transmittances[3 * patch];
  return glm::dvec3(t[0], t[1], t[2]);
}

uint32_t SphericalCover::VisibleCells(std::size_t entry) const
{
  uint32_t cells = 0;
  for (size_t s = this->StripBegin(entry); s < this->StripEnd(entry); ++s)
  {
    cells += static_cast<uint32_t>(this->Strips[s].PhiEnd - this->Strips[s].PhiBegin);
  }
  return cells;
}

std::vector<int32_t> SphericalCover::ExpandRow(std::size_t receiver) const
{
  const HemisphereGrid& grid = this->Grid();
  std::vector<int32_t> cells(static_cast<size_t>(grid.CellCount()), RBuffer::NoSource);
  for (size_t e = this->EntryBegin(receiver); e < this->EntryEnd(receiver); ++e)
  {
    if (this->Layer(e) != 0)
    {
      continue;
    }
    for (size_t s = this->StripBegin(e); s < this->StripEnd(e); ++s)
    {
      const Strip& strip = this->Strips[s];
      for (int column = strip.PhiBegin; column < strip.PhiEnd; ++column)
      {
        cells[static_cast<size_t>(grid.CellIndex(strip.Row, column))] =
          static_cast<int32_t>(this->Entries[e].Source);
      }
    }
  }
  return cells;
}

double SphericalCover::ProjectedSolidAngle(std::size_t entry) const
{
  return this->Measures.empty() ? this->CellsMeasure(entry) : this->Measures[entry];
}

double SphericalCover::CellsMeasure(std::size_t entry) const
{
  const Strip* strips = this->Strips.data();
  return MeasureOfStrips(
    this->Grid(), strips + this->StripBegin(entry), strips + this->StripEnd(entry));
}

double SphericalCover::ProjectedSolidAngle(std::size_t receiver, std::size_t source) const
{
  const std::ptrdiff_t entry = this->FindEntry(receiver, source);
  return entry < 0 ? 0.0 : this->ProjectedSolidAngle(static_cast<size_t>(entry));
}

double SphericalCover::CoveredProjectedSolidAngle(std::size_t receiver) const
{
  // Summed per theta row (cells of a row share a measure) to keep the rounding small.
  const HemisphereGrid& grid = this->Grid();
  std::vector<uint32_t> cellsPerRow(static_cast<size_t>(grid.ThetaBins()), 0);
  for (size_t e = this->EntryBegin(receiver); e < this->EntryEnd(receiver); ++e)
  {
    if (this->Layer(e) != 0)
    {
      continue;
    }
    for (size_t s = this->StripBegin(e); s < this->StripEnd(e); ++s)
    {
      cellsPerRow[this->Strips[s].Row] += this->Strips[s].PhiEnd - this->Strips[s].PhiBegin;
    }
  }
  double sum = 0.0;
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    sum += cellsPerRow[static_cast<size_t>(row)] * grid.CellMeasure(row);
  }
  return sum;
}

std::vector<double> SphericalCover::FormFactors(const std::vector<int>& groupOfPatch,
  int groupCount) const
{
  return FormFactorsOf(
    this->FormFactorSums(groupOfPatch, groupCount), groupOfPatch, groupCount, this->Areas);
}

std::vector<std::vector<SphericalCover::GroupSum>> SphericalCover::FormFactorSums(
  const std::vector<int>& groupOfPatch,
  int groupCount) const
{
  if (groupOfPatch.size() != this->PatchCount() || groupCount < 0)
  {
    throw std::invalid_argument("SphericalCover::FormFactors: need one group per patch (" +
      std::to_string(this->PatchCount()) + "), got " + std::to_string(groupOfPatch.size()));
  }
  const auto checked = [groupCount](int group)
  {
    if (group >= groupCount)
    {
      throw std::invalid_argument("SphericalCover::FormFactors: group out of range");
    }
    return group;
  };
  std::vector<std::vector<GroupSum>> sums(this->PatchCount());
  // Each row's sums per group in a dense scratch row, the groups seen listed to read it back.
  std::vector<double> scratch(static_cast<size_t>(groupCount), 0.0);
  std::vector<bool> seen(static_cast<size_t>(groupCount), false);
  std::vector<int32_t> groups;
  for (size_t i = 0; i < this->PatchCount(); ++i)
  {
    if (checked(groupOfPatch[i]) < 0)
    {
      continue;
    }
    groups.clear();
    for (size_t e = this->EntryBegin(i); e < this->EntryEnd(i); ++e)
    {
      const int b = checked(groupOfPatch[this->Entries[e].Source]);
      if (b >= 0 && this->Layer(e) == 0)
      {
        if (!seen[static_cast<size_t>(b)])
        {
          seen[static_cast<size_t>(b)] = true;
          groups.push_back(b);
        }
        scratch[static_cast<size_t>(b)] += this->ProjectedSolidAngle(e) / Pi;
      }
    }
    std::sort(groups.begin(), groups.end());
    for (const int32_t b : groups)
    {
      sums[i].push_back(GroupSum{ b, scratch[static_cast<size_t>(b)] });
      scratch[static_cast<size_t>(b)] = 0.0;
      seen[static_cast<size_t>(b)] = false;
    }
  }
  return sums;
}

std::vector<double> SphericalCover::FormFactorsOf(const std::vector<std::vector<GroupSum>>& rowSums,
  const std::vector<int>& groupOfPatch,
  int groupCount,
  const std::vector<double>& areas)
{
  if (rowSums.size() != groupOfPatch.size() || areas.size() != groupOfPatch.size() ||
    groupCount < 0)
  {
    throw std::invalid_argument("SphericalCover::FormFactorsOf: need one group, area and row of "
                                "sums per patch (" +
      std::to_string(groupOfPatch.size()) + "), got " + std::to_string(areas.size()) +
      " areas and " + std::to_string(rowSums.size()) + " rows");
  }
  const size_t g = static_cast<size_t>(groupCount);
  std::vector<double> matrix(g * g, 0.0);
  std::vector<double> groupArea(g, 0.0);
  for (size_t i = 0; i < groupOfPatch.size(); ++i)
  {
    const int a = groupOfPatch[i];
    if (a < 0)
    {
      continue;
    }
    if (a >= groupCount)
    {
      throw std::invalid_argument("SphericalCover::FormFactorsOf: group out of range");
    }
    groupArea[static_cast<size_t>(a)] += areas[i];
    for (const GroupSum& sum : rowSums[i])
    {
      if (sum.Group < 0 || sum.Group >= groupCount)
      {
        throw std::invalid_argument("SphericalCover::FormFactorsOf: group out of range");
      }
      matrix[static_cast<size_t>(a) * g + static_cast<size_t>(sum.Group)] += areas[i] * sum.Sum;
    }
  }
  for (size_t a = 0; a < g; ++a)
  {
    for (size_t b = 0; b < g; ++b)
    {
      matrix[a * g + b] = groupArea[a] > 0.0 ? matrix[a * g + b] / groupArea[a] : 0.0;
    }
  }
  return matrix;
}

std::size_t SphericalCover::MemoryBytes() const
{
  return this->RowOffsets.size() * sizeof(uint64_t) + this->Entries.size() * sizeof(Entry) +
    this->Unoccluded.size() * sizeof(float) + this->Strips.size() * sizeof(Strip) +
    this->StripDepths.size() * sizeof(float) + this->ColumnOffsets.size() * sizeof(uint64_t) +
    this->Columns.size() * sizeof(ColumnEntry) + this->Areas.size() * sizeof(double) +
    this->Measures.size() * sizeof(float) + this->Layers.size() * sizeof(uint8_t) +
    (this->Filters.size() + this->Transmittances.size()) * sizeof(float);
}

std::size_t SphericalCover::UpperBoundBytes(std::size_t patches,
  const SphericalCoverOptions& options)
{
  const std::size_t cells =
    static_cast<std::size_t>(options.ThetaBins) * static_cast<std::size_t>(options.PhiBins);
  const std::size_t entriesPerRow = std::min(patches, cells);
  return patches * (BytesPerPatch + cells * BytesPerStrip + entriesPerRow * BytesPerEntry) +
    2 * sizeof(uint64_t);
}

std::size_t SphericalCover::WorkingBytesPerThread(const SphericalCoverOptions& options)
{
  const std::size_t cells =
    static_cast<std::size_t>(options.ThetaBins) * static_cast<std::size_t>(options.PhiBins);
  const std::size_t samples = cells * static_cast<std::size_t>(options.SamplesTheta) *
    static_cast<std::size_t>(options.SamplesPhi);
  // RBuffer: per sample source, depth, flag; per cell source, depth, flags, votes. The
  // projection fill adds per sample a piece index, two depths and a stamp, per cell a count.
  const std::size_t buffer = samples * (4 + 4 + 1) + cells * (4 + 4 + 1 + 1);
  const std::size_t projection =
    options.Fill == RBufferFill::Projection ? samples * (4 + 8 + 8 + 4) + cells * 2 : 0;
  return buffer + projection;
}

std::size_t SphericalCover::WorkingBytes(const SphericalCoverOptions& options, std::size_t threads)
{
  // The grid's per-row and per-sample-row/column tables (a few doubles each).
  const std::size_t grid = 8 *
    (static_cast<std::size_t>(options.ThetaBins) * (1 + 2 * options.SamplesTheta) +
      static_cast<std::size_t>(options.PhiBins) * 2 * options.SamplesPhi);
  return std::max<std::size_t>(threads, 1) * WorkingBytesPerThread(options) + grid;
}

std::string SphericalCover::MemoryProblem(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  std::size_t threads,
  std::size_t limitBytes,
  std::shared_ptr<const RayCaster> rays)
{
  // Validates the grid (sizes, and a cell count that fits its int indices) without allocating.
  HemisphereGrid::CheckSizes(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  const auto mib = [](double bytes)
  {
    std::ostringstream text;
    text << std::fixed << std::setprecision(bytes < 1024.0 * 1024.0 ? 3 : 0)
         << bytes / (1024.0 * 1024.0) << " MiB";
    return text.str();
  };
  const std::size_t working = WorkingBytes(options, threads);
  std::ostringstream problem;
  if (working > limitBytes)
  {
    problem << "building the cover on " << std::max<std::size_t>(threads, 1)
            << " threads needs about " << mib(static_cast<double>(working))
            << " of R-buffers for a " << options.ThetaBins << " x " << options.PhiBins << " grid ("
            << options.SamplesTheta * options.SamplesPhi
            << " samples per cell), more than the limit of " << mib(static_cast<double>(limitBytes))
            << "; use a coarser grid or fewer threads";
    return problem.str();
  }
  if (patches.empty())
  {
    return std::string();
  }
  const std::size_t cover = EstimateBytes(patches, options, EstimateSamples, std::move(rays));
  if (cover > limitBytes - working)
  {
    problem << "the cover of " << patches.size() << " patches would need about "
            << mib(static_cast<double>(cover) + static_cast<double>(working))
            << " (with the R-buffers), more than the limit of "
            << mib(static_cast<double>(limitBytes))
            << "; use fewer patches (MaxLevel) or a coarser grid";
  }
  return problem.str();
}

} // namespace sphcover
