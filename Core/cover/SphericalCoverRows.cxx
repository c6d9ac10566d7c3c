// SPDX-License-Identifier: BSD-3-Clause
// The spherical cover's rows (paper §4.3 Steps 2 and 4): one R-buffer per characteristic point,
// filled (or interpolated from its neighbours', §3.4: HemisphereInterpolation.h), its regions
// extracted as strips, the layers behind panes and the lamps' measured regions added, and the
// rows appended in receiver order; and the estimate of the cover's bytes from a few rows.
#include "cover/SphericalCover.h"

#include "cover/HemisphereInterpolation.h"
#include "cover/RayCastFill.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sphcover
{

namespace
{
constexpr std::size_t DefaultBatchSize = 64;
}

/// One hemisphere's strips and entries before they join the cover.
struct SphericalCover::Row
{
  std::vector<uint32_t> Sources;
  std::vector<uint32_t> StripCounts;
  std::vector<float> Unoccluded;
  std::vector<Strip> Strips;
  std::vector<float> Depths;
  /// Per entry its region's measure, when the row has a measured region (else empty).
  std::vector<float> Measures;
  /// Per entry its layer and filter (see "Panes" in the header).
  std::vector<uint8_t> Layers;
  std::vector<glm::vec3> Filters;
  CullingStatistics Culling;
  PaneLimitDrops PaneLimit;
};

SphericalCover::SphericalCover() = default;
SphericalCover::~SphericalCover() = default;
SphericalCover::SphericalCover(SphericalCover&&) noexcept = default;
SphericalCover& SphericalCover::operator=(SphericalCover&&) noexcept = default;

void SphericalCover::Clear()
{
  this->GridPointer.reset();
  this->RowOffsets.clear();
  this->Entries.clear();
  this->Unoccluded.clear();
  this->Strips.clear();
  this->StripDepths.clear();
  this->ColumnOffsets.clear();
  this->Columns.clear();
  this->Areas.clear();
  this->Measures.clear();
  this->Layers.clear();
  this->Filters.clear();
  this->Transmittances.clear();
  this->UnoccludedKnown = false;
  this->CullingCounts = CullingStatistics();
  this->PaneLimitCounts = PaneLimitDrops();
}

void SphericalCover::ExtractRow(const RBuffer& buffer,
  Row& row,
  unsigned layer,
  const std::vector<glm::vec3>* filterOfCell)
{
  const HemisphereGrid& grid = buffer.Grid();
  struct Run
  {
    int32_t Source;
    glm::vec3 Filter;
    Strip Cells;
    float Depth;
  };
  auto filterAt = [filterOfCell](int cell)
  { return filterOfCell ? (*filterOfCell)[static_cast<size_t>(cell)] : glm::vec3(1.0f); };
  std::vector<Run> runs;
  for (int theta = 0; theta < grid.ThetaBins(); ++theta)
  {
    int column = 0;
    while (column < grid.PhiBins())
    {
      const int32_t source = buffer.CellSource(grid.CellIndex(theta, column));
      if (source == RBuffer::NoSource)
      {
        ++column;
        continue;
      }
      const glm::vec3 filter = filterAt(grid.CellIndex(theta, column));
      const int begin = column;
      double depth = 0.0;
      while (column < grid.PhiBins() &&
        buffer.CellSource(grid.CellIndex(theta, column)) == source &&
        filterAt(grid.CellIndex(theta, column)) == filter)
      {
        depth += buffer.CellDepth(grid.CellIndex(theta, column));
        ++column;
      }
      runs.push_back({ source,
        filter,
        { static_cast<uint16_t>(theta),
          static_cast<uint16_t>(begin),
          static_cast<uint16_t>(column) },
        static_cast<float>(depth / (column - begin)) });
    }
  }
  // Group by source (and filter); within an entry the strips stay in row-major order.
  std::stable_sort(runs.begin(),
    runs.end(),
    [layer](const Run& a, const Run& b)
    { return CompareEntryKeys(a.Source, layer, a.Filter, b.Source, layer, b.Filter) < 0; });
  const auto& unoccluded = buffer.UnoccludedProjectedSolidAngles();
  size_t next = 0;
  for (size_t k = 0; k < runs.size(); ++k)
  {
    if (k == 0 || runs[k].Source != runs[k - 1].Source || runs[k].Filter != runs[k - 1].Filter)
    {
      row.Sources.push_back(static_cast<uint32_t>(runs[k].Source));
      row.StripCounts.push_back(0);
      row.Layers.push_back(static_cast<uint8_t>(layer));
      row.Filters.push_back(runs[k].Filter);
      while (next < unoccluded.size() && unoccluded[next].first < runs[k].Source)
      {
        ++next;
      }
      row.Unoccluded.push_back(
        layer == 0 && next < unoccluded.size() && unoccluded[next].first == runs[k].Source
          ? unoccluded[next].second
          : 0.0f);
    }
    ++row.StripCounts.back();
    row.Strips.push_back(runs[k].Cells);
    row.Depths.push_back(runs[k].Depth);
  }
}

std::vector<glm::vec3> SphericalCover::PaneTransmittances(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  RBufferFillOptions& fill)
{
  std::vector<glm::vec3> transmittanceOfPatch;
  if (options.MaxPaneDepth > 0)
  {
    std::vector<bool>& paneSurfaces = fill.PaneSurfaces;
    paneSurfaces.assign(options.SurfaceTransmittance.size(), false);
    for (size_t s = 0; s < options.SurfaceTransmittance.size(); ++s)
    {
      const glm::vec3& t = options.SurfaceTransmittance[s];
      paneSurfaces[s] = t.x > 0.0f || t.y > 0.0f || t.z > 0.0f;
    }
    for (const Patch& patch : patches)
    {
      const size_t surface = static_cast<size_t>(patch.SurfaceIndex);
      const bool pane = surface < paneSurfaces.size() && paneSurfaces[surface];
      transmittanceOfPatch.push_back(
        pane ? options.SurfaceTransmittance[surface] : glm::vec3(0.0f));
    }
    if (std::find(paneSurfaces.begin(), paneSurfaces.end(), true) == paneSurfaces.end())
    {
      paneSurfaces.clear();
      transmittanceOfPatch.clear();
    }
    else if (options.Fill != RBufferFill::RayCasting)
    {
      throw std::invalid_argument(
        "SphericalCover: a scene with panes (transmittance) needs the ray-casting fill");
    }
  }
  return transmittanceOfPatch;
}

void SphericalCover::ExtractLayersBehindPanes(const RayCastFiller& filler,
  const std::vector<glm::vec3>& transmittanceOfPatch,
  int maxDepth,
  RBuffer& front,
  RBuffer& behind,
  Row& row)
{
  const HemisphereGrid& grid = front.Grid();
  // Per cell the product of the transmittances of the panes that won it in the layers so far.
  std::vector<glm::vec3> filter(static_cast<size_t>(grid.CellCount()), glm::vec3(1.0f));
  bool reachedLimit = true;
  for (int layer = 1; layer <= maxDepth; ++layer)
  {
    bool anyPane = false;
    for (int cell = 0; cell < grid.CellCount(); ++cell)
    {
      const int32_t source = front.CellSource(cell);
      if (source != RBuffer::NoSource && filler.IsPane(static_cast<size_t>(source)))
      {
        filter[static_cast<size_t>(cell)] *= transmittanceOfPatch[static_cast<size_t>(source)];
        anyPane = true;
      }
    }
    if (!anyPane)
    {
      reachedLimit = false;
      break;
    }
    filler.FillBehindPanes(front.Receiver(), front, layer, behind);
    ExtractRow(behind, row, static_cast<unsigned>(layer), &filter);
    std::swap(front, behind);
  }
  // The cells whose last layer is still a pane: what lies behind it is dropped, and counted.
  for (int cell = 0; reachedLimit && cell < grid.CellCount(); ++cell)
  {
    const int32_t source = front.CellSource(cell);
    if (source != RBuffer::NoSource && filler.IsPane(static_cast<size_t>(source)))
    {
      const glm::vec3 through =
        filter[static_cast<size_t>(cell)] * transmittanceOfPatch[static_cast<size_t>(source)];
      ++row.PaneLimit.Cells;
      row.PaneLimit.ProjectedSolidAngle += grid.CellMeasureOfCell(cell) *
        (static_cast<double>(through.x) + through.y + through.z) / 3.0;
    }
  }
  // The layers were appended one after the other: the row's entries are sorted by (source,
  // layer, filter), as FindEntry and the propagation's matching of transposed entries expect.
  const size_t entries = row.Sources.size();
  std::vector<size_t> firstStrip(entries + 1, 0);
  for (size_t e = 0; e < entries; ++e)
  {
    firstStrip[e + 1] = firstStrip[e] + row.StripCounts[e];
  }
  std::vector<size_t> order(entries);
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(),
    order.end(),
    [&row](size_t a, size_t b)
    {
      return CompareEntryKeys(row.Sources[a],
               row.Layers[a],
               row.Filters[a],
               row.Sources[b],
               row.Layers[b],
               row.Filters[b]) < 0;
    });
  Row sorted;
  sorted.Culling = row.Culling;
  sorted.PaneLimit = row.PaneLimit;
  for (const size_t e : order)
  {
    sorted.Sources.push_back(row.Sources[e]);
    sorted.StripCounts.push_back(row.StripCounts[e]);
    sorted.Unoccluded.push_back(row.Unoccluded[e]);
    sorted.Layers.push_back(row.Layers[e]);
    sorted.Filters.push_back(row.Filters[e]);
    sorted.Strips.insert(sorted.Strips.end(),
      row.Strips.begin() + static_cast<std::ptrdiff_t>(firstStrip[e]),
      row.Strips.begin() + static_cast<std::ptrdiff_t>(firstStrip[e + 1]));
    sorted.Depths.insert(sorted.Depths.end(),
      row.Depths.begin() + static_cast<std::ptrdiff_t>(firstStrip[e]),
      row.Depths.begin() + static_cast<std::ptrdiff_t>(firstStrip[e + 1]));
  }
  row = std::move(sorted);
}

void SphericalCover::MeasureRow(std::size_t receiver,
  const RayCastFiller& filler,
  const std::vector<Patch>& patches,
  const std::vector<std::vector<uint32_t>>& piecesOfSurface,
  Row& row) const
{
  const std::vector<bool>& measured = this->BuildOptions.MeasuredSurfaces;
  const HemisphereGrid& grid = *this->GridPointer;
  const size_t entries = row.Sources.size();
  std::vector<double> cells(entries, 0.0);
  std::vector<char> isMeasured(entries, 0);
  const Strip* strips = row.Strips.data();
  bool any = false;
  for (size_t e = 0; e < entries; ++e)
  {
    cells[e] = MeasureOfStrips(grid, strips, strips + row.StripCounts[e]);
    strips += row.StripCounts[e];
    const size_t surface = static_cast<size_t>(patches[row.Sources[e]].SurfaceIndex);
    // Regions seen through panes keep their cells (the lamp's visible part is layer 0's).
    isMeasured[e] = row.Layers[e] == 0 && surface < measured.size() && measured[surface];
    any = any || isMeasured[e];
  }
  if (!any)
  {
    return;
  }
  // Measured regions on their sources. A source of a measured surface that won no cell of
  // the row (a lamp in pieces each about a cell wide) is measured too, and its measure goes to
  // the surface's regions that are in the row, in proportion to their own measures: the row
  // sees the whole lamp, not only the pieces the vote kept. The other regions share what is
  // left of the row's covered measure, so that the row keeps it.
  double covered = 0.0;
  double measuredCells = 0.0;
  double measuredExact = 0.0;
  std::vector<double> measure(entries, 0.0);
  std::vector<int> surfaces;
  for (size_t e = 0; e < entries; ++e)
  {
    if (row.Layers[e] != 0)
    {
      continue;
    }
    covered += cells[e];
    if (isMeasured[e])
    {
      measuredCells += cells[e];
      surfaces.push_back(patches[row.Sources[e]].SurfaceIndex);
    }
  }
  std::sort(surfaces.begin(), surfaces.end());
  surfaces.erase(std::unique(surfaces.begin(), surfaces.end()), surfaces.end());
  std::vector<double> pieceMeasures;
  for (const int surface : surfaces)
  {
    // The surface's pieces together get at least 8 x 8 nodes, each at least 2 x 2.
    const std::vector<uint32_t>& pieces = piecesOfSurface[static_cast<size_t>(surface)];
    const int side =
      std::max(2, static_cast<int>(std::ceil(8.0 / std::sqrt(static_cast<double>(pieces.size())))));
    pieceMeasures.assign(pieces.size(), 0.0);
    double whole = 0.0;
    for (size_t k = 0; k < pieces.size(); ++k)
    {
      pieceMeasures[k] = filler.VisibleProjectedSolidAngle(receiver, pieces[k], side);
      whole += pieceMeasures[k];
    }
    double inRow = 0.0;
    double cellsInRow = 0.0;
    for (size_t e = 0; e < entries; ++e)
    {
      if (isMeasured[e] && patches[row.Sources[e]].SurfaceIndex == surface)
      {
        const size_t k = static_cast<size_t>(
          std::lower_bound(pieces.begin(), pieces.end(), row.Sources[e]) - pieces.begin());
        measure[e] = pieceMeasures[k];
        inRow += measure[e];
        cellsInRow += cells[e];
      }
    }
    for (size_t e = 0; e < entries; ++e)
    {
      if (isMeasured[e] && patches[row.Sources[e]].SurfaceIndex == surface)
      {
        measure[e] = inRow > 0.0 ? whole * measure[e] / inRow : whole * cells[e] / cellsInRow;
      }
    }
    measuredExact += whole;
  }
  const double others = covered - measuredCells;
  double measuredScale = 1.0;
  double othersScale = 1.0;
  if (others > 0.0 && covered - measuredExact >= 0.0)
  {
    othersScale = (covered - measuredExact) / others;
  }
  else
  {
    // Nothing else to take the difference (every region measured) or the measured regions
    // exceed the row's covered measure: they are scaled to it.
    othersScale = 0.0;
    measuredScale = measuredExact > 0.0 ? covered / measuredExact : 0.0;
    if (others > 0.0 && measuredExact <= 0.0)
    {
      othersScale = covered / others;
    }
  }
  // What lies behind a pane counts as the pane's region does.
  const double behindScale = others > 0.0 ? othersScale : 1.0;
  row.Measures.resize(entries);
  for (size_t e = 0; e < entries; ++e)
  {
    row.Measures[e] = static_cast<float>(isMeasured[e] ? measure[e] * measuredScale
        : row.Layers[e] != 0                           ? cells[e] * behindScale
                                                       : cells[e] * othersScale);
  }
}

void SphericalCover::AppendRow(Row& row)
{
  if (this->Strips.size() + row.Strips.size() > std::numeric_limits<uint32_t>::max())
  {
    throw std::length_error("SphericalCover: more than 2^32 - 1 strips");
  }
  // The strips of entry e are the next StripCounts[e] strips of the row.
  size_t stripIndex = this->Strips.size();
  for (size_t e = 0; e < row.Sources.size(); ++e)
  {
    this->Entries.push_back({ row.Sources[e], static_cast<uint32_t>(stripIndex) });
    this->Unoccluded.push_back(row.Unoccluded[e]);
    stripIndex += row.StripCounts[e];
    if (!this->Transmittances.empty())
    {
      this->Layers.push_back(row.Layers[e]);
      for (int b = 0; b < 3; ++b)
      {
        this->Filters.push_back(row.Filters[e][b]);
      }
    }
  }
  this->Strips.insert(this->Strips.end(), row.Strips.begin(), row.Strips.end());
  this->StripDepths.insert(this->StripDepths.end(), row.Depths.begin(), row.Depths.end());
  const size_t firstEntry = this->Entries.size() - row.Sources.size();
  // Measures exist once some row is measured: also when that is the very first row (whose
  // measures an emptiness test of Measures alone would drop).
  const bool measured = !this->Measures.empty() || !row.Measures.empty();
  if (!row.Measures.empty() && this->Measures.size() < firstEntry)
  {
    // The first measured row: the entries before it keep their cells' measures.
    this->Measures.reserve(this->Entries.capacity());
    for (size_t e = 0; e < firstEntry; ++e)
    {
      this->Measures.push_back(static_cast<float>(this->CellsMeasure(e)));
    }
  }
  if (measured)
  {
    for (size_t e = 0; e < row.Sources.size(); ++e)
    {
      this->Measures.push_back(row.Measures.empty()
          ? static_cast<float>(this->CellsMeasure(firstEntry + e))
          : row.Measures[e]);
    }
  }
  this->RowOffsets.push_back(this->Entries.size());
  this->CullingCounts += row.Culling;
  this->PaneLimitCounts += row.PaneLimit;
}

namespace
{
/// Paints the cells of strips [first, last) of source `source` with it and their strips' R.
void PaintStrips(const HemisphereGrid& grid,
  uint32_t source,
  const SphericalCover::Strip* first,
  const SphericalCover::Strip* last,
  const float* depths,
  int32_t* cellSources,
  float* cellDepths)
{
  for (const SphericalCover::Strip* strip = first; strip != last; ++strip, ++depths)
  {
    for (int column = strip->PhiBegin; column < strip->PhiEnd; ++column)
    {
      const size_t cell = static_cast<size_t>(grid.CellIndex(strip->Row, column));
      cellSources[cell] = static_cast<int32_t>(source);
      cellDepths[cell] = *depths;
    }
  }
}
}

void SphericalCover::PaintRowCells(const HemisphereGrid& grid,
  const Row& row,
  int32_t* cellSources,
  float* cellDepths)
{
  size_t strip = 0;
  for (size_t e = 0; e < row.Sources.size(); ++e)
  {
    const size_t end = strip + row.StripCounts[e];
    if (row.Layers[e] == 0)
    {
      PaintStrips(grid,
        row.Sources[e],
        row.Strips.data() + strip,
        row.Strips.data() + end,
        row.Depths.data() + strip,
        cellSources,
        cellDepths);
    }
    strip = end;
  }
}

void SphericalCover::PaintCoverRowCells(std::size_t row,
  int32_t* cellSources,
  float* cellDepths) const
{
  for (size_t e = this->EntryBegin(row); e < this->EntryEnd(row); ++e)
  {
    if (this->Layer(e) == 0)
    {
      PaintStrips(*this->GridPointer,
        this->Entries[e].Source,
        this->Strips.data() + this->StripBegin(e),
        this->Strips.data() + this->StripEnd(e),
        this->StripDepths.data() + this->StripBegin(e),
        cellSources,
        cellDepths);
    }
  }
}

bool SphericalCover::BuildRows(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  const std::vector<std::size_t>& receivers,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  std::shared_ptr<const RayCaster> rays)
{
  this->Clear();
  if (patches.size() >= std::numeric_limits<uint32_t>::max())
  {
    throw std::invalid_argument("SphericalCover: more than 2^32 - 2 patches");
  }
  this->BuildOptions = options;
  // Panes (see the file comment): the fill lets the rays through their back sides, the cover
  // keeps each patch's transmittance and the layers behind them.
  const std::vector<glm::vec3> transmittanceOfPatch =
    PaneTransmittances(patches, options, this->BuildOptions.FillOptions);
  for (const glm::vec3& t : transmittanceOfPatch)
  {
    this->Transmittances.insert(this->Transmittances.end(), { t.x, t.y, t.z });
  }
  this->GridPointer = std::make_unique<HemisphereGrid>(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  const HemisphereGrid& grid = *this->GridPointer;
  const std::unique_ptr<RBufferFiller> filler = RBufferFiller::Create(
    options.Fill, patches, grid, this->BuildOptions.FillOptions, std::move(rays));
  const RayCastFiller* paneFiller =
    transmittanceOfPatch.empty() ? nullptr : dynamic_cast<const RayCastFiller*>(filler.get());
  const ParallelFor& run = parallelFor ? parallelFor : ParallelFor(SequentialFor);
  // Regions measured on their sources (see the file comment): the ray fill's rays only.
  const RayCastFiller* rayFiller = nullptr;
  if (std::find(options.MeasuredSurfaces.begin(), options.MeasuredSurfaces.end(), true) !=
    options.MeasuredSurfaces.end())
  {
    rayFiller = dynamic_cast<const RayCastFiller*>(filler.get());
  }
  // Per measured surface its patches, ascending.
  std::vector<std::vector<uint32_t>> measuredPieces(options.MeasuredSurfaces.size());
  for (size_t j = 0; rayFiller && j < patches.size(); ++j)
  {
    const size_t surface = static_cast<size_t>(patches[j].SurfaceIndex);
    if (surface < options.MeasuredSurfaces.size() && options.MeasuredSurfaces[surface])
    {
      measuredPieces[surface].push_back(static_cast<uint32_t>(j));
    }
  }

  const size_t count = receivers.size();
  this->RowOffsets.reserve(count + 1);
  this->RowOffsets.push_back(0);
  this->Areas.resize(count);
  for (size_t i = 0; i < count; ++i)
  {
    this->Areas[i] = patches[receivers[i]].Area;
  }
  // Interpolated hemispheres (HemisphereInterpolation.h, ray fill with adaptive sampling): the
  // donors' rows are computed first, then every row in receiver order, the interpolated ones
  // from their donors. A donor outside `receivers` (another rank's row) is computed here too,
  // so a share's rows are the whole cover's bit for bit.
  const RayCastFiller* caster = dynamic_cast<const RayCastFiller*>(filler.get());
  const HemisphereInterpolationPlan plan = caster && options.FillOptions.AdaptiveSampling
    ? HemisphereInterpolationPlan(patches, options.Interpolation)
    : HemisphereInterpolationPlan();
  auto interpolated = [&plan](size_t patch)
  { return plan.PointCount() > 0 && plan.IsInterpolated(patch); };
  std::vector<size_t> donorsFirst;
  if (plan.InterpolatedCount() > 0)
  {
    std::vector<char> needed(patches.size(), 0);
    for (const size_t receiver : receivers)
    {
      for (const uint32_t* d = plan.DonorsBegin(receiver); d != plan.DonorsEnd(receiver); ++d)
      {
        needed[*d] = 1;
      }
    }
    for (size_t p = 0; p < patches.size(); ++p)
    {
      if (needed[p])
      {
        donorsFirst.push_back(p);
      }
    }
  }
  // Rows computed ahead and not yet appended, by patch; once appended a donor's cells are read
  // from the cover (rowOfPatch).
  std::vector<std::unique_ptr<Row>> ahead(donorsFirst.empty() ? 0 : patches.size());
  std::vector<std::ptrdiff_t> rowOfPatch(donorsFirst.empty() ? 0 : patches.size(), -1);
  const bool sampleBoundaries = options.Interpolation.SampleBoundaryCells;
  auto buildRow = [&](size_t receiver, Row& row, RBuffer& buffer, RBuffer* behind)
  {
    if (interpolated(receiver))
    {
      thread_local std::vector<int32_t> donorSources;
      thread_local std::vector<float> donorDepths;
      const size_t cells = static_cast<size_t>(grid.CellCount());
      const size_t donorCount =
        static_cast<size_t>(plan.DonorsEnd(receiver) - plan.DonorsBegin(receiver));
      donorSources.assign(cells * donorCount, RBuffer::NoSource);
      donorDepths.assign(cells * donorCount, 0.0f);
      std::vector<RayCastFiller::Donor> donors;
      for (size_t k = 0; k < donorCount; ++k)
      {
        const size_t donor = plan.DonorsBegin(receiver)[k];
        int32_t* sources = donorSources.data() + k * cells;
        float* depths = donorDepths.data() + k * cells;
        if (ahead[donor])
        {
          PaintRowCells(grid, *ahead[donor], sources, depths);
        }
        else
        {
          this->PaintCoverRowCells(static_cast<size_t>(rowOfPatch[donor]), sources, depths);
        }
        donors.push_back({ donor, sources, depths });
      }
      auto donorOf = [&](uint32_t patch)
      {
        return *std::find_if(donors.begin(),
          donors.end(),
          [patch](const RayCastFiller::Donor& d) { return d.Patch == patch; });
      };
      std::vector<RayCastFiller::DonorPair> pairs;
      for (int axis = 0; axis < 2; ++axis)
      {
        const uint32_t a = plan.PairDonor(receiver, axis, 0);
        const uint32_t b = plan.PairDonor(receiver, axis, 1);
        if (a != HemisphereInterpolationPlan::None && b != HemisphereInterpolationPlan::None)
        {
          const double toA = glm::length(patches[receiver].Point - patches[a].Point);
          const double toB = glm::length(patches[receiver].Point - patches[b].Point);
          pairs.push_back({ donorOf(a), donorOf(b), toA / (toA + toB) });
        }
      }
      caster->FillFromDonors(
        receiver, pairs, options.Interpolation.MaxDifference, sampleBoundaries, buffer);
    }
    else
    {
      filler->Fill(receiver, buffer, &row.Culling);
    }
    ExtractRow(buffer, row);
    if (paneFiller)
    {
      ExtractLayersBehindPanes(
        *paneFiller, transmittanceOfPatch, options.MaxPaneDepth, buffer, *behind, row);
    }
    if (rayFiller)
    {
      this->MeasureRow(receiver, *rayFiller, patches, measuredPieces, row);
    }
  };
  for (const size_t donor : donorsFirst)
  {
    ahead[donor] = std::make_unique<Row>();
  }
  auto isAhead = [&ahead](size_t patch) { return !ahead.empty() && ahead[patch] != nullptr; };
  // Progress counts a computed row as one and an interpolated one as a quarter (about what it
  // costs, Documentation/notes/interpolated-hemispheres.md).
  auto work = [&](size_t receiver) { return interpolated(receiver) ? 0.25 : 1.0; };
  double totalWork = static_cast<double>(donorsFirst.size());
  for (const size_t receiver : receivers)
  {
    totalWork += isAhead(receiver) ? 0.0 : work(receiver);
  }
  double doneWork = 0.0;
  const size_t batchSize = options.BatchSize > 0 ? options.BatchSize : DefaultBatchSize;
  // Pass 1: the donors' rows.
  for (size_t batchBegin = 0; batchBegin < donorsFirst.size(); batchBegin += batchSize)
  {
    const size_t batchCount = std::min(batchSize, donorsFirst.size() - batchBegin);
    run(batchCount,
      [&](size_t begin, size_t end)
      {
        RBuffer buffer(grid);
        const std::unique_ptr<RBuffer> behind =
          paneFiller ? std::make_unique<RBuffer>(grid) : nullptr;
        for (size_t k = begin; k < end; ++k)
        {
          const size_t receiver = donorsFirst[batchBegin + k];
          buildRow(receiver, *ahead[receiver], buffer, behind.get());
        }
      });
    doneWork += static_cast<double>(batchCount);
    if (progress && !progress(doneWork / totalWork))
    {
      this->Clear();
      return false;
    }
  }
  // Pass 2: every row in receiver order.
  std::vector<Row> rows;
  for (size_t batchBegin = 0; batchBegin < count; batchBegin += batchSize)
  {
    const size_t batchCount = std::min(batchSize, count - batchBegin);
    rows.assign(batchCount, Row());
    run(batchCount,
      [&](size_t begin, size_t end)
      {
        RBuffer buffer(grid);
        const std::unique_ptr<RBuffer> behind =
          paneFiller ? std::make_unique<RBuffer>(grid) : nullptr;
        for (size_t k = begin; k < end; ++k)
        {
          const size_t receiver = receivers[batchBegin + k];
          if (!isAhead(receiver))
          {
            buildRow(receiver, rows[k], buffer, behind.get());
          }
        }
      });
    for (size_t k = 0; k < batchCount; ++k)
    {
      const size_t receiver = receivers[batchBegin + k];
      if (isAhead(receiver))
      {
        this->AppendRow(*ahead[receiver]);
        ahead[receiver].reset();
      }
      else
      {
        this->AppendRow(rows[k]);
        doneWork += work(receiver);
      }
      if (!rowOfPatch.empty())
      {
        rowOfPatch[receiver] = static_cast<std::ptrdiff_t>(batchBegin + k);
      }
    }
    if (progress && !progress(doneWork / totalWork))
    {
      this->Clear();
      return false;
    }
  }
  this->UnoccludedKnown = filler->Kind() == RBufferFill::Projection;
  return true;
}

std::size_t SphericalCover::EstimateBytes(const std::vector<Patch>& patches,
  const SphericalCoverOptions& options,
  std::size_t sampleReceivers,
  std::shared_ptr<const RayCaster> rays)
{
  const std::size_t count = patches.size();
  if (count == 0)
  {
    return 0;
  }
  const std::size_t samples = std::max<std::size_t>(1, std::min(sampleReceivers, count));
  const HemisphereGrid grid(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  // The rows as Build makes them: through panes, with their layers behind them.
  RBufferFillOptions fill = options.FillOptions;
  const std::vector<glm::vec3> transmittanceOfPatch = PaneTransmittances(patches, options, fill);
  const std::unique_ptr<RBufferFiller> filler =
    RBufferFiller::Create(options.Fill, patches, grid, fill, std::move(rays));
  const RayCastFiller* paneFiller =
    transmittanceOfPatch.empty() ? nullptr : dynamic_cast<const RayCastFiller*>(filler.get());
  RBuffer buffer(grid);
  const std::unique_ptr<RBuffer> behind = paneFiller ? std::make_unique<RBuffer>(grid) : nullptr;
  std::size_t strips = 0;
  std::size_t entries = 0;
  for (std::size_t k = 0; k < samples; ++k)
  {
    // Evenly spread receivers: k (n - 1) / (samples - 1), or the middle one for one sample.
    const std::size_t receiver = samples == 1 ? count / 2 : k * (count - 1) / (samples - 1);
    filler->Fill(receiver, buffer, nullptr);
    Row row;
    ExtractRow(buffer, row);
    if (paneFiller)
    {
      ExtractLayersBehindPanes(
        *paneFiller, transmittanceOfPatch, options.MaxPaneDepth, buffer, *behind, row);
    }
    strips += row.Strips.size();
    entries += row.Sources.size();
  }
  // Per entry its layer and filter with panes (and per patch the transmittance); a measure per
  // entry once some surface is measured (the ray fill's, see "Measured regions").
  const bool measured = options.Fill == RBufferFill::RayCasting &&
    std::find(options.MeasuredSurfaces.begin(), options.MeasuredSurfaces.end(), true) !=
      options.MeasuredSurfaces.end();
  const std::size_t bytesPerEntry = BytesPerEntry + (measured ? sizeof(float) : 0) +
    (paneFiller ? sizeof(uint8_t) + 3 * sizeof(float) : 0);
  const std::size_t bytesPerPatch = BytesPerPatch + (paneFiller ? 3 * sizeof(float) : 0);
  const double scale = static_cast<double>(count) / samples;
  return static_cast<std::size_t>(
           std::ceil(scale * (strips * BytesPerStrip + entries * bytesPerEntry))) +
    count * bytesPerPatch + 2 * sizeof(uint64_t);
}

} // namespace sphcover
