// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLightPropagationFilter.h"
#include "vtkLightPropagationSteps.h"

#include "vtkIlluminationAdapter.h"
#include "vtkNamedArrays.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkStageProgress.h"

#include "cover/BrightEmitters.h"
#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "math/ByteBuffer.h"
#include "propagation/ExchangeBalance.h"
#include "propagation/LightPropagation.h"
#include "propagation/SolutionFigures.h"
#include "scene/Material.h"

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

namespace names = vtkSphericalCoverArrayNames;

using namespace vtkLightPropagationSteps;

namespace
{
/// True when the points name their surfaces (SurfaceNames, SurfaceNameId): the solution's
/// figures are per named surface.
bool HasSurfaceNames(vtkPolyData* points)
{
  return points->GetFieldData()->GetAbstractArray(names::SurfaceNames) &&
    points->GetPointData()->GetArray(names::SurfaceNameId);
}

/// Per point its named surface (SurfaceNameId, an index of SurfaceNames) and its area; "" or
/// the problem.
std::string ReadSurfaces(vtkPolyData* points, sphcover::PointIllumination& illumination)
{
  auto* surfaceNames =
    vtkStringArray::SafeDownCast(points->GetFieldData()->GetAbstractArray(names::SurfaceNames));
  vtkDataArray* nameId = points->GetPointData()->GetArray(names::SurfaceNameId);
  vtkDataArray* area = points->GetPointData()->GetArray(names::Area);
  if (!surfaceNames || !nameId || !area)
  {
    return "the cover lacks the surface names or areas";
  }
  const int groups = static_cast<int>(surfaceNames->GetNumberOfValues());
  const vtkIdType count = points->GetNumberOfPoints();
  illumination.SurfaceCount = groups;
  illumination.SurfaceOfPoint.resize(static_cast<size_t>(count));
  illumination.Area.resize(static_cast<size_t>(count));
  for (vtkIdType k = 0; k < count; ++k)
  {
    const double id = nameId->GetComponent(k, 0);
    if (!(id >= 0.0 && id < groups))
    {
      std::ostringstream text;
      text << "point " << k << " has SurfaceNameId " << id << ", not an index of the " << groups
           << " surface names";
      return text.str();
    }
    illumination.SurfaceOfPoint[static_cast<size_t>(k)] = static_cast<int>(id);
    illumination.Area[static_cast<size_t>(k)] = area->GetComponent(k, 0);
  }
  return std::string();
}

/// Core's progress callback through `progress`, noting in `aborted` that the user stopped it.
std::function<bool(double)> NotingAbort(vtkStageProgress& progress, bool& aborted)
{
  return [&progress, &aborted](double fraction)
  {
    aborted = !progress(fraction);
    return !aborted;
  };
}
}

namespace vtkLightPropagationSteps
{
/// The cover's part of the figures (the form factors between the named surfaces of
/// `surfaces`, ReadSurfaces'), into `figures`; "" or the problem.
std::string CoverFiguresOf(const sphcover::SphericalCover& cover,
  const sphcover::PointIllumination& surfaces,
  sphcover::CoverFigures& figures)
{
  try
  {
    figures = sphcover::ComputeCoverFigures(cover, surfaces);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return std::string();
}

/// Computes the figures of the solution `points` holds (with `cover`, its cover's part, and
/// `surfaces`, its points' named surfaces as ReadSurfaces read them) and adds them to its field
/// data; "" or the problem.
std::string StoreFigures(const sphcover::CoverFigures& cover,
  sphcover::PointIllumination illumination,
  vtkPolyData* points)
{
  vtkDataArray* irradiance = points->GetPointData()->GetArray(names::Irradiance);
  vtkDataArray* radiance = points->GetPointData()->GetArray(names::Radiosity);
  vtkDataArray* balance = points->GetFieldData()->GetArray(names::EnergyBalance);
  if (!irradiance || !radiance || !balance || irradiance->GetNumberOfComponents() != 3 ||
    radiance->GetNumberOfComponents() != 3 || balance->GetNumberOfComponents() != 3 ||
    balance->GetNumberOfTuples() < 2)
  {
    return "the illumination lacks Irradiance, Radiosity or EnergyBalance";
  }
  const vtkIdType count = points->GetNumberOfPoints();
  illumination.Irradiance.resize(static_cast<size_t>(count));
  illumination.ExitantRadiance.resize(static_cast<size_t>(count));
  for (vtkIdType k = 0; k < count; ++k)
  {
    irradiance->GetTuple(k, &illumination.Irradiance[static_cast<size_t>(k)][0]);
    radiance->GetTuple(k, &illumination.ExitantRadiance[static_cast<size_t>(k)][0]);
  }
  balance->GetTuple(0, &illumination.Emitted[0]);
  balance->GetTuple(1, &illumination.Absorbed[0]);
  sphcover::SolutionFigures figures;
  try
  {
    figures = sphcover::ComputeSolutionFigures(cover, illumination);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }

  const vtkIdType surfaces = static_cast<vtkIdType>(figures.Surfaces.size());
  auto area = vtkNamedArrays::Double(names::SurfaceArea, 1, surfaces);
  auto meanIrradiance = vtkNamedArrays::Double(names::SurfaceMeanIrradiance, 3, surfaces);
  auto meanRadiance = vtkNamedArrays::Double(names::SurfaceMeanExitantRadiance, 3, surfaces);
  for (vtkIdType a = 0; a < surfaces; ++a)
  {
    const sphcover::SurfaceFigures& surface = figures.Surfaces[static_cast<size_t>(a)];
    area->SetValue(a, surface.Area);
    meanIrradiance->SetTuple(a, &surface.MeanIrradiance[0]);
    meanRadiance->SetTuple(a, &surface.MeanExitantRadiance[0]);
  }
  // The pairs that see each other, by row (SurfaceFormFactorPairs): a dense matrix of
  // one component per surface is n^2 (3.3 GB for 20,000 surfaces).
  const sphcover::SurfaceFormFactors& formFactors = figures.FormFactors;
  const vtkIdType pairs = static_cast<vtkIdType>(formFactors.PairCount());
  auto factorPairs = vtkNamedArrays::Int(names::SurfaceFormFactorPairs, 2, pairs);
  factorPairs->SetComponentName(0, "From");
  factorPairs->SetComponentName(1, "To");
  auto factorValues = vtkNamedArrays::Double(names::SurfaceFormFactorValues, 1, pairs);
  for (vtkIdType a = 0; a < surfaces; ++a)
  {
    for (std::uint64_t k = formFactors.RowOffsets[static_cast<size_t>(a)];
         k < formFactors.RowOffsets[static_cast<size_t>(a) + 1];
         ++k)
    {
      const vtkIdType pair = static_cast<vtkIdType>(k);
      factorPairs->SetTypedComponent(pair, 0, static_cast<int>(a));
      factorPairs->SetTypedComponent(pair, 1, formFactors.Seen[k]);
      factorValues->SetValue(pair, formFactors.Values[k]);
    }
  }
  auto statistics = vtkNamedArrays::Double(names::SolutionStatistics, 3, 1);
  statistics->SetComponentName(0, "CharacteristicPoints");
  statistics->SetComponentName(1, "Strips");
  statistics->SetComponentName(2, "RelativeImbalance");
  statistics->SetComponent(0, 0, static_cast<double>(figures.CharacteristicPoints));
  statistics->SetComponent(0, 1, static_cast<double>(figures.Strips));
  statistics->SetComponent(0, 2, figures.RelativeImbalance);
  vtkFieldData* fd = points->GetFieldData();
  fd->AddArray(area);
  fd->AddArray(meanIrradiance);
  fd->AddArray(meanRadiance);
  // A solution saved before the form factors were sparse carries them as the dense matrix of
  // one component per surface; the pairs supersede it.
  fd->RemoveArray("SurfaceFormFactors");
  fd->AddArray(factorPairs);
  fd->AddArray(factorValues);
  fd->AddArray(statistics);
  return std::string();
}

/// "" when the propagation of `rows` and the figures of its `surfaces` named surfaces (none:
/// the points name none) fit in `memoryLimit` MiB, else the problem. Both are bounded from the
/// sizes before any of it is allocated.
std::string MemoryProblem(const sphcover::SphericalCover& rows,
  const std::vector<sphcover::Material>& materials,
  int surfaces,
  double memoryLimit)
{
  const double mib = 1024.0 * 1024.0;
  const double propagation =
    static_cast<double>(sphcover::LightPropagation::EstimateBytes(rows, materials)) / mib;
  const double figures = surfaces > 0
    ? static_cast<double>(sphcover::FiguresBoundBytes(
        rows.PatchCount(), rows.EntryCount(), static_cast<std::size_t>(surfaces))) /
      mib
    : 0.0;
  if (propagation + figures > memoryLimit)
  {
    std::ostringstream text;
    text << "it would need about " << static_cast<long long>(propagation + figures)
         << " MiB (state of " << rows.EntryCount() << " regions and weight tables of a "
         << rows.Options().ThetaBins << " x " << rows.Options().PhiBins << " grid";
    if (surfaces > 0)
    {
      text << ", figures of " << surfaces << " named surfaces: up to "
           << static_cast<long long>(std::ceil(figures)) << " MiB";
    }
    text << "), more than MemoryLimit (" << memoryLimit
         << " MiB); use a coarser grid or fewer patches.";
    return text.str();
  }
  return std::string();
}

/// The cover (`withCover`: else only the points' own arrays), materials and (`named`, when the
/// points name them) surfaces of the cover points `input`, checked before the propagation: ""
/// or the problem. The figures are per named surface: a point that names none is refused
/// before the propagation, not after it.
std::string ReadPropagationInput(vtkPolyData* input,
  bool withCover,
  bool share,
  double memoryLimit,
  sphcover::SphericalCover& cover,
  std::vector<sphcover::Material>& materials,
  bool& named,
  sphcover::PointIllumination& surfaces)
{
  const std::string problem = withCover ? vtkSphericalCoverArrays::Load(input, cover, share) : "";
  if (!problem.empty())
  {
    return problem;
  }
  std::string materialProblem;
  if (!vtkIlluminationAdapter::ReadMaterials(input, materials, materialProblem) ||
    !vtkIlluminationAdapter::ApplyTextureMeans(input, materials, materialProblem))
  {
    return materialProblem;
  }
  named = withCover && HasSurfaceNames(input);
  if (named)
  {
    const std::string surfaceProblem = ReadSurfaces(input, surfaces);
    if (!surfaceProblem.empty())
    {
      return surfaceProblem;
    }
  }
  return withCover ? MemoryProblem(cover, materials, named ? surfaces.SurfaceCount : 0, memoryLimit)
                   : std::string();
}

/// The exchange balance of `rows` (ExchangeBalance.h; the first 5% of the progress): its
/// factors, by entry. Under MPI (`share`) the ranks balance together, each its own rows, and a
/// rank that stops stops them all. False when stopped, with a warning on the rank whose user
/// stopped it.
bool BalanceFactors(vtkLightPropagationFilter* self,
  const sphcover::SphericalCover& rows,
  const sphcover::RankShare& share,
  std::vector<double>& factors)
{
  // The balance is a few passes over the entries (~1 s for the Cornell box's 6.5M).
  vtkStageProgress progress(self, "Light Propagation: balancing", 0.0, 0.05);
  bool aborted = false;
  const sphcover::ExchangeBalance balance(rows, {}, NotingAbort(progress, aborted), share);
  if (aborted)
  {
    vtkWarningWithObjectMacro(self, "Light propagation aborted.");
  }
  factors = balance.EntryFactors();
  return !balance.Aborted();
}

/// The rank and the rank count whose share of a cover's rows `input` holds (the field array
/// CoverRowShare of vtkSphericalCoverFilter with GatherRows off); {-1, 0} when it holds no
/// share, {-2, 0} when the array is malformed (no rank's).
std::pair<int, int> RowShareOf(vtkDataObject* input)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  vtkDataArray* share = fd ? fd->GetArray(names::CoverRowShare) : nullptr;
  if (!share)
  {
    return { -1, 0 };
  }
  if (share->GetNumberOfComponents() != 2 || share->GetNumberOfTuples() != 1)
  {
    return { -2, 0 };
  }
  return { static_cast<int>(share->GetComponent(0, 0)),
    static_cast<int>(share->GetComponent(0, 1)) };
}

/// "rank r of K's share" or "no share" of a RowShareOf.
std::string ShareName(const std::pair<int, int>& share)
{
  if (share.first == -1)
  {
    return "no share";
  }
  if (share.first < 0)
  {
    return "a malformed share (its CoverRowShare is not one pair of ints)";
  }
  return "rank " + std::to_string(share.first) + " of " + std::to_string(share.second) + "'s share";
}

/// Warns once when the scene has panes (a material's transmittance) but the cover does not see
/// through them (`seesPanes`: the whole cover's HasPanes): a cover saved before panes were seen
/// through (SphericalCover.h, "Panes").
void WarnOfOpaquePanes(vtkLightPropagationFilter* self,
  bool seesPanes,
  const std::vector<sphcover::Material>& materials)
{
  if (!seesPanes &&
    std::any_of(materials.begin(),
      materials.end(),
      [](const sphcover::Material& material) { return material.IsTransmitter(); }))
  {
    vtkWarningWithObjectMacro(self,
      << "The scene has panes (a material's transmittance) but its spherical cover does not "
         "see through them: they are solved as opaque, the transmitted light absorbed. "
         "Rebuild the cover.");
  }
}

/// The progressive shooting of paper §5.1 (5% to 95% of the progress), with the exchange
/// balance's `factors` when there are some (none: the cover's exchange as built); false, with a
/// warning, when aborted.
bool Propagate(vtkLightPropagationFilter* self,
  vtkPolyData* input,
  const std::vector<double>& factors,
  sphcover::LightPropagation& propagation,
  const std::function<void(sphcover::LightPropagation&)>& shareAmongRanks)
{
  sphcover::PropagationSettings settings;
  settings.ConvergenceTolerance = self->GetConvergenceTolerance();
  settings.MaximumShots = static_cast<size_t>(self->GetMaximumShots());
  settings.Order = self->GetShootingOrder() == vtkLightPropagationFilter::FIXED_ORDER
    ? sphcover::ShootingOrder::FixedOrder
    : sphcover::ShootingOrder::BrightestFirst;
  settings.ShotBatch = static_cast<size_t>(self->GetShotBatch());
  // The points' hemisphere frames (vtkSphericalCoverFilter's Normals and Tangents), for the
  // receivers a non-diffuse point's hemisphere does not hold (LightPropagation::SetFrames).
  std::vector<sphcover::HemisphereFrame> frames;
  if (vtkIlluminationAdapter::ReadFrames(input, frames))
  {
    propagation.SetFrames(std::move(frames));
  }
  if (!factors.empty())
  {
    propagation.SetExchangeFactors(factors);
  }
  if (shareAmongRanks)
  {
    shareAmongRanks(propagation);
  }
  bool aborted = false;
  vtkStageProgress progress(self, "Light Propagation: shooting", 0.05, 0.95);
  propagation.Run(settings, NotingAbort(progress, aborted));
  if (aborted)
  {
    vtkWarningWithObjectMacro(self, "Light propagation aborted.");
    return false;
  }
  return true;
}

/// Square metres per squared scene unit, from the input's SceneUnitMetres (1 without it: a scene
/// in metres, or a dataset from elsewhere): the propagation's powers are radiance times
/// solid angle times area in the scene's unit, so this factor makes them watts. False, with
/// the problem, when the array is there but not one finite length > 0.
bool SquareMetresPerUnit(vtkFieldData* fd, double& factor, std::string& problem)
{
  factor = 1.0;
  vtkDataArray* metres = fd ? fd->GetArray(names::SceneUnitMetres) : nullptr;
  if (!metres)
  {
    return true;
  }
  const double value = metres->GetNumberOfTuples() == 1 && metres->GetNumberOfComponents() == 1
    ? metres->GetComponent(0, 0)
    : -1.0;
  if (!(value > 0.0 && std::isfinite(value)))
  {
    problem = "the field data SceneUnitMetres is not one finite length in metres > 0";
    return false;
  }
  factor = value * value;
  return true;
}

/// With the nodes of vtkSphericalCoverFilter's DirectIrradiance on the points, which patches are
/// the lamps (the bright emitters among the points, as the cover filter chose them) and whether
/// the nodes hold the first bounce: the part of the points' Irradiance that the nodes hold, as
/// the cover carries it (CoverLampIrradiance). False without the nodes.
bool LampPatchesOf(vtkPolyData* points,
  const sphcover::SphericalCover& cover,
  const std::vector<sphcover::Material>& materials,
  std::vector<bool>& lampPatch,
  bool& firstBounce)
{
  vtkDataArray* surfaceId = points->GetPointData()->GetArray(names::SurfaceId);
  if (!points->GetPointData()->GetArray(names::DirectIrradiance) || !surfaceId)
  {
    return false;
  }
  vtkDataArray* bounceRays = points->GetFieldData()->GetArray(names::DirectBounceRays);
  firstBounce =
    bounceRays && bounceRays->GetNumberOfTuples() == 1 && bounceRays->GetComponent(0, 0) > 0.0;
  const std::size_t count = cover.PatchCount();
  std::vector<int> surfaces(count);
  std::vector<double> areas(count);
  std::vector<glm::dvec3> emission(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    surfaces[i] = static_cast<int>(surfaceId->GetComponent(static_cast<vtkIdType>(i), 0));
    areas[i] = cover.PatchArea(i);
    emission[i] = materials[i].Emission;
  }
  const std::vector<bool> lampSurface = sphcover::BrightEmitters(surfaces, areas, emission);
  lampPatch.assign(count, false);
  for (std::size_t i = 0; i < count; ++i)
  {
    lampPatch[i] = surfaces[i] >= 0 && lampSurface[static_cast<std::size_t>(surfaces[i])];
  }
  return true;
}

OwnResults OwnResultsOf(const sphcover::LightPropagation& propagation,
  const sphcover::SphericalCover& rows,
  const std::vector<bool>& lampPatch,
  bool firstBounce)
{
  OwnResults own;
  own.Count = propagation.PatchCount();
  own.Lamps = !lampPatch.empty();
  const std::vector<glm::dvec3> lamp =
    own.Lamps ? propagation.LampIrradiance(lampPatch, firstBounce) : std::vector<glm::dvec3>();
  own.Energy = propagation.Energy();
  for (std::size_t i = 0; i < own.Count; ++i)
  {
    if (!propagation.Owns(i))
    {
      continue;
    }
    own.PerPatch.push_back(propagation.Irradiance(i));
    own.PerPatch.push_back(propagation.ExitantRadiance(i));
    own.PerPatch.push_back(propagation.Brightness(i));
    own.PerPatch.push_back(own.Lamps ? lamp[i] : glm::dvec3(0.0));
    own.RowLengths.push_back(rows.EntryEnd(i) - rows.EntryBegin(i));
  }
  own.Incident = propagation.IncidentRadiances();
  return own;
}

void SplitPerPatch(const std::vector<glm::dvec3>& perPatch,
  std::size_t count,
  bool lamps,
  PropagationResults& results)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    results.Irradiance.push_back(perPatch[4 * i]);
    results.Radiosity.push_back(perPatch[4 * i + 1]);
    results.Brightness.push_back(perPatch[4 * i + 2]);
    if (lamps)
    {
      results.Lamp.push_back(perPatch[4 * i + 3]);
    }
  }
}

/// Output 0's own arrays: per point Irradiance, Radiosity and Brightness (and
/// CoverLampIrradiance with the direct light's nodes); in field data the regions'
/// IncidentRadiance, the EnergyBalance (in watts: the powers times `watts`, the square metres
/// of a squared scene unit) and the PropagationStatistics.
void WriteIllumination(const PropagationResults& results,
  int shots,
  double watts,
  vtkPolyData* output)
{
  const vtkIdType count = output->GetNumberOfPoints();
  auto irradiance = vtkNamedArrays::Double(names::Irradiance, 3, count);
  auto radiosity = vtkNamedArrays::Double(names::Radiosity, 3, count);
  auto brightness = vtkNamedArrays::Double(names::Brightness, 3, count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    irradiance->SetTuple(i, &results.Irradiance[static_cast<size_t>(i)][0]);
    radiosity->SetTuple(i, &results.Radiosity[static_cast<size_t>(i)][0]);
    brightness->SetTuple(i, &results.Brightness[static_cast<size_t>(i)][0]);
  }
  output->GetPointData()->AddArray(irradiance);
  output->GetPointData()->AddArray(radiosity);
  output->GetPointData()->AddArray(brightness);
  if (!results.Lamp.empty())
  {
    auto lamp = vtkNamedArrays::Double(names::CoverLampIrradiance, 3, count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      lamp->SetTuple(i, &results.Lamp[static_cast<size_t>(i)][0]);
    }
    output->GetPointData()->AddArray(lamp);
  }

  const std::vector<glm::dvec3>& incident = results.Incident;
  auto regions =
    vtkNamedArrays::Double(names::IncidentRadiance, 3, static_cast<vtkIdType>(incident.size()));
  for (size_t e = 0; e < incident.size(); ++e)
  {
    regions->SetTuple(static_cast<vtkIdType>(e), &incident[e][0]);
  }
  output->GetFieldData()->AddArray(regions);
  const sphcover::EnergyBalance& energy = results.Energy;
  auto balance = vtkNamedArrays::Double(names::EnergyBalance, 3, 2);
  const glm::dvec3 emitted = watts * energy.Emitted;
  const glm::dvec3 absorbed = watts * energy.Absorbed;
  balance->SetTuple(0, &emitted[0]);
  balance->SetTuple(1, &absorbed[0]);
  output->GetFieldData()->AddArray(balance);
  // No time here: a saved solution is the same file for the same input (the seconds per shot
  // are in the History, output 1, which is not part of a solution).
  auto statistics = vtkNamedArrays::Double(names::PropagationStatistics, 1, 1);
  statistics->SetComponentName(0, "Shots");
  statistics->SetComponent(0, 0, static_cast<double>(shots));
  output->GetFieldData()->AddArray(statistics);
}

bool WriteSolution(vtkLightPropagationFilter* self,
  const PropagationResults& results,
  int shots,
  double watts,
  const sphcover::CoverFigures* figures,
  sphcover::PointIllumination surfaces,
  vtkPolyData* output)
{
  WriteIllumination(results, shots, watts, output);
  if (figures)
  {
    const std::string problem = StoreFigures(*figures, std::move(surfaces), output);
    if (!problem.empty())
    {
      output->Initialize();
      vtkErrorWithObjectMacro(self, << "Cannot sum up the solution: " << problem);
      return false;
    }
  }
  return true;
}

/// Output 1: one row per shot (shooter, relative change, unshot energy in watts: the propagation's
/// times `watts`, seconds).
void WriteShotHistory(const std::vector<sphcover::ShotRecord>& shots,
  double watts,
  vtkTable* history)
{
  const vtkIdType rows = static_cast<vtkIdType>(shots.size());
  auto shot = vtkNamedArrays::Int(names::Shot, 1, rows);
  auto shooter = vtkNamedArrays::Int(names::Shooter, 1, rows);
  auto change = vtkNamedArrays::Double(names::MaxChange, 1, rows);
  auto unshot = vtkNamedArrays::Double(names::UnshotEnergy, 1, rows);
  auto seconds = vtkNamedArrays::Double(names::Seconds, 1, rows);
  for (vtkIdType k = 0; k < rows; ++k)
  {
    const sphcover::ShotRecord& record = shots[static_cast<size_t>(k)];
    shot->SetValue(k, static_cast<int>(record.Shot));
    shooter->SetValue(k, static_cast<int>(record.Shooter));
    change->SetValue(k, record.RelativeChange);
    unshot->SetValue(k, watts * record.UnshotEnergy);
    seconds->SetValue(k, record.Seconds);
  }
  history->Initialize();
  history->AddColumn(shot);
  history->AddColumn(shooter);
  history->AddColumn(change);
  history->AddColumn(unshot);
  history->AddColumn(seconds);
}
}

vtkStandardNewMacro(vtkLightPropagationFilter);

std::string vtkLightPropagationFilter::AddSolutionFigures(vtkPolyData* illumination)
{
  if (!illumination)
  {
    return "no illumination";
  }
  sphcover::SphericalCover cover;
  sphcover::PointIllumination surfaces;
  sphcover::CoverFigures figures;
  std::string problem = vtkSphericalCoverArrays::Load(illumination, cover);
  if (problem.empty())
  {
    problem = ReadSurfaces(illumination, surfaces);
  }
  if (problem.empty())
  {
    problem = CoverFiguresOf(cover, surfaces, figures);
  }
  return problem.empty() ? StoreFigures(figures, std::move(surfaces), illumination) : problem;
}

vtkLightPropagationFilter::vtkLightPropagationFilter()
{
  // ParaView's status bar labels progress with this text (vtkStageProgress.h).
  this->SetProgressText("Light Propagation");
  this->SetNumberOfOutputPorts(2);
}

vtkLightPropagationFilter::~vtkLightPropagationFilter() = default;

int vtkLightPropagationFilter::FillInputPortInformation(int, vtkInformation* info)
{
  // Any dataset is accepted so that a wrong one (the reader's surfaces) gets one clear error
  // from RequestData instead of the executive's type error at every pipeline pass.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkLightPropagationFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

int vtkLightPropagationFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* inputData = vtkDataSet::GetData(inputVector[0], 0);
  vtkPolyData* input = vtkPolyData::SafeDownCast(inputData);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* history = vtkTable::GetData(outputVector, 1);
  this->Shots = 0;
  const std::pair<int, int> rowShare = RowShareOf(inputData);
  if (rowShare.first != -1)
  {
    // A share lacks the other ranks' rows (vtkPLightPropagationFilter propagates it there).
    output->Initialize();
    history->Initialize();
    vtkErrorMacro(<< "Cannot propagate light: the input holds " << ShareName(rowShare)
                  << " of a cover's rows (vtkSphericalCoverFilter with GatherRows off), which "
                     "propagates only on those ranks together in the BrightestFirst order; "
                     "gather the rows (GatherRows on) to propagate it here.");
    return 0;
  }
  // Pieces > 0 idle: the whole scene is piece 0 (vtkScenePieces.h).
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, inputData);
  if (role != vtkScenePieces::Role::WholeScene)
  {
    output->Initialize();
    history->Initialize();
    if (role == vtkScenePieces::Role::PartialScene)
    {
      vtkErrorMacro(<< "Cannot propagate light: " << vtkScenePieces::PartialSceneError(outputVector)
                    << ".");
      return 0;
    }
    return 1;
  }
  if (!input)
  {
    vtkErrorMacro(<< "Cannot propagate light: the input is a "
                  << (inputData ? inputData->GetClassName() : "null data object")
                  << ", not the cover points (vtkPolyData) of vtkSphericalCoverFilter.");
    return 0;
  }

  sphcover::SphericalCover rows;
  std::vector<sphcover::Material> materials;
  bool named = false;
  sphcover::PointIllumination surfaces;
  sphcover::CoverFigures figures;
  std::string problem =
    ReadPropagationInput(input, true, false, this->MemoryLimit, rows, materials, named, surfaces);
  double watts = 1.0;
  if (problem.empty())
  {
    SquareMetresPerUnit(input->GetFieldData(), watts, problem);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot propagate light: " << problem);
    return 0;
  }
  if (named)
  {
    problem = CoverFiguresOf(rows, surfaces, figures);
    if (!problem.empty())
    {
      vtkErrorMacro(<< "Cannot sum up the solution: " << problem);
      return 0;
    }
  }
  WarnOfOpaquePanes(this, rows.HasPanes(), materials);

  PropagationResults results;
  try
  {
    // One process: every receiver's row is this process's.
    const sphcover::RankShare alone;
    std::vector<double> factors;
    if (this->BalanceExchanges && !BalanceFactors(this, rows, alone, factors))
    {
      return 0;
    }
    std::vector<bool> lampPatch;
    bool firstBounce = false;
    LampPatchesOf(input, rows, materials, lampPatch, firstBounce);
    auto propagation = std::make_unique<sphcover::LightPropagation>(rows, materials);
    if (!Propagate(this, input, factors, *propagation, nullptr))
    {
      return 0;
    }
    OwnResults own = OwnResultsOf(*propagation, rows, lampPatch, firstBounce);
    const std::vector<sphcover::ShotRecord>& shots = propagation->History();
    this->Shots = static_cast<int>(shots.size());
    WriteShotHistory(shots, watts, history);
    propagation.reset();
    rows = sphcover::SphericalCover();
    results.Energy = own.Energy;
    results.Incident = std::move(own.Incident);
    SplitPerPatch(own.PerPatch, own.Count, own.Lamps, results);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Light propagation failed: " << e.what());
    return 0;
  }
  output->ShallowCopy(input);
  if (!WriteSolution(
        this, results, this->Shots, watts, named ? &figures : nullptr, std::move(surfaces), output))
  {
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkLightPropagationFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ConvergenceTolerance: " << this->ConvergenceTolerance << "\n";
  os << indent << "MaximumShots: " << this->MaximumShots << "\n";
  os << indent << "ShootingOrder: "
     << (this->ShootingOrder == BRIGHTEST_FIRST ? "BrightestFirst" : "FixedOrder") << "\n";
  os << indent << "ShotBatch: " << this->ShotBatch << "\n";
  os << indent << "BalanceExchanges: " << (this->BalanceExchanges ? "On" : "Off") << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "Shots: " << this->Shots << "\n";
}
