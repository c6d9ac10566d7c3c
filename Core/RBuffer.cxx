// SPDX-License-Identifier: BSD-3-Clause
#include "RBuffer.h"

#include "ProjectionFill.h"
#include "RayCastFill.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sphcover
{

const char* RBufferFillName(RBufferFill fill)
{
  switch (fill)
  {
    case RBufferFill::Projection:
      return "Projection";
    case RBufferFill::RayCasting:
      return "RayCasting";
  }
  return "Unknown";
}

RBuffer::RBuffer(const HemisphereGrid& grid)
  : GridPointer(&grid)
  , SampleSources(grid.SampleCount(), NoSource)
  , SampleDepths(grid.SampleCount(), std::numeric_limits<float>::quiet_NaN())
  , SampleGrazings(grid.SampleCount(), 0)
  , CellSources(static_cast<size_t>(grid.CellCount()), NoSource)
  , CellDepths(static_cast<size_t>(grid.CellCount()), std::numeric_limits<float>::quiet_NaN())
  , CellFlagValues(static_cast<size_t>(grid.CellCount()), 0)
  , CellVoteCounts(static_cast<size_t>(grid.CellCount()), 0)
{
}

void RBuffer::Reset(std::size_t receiver)
{
  this->ReceiverIndex = receiver;
  std::fill(this->SampleSources.begin(), this->SampleSources.end(), NoSource);
  std::fill(
    this->SampleDepths.begin(), this->SampleDepths.end(), std::numeric_limits<float>::quiet_NaN());
  std::fill(this->SampleGrazings.begin(), this->SampleGrazings.end(), 0);
  std::fill(this->CellSources.begin(), this->CellSources.end(), NoSource);
  std::fill(
    this->CellDepths.begin(), this->CellDepths.end(), std::numeric_limits<float>::quiet_NaN());
  std::fill(this->CellFlagValues.begin(), this->CellFlagValues.end(), 0);
  std::fill(this->CellVoteCounts.begin(), this->CellVoteCounts.end(), 0);
  this->HasUnoccludedValues = false;
  this->Unoccluded.clear();
}

void RBuffer::Classify(const std::function<float(std::size_t sample, int32_t source)>& depthOf,
  const std::vector<int32_t>* groupOfSource)
{
  const HemisphereGrid& grid = *this->GridPointer;
  const int kt = grid.SamplesTheta();
  const int kp = grid.SamplesPhi();
  const int perCell = grid.SamplesPerCell();
  const std::vector<int>& order = grid.SamplesFromCentre();
  // The group of a sample's source; "no source" is a group of its own.
  auto groupOf = [groupOfSource](int32_t source) -> int64_t
  {
    if (source == NoSource)
    {
      return -1;
    }
    return groupOfSource ? (*groupOfSource)[static_cast<size_t>(source)] : source;
  };
  // Distinct keys (groups, then sources) of one cell and their counts.
  std::vector<int64_t> keys(static_cast<size_t>(perCell));
  std::vector<int> counts(static_cast<size_t>(perCell));
  std::vector<std::size_t> sampleOf(static_cast<size_t>(perCell));
  // Plurality vote over the samples for which `eligible` holds, by `key`; the tie rule picks
  // the tied key met first in centre order. Returns the winning key; sets tie.
  auto vote = [&](auto&& key, auto&& eligible, bool& tie) -> int64_t
  {
    int distinct = 0;
    for (int k = 0; k < perCell; ++k)
    {
      const int32_t source = this->SampleSources[sampleOf[static_cast<size_t>(k)]];
      if (!eligible(source))
      {
        continue;
      }
      const int64_t value = key(source);
      int index = 0;
      while (index < distinct && keys[static_cast<size_t>(index)] != value)
      {
        ++index;
      }
      if (index == distinct)
      {
        keys[static_cast<size_t>(index)] = value;
        counts[static_cast<size_t>(index)] = 0;
        ++distinct;
      }
      ++counts[static_cast<size_t>(index)];
    }
    int top = 0;
    int tied = 0;
    for (int index = 0; index < distinct; ++index)
    {
      if (counts[static_cast<size_t>(index)] > top)
      {
        top = counts[static_cast<size_t>(index)];
        tied = 1;
      }
      else if (counts[static_cast<size_t>(index)] == top)
      {
        ++tied;
      }
    }
    tie = tied > 1;
    for (const int k : order)
    {
      const int32_t source = this->SampleSources[sampleOf[static_cast<size_t>(k)]];
      if (!eligible(source))
      {
        continue;
      }
      const int64_t value = key(source);
      int index = 0;
      while (keys[static_cast<size_t>(index)] != value)
      {
        ++index;
      }
      if (counts[static_cast<size_t>(index)] == top)
      {
        return value;
      }
    }
    return -1;
  };
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    for (int column = 0; column < grid.PhiBins(); ++column)
    {
      bool grazing = false;
      for (int a = 0; a < kt; ++a)
      {
        for (int b = 0; b < kp; ++b)
        {
          const std::size_t s = grid.SampleIndex(row * kt + a, column * kp + b);
          sampleOf[static_cast<size_t>(a * kp + b)] = s;
          grazing = grazing || this->SampleGrazings[s] != 0;
        }
      }
      // First the group (surface) covering most samples, then its patch covering most.
      bool groupTie = false;
      bool sourceTie = false;
      const int64_t group = vote(
        groupOf, [](int32_t) { return true; }, groupTie);
      int32_t winner = NoSource;
      int votes = 0;
      if (group >= 0)
      {
        winner = static_cast<int32_t>(vote([](int32_t source) -> int64_t { return source; },
          [&groupOf, group](int32_t source) { return groupOf(source) == group; },
          sourceTie));
      }
      std::size_t representative = sampleOf[static_cast<size_t>(order[0])];
      bool found = false;
      for (const int k : order)
      {
        const std::size_t s = sampleOf[static_cast<size_t>(k)];
        if (this->SampleSources[s] == winner)
        {
          ++votes;
          if (!found)
          {
            representative = s;
            found = true;
          }
        }
      }
      const int cell = grid.CellIndex(row, column);
      this->CellSources[static_cast<size_t>(cell)] = winner;
      this->CellVoteCounts[static_cast<size_t>(cell)] = static_cast<uint8_t>(std::min(votes, 255));
      this->CellFlagValues[static_cast<size_t>(cell)] =
        static_cast<uint8_t>((groupTie || sourceTie ? CellTie : 0) | (grazing ? CellGrazing : 0));
      float depth = std::numeric_limits<float>::quiet_NaN();
      if (winner != NoSource)
      {
        depth = this->SampleDepths[representative];
        if (std::isnan(depth) && depthOf)
        {
          depth = depthOf(representative, winner);
        }
      }
      this->CellDepths[static_cast<size_t>(cell)] = depth;
    }
  }
}

double RBuffer::CoveredProjectedSolidAngle() const
{
  const HemisphereGrid& grid = *this->GridPointer;
  double sum = 0.0;
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    int covered = 0;
    for (int column = 0; column < grid.PhiBins(); ++column)
    {
      covered += this->CellSources[static_cast<size_t>(grid.CellIndex(row, column))] != NoSource;
    }
    sum += covered * grid.CellMeasure(row);
  }
  return sum;
}

void RBuffer::SetUnoccludedProjectedSolidAngles(std::vector<std::pair<int32_t, float>> values)
{
  this->Unoccluded = std::move(values);
  this->HasUnoccludedValues = true;
}

std::unique_ptr<RBufferFiller> RBufferFiller::Create(RBufferFill kind,
  const std::vector<Patch>& patches,
  const HemisphereGrid& grid,
  const RBufferFillOptions& options)
{
  switch (kind)
  {
    case RBufferFill::Projection:
      return std::make_unique<ProjectionFiller>(patches, grid, options);
    case RBufferFill::RayCasting:
      return std::make_unique<RayCastFiller>(patches, grid, options);
  }
  return nullptr;
}

} // namespace sphcover
