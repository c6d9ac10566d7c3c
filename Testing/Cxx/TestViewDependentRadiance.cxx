// SPDX-License-Identifier: BSD-3-Clause
// vtkViewDependentRadiance (issue 18, the per-vertex evaluation of a walk-through in a render
// view) on the mixed box (a lamp wall, a mirror wall, phong, tabulated and diffuse walls):
// - diffuse surfaces show exactly the Illumination Field's Radiance, from every eye;
// - the mirror's vertices change with the eye (its image is the room seen from the eye's
//   mirror position, paper §5.3.1);
// - a vertex's value is what the image filter's ray sees there: one centred sample of a tiny
//   camera at the eye looking at the vertex (ray cast and refined on the exact patch, an
//   independent route to the same (surface, u, v)) has the same radiance within 0.1 %;
// - no solution, or a field without UV: one clear error, the field unchanged.
#include "RenderTestPipeline.h"
#include "TestFailures.h"
#include "vtkIlluminationField.h"
#include "vtkViewDependentRadiance.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace
{
using TestFailures::Check;

/// Runs `call`, which must fail with one error naming `fragment` (the observer also keeps VTK's
/// "ERROR:" block out of the log, which CTest would fail on).
template<typename Call>
void ExpectOneError(vtkObject* object, const std::string& fragment, Call&& call)
{
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&errors);
  observer->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      static_cast<std::vector<std::string>*>(clientData)
        ->push_back(callData ? static_cast<const char*>(callData) : "");
    });
  const unsigned long tag = object->AddObserver(vtkCommand::ErrorEvent, observer);
  const bool succeeded = call();
  object->RemoveObserver(tag);
  Check(!succeeded && errors.size() == 1 && errors[0].find(fragment) != std::string::npos,
    "one error naming '" + fragment + "'");
}

/// The material type (0 diffuse, 1 mirror, ...) of every surface, from its characteristic points.
std::map<int, int> SurfaceTypes(vtkPolyData* illumination)
{
  std::map<int, int> types;
  vtkDataArray* surface = illumination->GetPointData()->GetArray("SurfaceId");
  vtkDataArray* type = illumination->GetPointData()->GetArray("MaterialType");
  for (vtkIdType p = 0; surface && type && p < illumination->GetNumberOfPoints(); ++p)
  {
    types[static_cast<int>(surface->GetComponent(p, 0))] =
      static_cast<int>(type->GetComponent(p, 0));
  }
  return types;
}
}

int TestViewDependentRadiance(int, char*[])
{
  RenderTestPipeline::Pipeline pipeline("mixed_box.scene", 2);
  vtkNew<vtkIlluminationField> field;
  field->SetInputConnection(0, pipeline.Propagation->GetOutputPort(0));
  field->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
  field->SetResolution(4);
  field->Update();
  vtkPolyData* mesh = field->GetOutput();
  const std::map<int, int> types = SurfaceTypes(pipeline.Propagation->GetOutput());

  vtkNew<vtkViewDependentRadiance> view;
  ExpectOneError(view, "no solution", [&] { return view->Update(mesh, 0.5, 0.5, 0.5, 0.0); });
  Check(view->SetSolution(pipeline.Propagation->GetOutput(), pipeline.Subdivision->GetOutput()),
    "the solution is accepted");

  const double eyes[2][3] = { { 0.5, 0.5, 0.5 }, { 0.25, 0.7, 0.3 } };
  std::vector<std::vector<float>> values;
  for (const auto& eye : eyes)
  {
    Check(view->Update(mesh, eye[0], eye[1], eye[2], 0.0), "Update succeeds");
    vtkDataArray* seen = mesh->GetPointData()->GetArray("ViewRadiance");
    std::vector<float> copy(static_cast<size_t>(3 * mesh->GetNumberOfPoints()));
    for (vtkIdType p = 0; seen && p < mesh->GetNumberOfPoints(); ++p)
    {
      for (int b = 0; b < 3; ++b)
      {
        copy[static_cast<size_t>(3 * p + b)] = static_cast<float>(seen->GetComponent(p, b));
      }
    }
    values.push_back(copy);
  }

  // A camera move evaluates the view-dependent vertices only (the mirror's, the glossy cube's),
  // from their tabulated terms and the caches the first eye filled; the same eye again nothing.
  // The values are a fresh evaluator's for that eye alone, bit for bit, exposure included.
  const vtkIdType moved = view->GetLastEvaluatedVertices();
  vtkIdType nonDiffuse = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    nonDiffuse += types.at(static_cast<int>(
                    mesh->GetPointData()->GetArray("SurfaceId")->GetComponent(p, 0))) != 0;
  }
  std::cout << "the camera move evaluated " << moved << " of " << mesh->GetNumberOfPoints()
            << " vertices, " << nonDiffuse << " on non-diffuse surfaces\n";
  Check(moved == nonDiffuse && moved < mesh->GetNumberOfPoints(),
    "a camera move evaluates the non-diffuse surfaces' vertices only (" + std::to_string(moved) +
      ")");
  Check(view->Update(mesh, eyes[1][0], eyes[1][1], eyes[1][2], 1.0) &&
      view->GetLastEvaluatedVertices() == 0,
    "an exposure change evaluates no vertex");
  vtkNew<vtkPolyData> alone;
  alone->DeepCopy(mesh);
  vtkNew<vtkViewDependentRadiance> fresh;
  Check(fresh->SetSolution(pipeline.Propagation->GetOutput(), pipeline.Subdivision->GetOutput()) &&
      fresh->Update(alone, eyes[1][0], eyes[1][1], eyes[1][2], 1.0),
    "a fresh evaluator evaluates the second eye");
  for (const char* name : { "ViewRadiance", "DisplayRGB" })
  {
    vtkDataArray* incremental = mesh->GetPointData()->GetArray(name);
    vtkDataArray* direct = alone->GetPointData()->GetArray(name);
    vtkIdType differ = 0;
    for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    {
      for (int b = 0; b < 3; ++b)
      {
        differ += incremental->GetComponent(p, b) != direct->GetComponent(p, b);
      }
    }
    Check(differ == 0,
      std::string(name) + " after a camera move and an exposure change is a fresh evaluation's (" +
        std::to_string(differ) + " values differ)");
  }

  vtkDataArray* radiance = mesh->GetPointData()->GetArray("Radiance");
  vtkDataArray* surfaces = mesh->GetPointData()->GetArray("SurfaceId");
  vtkIdType diffuseDiffer = 0;
  vtkIdType diffuseCount = 0;
  vtkIdType mirrorChanged = 0;
  vtkIdType mirrorCount = 0;
  vtkIdType mirrorVertex = -1;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const int type = types.at(static_cast<int>(surfaces->GetComponent(p, 0)));
    bool changed = false;
    for (int b = 0; b < 3; ++b)
    {
      const size_t k = static_cast<size_t>(3 * p + b);
      if (type == 0)
      {
        diffuseDiffer += values[0][k] != static_cast<float>(radiance->GetComponent(p, b)) ||
          values[1][k] != static_cast<float>(radiance->GetComponent(p, b));
      }
      changed = changed ||
        std::fabs(values[0][k] - values[1][k]) > 0.01 * std::max(values[0][k], values[1][k]);
    }
    diffuseCount += type == 0;
    if (type == 1)
    {
      ++mirrorCount;
      mirrorChanged += changed;
      double x[3];
      mesh->GetPoint(p, x);
      // A vertex inside the mirror wall (x = 1), away from its edges.
      if (mirrorVertex < 0 && std::fabs(x[1] - 0.5) < 0.2 && std::fabs(x[2] - 0.5) < 0.2)
      {
        mirrorVertex = p;
      }
    }
  }
  std::cout << "diffuse vertices " << diffuseCount << " (" << diffuseDiffer
            << " differ from Radiance), mirror vertices " << mirrorCount << " (" << mirrorChanged
            << " change with the eye)\n";
  Check(diffuseCount > 0 && diffuseDiffer == 0,
    "diffuse vertices show the Illumination Field's Radiance from every eye (" +
      std::to_string(diffuseDiffer) + " of " + std::to_string(diffuseCount) + " differ)");
  Check(mirrorCount > 0 && mirrorChanged > mirrorCount / 2,
    "the mirror changes with the eye (" + std::to_string(mirrorChanged) + " of " +
      std::to_string(mirrorCount) + " vertices)");

  // The vertex against the image filter's centre ray from the second eye.
  Check(mirrorVertex >= 0, "a vertex inside the mirror");
  if (mirrorVertex >= 0)
  {
    double x[3];
    mesh->GetPoint(mirrorVertex, x);
    pipeline.Render->SetPosition(eyes[1][0], eyes[1][1], eyes[1][2]);
    pipeline.Render->SetFocalPoint(x);
    pipeline.Render->SetViewUp(0.0, 1.0, 0.0);
    pipeline.Render->SetViewAngle(0.001);
    pipeline.Render->SetWidth(1);
    pipeline.Render->SetHeight(1);
    pipeline.Render->SetSamplesPerPixel(1);
    pipeline.Render->Update();
    vtkDataArray* pixel = pipeline.Render->GetOutput()->GetPointData()->GetArray("Radiance");
    for (int b = 0; b < 3; ++b)
    {
      const double image = pixel->GetComponent(0, b);
      const double vertex = values[1][static_cast<size_t>(3 * mirrorVertex + b)];
      std::cout << "mirror vertex " << mirrorVertex << ", band " << b << ": " << vertex
                << ", the image's ray " << image << "\n";
      Check(std::fabs(image - vertex) <= 1e-3 * std::max(image, 1e-6),
        "the mirror vertex " + std::to_string(vertex) + " is the image's ray " +
          std::to_string(image) + " (band " + std::to_string(b) + ")");
    }
  }

  vtkNew<vtkPolyData> bare;
  bare->ShallowCopy(mesh);
  bare->GetPointData()->RemoveArray("UV");
  ExpectOneError(
    view, "lacks SurfaceId or UV", [&] { return view->Update(bare, 0.5, 0.5, 0.5, 0.0); });
  return TestFailures::ExitCode();
}
