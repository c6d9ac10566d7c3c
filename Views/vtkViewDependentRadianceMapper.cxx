// SPDX-License-Identifier: BSD-3-Clause
#include "vtkViewDependentRadianceMapper.h"

#include "vtkSphericalCoverArrayNames.h"
#include "vtkViewDependentRadiance.h"

#include <vtkCamera.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <string>

vtkStandardNewMacro(vtkViewDependentRadianceMapper);

vtkViewDependentRadianceMapper::vtkViewDependentRadianceMapper()
{
  // The colours are the light already (paper §5.3): the field's display bytes, as they are.
  this->Superclass::SetScalarVisibility(1);
  this->Superclass::SetScalarMode(VTK_SCALAR_MODE_USE_POINT_FIELD_DATA);
  this->Superclass::SetColorMode(VTK_COLOR_MODE_DIRECT_SCALARS);
  this->Superclass::SetArrayName(vtkSphericalCoverArrayNames::DisplayRGB);
  this->Superclass::SetArrayAccessMode(VTK_GET_ARRAY_BY_NAME);
}

vtkViewDependentRadianceMapper::~vtkViewDependentRadianceMapper() = default;

void vtkViewDependentRadianceMapper::SetEvaluator(vtkViewDependentRadiance* evaluator)
{
  if (this->Evaluator != evaluator)
  {
    this->Evaluator = evaluator;
    this->Modified();
  }
}

void vtkViewDependentRadianceMapper::Render(vtkRenderer* renderer, vtkActor* actor)
{
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  vtkCamera* camera = renderer ? renderer->GetActiveCamera() : nullptr;
  if (this->Evaluator && this->Evaluator->HasSolution() && input && camera)
  {
    // The eye of this frame: the colours are the radiance toward it (paper §5.3.1).
    double eye[3];
    camera->GetPosition(eye);
    std::string problem;
    auto update = [&](vtkDataObject* leaf)
    {
      auto* field = vtkPolyData::SafeDownCast(leaf);
      if (field && vtkViewDependentRadiance::CanEvaluate(field, problem))
      {
        this->Evaluator->Update(field, eye[0], eye[1], eye[2], this->ExposureStops);
      }
    };
    if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
    {
      vtkSmartPointer<vtkCompositeDataIterator> leaves;
      leaves.TakeReference(composite->NewIterator());
      for (leaves->InitTraversal(); !leaves->IsDoneWithTraversal(); leaves->GoToNextItem())
      {
        update(leaves->GetCurrentDataObject());
      }
    }
    else
    {
      update(input);
    }
  }
  this->Superclass::Render(renderer, actor);
}

void vtkViewDependentRadianceMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Evaluator: " << this->Evaluator.GetPointer() << "\n";
  os << indent << "ExposureStops: " << this->ExposureStops << "\n";
}
