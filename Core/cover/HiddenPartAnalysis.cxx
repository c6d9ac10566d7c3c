// SPDX-License-Identifier: BSD-3-Clause
#include "cover/HiddenPartAnalysis.h"

#include "math/Constants.h"

#include "cover/HemisphereGrid.h"
#include "geometry/BoundingBoxTree.h"

#include <algorithm>
#include <utility>

namespace sphcover
{

HiddenPartAnalyser::HiddenPartAnalyser(const RefinementSettings& settings)
  : Settings(settings)
{
}

int32_t HiddenPartAnalyser::Find(int32_t x)
{
  while (this->Parent[static_cast<size_t>(x)] != x)
  {
    const int32_t grand = this->Parent[static_cast<size_t>(this->Parent[static_cast<size_t>(x)])];
    this->Parent[static_cast<size_t>(x)] = grand;
    x = grand;
  }
  return x;
}

void HiddenPartAnalyser::Join(int32_t a, int32_t b)
{
  a = this->Find(a);
  b = this->Find(b);
  if (a != b)
  {
    this->Parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
  }
}

void HiddenPartAnalyser::LabelImages(const RBuffer& buffer, HemisphereAnalysis& result)
{
  const HemisphereGrid& grid = buffer.Grid();
  const int rows = grid.SampleRows();
  const int columns = grid.SampleColumns();
  const int perCell = grid.SamplesPerCell();
  const int samplesTheta = grid.SamplesTheta();
  this->Parent.resize(grid.SampleCount());
  for (std::size_t k = 0; k < grid.SampleCount(); ++k)
  {
    this->Parent[k] = static_cast<int32_t>(k);
  }
  this->RegionSamples.assign(grid.SampleCount(), 0);
  std::vector<std::pair<int32_t, int32_t>> poleSamples; // (source, first sample of row 0)
  for (int r = 0; r < rows; ++r)
  {
    const double weight = grid.CellMeasure(r / samplesTheta) / perCell;
    for (int c = 0; c < columns; ++c)
    {
      const size_t s = grid.SampleIndex(r, c);
      const int32_t source = buffer.SampleSource(s);
      if (source < 0)
      {
        continue;
      }
      if (this->VisibleSamples[static_cast<size_t>(source)] == 0)
      {
        result.Visible.push_back(static_cast<uint32_t>(source));
      }
      ++this->VisibleSamples[static_cast<size_t>(source)];
      this->VisibleMeasure[static_cast<size_t>(source)] += weight;
      // 8-neighbours already visited: left (wrapping in phi) and the three above.
      const int32_t self = static_cast<int32_t>(s);
      auto join = [&](int rr, int cc)
      {
        const size_t t = grid.SampleIndex(rr, (cc + columns) % columns);
        if (buffer.SampleSource(t) == source)
        {
          this->Join(self, static_cast<int32_t>(t));
        }
      };
      join(r, c - 1);
      if (c == columns - 1)
      {
        join(r, 0);
      }
      if (r > 0)
      {
        join(r - 1, c - 1);
        join(r - 1, c);
        join(r - 1, c + 1);
      }
      else
      {
        // The first sample row is a small circle around the normal: all of it is adjacent.
        auto found = std::find_if(poleSamples.begin(),
          poleSamples.end(),
          [source](const std::pair<int32_t, int32_t>& p) { return p.first == source; });
        if (found == poleSamples.end())
        {
          poleSamples.emplace_back(source, self);
        }
        else
        {
          this->Join(self, found->second);
        }
      }
    }
  }
  std::sort(result.Visible.begin(), result.Visible.end());
  for (size_t s = 0; s < grid.SampleCount(); ++s)
  {
    if (buffer.SampleSource(s) >= 0)
    {
      ++this->RegionSamples[static_cast<size_t>(this->Find(static_cast<int32_t>(s)))];
    }
  }
  for (size_t s = 0; s < grid.SampleCount(); ++s)
  {
    const int32_t source = buffer.SampleSource(s);
    if (source >= 0 && this->Parent[s] == static_cast<int32_t>(s) &&
      this->RegionSamples[s] >= static_cast<uint32_t>(perCell))
    {
      ++this->LargeRegions[static_cast<size_t>(source)];
    }
  }
}

void HiddenPartAnalyser::Analyse(std::size_t receiver,
  const std::vector<Patch>& current,
  const RBufferFiller& filler,
  RBuffer& buffer,
  HemisphereAnalysis& result)
{
  filler.Fill(receiver, buffer, nullptr);
  const HemisphereGrid& grid = buffer.Grid();
  const size_t count = current.size();
  if (this->VisibleMeasure.size() != count)
  {
    this->VisibleMeasure.assign(count, 0.0);
    this->VisibleSamples.assign(count, 0);
    this->LargeRegions.assign(count, 0);
  }
  const int perCell = grid.SamplesPerCell();

  // The image of every source at sample resolution: measure, sample count, regions.
  this->LabelImages(buffer, result);

  // Step 3: compare each visible source's image with its unoccluded projection.
  const std::vector<std::pair<int32_t, float>>& unoccluded =
    buffer.UnoccludedProjectedSolidAngles();
  const Patch& receiverPatch = current[receiver];
  const double cellAngle = std::min(HalfPi / grid.ThetaBins(), TwoPi / grid.PhiBins());
  for (const uint32_t j : result.Visible)
  {
    const double visible = this->VisibleMeasure[j];
    const uint32_t samples = this->VisibleSamples[j];
    const uint32_t regions = this->LargeRegions[j];
    this->VisibleMeasure[j] = 0.0;
    this->VisibleSamples[j] = 0;
    this->LargeRegions[j] = 0;
    if (j == receiver || samples < this->Settings.MinimumVisibleCells * perCell)
    {
      continue; // a concave patch seeing itself; or (note 4) Q_j fully hidden from P_i
    }
    const auto found = std::lower_bound(unoccluded.begin(),
      unoccluded.end(),
      static_cast<int32_t>(j),
      [](const std::pair<int32_t, float>& p, int32_t source) { return p.first < source; });
    const double projection =
      found != unoccluded.end() && found->first == static_cast<int32_t>(j) ? found->second : 0.0;
    // The cell measure where Q_j is seen: its image's mean measure per sample, times a cell's.
    const double cellMeasure = visible / samples * perCell;
    const double hidden = projection - visible;
    const bool hiddenSubstantially = hidden > this->Settings.HiddenFraction * projection &&
      hidden > this->Settings.MinimumHiddenCells * cellMeasure;
    const bool disconnected = this->Settings.SplitDisconnected && regions >= 2;
    if (!hiddenSubstantially && !disconnected)
    {
      continue;
    }
    // The limits of §4.3 note 2, as in the subdivision.
    const Patch& source = current[j];
    const IntervalVec3& bounds = source.Geometry.Bounds();
    const Box box{ bounds.Lower(), bounds.Upper() };
    const double distance = box.DistanceTo(receiverPatch.Point);
    const bool maySplit = source.Level < this->Settings.MaxLevel &&
      (distance <= 0.0 || box.Diagonal() > cellAngle * distance);
    if (!maySplit)
    {
      ++result.Limited;
      continue;
    }
    (hiddenSubstantially ? result.Hidden : result.Disconnected).push_back(j);
  }
}

} // namespace sphcover
