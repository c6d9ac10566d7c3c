// SPDX-License-Identifier: BSD-3-Clause
#include "cover/RBuffer.h"

#include "cover/ProjectionFill.h"
#include "cover/RayCastFill.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

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
  const std::vector<int32_t>* groupOfSource,
  bool diffuseRounding)
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
  std::vector<int> scores(static_cast<size_t>(perCell));
  std::vector<std::size_t> sampleOf(static_cast<size_t>(perCell));
  // The coverage carried along the row (error diffusion, see the header), in samples: per
  // group and per source, what it covered minus what it was given (perCell per cell won).
  std::unordered_map<int64_t, int> groupCarry;
  std::unordered_map<int64_t, int> sourceCarry;
  constexpr int64_t NoGroup = std::numeric_limits<int64_t>::min();
  // Counts the samples of the cell per `key` over all its samples (`distinct` keys).
  auto count = [&](auto&& key) -> int
  {
    int distinct = 0;
    for (int k = 0; k < perCell; ++k)
    {
      const int32_t source = this->SampleSources[sampleOf[static_cast<size_t>(k)]];
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
    return distinct;
  };
  // Among the `distinct` keys counted for which `eligible` holds, the one of largest score =
  // count + carry; the tie rule picks the tied key met first in centre order. Then every
  // counted key's carry grows by its count and the winner's shrinks by perCell. Returns the
  // winner (-1 when none is eligible); sets tie.
  auto vote = [&](int distinct,
                auto&& key,
                auto&& eligible,
                std::unordered_map<int64_t, int>& carry,
                bool& tie) -> int64_t
  {
    bool any = false;
    int top = 0;
    int tied = 0;
    for (int index = 0; index < distinct; ++index)
    {
      const int64_t value = keys[static_cast<size_t>(index)];
      const auto found = carry.find(value);
      const int score =
        counts[static_cast<size_t>(index)] + (found == carry.end() ? 0 : found->second);
      scores[static_cast<size_t>(index)] = score;
      if (!eligible(value))
      {
        continue;
      }
      if (!any || score > top)
      {
        top = score;
        tied = 1;
        any = true;
      }
      else if (score == top)
      {
        ++tied;
      }
    }
    tie = tied > 1;
    int64_t winner = -1;
    if (any)
    {
      for (const int k : order)
      {
        const int64_t value = key(this->SampleSources[sampleOf[static_cast<size_t>(k)]]);
        int index = 0;
        while (keys[static_cast<size_t>(index)] != value)
        {
          ++index;
        }
        if (eligible(value) && scores[static_cast<size_t>(index)] == top)
        {
          winner = value;
          break;
        }
      }
    }
    for (int index = 0; index < distinct; ++index)
    {
      // "No source" carries nothing: it is no measure to keep, and in a closed scene a few
      // empty samples (gaps between tessellated patches) must not add up to empty cells.
      if (!diffuseRounding || keys[static_cast<size_t>(index)] == NoGroup ||
        keys[static_cast<size_t>(index)] == NoSource)
      {
        continue;
      }
      carry[keys[static_cast<size_t>(index)]] += counts[static_cast<size_t>(index)] -
        (any && keys[static_cast<size_t>(index)] == winner ? perCell : 0);
    }
    return winner;
  };
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    groupCarry.clear();
    sourceCarry.clear();
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
      // First the group (surface), then its patch (see the header). "No source" is a group of
      // its own (key NoGroup) that can win a cell.
      bool groupTie = false;
      bool sourceTie = false;
      auto groupKey = [&groupOf, NoGroup](int32_t source) -> int64_t
      {
        const int64_t group = groupOf(source);
        return source == NoSource ? NoGroup : group;
      };
      const int64_t group = vote(
        count(groupKey), groupKey, [](int64_t) { return true; }, groupCarry, groupTie);
      // The sources of the winning group compete; the carries of all sources counted grow.
      auto sourceKey = [](int32_t source) -> int64_t { return source; };
      int32_t winner = static_cast<int32_t>(vote(
        count(sourceKey),
        sourceKey,
        [&groupKey, group](int64_t source)
        { return source != NoSource && groupKey(static_cast<int32_t>(source)) == group; },
        sourceCarry,
        sourceTie));
      if (group == NoGroup)
      {
        winner = NoSource;
        sourceTie = false;
      }
      int votes = 0;
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
