// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLightPropagationFilter.h"

#include "vtkIlluminationAdapter.h"
#include "vtkNamedArrays.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "propagation/ExchangeBalance.h"
#include "propagation/LightPropagation.h"
#include "scene/Material.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <glm/geometric.hpp>

#include <exception>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkLightPropagationFilter);

vtkLightPropagationFilter::vtkLightPropagationFilter()
{
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

  sphcover::SphericalCover cover;
  const std::string problem = vtkSphericalCoverArrays::Load(input, cover);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot propagate light: " << problem);
    return 0;
  }
  std::vector<sphcover::Material> materials;
  std::string materialProblem;
  if (!vtkIlluminationAdapter::ReadMaterials(input, materials, materialProblem))
  {
    vtkErrorMacro(<< "Cannot propagate light: " << materialProblem);
    return 0;
  }
  const vtkIdType count = input->GetNumberOfPoints();
  const double needed =
    static_cast<double>(sphcover::LightPropagation::EstimateBytes(cover, materials)) /
    (1024.0 * 1024.0);
  if (needed > this->MemoryLimit)
  {
    vtkErrorMacro(<< "Cannot propagate light: it would need about " << static_cast<int>(needed)
                  << " MiB (state of " << cover.EntryCount() << " regions and weight tables of a "
                  << cover.Options().ThetaBins << " x " << cover.Options().PhiBins
                  << " grid), more than MemoryLimit (" << this->MemoryLimit
                  << " MiB); use a coarser grid or fewer patches.");
    return 0;
  }

  sphcover::PropagationSettings settings;
  settings.ConvergenceTolerance = this->ConvergenceTolerance;
  settings.MaximumShots = static_cast<size_t>(this->MaximumShots);
  settings.Order = this->ShootingOrder == FIXED_ORDER ? sphcover::ShootingOrder::FixedOrder
                                                      : sphcover::ShootingOrder::BrightestFirst;
  try
  {
    sphcover::LightPropagation propagation(cover, materials);
    // The points' hemisphere frames (vtkSphericalCoverFilter's Normals and Tangents), for the
    // receivers a non-diffuse point's hemisphere does not hold (LightPropagation::SetFrames).
    std::vector<sphcover::HemisphereFrame> frames;
    if (vtkIlluminationAdapter::ReadFrames(input, frames))
    {
      propagation.SetFrames(std::move(frames));
    }
    bool aborted = false;
    // The balance is a few passes over the entries (~1 s for the Cornell box's 6.5M): the
    // first 5% of the progress.
    if (this->BalanceExchanges)
    {
      const sphcover::ExchangeBalance balance(cover,
        {},
        [this, &aborted](double fraction)
        {
          this->UpdateProgress(0.05 * fraction);
          aborted = this->GetAbortExecute() != 0;
          return !aborted;
        });
      if (aborted)
      {
        vtkWarningMacro("Light propagation aborted.");
        return 0;
      }
      propagation.SetExchangeFactors(balance.EntryFactors());
    }
    propagation.Run(settings,
      [this, &aborted](double fraction)
      {
        this->UpdateProgress(0.05 + 0.9 * fraction);
        aborted = this->GetAbortExecute() != 0;
        return !aborted;
      });
    if (aborted)
    {
      vtkWarningMacro("Light propagation aborted.");
      return 0;
    }
    this->Shots = static_cast<int>(propagation.History().size());

    output->ShallowCopy(input);
    auto irradiance = vtkNamedArrays::Double(names::Irradiance, 3, count);
    auto radiosity = vtkNamedArrays::Double(names::Radiosity, 3, count);
    auto brightness = vtkNamedArrays::Double(names::Brightness, 3, count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      const glm::dvec3 e = propagation.Irradiance(static_cast<size_t>(i));
      const glm::dvec3 l = propagation.ExitantRadiance(static_cast<size_t>(i));
      const glm::dvec3 b = propagation.Brightness(static_cast<size_t>(i));
      irradiance->SetTuple(i, &e[0]);
      radiosity->SetTuple(i, &l[0]);
      brightness->SetTuple(i, &b[0]);
    }
    output->GetPointData()->AddArray(irradiance);
    output->GetPointData()->AddArray(radiosity);
    output->GetPointData()->AddArray(brightness);

    const std::vector<glm::dvec3>& incident = propagation.IncidentRadiances();
    auto regions =
      vtkNamedArrays::Double(names::IncidentRadiance, 3, static_cast<vtkIdType>(incident.size()));
    for (size_t e = 0; e < incident.size(); ++e)
    {
      regions->SetTuple(static_cast<vtkIdType>(e), &incident[e][0]);
    }
    output->GetFieldData()->AddArray(regions);
    const sphcover::EnergyBalance energy = propagation.Energy();
    auto balance = vtkNamedArrays::Double(names::EnergyBalance, 3, 2);
    balance->SetTuple(0, &energy.Emitted[0]);
    balance->SetTuple(1, &energy.Absorbed[0]);
    output->GetFieldData()->AddArray(balance);

    const std::vector<sphcover::ShotRecord>& shots = propagation.History();
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
      unshot->SetValue(k, record.UnshotEnergy);
      seconds->SetValue(k, record.Seconds);
    }
    history->Initialize();
    history->AddColumn(shot);
    history->AddColumn(shooter);
    history->AddColumn(change);
    history->AddColumn(unshot);
    history->AddColumn(seconds);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Light propagation failed: " << e.what());
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
  os << indent << "BalanceExchanges: " << (this->BalanceExchanges ? "On" : "Off") << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "Shots: " << this->Shots << "\n";
}
