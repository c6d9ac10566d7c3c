// SPDX-License-Identifier: BSD-3-Clause
#include "vtkIntervalSubdivisionFilter.h"

#include "vtkNamedArrays.h"
#include "vtkSMPParallelFor.h"
#include "vtkScenePieces.h"
#include "vtkSceneSettingsArray.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkStageProgress.h"
#include "vtkSurfaceGridAdapter.h"
#include "vtkSurfaceGridBuilder.h"

#include "scene/Scene.h"
#include "subdivision/IntervalSubdivision.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <exception>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
/// A property's value, or the scene's where it is left at SCENE_SETTING.
int OrScene(int property, int scene)
{
  return property == vtkIntervalSubdivisionFilter::SCENE_SETTING ? scene : property;
}

double OrScene(double property, double scene)
{
  return property == vtkIntervalSubdivisionFilter::SCENE_SETTING ? scene : property;
}

/// The subdivision's settings from the filter's properties, those left at SCENE_SETTING taking
/// the scene's settings block.
sphcover::SubdivisionSettings SubdivisionSettingsOf(vtkIntervalSubdivisionFilter* self,
  vtkDataObject* input)
{
  const sphcover::SceneSettings fromScene = vtkSceneSettingsArray::Read(input->GetFieldData());
  sphcover::SubdivisionSettings settings;
  settings.Method = self->GetRangeMethod() == vtkIntervalSubdivisionFilter::NATURAL_INTERVAL
    ? sphcover::RangeMethod::NaturalInterval
    : sphcover::RangeMethod::Bernstein;
  settings.MaxLevel = OrScene(self->GetMaxLevel(), fromScene.MaxLevel);
  settings.MinPatchSize = OrScene(self->GetMinPatchSize(), fromScene.MinPatchSize);
  settings.MaximumPatches = static_cast<size_t>(self->GetMaximumPatches());
  settings.MemoryLimitBytes = static_cast<size_t>(self->GetMemoryLimit() * 1024.0 * 1024.0);
  settings.MaximumPairTests = static_cast<size_t>(self->GetMaximumPairTests());
  settings.ThetaBins = OrScene(self->GetThetaBins(), fromScene.ThetaBins);
  settings.PhiBins = OrScene(self->GetPhiBins(), fromScene.PhiBins);
  const bool enabled[4] = { self->GetSelfShadowing(),
    self->GetHemisphericalContainment(),
    self->GetSphericalShape(),
    self->GetCharacterisability() };
  const double tolerances[4] = { OrScene(self->GetSelfShadowingTolerance(), fromScene.Tolerance),
    OrScene(self->GetHemisphericalContainmentTolerance(), fromScene.Tolerance),
    OrScene(self->GetSphericalShapeTolerance(), fromScene.Tolerance),
    OrScene(self->GetCharacterisabilityTolerance(), fromScene.Tolerance) };
  for (int c = 0; c < sphcover::NumberOfCriteria; ++c)
  {
    settings.Enabled[c] = enabled[c];
    settings.Tolerance[c] = tolerances[c];
  }
  return settings;
}

/// Output 0: the patches with their exact geometry and materials; in field data the input's,
/// the SubdivisionStatistics and the settings used (SubdivisionSettings), for the next stages
/// (the cover's grid) and for the user to see.
void WritePatchCells(vtkDataSet* input,
  const sphcover::Scene& scene,
  const std::vector<sphcover::Patch>& patches,
  const sphcover::SubdivisionSettings& settings,
  vtkIdType pairTests,
  int sweeps,
  vtkUnstructuredGrid* patchesOut)
{
  std::vector<const sphcover::BezierPatch*> geometry;
  std::vector<int> surfaceOfPatch;
  for (const sphcover::Patch& patch : patches)
  {
    geometry.push_back(&patch.Geometry);
    surfaceOfPatch.push_back(patch.SurfaceIndex);
  }
  patchesOut->Initialize();
  vtkSurfaceGridBuilder::BuildCells(geometry, patchesOut);
  vtkSurfaceGridBuilder::AddMaterialArrays(scene, surfaceOfPatch, patchesOut);
  patchesOut->GetFieldData()->PassData(input->GetFieldData());
  auto statistics = vtkNamedArrays::Double(names::SubdivisionStatistics, 2, 1);
  statistics->SetComponentName(0, "PairTests");
  statistics->SetComponentName(1, "Sweeps");
  statistics->SetComponent(0, 0, static_cast<double>(pairTests));
  statistics->SetComponent(0, 1, sweeps);
  patchesOut->GetFieldData()->AddArray(statistics);
  auto used = vtkNamedArrays::Double(names::SubdivisionSettings, 8, 1);
  const char* usedNames[8] = { "max_level",
    "theta_bins",
    "phi_bins",
    "self_shadowing_tolerance",
    "hemispherical_containment_tolerance",
    "spherical_shape_tolerance",
    "characterisability_tolerance",
    "min_patch_size" };
  const double usedValues[8] = { double(settings.MaxLevel),
    double(settings.ThetaBins),
    double(settings.PhiBins),
    settings.Tolerance[0],
    settings.Tolerance[1],
    settings.Tolerance[2],
    settings.Tolerance[3],
    settings.MinPatchSize };
  for (int k = 0; k < 8; ++k)
  {
    used->SetComponentName(k, usedNames[k]);
  }
  used->SetTuple(0, usedValues);
  patchesOut->GetFieldData()->AddArray(used);
}

/// The patches' attributes (SurfaceId, PatchId, Level, UVRange, Area, SplitReason, with the
/// reasons' names) as output 0's cell data, and output 1: the characteristic points, with the
/// attributes of their patches.
void WritePatchAttributes(const std::vector<sphcover::Patch>& patches,
  vtkUnstructuredGrid* patchesOut,
  vtkPolyData* pointsOut)
{
  const vtkIdType count = static_cast<vtkIdType>(patches.size());
  auto surfaceId = vtkNamedArrays::Int(names::SurfaceId, 1, count);
  auto patchId = vtkNamedArrays::Int(names::PatchId, 1, count);
  auto level = vtkNamedArrays::Int(names::Level, 1, count);
  auto reason = vtkNamedArrays::Int(names::SplitReason, 1, count);
  auto uvRange = vtkNamedArrays::Double(names::UVRange, 4, count);
  auto area = vtkNamedArrays::Double(names::Area, 1, count);
  for (int k = 0; k < 4; ++k)
  {
    uvRange->SetComponentName(k, k == 0 ? "u0" : k == 1 ? "u1" : k == 2 ? "v0" : "v1");
  }
  vtkSurfaceGridBuilder::BuildCharacteristicPoints(patches, pointsOut);
  auto normals = vtkNamedArrays::Double(names::Normals, 3, count);
  auto uv = vtkNamedArrays::Double(names::UV, 2, count);
  for (vtkIdType p = 0; p < count; ++p)
  {
    const sphcover::Patch& patch = patches[static_cast<size_t>(p)];
    surfaceId->SetValue(p, patch.SurfaceIndex);
    patchId->SetValue(p, static_cast<int>(p));
    level->SetValue(p, patch.Level);
    reason->SetValue(p, static_cast<int>(patch.Reason));
    const double range[4] = { patch.Domain.U0, patch.Domain.U1, patch.Domain.V0, patch.Domain.V1 };
    uvRange->SetTuple(p, range);
    area->SetValue(p, patch.Area);
    normals->SetTuple(p, &patch.Normal[0]);
    const double centre[2] = { patch.Domain.CenterU(), patch.Domain.CenterV() };
    uv->SetTuple(p, centre);
  }
  vtkCellData* cd = patchesOut->GetCellData();
  cd->AddArray(surfaceId);
  cd->AddArray(patchId);
  cd->AddArray(level);
  cd->AddArray(uvRange);
  cd->AddArray(area);
  cd->AddArray(reason);
  cd->SetActiveScalars(names::SplitReason);
  vtkNew<vtkStringArray> reasonNames;
  reasonNames->SetName(names::SplitReasonNames);
  for (int r = 0; r <= static_cast<int>(sphcover::SplitReason::RBuffer); ++r)
  {
    reasonNames->InsertNextValue(sphcover::SplitReasonName(static_cast<sphcover::SplitReason>(r)));
  }
  patchesOut->GetFieldData()->AddArray(reasonNames);

  vtkPointData* pd = pointsOut->GetPointData();
  pd->SetNormals(normals);
  pd->AddArray(surfaceId);
  pd->AddArray(uv);
  pd->AddArray(level);
}
}

vtkStandardNewMacro(vtkIntervalSubdivisionFilter);

vtkIntervalSubdivisionFilter::vtkIntervalSubdivisionFilter()
{
  // ParaView's status bar labels progress with this text (vtkStageProgress.h).
  this->SetProgressText("Interval Subdivision");
  this->SetNumberOfOutputPorts(2);
}

vtkIntervalSubdivisionFilter::~vtkIntervalSubdivisionFilter() = default;

void vtkIntervalSubdivisionFilter::SetTolerance(double tolerance)
{
  this->SetSelfShadowingTolerance(tolerance);
  this->SetHemisphericalContainmentTolerance(tolerance);
  this->SetSphericalShapeTolerance(tolerance);
  this->SetCharacterisabilityTolerance(tolerance);
}

int vtkIntervalSubdivisionFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkIntervalSubdivisionFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

int vtkIntervalSubdivisionFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* patchesOut = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* pointsOut = vtkPolyData::GetData(outputVector, 1);
  this->PairTests = 0;

  // Pieces > 0 idle: the whole scene is piece 0 (vtkScenePieces.h).
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, input);
  if (role != vtkScenePieces::Role::WholeScene)
  {
    patchesOut->Initialize();
    pointsOut->Initialize();
    if (role == vtkScenePieces::Role::PartialScene)
    {
      vtkErrorMacro(<< "Cannot subdivide this input: "
                    << vtkScenePieces::PartialSceneError(outputVector) << ".");
      return 0;
    }
    return 1;
  }

  const sphcover::SubdivisionSettings settings = SubdivisionSettingsOf(this, input);
  const std::string problem = settings.Problem();
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }

  sphcover::Scene scene;
  std::string error;
  if (!vtkSurfaceGridAdapter::ToScene(input, false, scene, error))
  {
    vtkErrorMacro(<< "Cannot subdivide this input: " << error);
    return 0;
  }

  std::vector<sphcover::Patch> patches;
  int sweeps = 0;
  try
  {
    sphcover::IntervalSubdivision subdivision(scene, settings);
    vtkStageProgress progress(this, "Interval Subdivision: subdividing", 0.0, 0.95);
    const bool completed = subdivision.Run(
      [&progress](double fraction) { return progress(fraction); }, vtkSMPParallelFor::Make());
    if (!completed)
    {
      vtkWarningMacro("Subdivision aborted.");
      return 0;
    }
    patches = subdivision.Patches();
    this->PairTests = static_cast<vtkIdType>(subdivision.Statistics().PairTests);
    sweeps = subdivision.Statistics().Sweeps;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Subdivision failed: " << e.what());
    return 0;
  }

  WritePatchCells(input, scene, patches, settings, this->PairTests, sweeps, patchesOut);
  WritePatchAttributes(patches, patchesOut, pointsOut);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkIntervalSubdivisionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "RangeMethod: " << (this->RangeMethod == BERNSTEIN ? "Bernstein" : "NaturalInterval")
     << "\n";
  os << indent << "MaxLevel: " << this->MaxLevel << "\n";
  os << indent << "MinPatchSize: " << this->MinPatchSize << "\n";
  os << indent << "MaximumPatches: " << this->MaximumPatches << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "MaximumPairTests: " << this->MaximumPairTests << "\n";
  os << indent << "ThetaBins: " << this->ThetaBins << "\n";
  os << indent << "PhiBins: " << this->PhiBins << "\n";
  os << indent << "SelfShadowing: " << this->SelfShadowing << " (" << this->SelfShadowingTolerance
     << ")\n";
  os << indent << "HemisphericalContainment: " << this->HemisphericalContainment << " ("
     << this->HemisphericalContainmentTolerance << ")\n";
  os << indent << "SphericalShape: " << this->SphericalShape << " ("
     << this->SphericalShapeTolerance << ")\n";
  os << indent << "Characterisability: " << this->Characterisability << " ("
     << this->CharacterisabilityTolerance << ")\n";
  os << indent << "PairTests: " << this->PairTests << "\n";
}
