// SPDX-License-Identifier: BSD-3-Clause
// The spherical cover's own arrays (SphericalCover::Arrays): exported for saving, checked and
// imported when loaded or joined (distributed/RowShares.h); the columns are derived from the rows.
#include "cover/SphericalCover.h"

#include <cmath>
#include <memory>
#include <string>
#include <utility>

namespace sphcover
{

SphericalCover::Arrays SphericalCover::EmptyArrays(const SphericalCoverOptions& options,
  bool unoccludedKnown)
{
  Arrays arrays;
  arrays.ThetaBins = options.ThetaBins;
  arrays.PhiBins = options.PhiBins;
  arrays.SamplesTheta = options.SamplesTheta;
  arrays.SamplesPhi = options.SamplesPhi;
  arrays.Fill = static_cast<int>(options.Fill);
  arrays.UnoccludedKnown = unoccludedKnown;
  arrays.RowOffsets.assign(1, 0);
  return arrays;
}

template<typename Cover>
SphericalCover::Arrays SphericalCover::ArraysOf(Cover&& cover)
{
  Arrays arrays = EmptyArrays(cover.BuildOptions, cover.UnoccludedKnown);
  arrays.RowOffsets = std::forward<Cover>(cover).RowOffsets;
  arrays.Entries = std::forward<Cover>(cover).Entries;
  arrays.Unoccluded = std::forward<Cover>(cover).Unoccluded;
  arrays.Strips = std::forward<Cover>(cover).Strips;
  arrays.StripDepths = std::forward<Cover>(cover).StripDepths;
  arrays.Areas = std::forward<Cover>(cover).Areas;
  arrays.Measures = std::forward<Cover>(cover).Measures;
  arrays.Layers = std::forward<Cover>(cover).Layers;
  arrays.Filters = std::forward<Cover>(cover).Filters;
  arrays.Transmittances = std::forward<Cover>(cover).Transmittances;
  return arrays;
}

SphericalCover::Arrays SphericalCover::ExportArrays() &&
{
  Arrays arrays = ArraysOf(std::move(*this));
  *this = SphericalCover(); // the columns' memory too
  return arrays;
}

SphericalCover::Arrays SphericalCover::ExportArrays() const&
{
  return ArraysOf(*this);
}

std::string SphericalCover::CheckArrays(const Arrays& arrays)
{
  if (arrays.ThetaBins < 1 || arrays.PhiBins < 1 || arrays.ThetaBins > 65535 ||
    arrays.PhiBins > 65535 || arrays.SamplesTheta < 1 || arrays.SamplesPhi < 1)
  {
    return "the grid sizes are invalid";
  }
  const size_t count = arrays.Areas.size();
  if (arrays.RowOffsets.size() != count + 1 || arrays.RowOffsets.front() != 0 ||
    arrays.RowOffsets.back() != arrays.Entries.size())
  {
    return "the row offsets do not match the entries";
  }
  for (size_t i = 0; i < count; ++i)
  {
    if (arrays.RowOffsets[i] > arrays.RowOffsets[i + 1])
    {
      return "the row offsets decrease";
    }
  }
  if (arrays.Unoccluded.size() != arrays.Entries.size() ||
    arrays.StripDepths.size() != arrays.Strips.size() ||
    (!arrays.Measures.empty() && arrays.Measures.size() != arrays.Entries.size()))
  {
    return "the entry or strip arrays have different lengths";
  }
  for (size_t e = 0; e < arrays.Entries.size(); ++e)
  {
    const Entry& entry = arrays.Entries[e];
    const size_t next =
      e + 1 < arrays.Entries.size() ? arrays.Entries[e + 1].FirstStrip : arrays.Strips.size();
    if (entry.Source >= count || entry.FirstStrip > next || next > arrays.Strips.size())
    {
      return "entry " + std::to_string(e) + " refers to a missing source or strip";
    }
  }
  const size_t entryCount = arrays.Entries.size();
  if (arrays.Layers.empty() ? !arrays.Filters.empty() || !arrays.Transmittances.empty()
                            : arrays.Layers.size() != entryCount ||
        arrays.Filters.size() != 3 * entryCount || arrays.Transmittances.size() != 3 * count)
  {
    return "the pane arrays (layers, filters, transmittances) do not match the entries";
  }
  for (const std::vector<float>* values : { &arrays.Filters, &arrays.Transmittances })
  {
    for (const float value : *values)
    {
      if (!(value >= 0.0f && value <= 1.0f))
      {
        return "a pane's filter or transmittance is not in [0, 1]";
      }
    }
  }
  for (const float measure : arrays.Measures)
  {
    if (!(measure >= 0.0f) || !std::isfinite(measure))
    {
      return "a region's measure is negative or not finite";
    }
  }
  for (const Strip& strip : arrays.Strips)
  {
    if (strip.Row >= arrays.ThetaBins || strip.PhiBegin >= strip.PhiEnd ||
      strip.PhiEnd > arrays.PhiBins)
    {
      return "a strip lies outside the grid";
    }
  }
  return std::string();
}

std::string SphericalCover::ImportArrays(Arrays arrays)
{
  this->Clear();
  const std::string problem = CheckArrays(arrays);
  if (!problem.empty())
  {
    return problem;
  }
  SphericalCoverOptions options;
  options.ThetaBins = arrays.ThetaBins;
  options.PhiBins = arrays.PhiBins;
  options.SamplesTheta = arrays.SamplesTheta;
  options.SamplesPhi = arrays.SamplesPhi;
  options.Fill = static_cast<RBufferFill>(arrays.Fill);
  this->Adopt(std::move(arrays), options);
  return std::string();
}

void SphericalCover::Adopt(Arrays arrays, const SphericalCoverOptions& options)
{
  this->BuildOptions = options;
  this->GridPointer = std::make_unique<HemisphereGrid>(
    arrays.ThetaBins, arrays.PhiBins, arrays.SamplesTheta, arrays.SamplesPhi);
  this->RowOffsets = std::move(arrays.RowOffsets);
  this->Entries = std::move(arrays.Entries);
  this->Unoccluded = std::move(arrays.Unoccluded);
  this->UnoccludedKnown = arrays.UnoccludedKnown;
  this->Strips = std::move(arrays.Strips);
  this->StripDepths = std::move(arrays.StripDepths);
  this->Areas = std::move(arrays.Areas);
  this->Measures = std::move(arrays.Measures);
  this->Layers = std::move(arrays.Layers);
  this->Filters = std::move(arrays.Filters);
  this->Transmittances = std::move(arrays.Transmittances);
  this->BuildColumns();
}

} // namespace sphcover
