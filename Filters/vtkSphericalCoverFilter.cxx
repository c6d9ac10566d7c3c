// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSphericalCoverFilter.h"
#include "vtkSphericalCoverSteps.h"

#include "vtkNamedArrays.h"
#include "vtkSMPParallelFor.h"
#include "vtkScenePieces.h"
#include "vtkSceneSettingsArray.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkStageProgress.h"
#include "vtkSurfaceGridAdapter.h"
#include "vtkSurfaceGridBuilder.h"

#include "cover/BrightEmitters.h"
#include "cover/CoverRefinement.h"
#include "cover/DirectIrradiance.h"
#include "cover/HemisphereGrid.h"
#include "cover/RayCastFill.h"
#include "cover/SphericalCover.h"
#include "geometry/RayCaster.h"
#include "math/Constants.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace names = vtkSphericalCoverArrayNames;
using namespace vtkSphericalCoverSteps;

namespace
{
/// The (theta, phi) grid of the input's settings: the subdivision's (SubdivisionSettings:
/// max_level, theta_bins, phi_bins, ...), else the scene's (SceneSettings: theta_bins,
/// phi_bins, ...), else the scene file's defaults.
void GridOf(vtkDataObject* input, int& thetaBins, int& phiBins)
{
  vtkFieldData* fd = input->GetFieldData();
  const sphcover::SceneSettings scene = vtkSceneSettingsArray::Read(fd);
  thetaBins = scene.ThetaBins;
  phiBins = scene.PhiBins;
  vtkDataArray* subdivision = fd->GetArray(names::SubdivisionSettings);
  // 7 components in files written before min_patch_size, 8 since.
  if (subdivision && subdivision->GetNumberOfComponents() >= 7 &&
    subdivision->GetNumberOfTuples() == 1)
  {
    thetaBins = static_cast<int>(subdivision->GetComponent(0, 1));
    phiBins = static_cast<int>(subdivision->GetComponent(0, 2));
  }
}

/// The cover's options from the filter's properties, the grid left at SCENE_SETTING being the
/// input's (the subdivision's or the scene's); false, with the error reported, for an empty grid.
bool CoverOptionsOf(vtkSphericalCoverFilter* self,
  vtkDataObject* input,
  sphcover::SphericalCoverOptions& options)
{
  int inputTheta = 0;
  int inputPhi = 0;
  GridOf(input, inputTheta, inputPhi);
  const int sceneSetting = vtkSphericalCoverFilter::SCENE_SETTING;
  options.ThetaBins = self->GetThetaBins() == sceneSetting ? inputTheta : self->GetThetaBins();
  options.PhiBins = self->GetPhiBins() == sceneSetting ? inputPhi : self->GetPhiBins();
  if (options.ThetaBins < 1 || options.PhiBins < 1)
  {
    vtkErrorWithObjectMacro(self,
      << "Cannot build the spherical cover: ThetaBins and PhiBins must be >= 1 (or "
      << vtkSphericalCoverFilter::SCENE_SETTING << ", the input's grid), got " << options.ThetaBins
      << " and " << options.PhiBins << ".");
    return false;
  }
  options.SamplesTheta = self->GetSamplesPerCell();
  options.SamplesPhi = self->GetSamplesPerCell();
  options.Fill = self->GetFillMethod() == vtkSphericalCoverFilter::RAY_CASTING
    ? sphcover::RBufferFill::RayCasting
    : sphcover::RBufferFill::Projection;
  options.FillOptions.BackFacesOcclude = self->GetBackFacesOcclude();
  return true;
}

/// Each cell's probes may reach into its neighbours, within the surface it was cut from: that
/// surface's unit square in the cell's own parameters; the cell's group is that surface.
void ProbeExtentsOf(const std::vector<sphcover::Patch>& patches,
  std::vector<sphcover::UVRect>& extents,
  std::vector<int>& groups)
{
  for (const sphcover::Patch& patch : patches)
  {
    const sphcover::UVRect& d = patch.Domain;
    const double du = d.U1 - d.U0;
    const double dv = d.V1 - d.V0;
    extents.push_back(du > 0.0 && dv > 0.0
        ? sphcover::UVRect{ -d.U0 / du, (1.0 - d.U0) / du, -d.V0 / dv, (1.0 - d.V0) / dv }
        : sphcover::UVRect::Unit());
    groups.push_back(patch.SurfaceIndex);
  }
}

/// The refined pieces of whole cells mapped back to the cells' surfaces and parameter
/// rectangles, with the cell each piece was cut from.
std::vector<sphcover::Patch> PiecesInCells(std::vector<sphcover::Patch> pieces,
  const std::vector<sphcover::Patch>& patches,
  std::vector<vtkIdType>& cellOfPatch)
{
  std::vector<sphcover::Patch> refined;
  refined.reserve(pieces.size());
  cellOfPatch.clear();
  for (sphcover::Patch& piece : pieces)
  {
    const size_t cell = static_cast<size_t>(piece.SurfaceIndex);
    const sphcover::UVRect& whole = patches[cell].Domain;
    const sphcover::UVRect part = piece.Domain;
    // An unsplit cell keeps its rectangle exactly; a piece's is mapped into it.
    piece.Domain = piece.Reason == sphcover::SplitReason::None
      ? whole
      : sphcover::UVRect{ whole.U0 + (whole.U1 - whole.U0) * part.U0,
          whole.U0 + (whole.U1 - whole.U0) * part.U1,
          whole.V0 + (whole.V1 - whole.V0) * part.V0,
          whole.V0 + (whole.V1 - whole.V0) * part.V1 };
    piece.SurfaceIndex = patches[cell].SurfaceIndex;
    refined.push_back(std::move(piece));
    cellOfPatch.push_back(static_cast<vtkIdType>(cell));
  }
  return refined;
}

/// The R-buffer refinement (paper §4.2.5 / §4.3 Steps 3 and 5) of the patches, reporting
/// progress up to refinementShare; replaces patches and cellOfPatch by the pieces. False, with
/// a warning or the error reported, when aborted or failed.
bool RefinePatches(vtkSphericalCoverFilter* self,
  const sphcover::Scene& scene,
  const sphcover::SphericalCoverOptions& options,
  double refinementShare,
  const sphcover::RankShare& share,
  std::vector<sphcover::Patch>& patches,
  std::vector<vtkIdType>& cellOfPatch)
{
  // The refinement cuts pieces from the scene's surfaces; here each input cell is a surface
  // of its own (vtkSurfaceGridAdapter), so the patches are refined as whole cells and their
  // pieces mapped back to the cells' surfaces and parameter rectangles afterwards.
  std::vector<sphcover::Patch> cells;
  int deepest = 0;
  for (size_t c = 0; c < patches.size(); ++c)
  {
    cells.emplace_back(
      static_cast<int>(c), sphcover::UVRect::Unit(), patches[c].Level, scene.Surfaces[c].Patch);
    deepest = std::max(deepest, patches[c].Level);
  }
  sphcover::RefinementSettings settings;
  settings.Cover = options;
  // Here the cells are the surfaces: the fill's two-sided flags are the cells'.
  settings.Cover.FillOptions.TwoSidedSurfaces.clear();
  for (size_t c = 0; c < patches.size(); ++c)
  {
    settings.Cover.FillOptions.TwoSidedSurfaces.push_back(scene.Surfaces[c].TwoSided);
  }
  settings.MaxLevel = deepest + self->GetRefinementLevels();
  settings.AnalyseHemispheres = self->GetRefinement() == vtkSphericalCoverFilter::REFINEMENT_FULL;
  try
  {
    sphcover::CoverRefinement refinement(scene, std::move(cells), settings);
    std::vector<sphcover::UVRect> extents;
    std::vector<int> groups;
    ProbeExtentsOf(patches, extents, groups);
    refinement.SetProbeExtents(std::move(extents), std::move(groups));
    refinement.SetRankShare(share);
    vtkStageProgress progress(self, "Spherical Cover: refining", 0.0, refinementShare);
    const bool completed = refinement.Run(
      [&progress](double fraction) { return progress(fraction); }, vtkSMPParallelFor::Make());
    if (!completed)
    {
      vtkWarningWithObjectMacro(self, "Spherical cover aborted.");
      return false;
    }
    patches = PiecesInCells(refinement.Patches(), patches, cellOfPatch);
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << "Cover refinement failed: " << e.what());
    return false;
  }
  return true;
}

/// Each patch's value of a material property (its emitted radiance), that of the input cell
/// it was cut from.
std::vector<glm::dvec3> MaterialOf(const sphcover::Scene& scene,
  const std::vector<sphcover::Patch>& patches,
  const std::vector<vtkIdType>& cellOfPatch,
  glm::dvec3 sphcover::Material::*property)
{
  std::vector<glm::dvec3> values(patches.size(), glm::dvec3(0.0));
  for (size_t k = 0; k < patches.size(); ++k)
  {
    const size_t cell = static_cast<size_t>(cellOfPatch[k]);
    const size_t material = static_cast<size_t>(scene.Surfaces[cell].MaterialIndex);
    if (material < scene.Materials.size())
    {
      values[k] = scene.Materials[material].*property;
    }
  }
  return values;
}

/// Each patch's diffuse reflectance: its material's, times a texture's mean over the patch
/// (sphcover::MaterialOverPatch, paper §5.4), for the first bounce of the direct light.
std::vector<glm::dvec3> DiffuseOf(const sphcover::Scene& scene,
  const std::vector<sphcover::Patch>& patches,
  const std::vector<vtkIdType>& cellOfPatch)
{
  std::vector<glm::dvec3> values(patches.size(), glm::dvec3(0.0));
  for (size_t k = 0; k < patches.size(); ++k)
  {
    const size_t cell = static_cast<size_t>(cellOfPatch[k]);
    const size_t material = static_cast<size_t>(scene.Surfaces[cell].MaterialIndex);
    if (material < scene.Materials.size())
    {
      values[k] = sphcover::MaterialOverPatch(scene.Materials[material], patches[k].Domain).Diffuse;
    }
  }
  return values;
}

/// The lamps' direct irradiance and its first bounce on the nodes of every patch
/// (DirectIrradiance.h), reporting
/// progress from 0.9 to 0.98; false, with a warning or the error reported, when it was
/// aborted or failed. Empty when the scene has no bright emitter.
bool ComputeDirectIrradiance(vtkSphericalCoverFilter* self,
  const std::vector<sphcover::Patch>& patches,
  const std::vector<glm::dvec3>& emission,
  const sphcover::SphericalCoverOptions& options,
  const std::vector<glm::dvec3>& diffuse,
  const sphcover::RankShare& share,
  const std::shared_ptr<const sphcover::RayCaster>& rays,
  sphcover::DirectIrradianceNodes& nodes)
{
  try
  {
    const std::vector<bool> lamps = sphcover::BrightEmitters(patches, emission);
    if (std::find(lamps.begin(), lamps.end(), true) == lamps.end())
    {
      return true;
    }
    if (!rays)
    {
      throw std::logic_error("no ray caster of the patches");
    }
    sphcover::DirectIrradianceOptions direct;
    direct.NodesPerSide = self->GetDirectIrradianceNodes();
    direct.SelfExclusionFraction = options.FillOptions.SelfExclusionFraction;
    direct.BackFacesOcclude = options.FillOptions.BackFacesOcclude;
    direct.BounceRaysPerSide = self->GetDirectBounceRays();
    direct.RefinementTolerance = self->GetDirectNodesTolerance();
    // Panes (paper §5.4): the lamps' light reaches the nodes through them.
    const std::vector<glm::vec3>& panes = options.SurfaceTransmittance;
    if (std::any_of(
          panes.begin(), panes.end(), [](const glm::vec3& t) { return t != glm::vec3(0.0f); }))
    {
      for (const sphcover::Patch& patch : patches)
      {
        const size_t surface = static_cast<size_t>(patch.SurfaceIndex);
        direct.Transmittance.push_back(surface < panes.size() ? panes[surface] : glm::vec3(0.0f));
      }
    }
    // Two-sided surfaces: the rays pass each side's back, the other side's front.
    direct.TwoSidedSurfaces = options.FillOptions.TwoSidedSurfaces;
    vtkStageProgress progress(self, "Spherical Cover: direct light", 0.9, 0.98);
    const bool completed = sphcover::ComputeDirectIrradiance(
      patches,
      *rays,
      lamps,
      emission,
      diffuse,
      direct,
      nodes,
      vtkSMPParallelFor::Make(),
      [&progress](double fraction) { return progress(fraction); },
      share);
    if (!completed)
    {
      vtkWarningWithObjectMacro(self, "Spherical cover aborted.");
      return false;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << "Direct irradiance failed: " << e.what());
    return false;
  }
  return true;
}

/// The spherical cover of the patches (paper §3.3), reporting progress from coverStart to
/// 0.9; false, with a warning or the error reported, when it does not fit the budget, was
/// aborted or failed.
bool BuildCover(vtkSphericalCoverFilter* self,
  const std::vector<sphcover::Patch>& patches,
  const sphcover::SphericalCoverOptions& options,
  const MemoryBudget& budget,
  double coverStart,
  const std::shared_ptr<const sphcover::RayCaster>& rays,
  sphcover::SphericalCover& cover)
{
  try
  {
    if (!MemoryFits(self, patches, options, budget, rays))
    {
      return false;
    }
    vtkStageProgress progress(self, "Spherical Cover: cover", coverStart, 0.9);
    const bool completed = cover.Build(
      patches,
      options,
      vtkSMPParallelFor::Make(),
      [&progress](double fraction) { return progress(fraction); },
      rays);
    if (!completed)
    {
      vtkWarningWithObjectMacro(self, "Spherical cover aborted.");
      return false;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << "Spherical cover failed: " << e.what());
    return false;
  }
  return true;
}

/// Each point gets the cell data of the input patch it was cut from; after a refinement, a
/// piece's own UVRange, Level and SplitReason replace its cell's.
void CopyCellDataOfPatches(vtkDataSet* input,
  const std::vector<sphcover::Patch>& patches,
  const std::vector<vtkIdType>& cellOfPatch,
  bool refined,
  vtkPointData* pd)
{
  const vtkIdType count = static_cast<vtkIdType>(patches.size());
  vtkCellData* cd = input->GetCellData();
  pd->CopyAllocate(cd, count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    pd->CopyData(cd, cellOfPatch[static_cast<size_t>(i)], i);
  }
  pd->SetNumberOfTuples(count);
  if (!refined)
  {
    return;
  }
  vtkDataArray* uvRange = pd->GetArray(names::UVRange);
  vtkDataArray* level = pd->GetArray(names::Level);
  vtkDataArray* reason = pd->GetArray(names::SplitReason);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const sphcover::Patch& patch = patches[static_cast<size_t>(i)];
    if (patch.Reason != sphcover::SplitReason::RBuffer)
    {
      continue; // not split: its cell's values
    }
    if (uvRange && uvRange->GetNumberOfComponents() == 4)
    {
      const double rect[4] = { patch.Domain.U0, patch.Domain.U1, patch.Domain.V0, patch.Domain.V1 };
      uvRange->SetTuple(i, rect);
    }
    if (level)
    {
      level->SetComponent(i, 0, patch.Level);
    }
    if (reason)
    {
      reason->SetComponent(i, 0, static_cast<double>(patch.Reason));
    }
  }
}

/// Output 0: the characteristic points with PatchId and Area; the patches' cell arrays
/// (SurfaceId, materials, UV, Level, ...) become their point data, then the cover's own
/// arrays, which take precedence; `coverage` is the cover's (CoverageOf).
void WriteCharacteristicPoints(vtkDataSet* input,
  const std::vector<sphcover::Patch>& patches,
  const std::vector<vtkIdType>& cellOfPatch,
  bool refined,
  const sphcover::SphericalCover& cover,
  const vtkSphericalCoverSteps::PointCoverage& coverage,
  vtkPolyData* pointsOut)
{
  const vtkIdType count = static_cast<vtkIdType>(patches.size());
  auto normals = vtkNamedArrays::Double(names::Normals, 3, count);
  auto tangents = vtkNamedArrays::Double(names::Tangents, 3, count);
  auto covered = vtkNamedArrays::Double(names::CoveredProjectedSolidAngle, 1, count);
  auto visible = vtkNamedArrays::Int(names::VisibleSources, 1, count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    const sphcover::Patch& patch = patches[static_cast<size_t>(i)];
    const sphcover::HemisphereFrame frame = sphcover::HemisphereFrame::OfPatch(patch);
    normals->SetTuple(i, &frame.Normal[0]);
    tangents->SetTuple(i, &frame.Tangent[0]);
    covered->SetValue(i, coverage.Covered[static_cast<size_t>(i)]);
    visible->SetValue(i, coverage.Visible[static_cast<size_t>(i)]);
  }
  vtkNew<vtkPolyData> characteristic;
  vtkSurfaceGridBuilder::BuildCharacteristicPoints(patches, characteristic);
  pointsOut->Initialize();
  pointsOut->SetPoints(characteristic->GetPoints());
  pointsOut->SetVerts(characteristic->GetVerts());
  vtkPointData* pd = pointsOut->GetPointData();
  CopyCellDataOfPatches(input, patches, cellOfPatch, refined, pd);
  pd->RemoveArray(names::HigherOrderDegrees);
  pd->SetNormals(normals);
  pd->AddArray(tangents);
  pd->AddArray(characteristic->GetPointData()->GetArray(names::Area));
  pd->AddArray(characteristic->GetPointData()->GetArray(names::PatchId));
  auto inputPatch = vtkNamedArrays::Int(names::InputPatchId, 1, count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    inputPatch->SetValue(i, static_cast<int>(cellOfPatch[static_cast<size_t>(i)]));
  }
  pd->AddArray(inputPatch);
  pd->AddArray(covered);
  pd->AddArray(visible);
  pointsOut->GetFieldData()->PassData(input->GetFieldData());
  vtkSphericalCoverArrays::Store(cover, pointsOut);
}

/// Output 1: the strips, one row each (receiver, source, theta row, phi range, depth), for
/// the spreadsheet view.
void WriteStrips(const sphcover::SphericalCover& cover, std::size_t patchCount, vtkTable* stripsOut)
{
  const vtkIdType strips = static_cast<vtkIdType>(cover.StripCount());
  auto receiver = vtkNamedArrays::Int(names::Receiver, 1, strips);
  auto source = vtkNamedArrays::Int(names::Source, 1, strips);
  auto theta = vtkNamedArrays::Int(names::Theta, 1, strips);
  auto phiBegin = vtkNamedArrays::Int(names::PhiBegin, 1, strips);
  auto phiEnd = vtkNamedArrays::Int(names::PhiEnd, 1, strips);
  auto depth = vtkNamedArrays::New<vtkFloatArray>(names::R, 1, strips);
  vtkIdType k = 0;
  for (size_t i = 0; i < patchCount; ++i)
  {
    for (size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
    {
      for (size_t s = cover.StripBegin(e); s < cover.StripEnd(e); ++s, ++k)
      {
        const sphcover::SphericalCover::Strip& strip = cover.StripAt(s);
        receiver->SetValue(k, static_cast<int>(i));
        source->SetValue(k, static_cast<int>(cover.EntryAt(e).Source));
        theta->SetValue(k, strip.Row);
        phiBegin->SetValue(k, strip.PhiBegin);
        phiEnd->SetValue(k, strip.PhiEnd);
        depth->SetValue(k, cover.StripDepth(s));
      }
    }
  }
  stripsOut->AddColumn(receiver);
  stripsOut->AddColumn(source);
  stripsOut->AddColumn(theta);
  stripsOut->AddColumn(phiBegin);
  stripsOut->AddColumn(phiEnd);
  stripsOut->AddColumn(depth);
}

}

namespace vtkSphericalCoverSteps
{
/// Whether the cover's memory fits the budget; false, with the error reported, when it does
/// not. Without patches this is the working memory of the grid on every thread (the
/// refinement builds R-buffers too), from the options alone; with them, an estimate of the
/// cover from a few rows actually built.
bool MemoryFits(vtkSphericalCoverFilter* self,
  const std::vector<sphcover::Patch>& patches,
  const sphcover::SphericalCoverOptions& options,
  const MemoryBudget& budget,
  const std::shared_ptr<const sphcover::RayCaster>& rays)
{
  const std::string memory = sphcover::SphericalCover::MemoryProblem(
    patches, options, budget.Threads, budget.LimitBytes, rays);
  if (!memory.empty())
  {
    vtkErrorWithObjectMacro(
      self, << "Cannot build the spherical cover: " << memory << " (MemoryLimit).");
    return false;
  }
  return true;
}

PointCoverage CoverageOf(const sphcover::SphericalCover& cover)
{
  PointCoverage coverage;
  for (size_t i = 0; i < cover.PatchCount(); ++i)
  {
    coverage.Covered.push_back(cover.CoveredProjectedSolidAngle(i));
    coverage.Visible.push_back(static_cast<int>(cover.VisibleSourceCount(i)));
  }
  return coverage;
}

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The input's patches, the options from the properties and the refinement (paper §4.3 Steps
/// 3 and 5), refused before any R-buffer exists when the grid's working memory cannot fit;
/// false, with the error reported, when anything fails.
bool PrepareCover(vtkSphericalCoverFilter* self, vtkDataSet* input, CoverInput& prepared)
{
  std::string error;
  if (!vtkSurfaceGridAdapter::ToPatches(input, prepared.Scene, prepared.Patches, error))
  {
    vtkErrorWithObjectMacro(self, << "Cannot build a spherical cover of this input: " << error);
    return false;
  }
  sphcover::SphericalCoverOptions& options = prepared.Options;
  if (!CoverOptionsOf(self, input, options))
  {
    return false;
  }
  // Panes (paper §5.4): the cover, its refinement and the direct-light nodes see through them
  // (SphericalCover.h, "Panes").
  for (const glm::dvec3& t :
    vtkSurfaceGridAdapter::TransmittanceOfSurfaces(prepared.Scene, prepared.Patches))
  {
    options.SurfaceTransmittance.push_back(glm::vec3(t));
    options.FillOptions.PaneSurfaces.push_back(t != glm::dvec3(0.0));
  }
  // Two-sided surfaces (Surface::TwoSided): pairs of one-sided surfaces whose backs the rays
  // pass. Per surface index (Patch::SurfaceIndex), from the cell of each of its patches.
  std::vector<bool>& twoSided = options.FillOptions.TwoSidedSurfaces;
  for (size_t k = 0; k < prepared.Patches.size() && k < prepared.Scene.Surfaces.size(); ++k)
  {
    const size_t surface = static_cast<size_t>(std::max(0, prepared.Patches[k].SurfaceIndex));
    twoSided.resize(std::max(twoSided.size(), surface + 1), false);
    twoSided[surface] = twoSided[surface] || prepared.Scene.Surfaces[k].TwoSided;
  }

  // Refuse before any R-buffer exists what could not fit: first the working memory of the
  // grid on every thread (the refinement builds R-buffers too), from the options alone.
  MemoryBudget& budget = prepared.Budget;
  budget.Threads =
    static_cast<std::size_t>(std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads()));
  budget.LimitBytes =
    static_cast<std::size_t>(std::min(self->GetMemoryLimit() * 1024.0 * 1024.0, 1.0e18));
  try
  {
    if (!MemoryFits(self, {}, options, budget, nullptr))
    {
      return false;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << "Cannot build the spherical cover: " << e.what());
    return false;
  }
  prepared.CellOfPatch.resize(prepared.Patches.size());
  for (size_t k = 0; k < prepared.Patches.size(); ++k)
  {
    prepared.CellOfPatch[k] = static_cast<vtkIdType>(k);
  }
  return true;
}

/// The refinement of the prepared patches (paper §4.3 Steps 3 and 5; under MPI shared by the
/// ranks, collective) and what depends on the refined patches: their emission, the measured
/// lamps and the ray caster. False, with the error reported, when anything fails.
bool RefineCover(vtkSphericalCoverFilter* self,
  const sphcover::RankShare& share,
  CoverInput& prepared)
{
  sphcover::SphericalCoverOptions& options = prepared.Options;
  std::vector<sphcover::Patch>& patches = prepared.Patches;
  const auto start = std::chrono::steady_clock::now();
  const int refinement = self->GetRefinement();
  const double refinementShare =
    refinement == vtkSphericalCoverFilter::REFINEMENT_FULL ? 0.6 : 0.05;
  if (refinement != vtkSphericalCoverFilter::REFINEMENT_OFF && !patches.empty() &&
    !RefinePatches(
      self, prepared.Scene, options, refinementShare, share, patches, prepared.CellOfPatch))
  {
    return false;
  }
  self->RecordStageSeconds(0, SecondsSince(start));
  prepared.CoverStart =
    refinement == vtkSphericalCoverFilter::REFINEMENT_OFF ? 0.0 : refinementShare;
  prepared.Emission =
    MaterialOf(prepared.Scene, patches, prepared.CellOfPatch, &sphcover::Material::Emission);
  const std::vector<bool> lamps = sphcover::BrightEmitters(patches, prepared.Emission);
  if (self->GetMeasureLamps())
  {
    options.MeasuredSurfaces = lamps;
  }
  options.Interpolation.Enabled = self->GetInterpolateHemispheres();
  // Built once: the ray fill's estimate and rows and the direct light cast at the same patches,
  // and a large scene's tessellation and BVH take a while to build.
  const bool lit = self->GetDirectIrradianceNodes() > 0 &&
    std::find(lamps.begin(), lamps.end(), true) != lamps.end();
  if (!patches.empty() && (options.Fill == sphcover::RBufferFill::RayCasting || lit))
  {
    try
    {
      prepared.Rays = std::make_shared<const sphcover::RayCaster>(
        sphcover::RayCastPatches(patches), sphcover::RayCastOptions(options.FillOptions));
    }
    catch (const std::exception& e)
    {
      vtkErrorWithObjectMacro(self, << "Spherical cover failed: " << e.what());
      return false;
    }
  }
  return true;
}

/// The lamps' direct light on the patches' nodes when DirectIrradianceNodes asks for it;
/// false, with the error reported, when it failed or was aborted.
bool ComputeDirectIrradianceOf(vtkSphericalCoverFilter* self,
  const sphcover::RankShare& share,
  const CoverInput& prepared,
  sphcover::DirectIrradianceNodes& direct)
{
  const auto start = std::chrono::steady_clock::now();
  const bool completed = self->GetDirectIrradianceNodes() <= 0 ||
    ComputeDirectIrradiance(self,
      prepared.Patches,
      prepared.Emission,
      prepared.Options,
      DiffuseOf(prepared.Scene, prepared.Patches, prepared.CellOfPatch),
      share,
      prepared.Rays,
      direct);
  self->RecordStageSeconds(2, SecondsSince(start));
  return completed;
}

void WriteOutputs(vtkSphericalCoverFilter* self,
  vtkDataSet* input,
  const CoverInput& prepared,
  const sphcover::SphericalCover& cover,
  const PointCoverage& coverage,
  const sphcover::DirectIrradianceNodes& direct,
  vtkPolyData* pointsOut,
  vtkTable* stripsOut)
{
  const std::vector<sphcover::Patch>& patches = prepared.Patches;
  WriteCharacteristicPoints(input,
    patches,
    prepared.CellOfPatch,
    self->GetRefinement() != vtkSphericalCoverFilter::REFINEMENT_OFF,
    cover,
    coverage,
    pointsOut);
  if (!direct.Empty())
  {
    const int components = 3 * direct.NodesPerSide * direct.NodesPerSide;
    auto array = vtkNamedArrays::New<vtkFloatArray>(
      names::DirectIrradiance, components, static_cast<vtkIdType>(patches.size()));
    std::copy(direct.Values.begin(), direct.Values.end(), array->GetPointer(0));
    pointsOut->GetPointData()->AddArray(array);
    auto bounce = vtkNamedArrays::New<vtkIntArray>(names::DirectBounceRays, 1, 1);
    bounce->SetValue(0, self->GetDirectBounceRays());
    pointsOut->GetFieldData()->AddArray(bounce);
  }
  // The light left out behind more panes than the layers and the nodes' rays follow.
  const sphcover::PaneLimitDrops& drops = cover.PaneLimit();
  const double hemispheres = sphcover::Pi * static_cast<double>(cover.PatchCount());
  const double fraction = hemispheres > 0.0 ? drops.ProjectedSolidAngle / hemispheres : 0.0;
  auto paneLimit = vtkNamedArrays::Double(names::CoverPaneLimit, 3, 1);
  paneLimit->SetComponent(0, 0, static_cast<double>(drops.Cells));
  paneLimit->SetComponent(0, 1, fraction);
  paneLimit->SetComponent(0, 2, static_cast<double>(direct.PaneLimitRays));
  pointsOut->GetFieldData()->AddArray(paneLimit);
  if (drops.Cells > 0 || direct.PaneLimitRays > 0)
  {
    // Once per cover, not per ray: the counts are in the output's CoverPaneLimit.
    vtkWarningWithObjectMacro(self,
      << "Light behind more panes than are followed is left out: " << drops.Cells
      << " hemisphere cells still show a pane as the last of their "
      << cover.Options().MaxPaneDepth + 1 << " layers (" << 100.0 * fraction
      << " % of their projected solid angle, weighted by the "
      << "panes' transmittance) and " << direct.PaneLimitRays
      << " of the direct light's rays behind more than " << sphcover::MaxPanesPerRay
      << " (CoverPaneLimit).");
  }
  stripsOut->Initialize();
  if (self->GetGenerateStripTable())
  {
    WriteStrips(cover, patches.size(), stripsOut);
  }
}
}

vtkStandardNewMacro(vtkSphericalCoverFilter);

vtkSphericalCoverFilter::vtkSphericalCoverFilter()
{
  // ParaView's status bar labels progress with this text (vtkStageProgress.h).
  this->SetProgressText("Spherical Cover");
  this->SetNumberOfOutputPorts(2);
}

vtkSphericalCoverFilter::~vtkSphericalCoverFilter() = default;

int vtkSphericalCoverFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkSphericalCoverFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

int vtkSphericalCoverFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkPolyData* pointsOut = vtkPolyData::GetData(outputVector, 0);
  vtkTable* stripsOut = vtkTable::GetData(outputVector, 1);
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, input);
  // Pieces > 0 idle: the whole scene is piece 0 (vtkScenePieces.h).
  if (role != vtkScenePieces::Role::WholeScene)
  {
    pointsOut->Initialize();
    stripsOut->Initialize();
    if (role == vtkScenePieces::Role::PartialScene)
    {
      vtkErrorMacro(<< "Cannot build a spherical cover of this input: "
                    << vtkScenePieces::PartialSceneError(outputVector) << ".");
      return 0;
    }
    return 1;
  }

  CoverInput prepared;
  // One process: every item of the refinement and the direct light is this process's.
  const sphcover::RankShare serial;
  if (!PrepareCover(this, input, prepared) || !RefineCover(this, serial, prepared))
  {
    return 0;
  }
  sphcover::SphericalCover cover;
  const auto start = std::chrono::steady_clock::now();
  if (!BuildCover(this,
        prepared.Patches,
        prepared.Options,
        prepared.Budget,
        prepared.CoverStart,
        prepared.Rays,
        cover))
  {
    return 0;
  }
  this->RecordStageSeconds(1, SecondsSince(start));
  sphcover::DirectIrradianceNodes direct;
  if (!ComputeDirectIrradianceOf(this, serial, prepared, direct))
  {
    return 0;
  }
  prepared.Rays.reset();
  WriteOutputs(this, input, prepared, cover, CoverageOf(cover), direct, pointsOut, stripsOut);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkSphericalCoverFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ThetaBins: " << this->ThetaBins << "\n";
  os << indent << "PhiBins: " << this->PhiBins << "\n";
  os << indent << "SamplesPerCell: " << this->SamplesPerCell << "\n";
  os << indent << "FillMethod: " << (this->FillMethod == PROJECTION ? "Projection" : "RayCasting")
     << "\n";
  os << indent << "BackFacesOcclude: " << this->BackFacesOcclude << "\n";
  os << indent << "GenerateStripTable: " << this->GenerateStripTable << "\n";
  os << indent << "MeasureLamps: " << this->MeasureLamps << "\n";
  os << indent << "InterpolateHemispheres: " << this->InterpolateHemispheres << "\n";
  os << indent << "DirectIrradianceNodes: " << this->DirectIrradianceNodes << "\n";
  os << indent << "DirectBounceRays: " << this->DirectBounceRays << "\n";
  os << indent << "DirectNodesTolerance: " << this->DirectNodesTolerance << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "Refinement: "
     << (this->Refinement == REFINEMENT_OFF
            ? "Off"
            : (this->Refinement == REFINEMENT_ENCLOSURES ? "EnclosureBoundaries" : "Full"))
     << "\n";
  os << indent << "RefinementLevels: " << this->RefinementLevels << "\n";
}
