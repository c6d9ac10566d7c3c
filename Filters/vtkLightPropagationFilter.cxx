// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLightPropagationFilter.h"

#include "vtkCoverDistribution.h"
#include "vtkHeldMessages.h"
#include "vtkIlluminationAdapter.h"
#include "vtkNamedArrays.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkStageProgress.h"

#include "cover/BrightEmitters.h"
#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "distributed/RowBlockBytes.h"
#include "distributed/RowShares.h"
#include "distributed/SharedPropagation.h"
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
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

namespace names = vtkSphericalCoverArrayNames;

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
  // One component per named surface (VTK keeps at least one, for a scene without surfaces).
  auto factors =
    vtkNamedArrays::Double(names::SurfaceFormFactors, static_cast<int>(surfaces), surfaces);
  auto* surfaceNames =
    vtkStringArray::SafeDownCast(points->GetFieldData()->GetAbstractArray(names::SurfaceNames));
  for (vtkIdType a = 0; a < surfaces; ++a)
  {
    const sphcover::SurfaceFigures& surface = figures.Surfaces[static_cast<size_t>(a)];
    area->SetValue(a, surface.Area);
    meanIrradiance->SetTuple(a, &surface.MeanIrradiance[0]);
    meanRadiance->SetTuple(a, &surface.MeanExitantRadiance[0]);
    factors->SetTuple(a, &figures.FormFactors[static_cast<size_t>(a * surfaces)]);
    factors->SetComponentName(a, surfaceNames->GetValue(a).c_str());
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
  fd->AddArray(factors);
  fd->AddArray(statistics);
  return std::string();
}

/// "" when the propagation of `rows` fits in `memoryLimit` MiB, else the problem.
std::string MemoryProblem(const sphcover::SphericalCover& rows,
  const std::vector<sphcover::Material>& materials,
  double memoryLimit)
{
  const double needed =
    static_cast<double>(sphcover::LightPropagation::EstimateBytes(rows, materials)) /
    (1024.0 * 1024.0);
  if (needed > memoryLimit)
  {
    std::ostringstream text;
    text << "it would need about " << static_cast<int>(needed) << " MiB (state of "
         << rows.EntryCount() << " regions and weight tables of a " << rows.Options().ThetaBins
         << " x " << rows.Options().PhiBins << " grid), more than MemoryLimit (" << memoryLimit
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
  return withCover ? MemoryProblem(cover, materials, memoryLimit) : std::string();
}

/// Under MPI: the ranks that propagate together, this rank's receivers, and whether every rank
/// writes the solution (else rank 0 alone, and the results are gathered there).
struct PropagationRanks
{
  vtkMultiProcessController* Controller = nullptr;
  bool EveryRankWrites = true;
  /// The solution kept in pieces (GatherSolution off): each rank keeps its own rows' regions.
  bool KeepsOwnRegions = false;
  sphcover::RankShare Share;
};

/// Core's progress callback through `progress`, noting in `aborted` that the user stopped it.
std::function<bool(double)> NotingAbort(vtkStageProgress& progress, bool& aborted)
{
  return [&progress, &aborted](double fraction)
  {
    aborted = !progress(fraction);
    return !aborted;
  };
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

/**
 * The whole cover into `whole` on rank 0, joined from the ranks' shares (CoverHeld::Shares:
 * each rank's `rows`, let go as they are sent); nothing on the other ranks. Collective; what
 * rank 0 finds wrong in the shares ("" when nothing), for the ranks to agree on.
 */
std::string GatherShares(vtkMultiProcessController* controller,
  sphcover::SphericalCover rows,
  sphcover::SphericalCover& whole)
{
  const sphcover::SphericalCoverOptions options = rows.Options();
  std::vector<std::vector<char>> all = vtkCoverDistribution::GatherBytes(
    controller, sphcover::PackRowBlock(std::move(rows).ExportArrays(), {}), false);
  std::string problem;
  if (all.empty())
  {
    return problem; // rank 0 joins
  }
  std::vector<sphcover::SphericalCover::Arrays> shares(all.size());
  for (std::size_t r = 0; r < all.size() && problem.empty(); ++r)
  {
    sphcover::CullingStatistics culling;
    problem = sphcover::UnpackRowBlock(all[r].data(), all[r].size(), shares[r], culling);
    if (!problem.empty())
    {
      problem = "rank " + std::to_string(r) + "'s share of the cover: " + problem;
    }
    all[r] = std::vector<char>();
  }
  if (problem.empty())
  {
    problem = sphcover::RowShares::JoinRows(whole, std::move(shares), options, {});
    if (!problem.empty())
    {
      problem = "the ranks' shares of the cover: " + problem;
    }
  }
  return problem;
}

/**
 * The cover's part of the figures on rank 0 when no rank holds the whole cover (a solution
 * kept in pieces of shares): each rank's rows' form-factor sums (SphericalCover::
 * FormFactorSums) and strip counts, joined in receiver order, give the whole cover's figures
 * bit for bit. Collective; "" or the problem, on the rank that meets it.
 */
std::string JoinCoverFigures(const sphcover::RankShare& share,
  const sphcover::SphericalCover& rows,
  const sphcover::PointIllumination& surfaces,
  sphcover::CoverFigures& figures)
{
  using GroupSum = sphcover::SphericalCover::GroupSum;
  std::vector<uint64_t> counts;
  std::vector<GroupSum> sums;
  std::string problem;
  try
  {
    std::vector<std::vector<GroupSum>> rowSums =
      rows.FormFactorSums(surfaces.SurfaceOfPoint, surfaces.SurfaceCount);
    for (const std::size_t i : share.MyItems(rows.PatchCount()))
    {
      counts.push_back(rowSums[i].size());
      sums.insert(sums.end(), rowSums[i].begin(), rowSums[i].end());
    }
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  const uint64_t strips = rows.StripCount();
  std::vector<char> bytes;
  sphcover::ByteWriter writer(bytes);
  writer.Value(strips);
  writer.Array(counts);
  writer.Array(sums);
  std::vector<std::vector<char>> all;
  if (!share.Join(bytes, problem.empty(), all))
  {
    return problem.empty() ? "another rank could not sum up its rows' form factors" : problem;
  }
  if (share.Rank() != 0)
  {
    return problem;
  }
  // Every receiver's sums from its rank, in receiver order.
  const std::size_t count = rows.PatchCount();
  std::vector<std::vector<GroupSum>> rowSums(count);
  figures.Strips = 0;
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    sphcover::ByteReader reader(all[r]);
    uint64_t rankStrips = 0;
    const std::size_t items = r < count ? (count - r + all.size() - 1) / all.size() : 0;
    if (!reader.Value(rankStrips) || !reader.Array(counts) || !reader.Array(sums) ||
      counts.size() != items)
    {
      return "rank " + std::to_string(r) + "'s form-factor sums are malformed";
    }
    figures.Strips += static_cast<std::size_t>(rankStrips);
    std::size_t next = 0;
    std::size_t k = 0;
    for (std::size_t i = r; i < count; i += all.size(), ++k)
    {
      if (counts[k] > sums.size() - next)
      {
        return "rank " + std::to_string(r) + "'s form-factor sums are malformed";
      }
      rowSums[i].assign(sums.begin() + static_cast<std::ptrdiff_t>(next),
        sums.begin() + static_cast<std::ptrdiff_t>(next + counts[k]));
      next += counts[k];
    }
  }
  std::vector<double> areas(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    areas[i] = rows.PatchArea(i);
  }
  try
  {
    figures.FormFactors = sphcover::SphericalCover::FormFactorsOf(
      rowSums, surfaces.SurfaceOfPoint, surfaces.SurfaceCount, areas);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  figures.CharacteristicPoints = count;
  return std::string();
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

/// Rank `rank`'s (of `ranks`) rows of `cover`: those of its receivers rank, rank + K, ...
/// (RankShare::MyItems, as sphcover::SharePropagation takes them).
sphcover::SphericalCover RowsOfRank(const sphcover::SphericalCover& cover, int rank, int ranks)
{
  return sphcover::RowShares::RowsOf(
    cover, sphcover::RankShare::ItemsOf(rank, ranks, cover.PatchCount()));
}

/**
 * Rank 0 holds the whole `cover`, keeps its own rows and deals every other rank its rows
 * (vtkCoverDistribution::DealFromFirst), one rank at a time; the other ranks hold none and
 * receive theirs. Collective; throws what the bytes' reading finds wrong.
 */
sphcover::SphericalCover DealRows(vtkMultiProcessController* controller,
  const sphcover::SphericalCover& cover)
{
  const bool dealer = controller->GetLocalProcessId() == 0;
  const int ranks = controller->GetNumberOfProcesses();
  const std::vector<char> bytes = vtkCoverDistribution::DealFromFirst(controller,
    [&](int rank)
    {
      // One copy of the rank's rows at a time beside the cover (they are a K-th of it).
      sphcover::SphericalCover::Arrays arrays = RowsOfRank(cover, rank, ranks).ExportArrays();
      return sphcover::PackRowBlock(arrays, {});
    });
  if (dealer)
  {
    return RowsOfRank(cover, 0, ranks);
  }
  sphcover::SphericalCover mine;
  sphcover::SphericalCover::Arrays arrays;
  sphcover::CullingStatistics culling;
  std::string problem = sphcover::UnpackRowBlock(bytes.data(), bytes.size(), arrays, culling);
  if (problem.empty())
  {
    problem = mine.ImportArrays(std::move(arrays));
  }
  if (!problem.empty())
  {
    throw std::runtime_error("the rows dealt to this rank are damaged: " + problem);
  }
  return mine;
}

/// The progressive shooting of paper §5.1 (5% to 95% of the progress), with the exchange
/// balance's `factors` when there are some (none: the cover's exchange as built); false, with a
/// warning, when aborted.
bool Propagate(vtkLightPropagationFilter* self,
  vtkPolyData* input,
  const PropagationRanks& ranks,
  const std::vector<double>& factors,
  sphcover::LightPropagation& propagation)
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
  if (ranks.Share.Distributed())
  {
    sphcover::SharePropagation(propagation, ranks.Share);
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

/// What the outputs are written from: per point and per region the propagation's results
/// (under MPI gathered from the ranks, ResultsOf), the energy and the history.
struct PropagationResults
{
  std::vector<glm::dvec3> Irradiance;
  std::vector<glm::dvec3> Radiosity;
  std::vector<glm::dvec3> Brightness;
  /// CoverLampIrradiance (empty without the direct light's nodes).
  std::vector<glm::dvec3> Lamp;
  std::vector<glm::dvec3> Incident;
  sphcover::EnergyBalance Energy;
};

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

/// This rank's part of the results: per own patch (RankShare::MyItems) its irradiance,
/// radiosity, brightness and lamp irradiance, its row's length and the incident radiance of its
/// row's regions, and the energy. Collective under MPI (the lamps' irradiance and the energy
/// join inside).
struct OwnResults
{
  std::vector<glm::dvec3> PerPatch;
  std::vector<uint64_t> RowLengths;
  std::vector<glm::dvec3> Incident;
  sphcover::EnergyBalance Energy;
  std::size_t Count = 0;
  bool Lamps = false;
};

OwnResults OwnResultsOf(const sphcover::LightPropagation& propagation,
  const sphcover::SphericalCover& rows,
  const std::vector<bool>& lampPatch,
  bool firstBounce)
{
  OwnResults own;
  own.Count = propagation.PatchCount();
  own.Lamps = !lampPatch.empty();
  const std::vector<glm::dvec3> lamp = own.Lamps
    ? propagation.LampIrradiance(lampPatch, firstBounce)
    : std::vector<glm::dvec3>();
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

/// The results of every patch and region: this rank's own alone, or under MPI (collective)
/// each rank's patches and rows put back in patch order (the ranks' own patches are dealt
/// round them: RankShare::MyItems), on every rank or on rank 0 alone.
PropagationResults JoinResults(const PropagationRanks& ranks, OwnResults own)
{
  const bool everyRank = ranks.EveryRankWrites || !ranks.Controller;
  const bool writer = everyRank || ranks.Controller->GetLocalProcessId() == 0;
  // Every rank's values of its own patches, item k's lengths[k] of them, in patch order on the
  // ranks that write (empty on the others).
  const auto join = [&ranks, everyRank, writer](
                      const auto& values, const std::vector<std::size_t>& lengths)
  {
    using Value = typename std::decay_t<decltype(values)>::value_type;
    std::vector<char> bytes;
    sphcover::ByteWriter(bytes).Values(values.data(), values.size());
    std::vector<std::vector<char>> all;
    if (everyRank)
    {
      if (!ranks.Share.Join(bytes, true, all))
      {
        throw sphcover::RankShare::PeerFailure();
      }
    }
    else
    {
      all = vtkCoverDistribution::GatherBytes(ranks.Controller, std::move(bytes), false);
    }
    return writer ? sphcover::ItemsFromRanks<Value>(all, lengths) : std::vector<Value>();
  };
  PropagationResults results;
  results.Energy = own.Energy;
  const std::vector<uint64_t> rowLengths =
    join(own.RowLengths, std::vector<std::size_t>(own.Count, 1));
  const std::vector<glm::dvec3> perPatch =
    join(own.PerPatch, std::vector<std::size_t>(own.Count, 4));
  own.PerPatch = std::vector<glm::dvec3>();
  if (ranks.KeepsOwnRegions)
  {
    results.Incident = std::move(own.Incident);
  }
  else
  {
    results.Incident =
      join(own.Incident, std::vector<std::size_t>(rowLengths.begin(), rowLengths.end()));
    own.Incident = std::vector<glm::dvec3>();
  }
  if (!writer)
  {
    return results; // rank 0 writes the solution
  }
  for (std::size_t i = 0; i < own.Count; ++i)
  {
    results.Irradiance.push_back(perPatch[4 * i]);
    results.Radiosity.push_back(perPatch[4 * i + 1]);
    results.Brightness.push_back(perPatch[4 * i + 2]);
    if (own.Lamps)
    {
      results.Lamp.push_back(perPatch[4 * i + 3]);
    }
  }
  return results;
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
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkLightPropagationFilter::~vtkLightPropagationFilter()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkLightPropagationFilter, Controller, vtkMultiProcessController);

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
  this->RankFigures.clear();
  this->RankCount = 1;

  // Pieces > 0 idle: the whole scene is piece 0 (vtkScenePieces.h).
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, inputData);
  // Under MPI the ranks propagate together (see the header); the count is collective, so it
  // comes before any rank returns.
  vtkMultiProcessController* controller = this->Controller;
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  const std::pair<int, int> rowShare = RowShareOf(inputData);
  if (ranks > 1 && this->ShootingOrder == BRIGHTEST_FIRST)
  {
    const int rank = controller->GetLocalProcessId();
    if (vtkCoverDistribution::Count(controller, rowShare.first != -1) > 0)
    {
      // The cover kept on the ranks (vtkSphericalCoverFilter's GatherRows off): each must hold
      // its own share.
      std::string problem;
      if (rowShare.first != rank || rowShare.second != ranks)
      {
        problem = "this rank's input holds " + ShareName(rowShare) + " of the cover's rows, not " +
          ShareName({ rank, ranks }) + ": build the cover on these ranks, or gather its rows " +
          "(vtkSphericalCoverFilter's GatherRows)";
      }
      problem = vtkCoverDistribution::Agree(controller, problem);
      if (!problem.empty())
      {
        output->Initialize();
        history->Initialize();
        vtkErrorMacro(<< "Cannot propagate light: " << problem << ".");
        return 0;
      }
      return this->PropagateOnRanks(controller, input, output, history, CoverHeld::Shares);
    }
    const bool whole = role == vtkScenePieces::Role::WholeScene;
    if (vtkCoverDistribution::Count(controller, whole) == ranks)
    {
      return this->PropagateOnRanks(controller, input, output, history);
    }
    return this->PropagateFromFirst(
      controller, static_cast<int>(role), outputVector, input, output, history);
  }
  if (rowShare.first != -1)
  {
    // One process, or FixedOrder on each alone: a share lacks the other ranks' rows.
    output->Initialize();
    history->Initialize();
    vtkErrorMacro(<< "Cannot propagate light: the input holds " << ShareName(rowShare)
                  << " of a cover's rows (vtkSphericalCoverFilter with GatherRows off), which "
                     "propagates only on those ranks together in the BrightestFirst order; "
                     "gather the rows (GatherRows on) to propagate it here.");
    return 0;
  }
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

  return this->PropagateOnRanks(nullptr, input, output, history);
}

int vtkLightPropagationFilter::PropagateFromFirst(vtkMultiProcessController* controller,
  int role,
  vtkInformationVector* outputVector,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkTable* history)
{
  // pvbatch and pvserver: rank 0 holds the cover (piece 0), the others empty pieces. Every rank
  // gets rank 0's points without the cover (their materials, frames and lamps: small), rank 0
  // deals each rank its rows, the ranks propagate together and rank 0 writes the solution; the
  // others keep empty outputs (vtkScenePieces.h) and never hold the whole cover.
  output->Initialize();
  history->Initialize();
  const int rank = controller->GetLocalProcessId();
  const auto pieceRole = static_cast<vtkScenePieces::Role>(role);
  std::string problem;
  if (pieceRole == vtkScenePieces::Role::PartialScene)
  {
    problem = vtkScenePieces::PartialSceneError(outputVector);
  }
  else if (rank == 0 && pieceRole != vtkScenePieces::Role::WholeScene)
  {
    problem = "rank 0 must hold the whole cover (piece 0)";
  }
  else if (rank != 0 && pieceRole == vtkScenePieces::Role::WholeScene)
  {
    problem = "some ranks other than rank 0 hold piece 0, but not all";
  }
  else if (rank == 0 && !input)
  {
    problem = "the input is not the cover points (vtkPolyData) of vtkSphericalCoverFilter";
  }
  problem = vtkCoverDistribution::Agree(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot propagate light: " << problem << ".");
    return 0;
  }
  vtkNew<vtkPolyData> points;
  if (rank == 0)
  {
    points->ShallowCopy(input);
    vtkNew<vtkFieldData> withoutCover;
    vtkFieldData* fd = input->GetFieldData();
    for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = fd->GetAbstractArray(a);
      if (!vtkSphericalCoverArrays::IsCoverArray(array->GetName()))
      {
        withoutCover->AddArray(array);
      }
    }
    points->SetFieldData(withoutCover);
  }
  vtkCoverDistribution::BroadcastFromFirst(controller, points);
  return this->PropagateOnRanks(
    controller, rank == 0 ? input : points.Get(), output, history, CoverHeld::FirstRank);
}

int vtkLightPropagationFilter::PropagateOnRanks(vtkMultiProcessController* controller,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkTable* history,
  CoverHeld held)
{
  // One process, or the ranks together (see the header): every rank reads the same cover (or,
  // FirstRank, rank 0 reads it and the others its points; or, Shares, every rank its share) and
  // agrees on each step before the next collective one, so that a failure is one error on
  // every rank and none waits for ever (vtkCoverDistribution.h).
  auto agree = [controller](const std::string& problem)
  { return controller ? vtkCoverDistribution::Agree(controller, problem) : problem; };
  const bool first = !controller || controller->GetLocalProcessId() == 0;
  // Whether this rank reads a cover from its input, whether that cover is the whole one, and
  // whether this rank writes the solution.
  const bool readsCover = held != CoverHeld::FirstRank || first;
  const bool wholeCover = readsCover && held != CoverHeld::Shares;
  // GatherSolution off: every rank keeps its piece of the solution (its rows and their regions).
  const bool pieces = controller && !this->GatherSolution;
  const bool writer = pieces || held == CoverHeld::EveryRank || first;
  std::string problem;
  if (!input)
  {
    problem = "the input is not the cover points (vtkPolyData) of vtkSphericalCoverFilter.";
  }
  sphcover::SphericalCover cover;
  std::vector<sphcover::Material> materials;
  bool named = false;
  sphcover::PointIllumination surfaces;
  sphcover::CoverFigures figures;
  if (problem.empty())
  {
    // Under MPI a rank propagates its rows: their state must fit, checked when they are known.
    problem = ReadPropagationInput(input,
      readsCover,
      held == CoverHeld::Shares,
      controller ? std::numeric_limits<double>::infinity() : this->MemoryLimit,
      cover,
      materials,
      named,
      surfaces);
  }
  double watts = 1.0;
  if (problem.empty())
  {
    SquareMetresPerUnit(input->GetFieldData(), watts, problem);
  }
  if (!problem.empty())
  {
    problem = "Cannot propagate light: " + problem;
  }
  else if (wholeCover && named)
  {
    // The cover's part of the figures now: under MPI the cover is let go before the
    // propagation (below). Of shares, on rank 0 once it has gathered them.
    problem = CoverFiguresOf(cover, surfaces, figures);
    if (!problem.empty())
    {
      problem = "Cannot sum up the solution: " + problem;
    }
  }
  problem = agree(problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  if (wholeCover)
  {
    WarnOfOpaquePanes(this, cover.HasPanes(), materials);
  }

  PropagationRanks ranks;
  sphcover::SphericalCover rows;
  // Shares: the whole cover's arrays, gathered on rank 0 for the solution.
  vtkNew<vtkPolyData> gatheredCover;
  std::vector<bool> lampPatch;
  bool firstBounce = false;
  PropagationResults results;
  try
  {
    // A step the user can abort (its warning held under MPI): the ranks agree on whether some
    // rank stopped, so that all stop together with its message as the error. True: go on.
    // The agreed error goes out after the held messages are let go (they would hold it too).
    auto completedOnEveryRank = [this, controller, &agree](const std::function<bool()>& step)
    {
      std::string stopped;
      {
        vtkHeldMessages held(controller ? this : nullptr);
        stopped = step() ? std::string() : held.First("Light propagation aborted.");
      }
      stopped = agree(stopped);
      if (!stopped.empty() && controller)
      {
        vtkErrorMacro(<< stopped);
      }
      return stopped.empty();
    };
    if (!controller)
    {
      rows = std::move(cover);
    }
    else
    {
      // Rank r shoots into the rows of its receivers. A rank keeps (or is dealt) its rows and
      // the whole cover goes before the balance and the propagation's state exist: the memory
      // that falls with the ranks. Its state must fit MemoryLimit, not the whole cover's.
      ranks.Share = vtkCoverDistribution::ShareOf(controller);
      ranks.Controller = controller;
      ranks.EveryRankWrites = held == CoverHeld::EveryRank || pieces;
      ranks.KeepsOwnRegions = pieces;
      if (held == CoverHeld::Shares)
      {
        rows = std::move(cover);
        const std::size_t foreign = sphcover::RowShares::FirstForeignRow(rows, ranks.Share);
        if (foreign < rows.PatchCount())
        {
          problem = "this rank's share of the cover holds the row of receiver " +
            std::to_string(foreign) + ", which another rank owns";
        }
      }
      else
      {
        rows = held == CoverHeld::FirstRank
          ? DealRows(controller, cover)
          : RowsOfRank(cover, controller->GetLocalProcessId(), controller->GetNumberOfProcesses());
      }
      cover = sphcover::SphericalCover();
      problem =
        agree(problem.empty() ? MemoryProblem(rows, materials, this->MemoryLimit) : problem);
      if (!problem.empty())
      {
        vtkErrorMacro(<< "Cannot propagate light: " << problem);
        return 0;
      }
    }
    // Under MPI the ranks balance the exchange together, each its own rows.
    std::vector<double> factors;
    if (this->BalanceExchanges &&
      !completedOnEveryRank([&] { return BalanceFactors(this, rows, ranks.Share, factors); }))
    {
      return 0;
    }
    LampPatchesOf(input, rows, materials, lampPatch, firstBounce);
    auto propagation = std::make_unique<sphcover::LightPropagation>(rows, materials);
    if (!completedOnEveryRank([&] { return Propagate(this, input, ranks, factors, *propagation); }))
    {
      return 0;
    }
    OwnResults own = OwnResultsOf(*propagation, rows, lampPatch, firstBounce);
    const std::vector<sphcover::ShotRecord>& shots = propagation->History();
    if (controller)
    {
      // What each rank held and did (GetRankFigures), gathered in rank order.
      const double done[4] = { static_cast<double>(own.RowLengths.size()),
        static_cast<double>(rows.EntryCount()),
        static_cast<double>(sphcover::LightPropagation::EstimateBytes(rows, materials)),
        shots.empty() ? 0.0 : shots.back().Seconds };
      this->RankFigures = sphcover::JoinValues(ranks.Share, done, 4, true);
      this->RankCount = controller->GetNumberOfProcesses();
    }
    this->Shots = static_cast<int>(shots.size());
    if (writer)
    {
      WriteShotHistory(shots, watts, history);
    }
    // The propagation's state goes before the ranks' results are joined: the join holds every
    // rank's regions, and beside the state it was each rank's peak memory.
    propagation.reset();
    factors = std::vector<double>();
    if (held == CoverHeld::Shares && !pieces)
    {
      // The solution holds the whole cover: rank 0 gathers the shares (the ranks' rows) now,
      // holding neither the propagation's state nor the joined results, then sums up its
      // figures and keeps its arrays alone (the whole cover goes before the results come).
      problem = GatherShares(controller, std::move(rows), cover);
      if (first && problem.empty() && named)
      {
        problem = CoverFiguresOf(cover, surfaces, figures);
        if (!problem.empty())
        {
          problem = "Cannot sum up the solution: " + problem;
        }
      }
      else if (!problem.empty())
      {
        problem = "Light propagation failed: " + problem;
      }
      problem = agree(problem);
      if (!problem.empty())
      {
        history->Initialize();
        vtkErrorMacro(<< problem);
        return 0;
      }
      if (first)
      {
        WarnOfOpaquePanes(this, cover.HasPanes(), materials);
        vtkSphericalCoverArrays::Store(std::move(cover).ExportArrays(), gatheredCover);
      }
    }
    else if (held == CoverHeld::Shares)
    {
      // Kept in pieces: no rank holds the whole cover; rank 0 sums up the figures from the
      // ranks' rows.
      problem = named ? JoinCoverFigures(ranks.Share, rows, surfaces, figures) : "";
      problem = agree(problem.empty() ? problem : "Cannot sum up the solution: " + problem);
      if (!problem.empty())
      {
        history->Initialize();
        vtkErrorMacro(<< problem);
        return 0;
      }
      const bool seesPanes = vtkCoverDistribution::Count(controller, rows.HasPanes()) > 0;
      if (first)
      {
        WarnOfOpaquePanes(this, seesPanes, materials);
      }
    }
    if (!pieces)
    {
      rows = sphcover::SphericalCover(); // sent and let go already when shares
    }
    results = JoinResults(ranks, std::move(own));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Light propagation failed: " << e.what());
    return 0;
  }
  if (!writer)
  {
    return 1; // rank 0 writes the solution
  }
  output->ShallowCopy(input);
  if (pieces && held != CoverHeld::Shares)
  {
    // This rank's rows in place of the cover it was given (a share's arrays are its rows
    // already), marked as its share.
    vtkFieldData* fd = output->GetFieldData();
    for (int a = fd->GetNumberOfArrays() - 1; a >= 0; --a)
    {
      if (vtkSphericalCoverArrays::IsCoverArray(fd->GetAbstractArray(a)->GetName()))
      {
        fd->RemoveArray(a);
      }
    }
    vtkSphericalCoverArrays::Store(std::move(rows).ExportArrays(), output);
    rows = sphcover::SphericalCover();
    vtkSphericalCoverArrays::MarkShare(output, ranks.Share.Rank(), ranks.Share.Ranks());
  }
  else if (held == CoverHeld::Shares && !pieces)
  {
    // The whole cover's arrays in place of this rank's share (referenced, not copied).
    vtkFieldData* fd = gatheredCover->GetFieldData();
    for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
    {
      output->GetFieldData()->AddArray(fd->GetAbstractArray(a));
    }
    output->GetFieldData()->RemoveArray(names::CoverRowShare);
  }
  WriteIllumination(results, this->Shots, watts, output);
  // The figures sum up the whole: of a cover in shares, rank 0 alone sums them up.
  if (named && (wholeCover || first))
  {
    const std::string figuresProblem = StoreFigures(figures, std::move(surfaces), output);
    if (!figuresProblem.empty())
    {
      output->Initialize();
      vtkErrorMacro(<< "Cannot sum up the solution: " << figuresProblem);
      return 0;
    }
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
  os << indent << "GatherSolution: " << (this->GatherSolution ? "On" : "Off") << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "Shots: " << this->Shots << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
