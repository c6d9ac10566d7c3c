// SPDX-License-Identifier: BSD-3-Clause
#include "vtkViewDependentRadianceRepresentation.h"

#include "vtkSphericalCoverArrayNames.h"
#include "vtkViewDependentRadiance.h"
#include "vtkViewDependentRadianceMapper.h"

#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <string>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkViewDependentRadianceRepresentation);

vtkViewDependentRadianceRepresentation::vtkViewDependentRadianceRepresentation()
{
  // Replace the superclass's mapper (as ParaView's Examples/Plugins/Representation does) and
  // give the new one the superclass's selection settings, then set the pipeline up again.
  this->Mapper->Delete();
  vtkViewDependentRadianceMapper* mapper = vtkViewDependentRadianceMapper::New();
  mapper->SetProcessIdArrayName("vtkProcessId");
  mapper->SetCompositeIdArrayName("vtkCompositeIndex");
  this->Mapper = mapper;
  this->SetArrayIdNames(nullptr, nullptr);
  this->SuppressLOD = true;
  // Unlit: the colours are the light already (paper §5.3).
  this->Ambient = 1.0;
  this->Diffuse = 0.0;
  this->Specular = 0.0;
  this->SetupDefaults();
}

vtkViewDependentRadianceRepresentation::~vtkViewDependentRadianceRepresentation() = default;

void vtkViewDependentRadianceRepresentation::SetExposureStops(double stops)
{
  auto* mapper = static_cast<vtkViewDependentRadianceMapper*>(this->Mapper);
  const double clamped = std::clamp(stops, -20.0, 20.0);
  // The mapper's alone: the next render re-encodes the colours (no pipeline execution, which
  // would give the mapper a new field to evaluate in full).
  mapper->SetExposureStops(clamped);
}

double vtkViewDependentRadianceRepresentation::GetExposureStops() const
{
  return static_cast<vtkViewDependentRadianceMapper*>(this->Mapper)->GetExposureStops();
}

void vtkViewDependentRadianceRepresentation::SetSuppressLOD(bool)
{
  this->SuppressLOD = true;
}

namespace
{
/// Whether every polydata leaf of `data` (or `data` itself) can be evaluated, with at least one
/// leaf; else the problem in one sentence.
bool CanShow(vtkDataObject* data, std::string& problem)
{
  int leaves = 0;
  auto check = [&](vtkDataObject* leaf)
  {
    auto* field = vtkPolyData::SafeDownCast(leaf);
    if (field && field->GetNumberOfPoints() > 0)
    {
      ++leaves;
      return vtkViewDependentRadiance::CanEvaluate(field, problem);
    }
    return true;
  };
  bool usable = true;
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); usable && !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      usable = check(it->GetCurrentDataObject());
    }
  }
  else
  {
    usable = check(data);
  }
  if (usable && leaves == 0)
  {
    problem = "no polygonal data: not an Illumination Field output";
    return false;
  }
  return usable;
}
}

namespace
{
/**
 * Gives every polydata leaf of the geometry shown its own `DisplayRGB` (a copy) and no
 * `ViewRadiance`: the geometry is a shallow copy of the Illumination Field's output, and the
 * mapper rewrites these arrays in place, which must not change the field's output (what other
 * views and filters read).
 */
void OwnColours(vtkDataObject* shown)
{
  auto own = [](vtkDataObject* leaf)
  {
    auto* field = vtkPolyData::SafeDownCast(leaf);
    vtkDataArray* colours = field ? field->GetPointData()->GetArray(names::DisplayRGB) : nullptr;
    if (!field)
    {
      return;
    }
    field->GetPointData()->RemoveArray(names::ViewRadiance);
    if (colours)
    {
      vtkSmartPointer<vtkDataArray> copy;
      copy.TakeReference(colours->NewInstance());
      copy->DeepCopy(colours);
      field->GetPointData()->AddArray(copy);
    }
  };
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(shown))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      own(it->GetCurrentDataObject());
    }
  }
  else if (shown)
  {
    own(shown);
  }
}
}

int vtkViewDependentRadianceRepresentation::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    return 0;
  }
  auto* mapper = static_cast<vtkViewDependentRadianceMapper*>(this->Mapper);
  mapper->SetEvaluator(nullptr);
  // No input: a client or render server of a remote session (see the class warning).
  if (inputVector[0]->GetNumberOfInformationObjects() == 0 ||
    this->GetNumberOfInputConnections(0) == 0)
  {
    return 1;
  }
  // An empty piece (a rank other than 0 under `mpiexec pvbatch`, vtkScenePieces.h): nothing to
  // show, and nothing wrong.
  vtkDataObject* data = vtkDataObject::GetData(inputVector[0], 0);
  if (!data || data->GetNumberOfElements(vtkDataObject::POINT) == 0)
  {
    return 1;
  }
  std::string problem;
  if (!CanShow(data, problem))
  {
    vtkErrorMacro(<< "View-Dependent Radiance cannot show this data: " << problem
                  << ". Showing it without the view-dependent radiance.");
    return 1;
  }
  // The field's solution, rebuilt only when it changed (its one error comes from there).
  if (this->Evaluator->SetSolutionFrom(this->GetInputAlgorithm(0, 0)))
  {
    OwnColours(this->MultiBlockMaker->GetOutputDataObject(0));
    mapper->SetEvaluator(this->Evaluator);
  }
  return 1;
}

void vtkViewDependentRadianceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ExposureStops: " << this->GetExposureStops() << "\n";
  os << indent << "Evaluator:\n";
  this->Evaluator->PrintSelf(os, indent.GetNextIndent());
}
