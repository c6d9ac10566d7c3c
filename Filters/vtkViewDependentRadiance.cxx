// SPDX-License-Identifier: BSD-3-Clause
#include "vtkViewDependentRadiance.h"

#include "vtkSolutionRenderer.h"
#include "vtkSphericalCoverArrayNames.h"

#include "render/RadianceRenderer.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <exception>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkViewDependentRadiance);

vtkViewDependentRadiance::vtkViewDependentRadiance() = default;
vtkViewDependentRadiance::~vtkViewDependentRadiance() = default;

bool vtkViewDependentRadiance::SetSolution(vtkPolyData* illumination, vtkDataSet* patches)
{
  this->Renderer.reset();
  std::string problem = "the illumination or the patches are missing";
  try
  {
    if (illumination && patches)
    {
      this->Renderer = vtkSolutionRenderer::New(illumination, patches, problem);
    }
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  if (!this->Renderer)
  {
    vtkErrorMacro(<< "Cannot use the solution: " << problem << ".");
    return false;
  }
  this->Modified();
  return true;
}

namespace
{
/// The field's array `name` of `components` components, created (float or bytes) when absent
/// or of another shape.
template<typename Array>
Array* FieldArray(vtkPolyData* field, const char* name, int components)
{
  auto* array = Array::SafeDownCast(field->GetPointData()->GetAbstractArray(name));
  if (!array || array->GetNumberOfComponents() != components ||
    array->GetNumberOfTuples() != field->GetNumberOfPoints())
  {
    vtkNew<Array> created;
    created->SetName(name);
    created->SetNumberOfComponents(components);
    created->SetNumberOfTuples(field->GetNumberOfPoints());
    field->GetPointData()->AddArray(created);
    array = created;
  }
  return array;
}
}

bool vtkViewDependentRadiance::Update(vtkPolyData* field,
  double x,
  double y,
  double z,
  double exposure)
{
  const auto start = std::chrono::steady_clock::now();
  if (!this->Renderer)
  {
    vtkErrorMacro(<< "Cannot evaluate the view: no solution (SetSolution).");
    return false;
  }
  vtkDataArray* surfaces = field ? field->GetPointData()->GetArray(names::SurfaceId) : nullptr;
  vtkDataArray* uv = field ? field->GetPointData()->GetArray(names::UV) : nullptr;
  if (!surfaces || !uv || uv->GetNumberOfComponents() != 2)
  {
    vtkErrorMacro(<< "Cannot evaluate the view: the field lacks " << names::SurfaceId << " or "
                  << names::UV << " (2 components): not an Illumination Field output.");
    return false;
  }
  auto* radiance = FieldArray<vtkFloatArray>(field, "ViewRadiance", 3);
  auto* rgb = FieldArray<vtkUnsignedCharArray>(field, names::DisplayRGB, 3);
  const glm::dvec3 eye(x, y, z);
  const double scale = std::exp2(exposure);
  const sphcover::RadianceRenderer& renderer = *this->Renderer;
  vtkSMPTools::For(vtkIdType(0),
    field->GetNumberOfPoints(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType id = begin; id < end; ++id)
      {
        double p[3];
        field->GetPoint(id, p);
        const glm::dvec3 toward = eye - glm::dvec3(p[0], p[1], p[2]);
        const double distance = glm::length(toward);
        // At the eye itself no direction: the front's Lambertian radiance.
        const glm::dvec3 l = distance > 0.0
          ? renderer.SurfaceRadianceToward(static_cast<int>(surfaces->GetComponent(id, 0)),
              uv->GetComponent(id, 0),
              uv->GetComponent(id, 1),
              toward / distance)
          : renderer.SurfaceRadiance(static_cast<int>(surfaces->GetComponent(id, 0)),
              uv->GetComponent(id, 0),
              uv->GetComponent(id, 1));
        for (int c = 0; c < 3; ++c)
        {
          radiance->SetTypedComponent(id, c, static_cast<float>(l[c]));
          // As the field's DisplayRGB: the float radiance, exposed and encoded.
          rgb->SetTypedComponent(
            id, c, vtkSolutionRenderer::EncodeSRGB(scale * static_cast<float>(l[c])));
        }
      }
    });
  field->GetPointData()->SetActiveScalars(names::DisplayRGB);
  radiance->Modified();
  rgb->Modified();
  this->LastUpdateSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

void vtkViewDependentRadiance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Solution: " << (this->Renderer ? "set" : "none") << "\n";
  os << indent << "LastUpdateSeconds: " << this->LastUpdateSeconds << "\n";
}
