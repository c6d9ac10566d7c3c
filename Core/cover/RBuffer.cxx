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

namespace
{
/// The key of "no source" in the group vote (a group of its own).
constexpr int64_t NoGroup = std::numeric_limits<int64_t>::min();
constexpr int32_t NoSource = RBuffer::NoSource;

/// The plurality votes of one cell over its samples (see the header), with the scratch space
/// of the distinct keys met in the cell, reused from cell to cell.
class CellVote
{
public:
  CellVote(const std::vector<int32_t>& sampleSources,
    const std::vector<int>& order,
    int perCell,
    bool diffuseRounding)
    : SampleSources(sampleSources)
    , Order(order)
    , PerCell(perCell)
    , DiffuseRounding(diffuseRounding)
    , Keys(static_cast<size_t>(perCell))
    , Counts(static_cast<size_t>(perCell))
    , Scores(static_cast<size_t>(perCell))
    , SampleOf(static_cast<size_t>(perCell))
  {
  }

  /// The cell's samples (indices into the sample arrays), in the grid's in-cell order.
  std::vector<std::size_t>& Samples() { return this->SampleOf; }

  /// Counts the samples of the cell per `key` over all its samples; returns the distinct keys.
  template<class Key>
  int Count(Key&& key);

  /// Among the `distinct` keys counted for which `eligible` holds, the one of largest score =
  /// count + carry; the tie rule picks the tied key met first in centre order. Then every
  /// counted key's carry grows by its count and the winner's shrinks by perCell. Returns the
  /// winner (-1 when none is eligible); sets tie.
  template<class Key, class Eligible>
  int64_t Vote(int distinct,
    Key&& key,
    Eligible&& eligible,
    std::unordered_map<int64_t, int>& carry,
    bool& tie);

private:
  const std::vector<int32_t>& SampleSources;
  const std::vector<int>& Order;
  const int PerCell;
  const bool DiffuseRounding;
  std::vector<int64_t> Keys;
  std::vector<int> Counts;
  std::vector<int> Scores;
  std::vector<std::size_t> SampleOf;
};

template<class Key>
int CellVote::Count(Key&& key)
{
  std::vector<int64_t>& keys = this->Keys;
  std::vector<int>& counts = this->Counts;
  int distinct = 0;
  for (int k = 0; k < this->PerCell; ++k)
  {
    const int32_t source = this->SampleSources[this->SampleOf[static_cast<size_t>(k)]];
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
}

template<class Key, class Eligible>
int64_t CellVote::Vote(int distinct,
  Key&& key,
  Eligible&& eligible,
  std::unordered_map<int64_t, int>& carry,
  bool& tie)
{
  const std::vector<int64_t>& keys = this->Keys;
  const std::vector<int>& counts = this->Counts;
  std::vector<int>& scores = this->Scores;
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
    for (const int k : this->Order)
    {
      const int64_t value = key(this->SampleSources[this->SampleOf[static_cast<size_t>(k)]]);
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
    if (!this->DiffuseRounding || keys[static_cast<size_t>(index)] == NoGroup ||
      keys[static_cast<size_t>(index)] == NoSource)
    {
      continue;
    }
    carry[keys[static_cast<size_t>(index)]] += counts[static_cast<size_t>(index)] -
      (any && keys[static_cast<size_t>(index)] == winner ? this->PerCell : 0);
  }
  return winner;
}

/// Puts the samples of cell (row, column) into `sampleOf`; returns whether any is grazing.
bool GatherCellSamples(const HemisphereGrid& grid,
  int row,
  int column,
  const std::vector<uint8_t>& sampleGrazings,
  std::vector<std::size_t>& sampleOf)
{
  const int kt = grid.SamplesTheta();
  const int kp = grid.SamplesPhi();
  bool grazing = false;
  for (int a = 0; a < kt; ++a)
  {
    for (int b = 0; b < kp; ++b)
    {
      const std::size_t s = grid.SampleIndex(row * kt + a, column * kp + b);
      sampleOf[static_cast<size_t>(a * kp + b)] = s;
      grazing = grazing || sampleGrazings[s] != 0;
    }
  }
  return grazing;
}

/// The source a cell is given and whether either vote was tied.
struct CellWinner
{
  int32_t Source;
  bool Tie;
};

/// The two rounds of the cell vote: first the group (surface), then its patch (see the
/// header); the carries of all groups and sources counted grow.
template<class GroupKey>
CellWinner ElectCellSource(CellVote& vote,
  const GroupKey& groupKey,
  std::unordered_map<int64_t, int>& groupCarry,
  std::unordered_map<int64_t, int>& sourceCarry)
{
  bool groupTie = false;
  bool sourceTie = false;
  const int64_t group = vote.Vote(
    vote.Count(groupKey), groupKey, [](int64_t) { return true; }, groupCarry, groupTie);
  // The sources of the winning group compete; the carries of all sources counted grow.
  auto sourceKey = [](int32_t source) -> int64_t { return source; };
  int32_t winner = static_cast<int32_t>(vote.Vote(
    vote.Count(sourceKey),
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
  return { winner, groupTie || sourceTie };
}

/// The first sample in centre order that shows `winner` (the first in centre order when none
/// does); `votes` is the number of the cell's samples that show it.
std::size_t RepresentativeSample(const std::vector<int32_t>& sampleSources,
  const std::vector<std::size_t>& sampleOf,
  const std::vector<int>& order,
  int32_t winner,
  int& votes)
{
  votes = 0;
  std::size_t representative = sampleOf[static_cast<size_t>(order[0])];
  bool found = false;
  for (const int k : order)
  {
    const std::size_t s = sampleOf[static_cast<size_t>(k)];
    if (sampleSources[s] == winner)
    {
      ++votes;
      if (!found)
      {
        representative = s;
        found = true;
      }
    }
  }
  return representative;
}
}

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
  // "No source" is a group of its own (key NoGroup) that can win a cell.
  auto groupKey = [&groupOf](int32_t source) -> int64_t
  {
    const int64_t group = groupOf(source);
    return source == NoSource ? NoGroup : group;
  };
  CellVote vote(this->SampleSources, order, grid.SamplesPerCell(), diffuseRounding);
  // The coverage carried along the row (error diffusion, see the header), in samples: per
  // group and per source, what it covered minus what it was given (perCell per cell won).
  std::unordered_map<int64_t, int> groupCarry;
  std::unordered_map<int64_t, int> sourceCarry;
  for (int row = 0; row < grid.ThetaBins(); ++row)
  {
    groupCarry.clear();
    sourceCarry.clear();
    for (int column = 0; column < grid.PhiBins(); ++column)
    {
      std::vector<std::size_t>& sampleOf = vote.Samples();
      const bool grazing = GatherCellSamples(grid, row, column, this->SampleGrazings, sampleOf);
      // Most cells show one source in all their samples (the ray fill's uniform cells): it
      // wins both rounds untied with every sample, and its carries change by its count minus
      // PerCell, zero, so the vote would give what this gives.
      const int32_t only = this->SampleSources[sampleOf[0]];
      bool uniform = true;
      for (std::size_t k = 1; k < sampleOf.size() && uniform; ++k)
      {
        uniform = this->SampleSources[sampleOf[k]] == only;
      }
      CellWinner elected{ only, false };
      int votes = static_cast<int>(sampleOf.size());
      std::size_t representative = sampleOf[static_cast<size_t>(order[0])];
      if (!uniform)
      {
        elected = ElectCellSource(vote, groupKey, groupCarry, sourceCarry);
        representative =
          RepresentativeSample(this->SampleSources, sampleOf, order, elected.Source, votes);
      }
      const int32_t winner = elected.Source;
      const int cell = grid.CellIndex(row, column);
      this->CellSources[static_cast<size_t>(cell)] = winner;
      this->CellVoteCounts[static_cast<size_t>(cell)] = static_cast<uint8_t>(std::min(votes, 255));
      this->CellFlagValues[static_cast<size_t>(cell)] =
        static_cast<uint8_t>((elected.Tie ? CellTie : 0) | (grazing ? CellGrazing : 0));
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
  const RBufferFillOptions& options,
  std::shared_ptr<const RayCaster> rays)
{
  switch (kind)
  {
    case RBufferFill::Projection:
      return std::make_unique<ProjectionFiller>(patches, grid, options);
    case RBufferFill::RayCasting:
      return std::make_unique<RayCastFiller>(patches, grid, options, std::move(rays));
  }
  return nullptr;
}

} // namespace sphcover
