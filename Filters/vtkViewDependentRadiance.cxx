// SPDX-License-Identifier: BSD-3-Clause
#include "vtkViewDependentRadiance.h"

#include "vtkCoverPatches.h"
#include "vtkIlluminationField.h"
#include "vtkSolutionRenderer.h"
#include "vtkSphericalCoverArrayNames.h"

#include "render/RadianceRenderer.h"

#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkTimeStamp.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWeakPointer.h>

#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <exception>
#include <vector>

namespace names = vtkSphericalCoverArrayNames;

/// The per-thread caches live as long as the solution; the rest as long as one field.
struct vtkViewDependentRadiance::FieldState
{
  /// 2^16 slots (2 MB) per thread: a frame's (point, eye cell) pairs of the teapot room's
  /// non-diffuse points fit, so the next frame finds most of them.
  static constexpr int CacheBits = 16;
  vtkSMPThreadLocal<sphcover::RadianceRenderer::DirectionalCache> Caches{
    sphcover::RadianceRenderer::DirectionalCache(CacheBits)
  };

  /// The solution SetSolutionFrom last used, and when.
  vtkWeakPointer<vtkDataObject> Illumination;
  vtkWeakPointer<vtkDataObject> Patches;
  vtkTimeStamp SolutionTime;

  /// The field last evaluated: its geometry's arrays (their identity and the time after which
  /// a change means another field), the vertices whose radiance depends on the eye, and the
  /// eye and exposure of its arrays' values.
  vtkWeakPointer<vtkPolyData> Field;
  const void* Points = nullptr;
  const void* Surfaces = nullptr;
  const void* UV = nullptr;
  vtkTimeStamp Prepared;
  std::vector<vtkIdType> ViewDependent;
  /// The eye-independent terms of each view-dependent vertex (same order).
  std::vector<sphcover::RadianceRenderer::TowardTerms> Terms;
  double Eye[3] = { 0.0, 0.0, 0.0 };
  double ExposureStops = 0.0;

  void ForgetField() { this->Field = nullptr; }
};

vtkStandardNewMacro(vtkViewDependentRadiance);

vtkViewDependentRadiance::vtkViewDependentRadiance()
  : State(std::make_unique<FieldState>())
{
}

vtkViewDependentRadiance::~vtkViewDependentRadiance() = default;

bool vtkViewDependentRadiance::HasSolution() const
{
  return this->Renderer != nullptr;
}

bool vtkViewDependentRadiance::SetSolution(vtkPolyData* illumination, vtkDataSet* patches)
{
  this->Renderer.reset();
  // Cached values and the field's state belong to the solution they were evaluated with.
  this->State = std::make_unique<FieldState>();
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

bool vtkViewDependentRadiance::SetSolutionFrom(vtkAlgorithm* consumer)
{
  // The nearest Illumination Field along first inputs; the bound only stops a cycle.
  vtkAlgorithm* algorithm = consumer;
  for (int depth = 0; algorithm && depth < 64 && !vtkIlluminationField::SafeDownCast(algorithm);
       ++depth)
  {
    algorithm =
      algorithm->GetNumberOfInputPorts() > 0 && algorithm->GetNumberOfInputConnections(0) > 0
      ? algorithm->GetInputAlgorithm(0, 0)
      : nullptr;
  }
  auto* field = vtkIlluminationField::SafeDownCast(algorithm);
  if (!field)
  {
    vtkErrorMacro(<< "Cannot find the solution: no Illumination Field upstream of the data "
                     "shown (the view-dependent radiance is evaluated on an Illumination Field's "
                     "output).");
    return false;
  }
  auto* illumination = vtkPolyData::SafeDownCast(field->GetInputDataObject(0, 0));
  vtkDataSet* patches = vtkCoverPatches::Find(field);
  FieldState& state = *this->State;
  if (this->Renderer && illumination && patches && state.Illumination == illumination &&
    state.Patches == patches && illumination->GetMTime() <= state.SolutionTime &&
    patches->GetMTime() <= state.SolutionTime)
  {
    return true;
  }
  if (!this->SetSolution(illumination, patches))
  {
    return false;
  }
  this->State->Illumination = illumination;
  this->State->Patches = patches;
  this->State->SolutionTime.Modified();
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

/// Whether `object` is the one remembered and unchanged since `time`.
bool Unchanged(vtkObject* object, const void* remembered, const vtkTimeStamp& time)
{
  return object && object == remembered && object->GetMTime() <= time;
}
}

bool vtkViewDependentRadiance::CanEvaluate(vtkPolyData* field, std::string& problem)
{
  vtkDataArray* surfaces = field ? field->GetPointData()->GetArray(names::SurfaceId) : nullptr;
  vtkDataArray* uv = field ? field->GetPointData()->GetArray(names::UV) : nullptr;
  if (!surfaces || !uv || uv->GetNumberOfComponents() != 2)
  {
    problem = std::string("the field lacks ") + names::SurfaceId + " or " + names::UV +
      " (2 components): not an Illumination Field output";
    return false;
  }
  return true;
}

bool vtkViewDependentRadiance::Update(vtkPolyData* field,
  double x,
  double y,
  double z,
  double exposureStops)
{
  const auto start = std::chrono::steady_clock::now();
  this->LastEvaluatedVertices = 0;
  if (!this->Renderer)
  {
    vtkErrorMacro(<< "Cannot evaluate the view: no solution (SetSolution).");
    return false;
  }
  std::string problem;
  if (!CanEvaluate(field, problem))
  {
    vtkErrorMacro(<< "Cannot evaluate the view: " << problem << ".");
    return false;
  }
  vtkDataArray* surfaces = field->GetPointData()->GetArray(names::SurfaceId);
  vtkDataArray* uv = field->GetPointData()->GetArray(names::UV);
  auto* radiance = FieldArray<vtkFloatArray>(field, names::ViewRadiance, 3);
  auto* rgb = FieldArray<vtkUnsignedCharArray>(field, names::DisplayRGB, 3);
  FieldState& state = *this->State;
  const bool sameField = state.Field == field &&
    Unchanged(field->GetPoints(), state.Points, state.Prepared) &&
    Unchanged(surfaces, state.Surfaces, state.Prepared) && Unchanged(uv, state.UV, state.Prepared);
  const bool sameEye = sameField && state.Eye[0] == x && state.Eye[1] == y && state.Eye[2] == z;
  const bool sameExposure = sameField && state.ExposureStops == exposureStops;
  if (sameEye && sameExposure)
  {
    this->LastUpdateSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
  }

  const glm::dvec3 eye(x, y, z);
  const double scale = std::exp2(exposureStops);
  const sphcover::RadianceRenderer& renderer = *this->Renderer;
  // The vertex's radiance toward the eye from its tabulated terms, and its bytes as the field's
  // DisplayRGB: the float radiance, exposed and encoded.
  using Terms = sphcover::RadianceRenderer::TowardTerms;
  auto evaluate = [&](vtkIdType id, const Terms& terms)
  {
    double p[3];
    field->GetPoint(id, p);
    const glm::dvec3 toward = eye - glm::dvec3(p[0], p[1], p[2]);
    const double distance = glm::length(toward);
    // At the eye itself no direction: the front's Lambertian radiance.
    const glm::dvec3 l = distance > 0.0
      ? renderer.RadianceToward(terms, toward / distance, state.Caches.Local())
      : renderer.SurfaceRadiance(terms.Surface, terms.U, terms.V);
    for (int c = 0; c < 3; ++c)
    {
      radiance->SetTypedComponent(id, c, static_cast<float>(l[c]));
    }
  };
  auto encode = [&](vtkIdType id)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb->SetTypedComponent(
        id, c, vtkSolutionRenderer::EncodeSRGB(scale * radiance->GetTypedComponent(id, c)));
    }
  };

  const vtkIdType count = field->GetNumberOfPoints();
  if (!sameField)
  {
    // A new field: every vertex once, and which of them depend on the eye, with their terms.
    std::vector<Terms> all(static_cast<std::size_t>(count));
    std::vector<char> dependent(static_cast<std::size_t>(count), 0);
    vtkSMPTools::For(vtkIdType(0),
      count,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType id = begin; id < end; ++id)
        {
          Terms& terms = all[static_cast<std::size_t>(id)];
          terms = renderer.Terms(static_cast<int>(surfaces->GetComponent(id, 0)),
            uv->GetComponent(id, 0),
            uv->GetComponent(id, 1));
          evaluate(id, terms);
          encode(id);
          dependent[static_cast<std::size_t>(id)] = renderer.IsViewDependent(terms);
        }
      });
    state.ViewDependent.clear();
    state.Terms.clear();
    for (vtkIdType id = 0; id < count; ++id)
    {
      if (dependent[static_cast<std::size_t>(id)])
      {
        state.ViewDependent.push_back(id);
        state.Terms.push_back(all[static_cast<std::size_t>(id)]);
      }
    }
    state.Field = field;
    state.Points = field->GetPoints();
    state.Surfaces = surfaces;
    state.UV = uv;
    state.Prepared.Modified();
    this->LastEvaluatedVertices = count;
  }
  else
  {
    if (!sameEye)
    {
      // Only the view-dependent vertices change with the eye (and their bytes with them).
      const std::vector<vtkIdType>& ids = state.ViewDependent;
      vtkSMPTools::For(std::size_t(0),
        ids.size(),
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t k = begin; k < end; ++k)
          {
            evaluate(ids[k], state.Terms[k]);
            encode(ids[k]);
          }
        });
      this->LastEvaluatedVertices = static_cast<vtkIdType>(ids.size());
    }
    if (!sameExposure)
    {
      vtkSMPTools::For(vtkIdType(0),
        count,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType id = begin; id < end; ++id)
          {
            encode(id);
          }
        });
    }
  }
  state.Eye[0] = x;
  state.Eye[1] = y;
  state.Eye[2] = z;
  state.ExposureStops = exposureStops;
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
  os << indent << "ViewDependentVertices: " << this->State->ViewDependent.size() << "\n";
  os << indent << "LastUpdateSeconds: " << this->LastUpdateSeconds << "\n";
  os << indent << "LastEvaluatedVertices: " << this->LastEvaluatedVertices << "\n";
}
