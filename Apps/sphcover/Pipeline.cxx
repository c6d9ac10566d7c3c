// SPDX-License-Identifier: BSD-3-Clause
#include "Pipeline.h"

#include "Budgets.h"
#include "Options.h"
#include "ProgressBar.h"

#include "vtkSceneSettingsArray.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"

#include "scene/SettingsOverride.h"

#include <vtkAbstractArray.h>
#include <vtkAlgorithm.h>
#include <vtkCommunicator.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkMultiProcessController.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <sys/resource.h>

#include <ctime>
#include <stdexcept>

namespace sphcover_cli
{
namespace names = vtkSphericalCoverArrayNames;

namespace
{
/// Bytes of the values of the field array `name` of `fd` (0 when it has none).
double ArrayBytes(vtkFieldData* fd, const char* name)
{
  vtkDataArray* array = fd->GetArray(name);
  return array ? static_cast<double>(array->GetNumberOfValues()) * array->GetDataTypeSize() : 0.0;
}
}

void Run(vtkAlgorithm* algorithm, ErrorCollector& errors, int piece, int pieces)
{
  errors.Watch(algorithm);
  const int updated =
    piece > 0 ? algorithm->UpdatePiece(piece, pieces, 0) : algorithm->GetExecutive()->Update();
  if (updated != 1)
  {
    throw std::runtime_error(errors.First());
  }
}

double ProcessorSeconds()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

sphcover::SceneSettings SettingsOf(vtkDataObject* surfaces, const std::vector<std::string>& sets)
{
  sphcover::SceneSettings settings = vtkSceneSettingsArray::Read(surfaces->GetFieldData());
  for (const std::string& assignment : sets)
  {
    settings = sphcover::OverrideSetting(settings, assignment);
  }
  return settings;
}

void Solution::Read(const Options& options, bool progress)
{
  this->Reader->SetFileName(options.Scene.c_str());
  ProgressBar bar(this->Reader, "read", options.Quiet || !progress);
  const double cpuStart = ProcessorSeconds();
  Run(this->Reader, this->Errors);
  this->ReadCpuSeconds = ProcessorSeconds() - cpuStart;
  this->ReadSeconds = bar.Seconds();
}

void Solution::Subdivide(const Options& options)
{
  this->Subdivision->SetInputConnection(this->Reader->GetOutputPort());
  this->Subdivision->SetMaximumPatches(options.MaxPatches);
  this->Subdivision->SetMaximumPairTests(options.MaxPairTests);
  this->Subdivision->SetMemoryLimit(options.MemoryLimit);
  // The filters take the scene's settings from the reader's field data themselves, as in
  // ParaView and Python (one pipeline); with --set the command line sets the settings it makes
  // of the scene's and the overrides, and the cover takes the subdivision's grid from its
  // SubdivisionSettings.
  if (!options.Settings.empty())
  {
    const sphcover::SceneSettings settings =
      SettingsOf(this->Reader->GetOutput(), options.Settings);
    this->Subdivision->SetThetaBins(settings.ThetaBins);
    this->Subdivision->SetPhiBins(settings.PhiBins);
    this->Subdivision->SetMaxLevel(settings.MaxLevel);
    this->Subdivision->SetMinPatchSize(settings.MinPatchSize);
    this->Subdivision->SetTolerance(settings.Tolerance);
  }
  if (options.RangeMethod == "natural")
  {
    this->Subdivision->SetRangeMethodToNaturalInterval();
  }
  {
    ProgressBar bar(this->Subdivision, "subdivide", options.Quiet);
    const double cpuStart = ProcessorSeconds();
    Run(this->Subdivision, this->Errors);
    this->SubdivideCpuSeconds = ProcessorSeconds() - cpuStart;
    this->SubdivideSeconds = bar.Seconds();
  }
}

void Solution::Solve(const Options& options, bool gather)
{
  const sphcover::SceneSettings settings = SettingsOf(this->Reader->GetOutput(), options.Settings);
  CheckCoverGrid(settings, options);
  // The scene's own size against the limit, before any of the work: what its patches and
  // named surfaces need whatever the subdivision makes of them.
  vtkUnstructuredGrid* scene = this->Reader->GetOutput();
  vtkAbstractArray* surfaceNames = scene->GetFieldData()->GetAbstractArray(names::SurfaceNames);
  CheckSceneSize(static_cast<std::size_t>(scene->GetNumberOfCells()),
    surfaceNames ? static_cast<std::size_t>(surfaceNames->GetNumberOfValues()) : 0,
    options);
  // Every rank subdivides (so that all fail alike on a bad scene), but under mpiexec only rank 0
  // gives the cover the patches: the other ranks ask for empty pieces, as pvbatch's ranks do,
  // and get rank 0's scene from the cover filter. Each rank keeps the rows it builds (GatherRows
  // off) and propagates them (vtkLightPropagationFilter); rank 0 gathers the whole cover only
  // for the solution, once the propagation's state is gone, and no other rank ever holds it.
  this->Subdivide(options);
  this->Cover->SetMemoryLimit(options.MemoryLimit);
  this->Cover->SetGatherRows(options.Ranks <= 1);
  // Nothing here reads the strip table (a spreadsheet's): it would stay in memory, as large as
  // the cover's strips again, beside the solve.
  this->Cover->GenerateStripTableOff();
  this->Propagation->SetMemoryLimit(options.MemoryLimit);
  this->Propagation->SetGatherSolution(gather);
  const int piece = options.Ranks > 1 ? options.Rank : 0;
  if (piece > 0)
  {
    vtkSmartPointer<vtkDataObject> none = vtkSmartPointer<vtkDataObject>::Take(
      this->Subdivision->GetOutputDataObject(0)->NewInstance());
    this->Cover->SetInputData(none);
  }
  else
  {
    this->Cover->SetInputConnection(this->Subdivision->GetOutputPort(0));
  }
  if (options.Fill == "projection")
  {
    this->Cover->SetFillMethodToProjection();
  }
  this->Cover->SetMeasureLamps(options.Lamps == "measured");
  this->Cover->SetInterpolateHemispheres(options.Hemispheres == "interpolated");
  this->Cover->SetDirectIrradianceNodes(options.DirectNodes);
  this->Cover->SetDirectBounceRays(options.BounceRays);
  this->Cover->SetDirectNodesTolerance(options.DirectTolerance);
  {
    ProgressBar bar(this->Cover, "cover", options.Quiet);
    const double cpuStart = ProcessorSeconds();
    Run(this->Cover, this->Errors, piece, options.Ranks);
    this->CoverCpuSeconds = ProcessorSeconds() - cpuStart;
    this->CoverSeconds = bar.Seconds();
  }
  this->Propagation->SetInputConnection(this->Cover->GetOutputPort(0));
  {
    ProgressBar bar(this->Propagation, "propagate", options.Quiet);
    const double cpuStart = ProcessorSeconds();
    Run(this->Propagation, this->Errors, piece, options.Ranks);
    this->PropagateCpuSeconds = ProcessorSeconds() - cpuStart;
    this->PropagateSeconds = bar.Seconds();
  }
  // Every rank's peak resident memory so far, in rank order (under mpiexec a collective: every
  // rank reaches it, the stages having agreed on success).
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak = static_cast<double>(usage.ru_maxrss) * 1024.0; // ru_maxrss is in KiB
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  this->PeakResidentBytes.assign(1, peak);
  // What the solution holds, over the ranks: rank 0's whole solution (the others' outputs are
  // empty) or the ranks' pieces.
  vtkFieldData* fd = this->Propagation->GetOutput()->GetFieldData();
  double held[2] = { 0.0, ArrayBytes(fd, names::IncidentRadiance) };
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
  {
    const char* name = fd->GetAbstractArray(a)->GetName();
    held[0] += vtkSphericalCoverArrays::IsCoverArray(name) ? ArrayBytes(fd, name) : 0.0;
  }
  double whole[2] = { held[0], held[1] };
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    this->PeakResidentBytes.resize(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
    controller->AllGather(&peak, this->PeakResidentBytes.data(), 1);
    controller->AllReduce(held, whole, 2, vtkCommunicator::SUM_OP);
  }
  this->CoverBytes = whole[0];
  this->IncidentRadianceBytes = whole[1];
}

nlohmann::json Solution::Timings() const
{
  return { { "read", this->ReadSeconds },
    { "subdivide", this->SubdivideSeconds },
    { "cover", this->CoverSeconds },
    { "propagate", this->PropagateSeconds } };
}

nlohmann::json Solution::CpuTimings() const
{
  return { { "read", this->ReadCpuSeconds },
    { "subdivide", this->SubdivideCpuSeconds },
    { "cover", this->CoverCpuSeconds },
    { "propagate", this->PropagateCpuSeconds } };
}
}
