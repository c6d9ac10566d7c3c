// SPDX-License-Identifier: BSD-3-Clause
#include "LightPropagation.h"

#include "Patch.h"
#include "Scene.h"
#include "SphericalCover.h"

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
constexpr double Pi = 3.14159265358979323846;

double BandSum(const glm::dvec3& v)
{
  return v.x + v.y + v.z;
}

std::vector<glm::dvec3> ReflectanceOf(const std::vector<Material>& materials)
{
  std::vector<glm::dvec3> rho;
  rho.reserve(materials.size());
  for (const Material& material : materials)
  {
    if (material.Type == MaterialType::Mirror || material.Type == MaterialType::Tabulated)
    {
      throw std::invalid_argument("LightPropagation: material '" + material.Name + "' is " +
        MaterialTypeName(material.Type) + "; only diffuse (and phong, as diffuse) is propagated");
    }
    // Phong: its diffuse part only (see the header's limitations).
    rho.push_back(material.Diffuse);
  }
  return rho;
}

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
  for (std::size_t i = 0; i < n; ++i)
  {
    this->TotalEmitted += Pi * cover.PatchArea(i) * BandSum(this->Le[i]);
  }
  this->Reset();
}

LightPropagation::LightPropagation(const SphericalCover& cover,
  const std::vector<Material>& materialOfPatch)
  : LightPropagation(cover, ReflectanceOf(materialOfPatch), EmissionOf(materialOfPatch))
{
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

void LightPropagation::Reset()
{
  this->Incident.assign(this->Cover.EntryCount(), glm::dvec3(0.0));
  // Before any shot every patch holds its own emission, unshot.
  this->Unshot = this->Le;
  this->Shots.clear();
  this->ElapsedSeconds = 0.0;
  this->NextInOrder = 0;
}

std::size_t LightPropagation::Shoot(std::size_t shooter)
{
  // Diffuse: the radiance leaving P_shooter is the same toward every receiver (§5.2), so it is
  // evaluated once. It is taken out before the column is walked, because the shooter may be in
  // its own column (a concave patch sees itself, h_ii) and then receives part of it back.
  const glm::dvec3 increment = this->Unshot[shooter];
  this->Unshot[shooter] = glm::dvec3(0.0);
  const std::size_t begin = this->Cover.ColumnBegin(shooter);
  const std::size_t end = this->Cover.ColumnEnd(shooter);
  for (std::size_t k = begin; k < end; ++k)
  {
    const SphericalCover::ColumnEntry& item = this->Cover.ColumnAt(k);
    this->Incident[item.EntryIndex] += increment;
    this->Unshot[item.Receiver] +=
      this->Rho[item.Receiver] * (this->EntryOmega[item.EntryIndex] / Pi) * increment;
  }
  return end - begin;
}

double LightPropagation::UnshotPower(std::size_t patch) const
{
  return Pi * this->Cover.PatchArea(patch) * BandSum(this->Unshot[patch]);
}

double LightPropagation::UnshotEnergy() const
{
  double sum = 0.0;
  for (std::size_t i = 0; i < this->PatchCount(); ++i)
  {
    sum += this->UnshotPower(i);
  }
  return sum;
}

std::size_t LightPropagation::Brightest(double& power) const
{
  std::size_t best = 0;
  power = -1.0;
  for (std::size_t i = 0; i < this->PatchCount(); ++i)
  {
    const double p = this->UnshotPower(i);
    // Strictly greater: ties go to the lowest index.
    if (p > power)
    {
      power = p;
      best = i;
    }
  }
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

bool LightPropagation::Run(const PropagationSettings& settings, const ProgressCallback& progress)
{
  if (!(settings.ConvergenceTolerance >= 0.0))
  {
    throw std::invalid_argument("LightPropagation: negative ConvergenceTolerance");
  }
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const double secondsBefore = this->ElapsedSeconds;
  const double initialUnshot = this->UnshotEnergy();
  double reported = 0.0;
  std::size_t shots = 0;
  double largest = 0.0;
  std::size_t brightest = this->Brightest(largest);
  while (!this->Converged(settings.ConvergenceTolerance))
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
    brightest = this->Brightest(largest);
    record.MaxUnshotRelative = largest / this->TotalEmitted;
    record.UnshotEnergy = this->UnshotEnergy();
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
  if (progress)
  {
    progress(1.0);
  }
  return true;
}

glm::dvec3 LightPropagation::Irradiance(std::size_t patch) const
{
  glm::dvec3 sum(0.0);
  for (std::size_t e = this->Cover.EntryBegin(patch); e < this->Cover.EntryEnd(patch); ++e)
  {
    sum += this->Incident[e] * this->EntryOmega[e];
  }
  return sum;
}

glm::dvec3 LightPropagation::ExitantRadiance(std::size_t patch) const
{
  return this->Le[patch] + this->Rho[patch] / Pi * this->Irradiance(patch);
}

glm::dvec3 LightPropagation::Brightness(std::size_t patch) const
{
  return this->Rho[patch] * this->Irradiance(patch) + Pi * this->Le[patch];
}

EnergyBalance LightPropagation::Energy() const
{
  EnergyBalance balance;
  for (std::size_t i = 0; i < this->PatchCount(); ++i)
  {
    const double area = this->Cover.PatchArea(i);
    balance.Emitted += Pi * area * this->Le[i];
    balance.Absorbed += area * (glm::dvec3(1.0) - this->Rho[i]) * this->Irradiance(i);
    balance.Unshot += Pi * area * this->Unshot[i];
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
