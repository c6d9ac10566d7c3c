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
#include <exception>
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

/// The emitted radiance Le of every material.
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
  if (cover.HasPanes())
  {
    this->ColumnFilter.resize(cover.EntryCount());
    for (std::size_t k = 0; k < cover.EntryCount(); ++k)
    {
      this->ColumnFilter[k] = cover.Filter(cover.ColumnAt(k).EntryIndex);
    }
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

std::size_t LightPropagation::Shoot(std::size_t shooter)
{
  if (this->Shared())
  {
    throw std::logic_error("LightPropagation::Shoot under a share: Run shoots collectively");
  }
  Candidate one;
  one.Shooter = shooter;
  one.Power = this->Power[shooter];
  return this->ShootBatch({ one }).front().ReceiverUpdates;
}

std::vector<ShotRecord> LightPropagation::ShootBatch(const std::vector<Candidate>& batch)
{
  const std::size_t members = batch.size();
  std::vector<ShotRecord> records(members);
  // Every member's unshot light is taken before any column is walked (see the file comment).
  // The uniform part (a diffuse patch's reflected light, any patch's emission) is the same
  // toward every receiver (§5.2), so it is evaluated once; it is taken out before the walk,
  // because the shooter may be in its own column (a concave patch sees itself, h_ii) and then
  // receives part of it back. Under a share the shooter's owner does this; the other ranks
  // have it from the scan before the batch (JoinScan) and, for a directional shot, from the
  // owner (ShareDirectionalShots).
  std::vector<glm::dvec3> increments(members, glm::dvec3(0.0));
  std::vector<bool> directional(members, false);
  if (this->BatchShots.size() < members)
  {
    this->BatchShots.resize(members);
  }
  bool ok = true;
  std::exception_ptr failure;
  try
  {
    for (std::size_t m = 0; m < members; ++m)
    {
      const std::size_t shooter = batch[m].Shooter;
      records[m].Shot = this->Shots.size() + m;
      records[m].Shooter = shooter;
      records[m].ShotPower = batch[m].Power;
      records[m].RelativeChange = batch[m].Power / this->TotalEmitted;
      if (!this->Owns(shooter))
      {
        increments[m] = batch[m].Increment;
        directional[m] = batch[m].Directional;
        continue;
      }
      increments[m] = this->Unshot[shooter];
      this->Unshot[shooter] = glm::dvec3(0.0);
      // The directional part of a non-diffuse shooter (see the file comment).
      directional[m] = this->ShootsDirectionally(shooter);
      if (directional[m])
      {
        this->DirectionalShot(shooter, this->BatchShots[m]);
      }
      this->Power[shooter] = this->PowerOf(shooter);
    }
  }
  catch (...)
  {
    if (!this->Shared())
    {
      throw;
    }
    failure = std::current_exception();
    ok = false;
  }
  if (this->Shared() &&
    std::any_of(batch.begin(), batch.end(), [](const Candidate& c) { return c.Directional; }))
  {
    this->Hook->ShareDirectionalShots(batch, directional, this->BatchShots, ok);
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  this->IncidentByEntryValid = false;
  for (std::size_t m = 0; m < members; ++m)
  {
    const std::size_t shooter = batch[m].Shooter;
    const glm::dvec3& increment = increments[m];
    const DirectionalShotData& shot = this->BatchShots[m];
    const std::size_t begin = this->Cover.ColumnBegin(shooter);
    const std::size_t end = this->Cover.ColumnEnd(shooter);
    std::size_t fallbacks = 0;
    std::size_t meanFallbacks = 0;
    for (std::size_t k = begin; k < end; ++k)
    {
      const SphericalCover::ColumnEntry& item = this->Cover.ColumnAt(k);
      // The radiance P_i sees through h_ij: the shooter's, whatever the balance.
      glm::dvec3 value = increment;
      if (directional[m])
      {
        const uint32_t back = this->ColumnBack[k];
        if (this->HasView(shooter, k))
        {
          // The shooter's light as the receiver sees it through the whole of Q_j (file comment).
          value += this->ViewRadiance(shooter, k, shot);
          fallbacks += back < FallbackFlag ? 0 : 1;
        }
        else if (back < FallbackFlag)
        {
          value += shot.Out[back];
        }
        else
        {
          value += this->TowardReceiver(shooter, back, shot, meanFallbacks);
          ++fallbacks;
        }
      }
      if (!this->ColumnFilter.empty())
      {
        value *= this->ColumnFilter[k]; // seen through panes
      }
      this->Incident[k] += value;
      // The Lambertian part (all of a diffuse receiver's reflection, phong's k_d) in closed
      // form, over the region's balanced measure f_e Omega_e (SetExchangeFactors).
      this->Unshot[item.Receiver] +=
        this->Rho[item.Receiver] * (this->ColumnMeasure[k] / Pi) * value;
      if (this->ModelOfPatch[item.Receiver] >= 0)
      {
        this->UnshotIncident[k] += value;
        this->DirectionalUnshot[item.Receiver] +=
          this->Cover.PatchArea(item.Receiver) * BandSum(value * this->ColumnAlbedoMeasure[k]);
      }
      this->Power[item.Receiver] = this->PowerOf(item.Receiver);
    }
    ShotRecord& record = records[m];
    record.ReceiverUpdates = end - begin;
    record.Fallbacks = fallbacks;
    record.MeanFallbacks = meanFallbacks;
    record.GridShot = directional[m] && shot.Grid;
    record.WeightEvaluations = directional[m] ? shot.WeightEvaluations : 0;
  }
  return records;
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
  // Under a share, this rank's own patches (JoinScan joins the ranks').
  std::size_t best = 0;
  power = -1.0;
  double partial[4] = { 0.0, 0.0, 0.0, 0.0 };
  // The own patches are rank, rank + K, ... (K = 1 without a share).
  const std::size_t stride = static_cast<std::size_t>(this->Share.Ranks());
  const std::size_t first = static_cast<std::size_t>(this->Share.Rank());
  const std::size_t patches = this->PatchCount();
  const std::size_t n = patches > first ? (patches - first + stride - 1) / stride : 0;
  const double* values = n > 0 ? this->Power.data() + first : nullptr;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
  {
    for (std::size_t lane = 0; lane < 4; ++lane)
    {
      const double p = values[(i + lane) * stride];
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
    const double p = values[i * stride];
    partial[0] += p;
    if (p > power)
    {
      power = p;
      best = i;
    }
  }
  total = (partial[0] + partial[1]) + (partial[2] + partial[3]);
  return first + best * stride;
}

std::vector<LightPropagation::Candidate> LightPropagation::LocalBatch(std::size_t best,
  double largest,
  std::size_t size) const
{
  std::vector<Candidate> batch;
  auto candidate = [this](std::size_t j)
  {
    Candidate c;
    c.Shooter = j;
    c.Power = this->Power[j];
    c.Increment = this->Unshot[j];
    c.Directional = this->ShootsDirectionally(j);
    return c;
  };
  if (size <= 1 || !(largest > 0.0))
  {
    // One at a time: the brightest, found by the scan.
    if (largest > 0.0)
    {
      batch.push_back(candidate(best));
    }
    return batch;
  }
  const double threshold = BatchPowerFraction * largest;
  const std::size_t stride = static_cast<std::size_t>(this->Share.Ranks());
  for (std::size_t j = static_cast<std::size_t>(this->Share.Rank()); j < this->PatchCount();
       j += stride)
  {
    if (this->Power[j] >= threshold)
    {
      batch.push_back(candidate(j));
    }
  }
  SelectBatch(batch, largest, size);
  return batch;
}

void LightPropagation::SelectBatch(std::vector<Candidate>& candidates,
  double largest,
  std::size_t size)
{
  const double threshold = BatchPowerFraction * largest;
  candidates.erase(
    std::remove_if(candidates.begin(),
      candidates.end(),
      [threshold](const Candidate& c) { return !(c.Power > 0.0 && c.Power >= threshold); }),
    candidates.end());
  // By decreasing power, ties to the lowest index: the order §5's scan would meet them in.
  auto before = [](const Candidate& a, const Candidate& b)
  { return a.Power > b.Power || (a.Power == b.Power && a.Shooter < b.Shooter); };
  const std::size_t kept = std::min(std::max<std::size_t>(size, 1), candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + kept, candidates.end(), before);
  candidates.resize(kept);
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
  // The receivers' views of the non-diffuse sources (BuildReceiverViews): a start per entry of
  // their columns, and ViewBytesPerCell per cell of their regions.
  std::size_t viewBytes = 0;
  for (std::size_t e = 0; e < cover.EntryCount(); ++e)
  {
    const std::size_t source = cover.EntryAt(e).Source;
    if (source < materialOfPatch.size() && materialOfPatch[source].Type != MaterialType::Diffuse)
    {
      std::size_t cells = 0;
      for (std::size_t k = cover.StripBegin(e); k < cover.StripEnd(e); ++k)
      {
        cells += static_cast<std::size_t>(cover.StripAt(k).PhiEnd - cover.StripAt(k).PhiBegin);
      }
      viewBytes += sizeof(std::size_t) + cells * ViewBytesPerCell;
    }
  }
  return cover.EntryCount() * BytesPerEntry + cover.PatchCount() * BytesPerPatch + viewBytes +
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
  const bool shared = this->Shared();
  if (shared && settings.Order != ShootingOrder::BrightestFirst)
  {
    throw std::invalid_argument("LightPropagation: only BrightestFirst is shared among ranks");
  }
  const std::size_t batchSize = settings.Order == ShootingOrder::BrightestFirst
    ? std::max<std::size_t>(settings.ShotBatch, 1)
    : 1;
  double largest = 0.0;
  double unshot = 0.0;
  // The next batch, from a scan of the state (joined over the ranks under a share).
  auto scan = [&](bool stop, std::vector<ShotRecord>* records)
  {
    const std::size_t best = this->Brightest(largest, unshot);
    std::vector<Candidate> batch = this->LocalBatch(best, largest, batchSize);
    const bool everyRankGoesOn =
      !shared || this->Hook->JoinScan(batch, largest, unshot, batchSize, stop, records);
    return std::make_pair(std::move(batch), everyRankGoesOn);
  };
  std::vector<Candidate> batch = scan(false, nullptr).first;
  const double initialUnshot = unshot;
  double reported = 0.0;
  std::size_t shots = 0;
  // Under a share: this rank's progress asked to stop; the ranks stop together, at the next
  // scan they join.
  bool stopping = false;
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
    if (settings.Order == ShootingOrder::FixedOrder)
    {
      Candidate next;
      next.Shooter = this->NextInFixedOrder();
      next.Power = this->Power[next.Shooter];
      batch.assign(1, next);
    }
    else if (settings.MaximumShots > 0)
    {
      batch.resize(std::min(batch.size(), settings.MaximumShots - shots));
    }
    if (batch.empty())
    {
      return false; // nothing has unshot power left to send (only rounding kept it unconverged)
    }
    std::vector<ShotRecord> records = this->ShootBatch(batch);
    auto next = scan(stopping, &records);
    batch = std::move(next.first);
    if (!std::isfinite(unshot))
    {
      throw std::overflow_error("the unshot energy is no longer finite after shot " +
        std::to_string(records.back().Shot) + " (an overflow); scale the emissions down");
    }
    this->ElapsedSeconds =
      secondsBefore + std::chrono::duration<double>(Clock::now() - start).count();
    for (ShotRecord& record : records)
    {
      record.MaxUnshotRelative = largest / this->TotalEmitted;
      record.UnshotEnergy = unshot;
      record.Seconds = this->ElapsedSeconds;
      this->Shots.push_back(record);
    }
    shots += records.size();
    if (!next.second)
    {
      return false;
    }

    if (progress && !stopping)
    {
      if (initialUnshot > 0.0)
      {
        reported = std::max(reported, std::min(1.0, 1.0 - unshot / initialUnshot));
      }
      if (!progress(reported))
      {
        if (!shared)
        {
          return false;
        }
        stopping = true;
      }
    }
  }
  this->CheckIncidentFinite();
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

std::size_t LightPropagation::NextInFixedOrder()
{
  // Not converged, so some patch has unshot power: the cycle finds it within N steps.
  while (this->UnshotPower(this->NextInOrder) <= 0.0)
  {
    this->NextInOrder = (this->NextInOrder + 1) % this->PatchCount();
  }
  const std::size_t shooter = this->NextInOrder;
  this->NextInOrder = (this->NextInOrder + 1) % this->PatchCount();
  return shooter;
}

void LightPropagation::CheckIncidentFinite() const
{
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

std::vector<glm::dvec3> LightPropagation::LampIrradiance(const std::vector<bool>& lampPatch,
  bool firstBounce) const
{
  const std::size_t count = this->PatchCount();
  if (lampPatch.size() != count)
  {
    throw std::invalid_argument("LightPropagation::LampIrradiance: " +
      std::to_string(lampPatch.size()) + " lamp flags for " + std::to_string(count) + " patches");
  }
  // Column j holds every receiver of patch j's light: one sweep per generation.
  std::vector<glm::dvec3> direct(count, glm::dvec3(0.0));
  for (std::size_t j = 0; j < count; ++j)
  {
    if (!lampPatch[j])
    {
      continue;
    }
    for (std::size_t k = this->Cover.ColumnBegin(j); k < this->Cover.ColumnEnd(j); ++k)
    {
      direct[this->Cover.ColumnAt(k).Receiver] +=
        this->ColumnMeasure[k] * this->Filtered(k, this->Le[j]);
    }
  }
  if (this->Shared())
  {
    // Each patch's direct light is known to its owner alone.
    direct = JoinOwnedItems(this->Share, direct);
  }
  std::vector<glm::dvec3> lamp = direct;
  for (std::size_t j = 0; firstBounce && j < count; ++j)
  {
    const glm::dvec3 reflected = this->Rho[j] / Pi * direct[j];
    for (std::size_t k = this->Cover.ColumnBegin(j); k < this->Cover.ColumnEnd(j); ++k)
    {
      lamp[this->Cover.ColumnAt(k).Receiver] +=
        this->ColumnMeasure[k] * this->Filtered(k, reflected);
    }
  }
  return lamp;
}

EnergyBalance LightPropagation::Energy() const
{
  EnergyBalance balance;
  for (const std::size_t i : this->Share.MyItems(this->PatchCount()))
  {
    const double area = this->Cover.PatchArea(i);
    balance.Emitted += Pi * area * this->Le[i];
    const glm::dvec3 irradiance = this->Irradiance(i);
    // A pane's transmitted part reached the points behind it (see the file comment).
    balance.Absorbed +=
      area * (irradiance - this->Reflected(i) - this->Cover.PaneTransmittance(i) * irradiance);
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
  if (this->Shared())
  {
    // Every rank's sums, added in rank order.
    const glm::dvec3 mine[3] = { balance.Emitted, balance.Absorbed, balance.Unshot };
    const std::vector<glm::dvec3> sums = JoinValues(this->Share, mine, 3, true);
    balance = EnergyBalance();
    for (std::size_t k = 0; k + 3 <= sums.size(); k += 3)
    {
      balance.Emitted += sums[k];
      balance.Absorbed += sums[k + 1];
      balance.Unshot += sums[k + 2];
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
