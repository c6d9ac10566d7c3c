// SPDX-License-Identifier: BSD-3-Clause
// LightPropagation's non-diffuse shots (paper §3.5 "general reflectance", §5.1, §5.2; the class
// is declared in LightPropagation.h, the derivation is in Documentation/notes/propagation.md):
// the set-up of the weight tables and transposed entries, the unshot incident radiance
// collected per shot, the two ways of summing the weight table (strip pairs, the
// whole-hemisphere grid), the receivers served without a region h_ji, and the receivers'
// views of the non-diffuse patches (LightPropagation.h, "Receivers' views").
#include "propagation/LightPropagation.h"

#include "cover/SphericalCover.h"
#include "math/Constants.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphcover
{

namespace
{

/// A hint to the processor to fetch `address` into the cache (a gather's later reads).
inline void Prefetch(const void* address)
{
#if defined(__GNUC__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

/// HemisphereGrid::CellOfLocalDirection for unit directions, cheaper: the row from cos theta
/// against the rows' edges (a binary search instead of an arc tangent), -1 for z <= 0.
class UnitCellLookup
{
public:
  explicit UnitCellLookup(const HemisphereGrid& grid)
    : Columns(grid.PhiBins())
    , PhiStep(grid.PhiStep())
  {
    // cos of the lower edges of rows 1 .. ThetaBins - 1, decreasing.
    for (int row = 1; row < grid.ThetaBins(); ++row)
    {
      this->EdgeCos.push_back(std::cos(grid.RowTheta(row)));
    }
  }
  int CellOf(const glm::dvec3& unit) const
  {
    if (!(unit.z > 0.0))
    {
      return -1;
    }
    // theta >= the edge of row r iff z <= cos(edge): the row is the count of such edges.
    const int row = static_cast<int>(
      std::upper_bound(this->EdgeCos.begin(), this->EdgeCos.end(), unit.z, std::greater<double>()) -
      this->EdgeCos.begin());
    double phi = std::atan2(unit.y, unit.x);
    if (phi < 0.0)
    {
      phi += TwoPi;
    }
    const int column = std::min(static_cast<int>(phi / this->PhiStep), this->Columns - 1);
    return row * this->Columns + column;
  }

private:
  std::vector<double> EdgeCos;
  int Columns;
  double PhiStep;
};

} // namespace

void LightPropagation::SetUpModels(const std::vector<Material>& materialOfPatch)
{
  this->Reflectances = PointReflectances(this->Cover.Grid(), materialOfPatch);
  for (std::size_t i = 0; i < materialOfPatch.size(); ++i)
  {
    this->ModelOfPatch[i] = this->Reflectances.ModelOf(i);
  }
  if (this->Reflectances.Empty())
  {
    return;
  }
  this->MatchTransposedEntries();
  this->ComputeAlbedoMeasures();
  this->Reset();
}

void LightPropagation::MatchTransposedEntries(const std::vector<std::vector<EntryKey>>& remoteRows)
{
  const SphericalCover& cover = this->Cover;
  // Row j is sorted by (source, layer, filter), column j by receiver and then in the order of
  // the receiver's row, so one merge of the two finds, for every receiver i of column j, the
  // entry (j, i) of row j seen through the same panes (SphericalCover.h, "Panes").
  auto keyOf = [&cover](std::size_t entry) -> EntryKey {
    return { cover.EntryAt(entry).Source, cover.Layer(entry), glm::vec3(cover.Filter(entry)) };
  };
  auto compare = [](const EntryKey& a, const EntryKey& b)
  { return CompareEntryKeys(a.Source, a.Layer, a.Filter, b.Source, b.Layer, b.Filter); };
  this->ColumnBack.assign(cover.EntryCount(), NoEntry);
  std::vector<EntryKey> local;
  for (std::size_t j = 0; j < this->PatchCount(); ++j)
  {
    const bool remote = j < remoteRows.size() && !remoteRows[j].empty();
    if (!remote)
    {
      local.clear();
      for (std::size_t e = cover.EntryBegin(j); e < cover.EntryEnd(j); ++e)
      {
        local.push_back(keyOf(e));
      }
    }
    const std::vector<EntryKey>& row = remote ? remoteRows[j] : local;
    std::size_t e = 0;
    std::size_t k = cover.ColumnBegin(j);
    while (e < row.size() && k < cover.ColumnEnd(j))
    {
      const SphericalCover::ColumnEntry& item = cover.ColumnAt(k);
      EntryKey back = keyOf(item.EntryIndex);
      back.Source = item.Receiver;
      const int order = compare(row[e], back);
      if (order < 0)
      {
        ++e;
      }
      else if (order > 0)
      {
        ++k;
      }
      else
      {
        this->ColumnBack[k++] = static_cast<uint32_t>(e++);
      }
    }
  }
}

void LightPropagation::ComputeAlbedoMeasures()
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  this->ColumnAlbedoMeasure.assign(cover.EntryCount(), glm::dvec3(0.0));
  for (std::size_t i = 0; i < this->PatchCount(); ++i)
  {
    if (this->ModelOfPatch[i] < 0)
    {
      continue;
    }
    const ReflectanceWeights& table = *this->Reflectances.Table(i);
    for (std::size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
    {
      glm::dvec3 measure(0.0);
      for (std::size_t k = cover.StripBegin(e); k < cover.StripEnd(e); ++k)
      {
        const SphericalCover::Strip& strip = cover.StripAt(k);
        measure += static_cast<double>(strip.PhiEnd - strip.PhiBegin) *
          grid.CellMeasure(strip.Row) * table.RowAlbedo(strip.Row);
      }
      this->ColumnAlbedoMeasure[this->EntryPosition[e]] = measure;
    }
  }
}

void LightPropagation::DirectionalShot(std::size_t shooter, DirectionalShotData& shot)
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const ReflectanceWeights& table = *this->Reflectances.Table(shooter);
  this->TakeUnshotInStrips(shooter, shot);
  const std::size_t pairs = this->CoupleInRows(shooter, table, shot);
  // A shooter whose receivers read their views needs the exitant radiance toward every cell
  // they see it from: the grid gives them all at once, so Automatic takes it. The choice must
  // not depend on which receivers this rank holds (the ranks' views differ), or a shared
  // propagation would sum in another order than the serial one.
  const bool views = !this->ViewColumn.empty() && this->ViewColumn[shooter] != NoView;
  shot.Grid = this->Method == DirectionalMethod::Grid ||
    (this->Method == DirectionalMethod::Automatic &&
      (views ||
        static_cast<double>(pairs) > GridCostInPairs * static_cast<double>(grid.CellCount())));
  shot.ByCell = shot.Grid;
  shot.Out.assign(cover.EntryEnd(shooter) - cover.EntryBegin(shooter), glm::dvec3(0.0));
  if (shot.Grid)
  {
    this->ShotByGrid(shooter, table, shot);
  }
  else
  {
    this->ShotByStripPairs(shooter, table, pairs, shot);
  }
  if (views)
  {
    this->FillViewCells(shooter, shot);
  }
}

void LightPropagation::TakeUnshotInStrips(std::size_t shooter, DirectionalShotData& shot)
{
  const SphericalCover& cover = this->Cover;
  const std::size_t rowBegin = cover.EntryBegin(shooter);
  const std::size_t rowEnd = cover.EntryEnd(shooter);
  std::vector<std::vector<InStrip>>& in = shot.In;
  in.resize(static_cast<std::size_t>(cover.Grid().ThetaBins()));
  for (std::vector<InStrip>& strips : in)
  {
    strips.clear();
  }
  for (std::size_t e = rowBegin; e < rowEnd; ++e)
  {
    // The row's entries lie all over the column-ordered state: ask for the ones ahead early.
    constexpr std::size_t Ahead = 16;
    if (e + Ahead < rowEnd)
    {
      Prefetch(&this->UnshotIncident[this->EntryPosition[e + Ahead]]);
    }
    glm::dvec3& unshot = this->UnshotIncident[this->EntryPosition[e]];
    const glm::dvec3 radiance = unshot;
    if (radiance == glm::dvec3(0.0))
    {
      continue;
    }
    unshot = glm::dvec3(0.0);
    for (std::size_t k = cover.StripBegin(e); k < cover.StripEnd(e); ++k)
    {
      const SphericalCover::Strip& strip = cover.StripAt(k);
      in[strip.Row].push_back({ strip.PhiBegin, strip.PhiEnd, radiance });
    }
  }
  this->DirectionalUnshot[shooter] = 0.0;
}

std::size_t LightPropagation::CoupleInRows(std::size_t shooter,
  const ReflectanceWeights& table,
  DirectionalShotData& shot)
{
  const SphericalCover& cover = this->Cover;
  const int rows = cover.Grid().ThetaBins();
  const std::size_t rowCount = static_cast<std::size_t>(rows);
  const std::vector<std::vector<InStrip>>& in = shot.In;
  std::vector<std::vector<int>>& coupled = shot.Coupled;
  coupled.resize(rowCount);
  for (std::vector<int>& rowsIn : coupled)
  {
    rowsIn.clear();
  }
  std::vector<std::size_t> coupledStrips(rowCount, 0);
  for (int rowOut = 0; rowOut < rows; ++rowOut)
  {
    for (int rowIn = 0; rowIn < rows; ++rowIn)
    {
      if (!in[static_cast<std::size_t>(rowIn)].empty() && table.RowsCoupled(rowOut, rowIn))
      {
        coupled[static_cast<std::size_t>(rowOut)].push_back(rowIn);
        coupledStrips[static_cast<std::size_t>(rowOut)] +=
          in[static_cast<std::size_t>(rowIn)].size();
      }
    }
  }
  // The strip pairs of the strip-pair sum: its cost, against the grid's (file comment).
  const std::size_t rowBegin = cover.EntryBegin(shooter);
  const std::size_t rowEnd = cover.EntryEnd(shooter);
  std::size_t pairs = 0;
  if (rowEnd > rowBegin)
  {
    for (std::size_t k = cover.StripBegin(rowBegin); k < cover.StripEnd(rowEnd - 1); ++k)
    {
      pairs += coupledStrips[cover.StripAt(k).Row];
    }
  }
  return pairs;
}

void LightPropagation::ShotByStripPairs(std::size_t shooter,
  const ReflectanceWeights& table,
  std::size_t pairs,
  DirectionalShotData& shot)
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const std::size_t rowBegin = cover.EntryBegin(shooter);
  const std::size_t rowEnd = cover.EntryEnd(shooter);
  const std::vector<std::vector<InStrip>>& in = shot.In;
  const std::vector<std::vector<int>>& coupled = shot.Coupled;
  // Mean over the whole hemisphere: every out row in full, sum_o Omega_o I(o) / sum_o Omega_o.
  glm::dvec3 meanFlux(0.0);
  for (int rowOut = 0; rowOut < grid.ThetaBins(); ++rowOut)
  {
    glm::dvec3 rowFlux(0.0);
    for (int rowIn : coupled[static_cast<std::size_t>(rowOut)])
    {
      const glm::dvec3 weight = table.RowWeight(rowOut, rowIn);
      for (const InStrip& strip : in[static_cast<std::size_t>(rowIn)])
      {
        rowFlux += static_cast<double>(strip.End - strip.Begin) * weight * strip.Radiance;
      }
    }
    meanFlux += grid.CellMeasure(rowOut) * rowFlux;
  }

  // The exitant radiance averaged over every region h_ji of the shooter's row.
  for (std::size_t e = rowBegin; e < rowEnd; ++e)
  {
    glm::dvec3 flux(0.0);
    for (std::size_t k = cover.StripBegin(e); k < cover.StripEnd(e); ++k)
    {
      const SphericalCover::Strip& out = cover.StripAt(k);
      glm::dvec3 stripFlux(0.0);
      for (int rowIn : coupled[out.Row])
      {
        for (const InStrip& strip : in[static_cast<std::size_t>(rowIn)])
        {
          stripFlux += table.StripPairWeight(
                         out.Row, out.PhiBegin, out.PhiEnd, rowIn, strip.Begin, strip.End) *
            strip.Radiance;
        }
      }
      flux += grid.CellMeasure(out.Row) * stripFlux;
    }
    if (this->EntryOmega[e] > 0.0)
    {
      shot.Out[e - rowBegin] = flux / this->EntryOmega[e];
    }
  }
  shot.WeightEvaluations = pairs;
  shot.Mean = meanFlux / grid.TotalMeasure();
}

void LightPropagation::ShotByGrid(std::size_t shooter,
  const ReflectanceWeights& table,
  DirectionalShotData& shot)
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const std::size_t rows = static_cast<std::size_t>(grid.ThetaBins());
  const std::size_t columns = static_cast<std::size_t>(grid.PhiBins());
  // The unshot incident radiance per cell (each cell of the row belongs to one entry).
  this->GridIn.assign(rows * columns, glm::dvec3(0.0));
  for (std::size_t row = 0; row < rows; ++row)
  {
    for (const InStrip& strip : shot.In[row])
    {
      for (int c = strip.Begin; c < strip.End; ++c)
      {
        this->GridIn[row * columns + static_cast<std::size_t>(c)] += strip.Radiance;
      }
    }
  }
  // I(o) toward every cell, then per out row the prefix sums of I over the columns, so that
  // a strip of out cells costs O(1).
  table.Reflect(this->GridIn, shot.GridOut, this->ReflectScratch);
  this->GridPrefix.resize(rows * (columns + 1));
  glm::dvec3 meanFlux(0.0);
  for (std::size_t row = 0; row < rows; ++row)
  {
    glm::dvec3* prefix = this->GridPrefix.data() + row * (columns + 1);
    prefix[0] = glm::dvec3(0.0);
    for (std::size_t c = 0; c < columns; ++c)
    {
      prefix[c + 1] = prefix[c] + shot.GridOut[row * columns + c];
    }
    meanFlux += grid.CellMeasure(static_cast<int>(row)) * prefix[columns];
  }
  const std::size_t rowBegin = cover.EntryBegin(shooter);
  const std::size_t rowEnd = cover.EntryEnd(shooter);
  for (std::size_t e = rowBegin; e < rowEnd; ++e)
  {
    glm::dvec3 flux(0.0);
    for (std::size_t k = cover.StripBegin(e); k < cover.StripEnd(e); ++k)
    {
      const SphericalCover::Strip& out = cover.StripAt(k);
      const glm::dvec3* prefix = this->GridPrefix.data() + out.Row * (columns + 1);
      flux += grid.CellMeasure(out.Row) * (prefix[out.PhiEnd] - prefix[out.PhiBegin]);
    }
    if (this->EntryOmega[e] > 0.0)
    {
      shot.Out[e - rowBegin] = flux / this->EntryOmega[e];
    }
  }
  shot.WeightEvaluations = 0;
  shot.Mean = meanFlux / grid.TotalMeasure();
}

void LightPropagation::SetFrames(std::vector<HemisphereFrame> frames)
{
  if (!frames.empty() && frames.size() != this->PatchCount())
  {
    throw std::invalid_argument("LightPropagation: " + std::to_string(frames.size()) +
      " frames for " + std::to_string(this->PatchCount()) + " patches");
  }
  this->Frames = std::move(frames);
  this->EncodeFallbacks();
  this->BuildReceiverViews();
  if (this->Hook)
  {
    this->Hook->FallbacksChanged();
  }
}

void LightPropagation::EncodeFallbacks()
{
  // The receivers without h_ji are fixed by the cover, and so is the cell of the direction
  // P_i - P_j in the shooter's hemisphere: found once here rather than in every shot.
  const SphericalCover& cover = this->Cover;
  if (this->ColumnBack.empty())
  {
    return;
  }
  for (std::size_t j = 0; j < this->PatchCount(); ++j)
  {
    for (std::size_t k = cover.ColumnBegin(j); k < cover.ColumnEnd(j); ++k)
    {
      uint32_t& code = this->ColumnBack[k];
      if (code < FallbackFlag)
      {
        continue;
      }
      code = NoEntry;
      if (this->Frames.empty())
      {
        continue;
      }
      const HemisphereFrame& from = this->Frames[j];
      const int cell = cover.Grid().CellOfLocalDirection(
        from.ToLocal(this->Frames[cover.ColumnAt(k).Receiver].Origin - from.Origin));
      if (cell >= 0)
      {
        code = FallbackFlag | static_cast<uint32_t>(cell);
      }
    }
  }
}

bool LightPropagation::ServedByViews(std::size_t patch) const
{
  // Every non-diffuse patch: the view is what P_i sees whatever the reflectance, and the
  // glossy room's error against Cycles falls with it too (Documentation/notes/propagation.md,
  // 2026-12-07).
  return this->ModelOfPatch[patch] >= 0;
}

void LightPropagation::BuildReceiverViews()
{
  this->ViewColumn.clear();
  this->ViewBegin.clear();
  this->Views.clear();
  this->ViewCellsOf.clear();
  const std::size_t n = this->PatchCount();
  bool any = false;
  for (std::size_t j = 0; j < n && !any; ++j)
  {
    any = this->ServedByViews(j);
  }
  if (this->Frames.empty() || !any)
  {
    return;
  }
  // A receiver i sees patch j through its region h_ij of H_i (paper §3.1): every sample
  // direction d of the region's cells (each standing for CellMeasure / SamplesPerCell of the
  // projected solid angle, HemisphereGrid.h) is a ray from P_i that meets Q_j, along which P_i
  // receives j's exitant radiance toward -d, read in the cell of -d in H_j (a mirror's: the
  // light it reflects from the mirror cell, where that ray goes on; file comment). The radiance
  // P_i sees through h_ij is their average: the view is the share of the region's samples per
  // cell of H_j.
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const int samplesTheta = grid.SamplesTheta();
  const int samplesPhi = grid.SamplesPhi();
  const UnitCellLookup lookup(grid);
  std::vector<double> share(static_cast<std::size_t>(grid.CellCount()), 0.0);
  std::vector<uint32_t> touched;
  this->ViewColumn.assign(n, NoView);
  this->ViewCellsOf.resize(n);
  for (std::size_t j = 0; j < n; ++j)
  {
    if (!this->ServedByViews(j))
    {
      continue;
    }
    this->ViewColumn[j] = this->ViewBegin.size();
    const HemisphereFrame& mirror = this->Frames[j];
    std::vector<uint32_t>& cellsOfColumn = this->ViewCellsOf[j];
    for (std::size_t k = cover.ColumnBegin(j); k < cover.ColumnEnd(j); ++k)
    {
      this->ViewBegin.push_back(this->Views.size());
      const SphericalCover::ColumnEntry& item = cover.ColumnAt(k);
      const HemisphereFrame& from = this->Frames[item.Receiver];
      // The receiver's local axes in the mirror's frame, turned around: a local direction d of
      // H_i toward Q_j leaves Q_j toward the receiver along -d.
      const glm::dvec3 back[3] = {
        -mirror.ToLocal(from.Tangent), -mirror.ToLocal(from.Bitangent), -mirror.ToLocal(from.Normal)
      };
      touched.clear();
      double total = 0.0;
      for (std::size_t s = cover.StripBegin(item.EntryIndex); s < cover.StripEnd(item.EntryIndex);
           ++s)
      {
        const SphericalCover::Strip& strip = cover.StripAt(s);
        const double sample = grid.CellMeasure(strip.Row) / grid.SamplesPerCell();
        for (int a = 0; a < samplesTheta; ++a)
        {
          const int sampleRow = strip.Row * samplesTheta + a;
          for (int sampleColumn = strip.PhiBegin * samplesPhi;
               sampleColumn < strip.PhiEnd * samplesPhi;
               ++sampleColumn)
          {
            const glm::dvec3 d = grid.SampleDirection(sampleRow, sampleColumn);
            const int cell = lookup.CellOf(d.x * back[0] + d.y * back[1] + d.z * back[2]);
            if (cell < 0)
            {
              continue; // behind the mirror's tangent plane (a curved patch seen edge on)
            }
            double& cellShare = share[static_cast<std::size_t>(cell)];
            if (cellShare == 0.0)
            {
              touched.push_back(static_cast<uint32_t>(cell));
            }
            cellShare += sample;
            total += sample;
          }
        }
      }
      std::sort(touched.begin(), touched.end());
      for (const uint32_t cell : touched)
      {
        this->Views.push_back({ cell, static_cast<float>(share[cell] / total) });
        share[cell] = 0.0;
        cellsOfColumn.push_back(cell);
      }
    }
    this->ViewBegin.push_back(this->Views.size());
    std::sort(cellsOfColumn.begin(), cellsOfColumn.end());
    cellsOfColumn.erase(
      std::unique(cellsOfColumn.begin(), cellsOfColumn.end()), cellsOfColumn.end());
  }
}

std::size_t LightPropagation::ViewStart(std::size_t j, std::size_t k) const
{
  return this->ViewBegin[this->ViewColumn[j] + (k - this->Cover.ColumnBegin(j))];
}

bool LightPropagation::HasView(std::size_t j, std::size_t k) const
{
  return !this->ViewColumn.empty() && this->ViewColumn[j] != NoView &&
    this->ViewStart(j, k + 1) > this->ViewStart(j, k);
}

glm::dvec3 LightPropagation::ViewRadiance(std::size_t j,
  std::size_t k,
  const DirectionalShotData& shot) const
{
  glm::dvec3 sum(0.0);
  const std::size_t end = this->ViewStart(j, k + 1);
  for (std::size_t v = this->ViewStart(j, k); v < end; ++v)
  {
    sum += static_cast<double>(this->Views[v].Weight) * shot.GridOut[this->Views[v].Cell];
  }
  return sum;
}

void LightPropagation::FillViewCells(std::size_t shooter, DirectionalShotData& shot) const
{
  if (shot.ByCell)
  {
    return; // a grid shot holds every cell
  }
  shot.GridOut.resize(static_cast<std::size_t>(this->Cover.Grid().CellCount()));
  std::size_t unused = 0;
  for (const uint32_t cell : this->ViewCellsOf[shooter])
  {
    shot.GridOut[cell] = this->TowardReceiver(shooter, FallbackFlag | cell, shot, unused);
  }
}

glm::dvec3 LightPropagation::TowardReceiver(std::size_t shooter,
  uint32_t code,
  const DirectionalShotData& shot,
  std::size_t& meanFallbacks) const
{
  if (code == NoEntry)
  {
    ++meanFallbacks;
    return shot.Mean;
  }
  // The exitant radiance toward the cell of the direction P_i - P_j (paper §5.1) in the
  // shooter's hemisphere, from the in-strips DirectionalShot kept.
  const HemisphereGrid& grid = this->Cover.Grid();
  const int cell = static_cast<int>(code & ~FallbackFlag);
  if (shot.ByCell)
  {
    return shot.GridOut[static_cast<std::size_t>(cell)];
  }
  const ReflectanceWeights& table = *this->Reflectances.Table(shooter);
  const int rowOut = grid.RowOfCell(cell);
  const int columnOut = grid.ColumnOfCell(cell);
  glm::dvec3 sum(0.0);
  for (int rowIn : shot.Coupled[static_cast<std::size_t>(rowOut)])
  {
    for (const InStrip& strip : shot.In[static_cast<std::size_t>(rowIn)])
    {
      sum += table.StripWeight(rowOut, columnOut, rowIn, strip.Begin, strip.End) * strip.Radiance;
    }
  }
  return sum;
}

} // namespace sphcover
