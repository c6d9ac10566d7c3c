// SPDX-License-Identifier: BSD-3-Clause
#include "propagation/LightPropagation.h"

#include "math/Constants.h"

#include "reflectance/DirectionalReflection.h"

#include "cover/SphericalCover.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace sphcover
{

namespace
{

double BandSum(const glm::dvec3& v)
{
  return v.x + v.y + v.z;
}

/// A hint to the processor to fetch `address` into the cache (a gather's later reads).
inline void Prefetch(const void* address)
{
#if defined(__GNUC__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}

/// The Lambertian reflectance k_d of every material (0 for mirror and tabulated).
std::vector<glm::dvec3> ReflectanceOf(const std::vector<Material>& materials)
{
  std::vector<glm::dvec3> rho;
  rho.reserve(materials.size());
  for (const Material& material : materials)
  {
    const bool lambertianPart =
      material.Type == MaterialType::Diffuse || material.Type == MaterialType::Phong;
    rho.push_back(lambertianPart ? material.Diffuse : glm::dvec3(0.0));
  }
  return rho;
}

/// Materials that give the same BRDF share a model and a weight table.
std::vector<glm::dvec3> EmissionOf(const std::vector<Material>& materials)
{
  std::vector<glm::dvec3> le;
  le.reserve(materials.size());
  for (const Material& material : materials)
  {
    le.push_back(material.Emission);
  }
  return le;
}
}

LightPropagation::LightPropagation(const SphericalCover& cover,
  std::vector<glm::dvec3> reflectance,
  std::vector<glm::dvec3> emission)
  : Cover(cover)
  , Rho(std::move(reflectance))
  , Le(std::move(emission))
{
  const std::size_t n = cover.PatchCount();
  if (this->Rho.size() != n || this->Le.size() != n)
  {
    throw std::invalid_argument("LightPropagation: " + std::to_string(this->Rho.size()) +
      " reflectances and " + std::to_string(this->Le.size()) + " emissions for " +
      std::to_string(n) + " patches");
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int b = 0; b < 3; ++b)
    {
      // Written as negations so that NaN is rejected too.
      if (!(this->Rho[i][b] >= 0.0 && this->Rho[i][b] <= 1.0))
      {
        throw std::invalid_argument(
          "LightPropagation: reflectance of patch " + std::to_string(i) + " not in [0, 1]");
      }
      if (!(this->Le[i][b] >= 0.0 && std::isfinite(this->Le[i][b])))
      {
        throw std::invalid_argument(
          "LightPropagation: emission of patch " + std::to_string(i) + " negative or not finite");
      }
    }
  }
  // Omega_e is a sum over the strips' cells; a shot needs it for every entry of a column, and
  // the same entries are visited over and over, so it is computed once.
  this->EntryOmega.resize(cover.EntryCount());
  for (std::size_t e = 0; e < cover.EntryCount(); ++e)
  {
    this->EntryOmega[e] = cover.ProjectedSolidAngle(e);
  }
  // The state of the entries is kept in column order (see the file comment): a shot walks
  // column j, whose entries lie all over the rows, and so reads and writes them in one sweep.
  if (cover.EntryCount() >= FallbackFlag)
  {
    throw std::invalid_argument("LightPropagation: too many cover entries for 32-bit positions");
  }
  this->EntryPosition.resize(cover.EntryCount());
  this->ColumnMeasure.resize(cover.EntryCount());
  for (std::size_t k = 0; k < cover.EntryCount(); ++k)
  {
    this->EntryPosition[cover.ColumnAt(k).EntryIndex] = static_cast<uint32_t>(k);
    this->ColumnMeasure[k] = this->EntryOmega[cover.ColumnAt(k).EntryIndex];
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    this->TotalEmitted += Pi * cover.PatchArea(i) * BandSum(this->Le[i]);
  }
  this->ModelOfPatch.assign(n, -1);
  this->Reset();
}

LightPropagation::LightPropagation(const SphericalCover& cover,
  const std::vector<Material>& materialOfPatch)
  : LightPropagation(cover, ReflectanceOf(materialOfPatch), EmissionOf(materialOfPatch))
{
  this->SetUpModels(materialOfPatch);
}

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
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const std::size_t entries = cover.EntryCount();
  // The transposed entries: row j is sorted by source, column j by receiver, so one merge of
  // the two finds, for every receiver i of column j, the entry (j, i) of row j.
  this->ColumnBack.assign(entries, NoEntry);
  for (std::size_t j = 0; j < this->PatchCount(); ++j)
  {
    std::size_t e = cover.EntryBegin(j);
    std::size_t k = cover.ColumnBegin(j);
    while (e < cover.EntryEnd(j) && k < cover.ColumnEnd(j))
    {
      const uint32_t source = cover.EntryAt(e).Source;
      const uint32_t receiver = cover.ColumnAt(k).Receiver;
      if (source < receiver)
      {
        ++e;
      }
      else if (receiver < source)
      {
        ++k;
      }
      else
      {
        this->ColumnBack[k++] = static_cast<uint32_t>(e++ - cover.EntryBegin(j));
      }
    }
  }
  this->ColumnAlbedoMeasure.assign(entries, glm::dvec3(0.0));
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
  this->Reset();
}

const Reflectance* LightPropagation::ReflectanceModel(std::size_t patch) const
{
  return this->Reflectances.Model(patch);
}

const ReflectanceWeights* LightPropagation::Weights(std::size_t patch) const
{
  return this->Reflectances.Table(patch);
}

std::vector<Material> LightPropagation::MaterialsOfPatches(const Scene& scene,
  const std::vector<Patch>& patches)
{
  std::vector<Material> materials;
  materials.reserve(patches.size());
  for (const Patch& patch : patches)
  {
    const Surface& surface = scene.Surfaces.at(static_cast<std::size_t>(patch.SurfaceIndex));
    materials.push_back(scene.Materials.at(static_cast<std::size_t>(surface.MaterialIndex)));
  }
  return materials;
}

void LightPropagation::SetExchangeFactors(const std::vector<double>& entryFactors)
{
  if (!entryFactors.empty() && entryFactors.size() != this->Cover.EntryCount())
  {
    throw std::invalid_argument("LightPropagation: " + std::to_string(entryFactors.size()) +
      " exchange factors for " + std::to_string(this->Cover.EntryCount()) + " entries");
  }
  std::vector<double> measure(this->EntryOmega.size());
  for (std::size_t e = 0; e < measure.size(); ++e)
  {
    const double factor = entryFactors.empty() ? 1.0 : entryFactors[e];
    if (!(factor >= 0.0 && std::isfinite(factor)))
    {
      // Rejected factors leave the cover's exchange as built.
      this->SetExchangeFactors({});
      throw std::invalid_argument("LightPropagation: exchange factor of entry " +
        std::to_string(e) + " is not finite and >= 0");
    }
    measure[this->EntryPosition[e]] = factor * this->EntryOmega[e];
  }
  this->ColumnMeasure = std::move(measure);
  this->Balanced = !entryFactors.empty();
  this->Reset();
}

void LightPropagation::Reset()
{
  this->Incident.assign(this->Cover.EntryCount(), glm::dvec3(0.0));
  this->IncidentByEntry.clear();
  this->IncidentByEntryValid = false;
  // Before any shot every patch holds its own emission, unshot.
  this->Unshot = this->Le;
  // Per-entry unshot incident radiance only when some patch is non-diffuse (24 bytes/entry).
  this->UnshotIncident.assign(
    this->Reflectances.Empty() ? 0 : this->Cover.EntryCount(), glm::dvec3(0.0));
  this->DirectionalUnshot.assign(this->PatchCount(), 0.0);
  this->Power.resize(this->PatchCount());
  for (std::size_t i = 0; i < this->PatchCount(); ++i)
  {
    this->Power[i] = this->PowerOf(i);
  }
  this->Shots.clear();
  this->ElapsedSeconds = 0.0;
  this->NextInOrder = 0;
}

glm::dvec3 LightPropagation::DirectionalShot(std::size_t shooter)
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const ReflectanceWeights& table = *this->Reflectances.Table(shooter);
  const std::size_t rowBegin = cover.EntryBegin(shooter);
  const std::size_t rowEnd = cover.EntryEnd(shooter);

  // The in-strips that hold unshot incident radiance, taken out of the shooter's row, by row.
  const int rows = grid.ThetaBins();
  const std::size_t rowCount = static_cast<std::size_t>(rows);
  std::vector<std::vector<InStrip>>& in = this->DirectionalIn;
  in.resize(rowCount);
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
  // For every out row, the in rows the table couples it with that hold unshot light, and the
  // number of their strips.
  std::vector<std::vector<int>>& coupled = this->DirectionalCoupled;
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
  std::size_t pairs = 0;
  if (rowEnd > rowBegin)
  {
    for (std::size_t k = cover.StripBegin(rowBegin); k < cover.StripEnd(rowEnd - 1); ++k)
    {
      pairs += coupledStrips[cover.StripAt(k).Row];
    }
  }
  this->GridShot = this->Method == DirectionalMethod::Grid ||
    (this->Method == DirectionalMethod::Automatic &&
      static_cast<double>(pairs) > GridCostInPairs * static_cast<double>(grid.CellCount()));
  this->DirectionalOut.assign(rowEnd - rowBegin, glm::dvec3(0.0));
  return this->GridShot ? this->ShotByGrid(shooter, table)
                        : this->ShotByStripPairs(shooter, table, pairs);
}

glm::dvec3 LightPropagation::ShotByStripPairs(std::size_t shooter,
  const ReflectanceWeights& table,
  std::size_t pairs)
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const std::size_t rowBegin = cover.EntryBegin(shooter);
  const std::size_t rowEnd = cover.EntryEnd(shooter);
  const std::vector<std::vector<InStrip>>& in = this->DirectionalIn;
  const std::vector<std::vector<int>>& coupled = this->DirectionalCoupled;
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
      this->DirectionalOut[e - rowBegin] = flux / this->EntryOmega[e];
    }
  }
  this->LastWeightEvaluations = pairs;
  return meanFlux / grid.TotalMeasure();
}

glm::dvec3 LightPropagation::ShotByGrid(std::size_t shooter, const ReflectanceWeights& table)
{
  const SphericalCover& cover = this->Cover;
  const HemisphereGrid& grid = cover.Grid();
  const std::size_t rows = static_cast<std::size_t>(grid.ThetaBins());
  const std::size_t columns = static_cast<std::size_t>(grid.PhiBins());
  // The unshot incident radiance per cell (each cell of the row belongs to one entry).
  this->GridIn.assign(rows * columns, glm::dvec3(0.0));
  for (std::size_t row = 0; row < rows; ++row)
  {
    for (const InStrip& strip : this->DirectionalIn[row])
    {
      for (int c = strip.Begin; c < strip.End; ++c)
      {
        this->GridIn[row * columns + static_cast<std::size_t>(c)] += strip.Radiance;
      }
    }
  }
  // I(o) toward every cell, then per out row the prefix sums of I over the columns, so that
  // a strip of out cells costs O(1).
  table.Reflect(this->GridIn, this->GridOut, this->ReflectScratch);
  this->GridPrefix.resize(rows * (columns + 1));
  glm::dvec3 meanFlux(0.0);
  for (std::size_t row = 0; row < rows; ++row)
  {
    glm::dvec3* prefix = this->GridPrefix.data() + row * (columns + 1);
    prefix[0] = glm::dvec3(0.0);
    for (std::size_t c = 0; c < columns; ++c)
    {
      prefix[c + 1] = prefix[c] + this->GridOut[row * columns + c];
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
      this->DirectionalOut[e - rowBegin] = flux / this->EntryOmega[e];
    }
  }
  this->LastWeightEvaluations = 0;
  return meanFlux / grid.TotalMeasure();
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

glm::dvec3 LightPropagation::TowardReceiver(std::size_t shooter,
  uint32_t code,
  const glm::dvec3& mean)
{
  if (code == NoEntry)
  {
    ++this->LastMeanFallbacks;
    return mean;
  }
  // The exitant radiance toward the cell of the direction P_i - P_j (paper §5.1) in the
  // shooter's hemisphere, from the in-strips DirectionalShot kept.
  const HemisphereGrid& grid = this->Cover.Grid();
  const int cell = static_cast<int>(code & ~FallbackFlag);
  if (this->GridShot)
  {
    return this->GridOut[static_cast<std::size_t>(cell)];
  }
  const ReflectanceWeights& table = *this->Reflectances.Table(shooter);
  const int rowOut = grid.RowOfCell(cell);
  const int columnOut = grid.ColumnOfCell(cell);
  glm::dvec3 sum(0.0);
  for (int rowIn : this->DirectionalCoupled[static_cast<std::size_t>(rowOut)])
  {
    for (const InStrip& strip : this->DirectionalIn[static_cast<std::size_t>(rowIn)])
    {
      sum += table.StripWeight(rowOut, columnOut, rowIn, strip.Begin, strip.End) * strip.Radiance;
    }
  }
  return sum;
}

std::size_t LightPropagation::Shoot(std::size_t shooter)
{
  // The uniform part (a diffuse patch's reflected light, any patch's emission) is the same
  // toward every receiver (§5.2), so it is evaluated once. It is taken out before the column is
  // walked, because the shooter may be in its own column (a concave patch sees itself, h_ii)
  // and then receives part of it back.
  const glm::dvec3 increment = this->Unshot[shooter];
  this->Unshot[shooter] = glm::dvec3(0.0);
  // The directional part of a non-diffuse shooter (see the file comment).
  const bool directional =
    this->ModelOfPatch[shooter] >= 0 && this->DirectionalUnshot[shooter] > 0.0;
  this->LastMeanFallbacks = 0;
  this->LastWeightEvaluations = 0;
  this->GridShot = false;
  const glm::dvec3 mean = directional ? this->DirectionalShot(shooter) : glm::dvec3(0.0);
  this->Power[shooter] = this->PowerOf(shooter);
  const std::size_t begin = this->Cover.ColumnBegin(shooter);
  const std::size_t end = this->Cover.ColumnEnd(shooter);
  std::size_t fallbacks = 0;
  this->IncidentByEntryValid = false;
  for (std::size_t k = begin; k < end; ++k)
  {
    const SphericalCover::ColumnEntry& item = this->Cover.ColumnAt(k);
    // The radiance P_i sees through h_ij: the shooter's, whatever the balance.
    glm::dvec3 value = increment;
    if (directional)
    {
      const uint32_t back = this->ColumnBack[k];
      if (back < FallbackFlag)
      {
        value += this->DirectionalOut[back];
      }
      else
      {
        value += this->TowardReceiver(shooter, back, mean);
        ++fallbacks;
      }
    }
    this->Incident[k] += value;
    // The Lambertian part (all of a diffuse receiver's reflection, phong's k_d) in closed form,
    // over the region's balanced measure f_e Omega_e (SetExchangeFactors).
    this->Unshot[item.Receiver] += this->Rho[item.Receiver] * (this->ColumnMeasure[k] / Pi) * value;
    if (this->ModelOfPatch[item.Receiver] >= 0)
    {
      this->UnshotIncident[k] += value;
      this->DirectionalUnshot[item.Receiver] +=
        this->Cover.PatchArea(item.Receiver) * BandSum(value * this->ColumnAlbedoMeasure[k]);
    }
    this->Power[item.Receiver] = this->PowerOf(item.Receiver);
  }
  this->LastFallbacks = fallbacks;
  return end - begin;
}

double LightPropagation::PowerOf(std::size_t patch) const
{
  return Pi * this->Cover.PatchArea(patch) * BandSum(this->Unshot[patch]) +
    this->DirectionalUnshot[patch];
}

double LightPropagation::UnshotEnergy() const
{
  double largest = 0.0;
  double total = 0.0;
  this->Brightest(largest, total);
  return total;
}

std::size_t LightPropagation::Brightest(double& power, double& total) const
{
  // One pass for both: this scan is the O(N) part of every shot (file comment). The sum runs
  // in four interleaved partial sums (a fixed order, so deterministic), which keeps the adds
  // from waiting on each other.
  std::size_t best = 0;
  power = -1.0;
  double partial[4] = { 0.0, 0.0, 0.0, 0.0 };
  const std::size_t n = this->Power.size();
  const double* values = this->Power.data();
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
  {
    for (std::size_t lane = 0; lane < 4; ++lane)
    {
      const double p = values[i + lane];
      partial[lane] += p;
      // Strictly greater, in index order: ties go to the lowest index.
      if (p > power)
      {
        power = p;
        best = i + lane;
      }
    }
  }
  for (; i < n; ++i)
  {
    partial[0] += values[i];
    if (values[i] > power)
    {
      power = values[i];
      best = i;
    }
  }
  total = (partial[0] + partial[1]) + (partial[2] + partial[3]);
  return best;
}

bool LightPropagation::Converged(double tolerance) const
{
  if (this->TotalEmitted <= 0.0 || this->PatchCount() == 0)
  {
    return true;
  }
  // All the light still to be shot, not only the brightest point's: with many patches each
  // can be below the tolerance while their sum is not (a 1458-patch furnace stopped 1.6% short).
  return this->UnshotEnergy() / this->TotalEmitted < tolerance;
}

std::size_t LightPropagation::EstimateBytes(const SphericalCover& cover,
  const std::vector<Material>& materialOfPatch)
{
  const SphericalCoverOptions& options = cover.Options();
  return cover.EntryCount() * BytesPerEntry + cover.PatchCount() * BytesPerPatch +
    PointReflectances::EstimateBytes(options.ThetaBins, options.PhiBins, materialOfPatch);
}

bool LightPropagation::Run(const PropagationSettings& settings, const ProgressCallback& progress)
{
  if (!(settings.ConvergenceTolerance >= 0.0))
  {
    throw std::invalid_argument("LightPropagation: negative ConvergenceTolerance");
  }
  // Finite emissions can still overflow in their power (Le 1e308 x pi x area): the convergence
  // measure would be inf / inf and the propagation would never end or write inf.
  if (!std::isfinite(this->TotalEmitted))
  {
    throw std::overflow_error("the emitted power (pi x area x emission, summed) overflows double "
                              "precision; scale the emissions down");
  }
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const double secondsBefore = this->ElapsedSeconds;
  double largest = 0.0;
  double unshot = 0.0;
  std::size_t brightest = this->Brightest(largest, unshot);
  const double initialUnshot = unshot;
  double reported = 0.0;
  std::size_t shots = 0;
  // Converged(), from the scan's sum.
  const auto converged = [&]
  {
    return this->TotalEmitted <= 0.0 || this->PatchCount() == 0 ||
      unshot / this->TotalEmitted < settings.ConvergenceTolerance;
  };
  while (!converged())
  {
    if (settings.MaximumShots > 0 && shots >= settings.MaximumShots)
    {
      return false;
    }
    std::size_t shooter = brightest;
    if (settings.Order == ShootingOrder::FixedOrder)
    {
      // Not converged, so some patch has unshot power: the cycle finds it within N steps.
      while (this->UnshotPower(this->NextInOrder) <= 0.0)
      {
        this->NextInOrder = (this->NextInOrder + 1) % this->PatchCount();
      }
      shooter = this->NextInOrder;
      this->NextInOrder = (this->NextInOrder + 1) % this->PatchCount();
    }

    ShotRecord record;
    record.Shot = this->Shots.size();
    record.Shooter = shooter;
    record.ShotPower = this->UnshotPower(shooter);
    record.RelativeChange = record.ShotPower / this->TotalEmitted;
    record.ReceiverUpdates = this->Shoot(shooter);
    record.WeightEvaluations = this->LastWeightEvaluations;
    record.Fallbacks = this->LastFallbacks;
    record.MeanFallbacks = this->LastMeanFallbacks;
    record.GridShot = this->GridShot;
    brightest = this->Brightest(largest, unshot);
    if (!std::isfinite(unshot))
    {
      throw std::overflow_error("the unshot energy is no longer finite after shot " +
        std::to_string(record.Shot) + " (an overflow); scale the emissions down");
    }
    record.MaxUnshotRelative = largest / this->TotalEmitted;
    record.UnshotEnergy = unshot;
    this->ElapsedSeconds =
      secondsBefore + std::chrono::duration<double>(Clock::now() - start).count();
    record.Seconds = this->ElapsedSeconds;
    this->Shots.push_back(record);
    ++shots;

    if (progress)
    {
      if (initialUnshot > 0.0)
      {
        reported = std::max(reported, std::min(1.0, 1.0 - record.UnshotEnergy / initialUnshot));
      }
      if (!progress(reported))
      {
        return false;
      }
    }
  }
  // The unshot energy stayed finite, but a radiance can overflow on its own (a tiny region's
  // measure): the result is refused rather than written as inf.
  for (const glm::dvec3& e : this->Incident)
  {
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(e.z))
    {
      throw std::overflow_error(
        "an incident radiance is not finite (an overflow); scale the emissions down");
    }
  }
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

const std::vector<glm::dvec3>& LightPropagation::IncidentRadiances() const
{
  if (!this->IncidentByEntryValid)
  {
    this->IncidentByEntry.resize(this->Incident.size());
    for (std::size_t e = 0; e < this->Incident.size(); ++e)
    {
      this->IncidentByEntry[e] = this->Incident[this->EntryPosition[e]];
    }
    this->IncidentByEntryValid = true;
  }
  return this->IncidentByEntry;
}

glm::dvec3 LightPropagation::Irradiance(std::size_t patch) const
{
  glm::dvec3 sum(0.0);
  for (std::size_t e = this->Cover.EntryBegin(patch); e < this->Cover.EntryEnd(patch); ++e)
  {
    const uint32_t k = this->EntryPosition[e];
    sum += this->Incident[k] * this->ColumnMeasure[k];
  }
  return sum;
}

glm::dvec3 LightPropagation::ExitantRadiance(std::size_t patch) const
{
  return this->Le[patch] + this->Rho[patch] / Pi * this->Irradiance(patch);
}

glm::dvec3 LightPropagation::Reflected(std::size_t patch) const
{
  if (this->ModelOfPatch[patch] < 0)
  {
    return this->Rho[patch] * this->Irradiance(patch);
  }
  glm::dvec3 sum = this->Rho[patch] * this->Irradiance(patch);
  for (std::size_t e = this->Cover.EntryBegin(patch); e < this->Cover.EntryEnd(patch); ++e)
  {
    const uint32_t k = this->EntryPosition[e];
    sum += this->Incident[k] * this->ColumnAlbedoMeasure[k];
  }
  return sum;
}

glm::dvec3 LightPropagation::Brightness(std::size_t patch) const
{
  return this->Reflected(patch) + Pi * this->Le[patch];
}

glm::dvec3 LightPropagation::ExitantRadianceToward(std::size_t patch,
  const glm::dvec3& localDirection) const
{
  if (!(localDirection.z > 0.0) || this->Cover.Grid().CellOfLocalDirection(localDirection) < 0)
  {
    return glm::dvec3(0.0);
  }
  const ReflectanceWeights* table = this->Reflectances.Table(patch);
  return table ? this->ExitantRadiance(patch) +
      DirectionalExitantRadiance(
        this->Cover, *table, patch, this->IncidentRadiances(), localDirection)
               : this->ExitantRadiance(patch);
}

EnergyBalance LightPropagation::Energy() const
{
  EnergyBalance balance;
  for (std::size_t i = 0; i < this->PatchCount(); ++i)
  {
    const double area = this->Cover.PatchArea(i);
    balance.Emitted += Pi * area * this->Le[i];
    balance.Absorbed += area * (this->Irradiance(i) - this->Reflected(i));
    balance.Unshot += Pi * area * this->Unshot[i];
    if (this->ModelOfPatch[i] >= 0)
    {
      for (std::size_t e = this->Cover.EntryBegin(i); e < this->Cover.EntryEnd(i); ++e)
      {
        const uint32_t k = this->EntryPosition[e];
        balance.Unshot += area * this->UnshotIncident[k] * this->ColumnAlbedoMeasure[k];
      }
    }
  }
  for (int b = 0; b < 3; ++b)
  {
    if (balance.Emitted[b] > 0.0)
    {
      balance.RelativeImbalance = std::max(balance.RelativeImbalance,
        std::fabs(balance.Emitted[b] - balance.Absorbed[b]) / balance.Emitted[b]);
    }
  }
  return balance;
}

} // namespace sphcover
