// SPDX-License-Identifier: BSD-3-Clause
// vtkIlluminationField (Documentation/Pipeline.md#inspection-filters): the lit surfaces for
// walk-throughs in a render window.
// - the white furnace (Documentation/Verification.md#correctness-references): every vertex's
// Radiance within 0.5% of Le / (1 - rho);
// - the field agrees with the image filter: the pixel at the image centre (one sample) and the
//   field interpolated at the same visible point come from the same §5.3.2 interpolation;
// - bad input (characteristic points without illumination): one clear error;
// - regression image (Data/Baseline, ImageRegression.h: every level counted, mutations fail): the
//   Cornell box's field in a render window through the scene's camera, coloured by the
//   radiance mapped to sRGB (no lighting: the colours are the solution's).
#include "FailureExpectation.h"
#include "ImageRegression.h"
#include "RenderTestPipeline.h"
#include "TestFailures.h"
#include "vtkIlluminationField.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>

namespace
{
using TestFailures::Check;

void Furnace()
{
  RenderTestPipeline::Pipeline pipeline("furnace_box.scene", 2, 32, 128);
  pipeline.Propagation->SetConvergenceTolerance(1e-6);
  vtkNew<vtkIlluminationField> field;
  field->SetInputConnection(0, pipeline.Propagation->GetOutputPort(0));
  field->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
  field->SetResolution(4);
  field->Update();
  vtkPolyData* mesh = field->GetOutput();
  const vtkIdType patches = pipeline.Subdivision->GetOutput()->GetNumberOfCells();
  Check(mesh->GetNumberOfPoints() == patches * 25 && mesh->GetNumberOfCells() == patches * 16,
    "furnace: 5 x 5 vertices and 4 x 4 quads per patch");
  vtkDataArray* radiance = mesh->GetPointData()->GetArray("Radiance");
  vtkDataArray* emission = pipeline.Reader->GetOutput()->GetCellData()->GetArray("Emission");
  vtkDataArray* diffuse = pipeline.Reader->GetOutput()->GetCellData()->GetArray("Diffuse");
  double worst = 0.0;
  for (vtkIdType p = 0; radiance && p < mesh->GetNumberOfPoints(); ++p)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double expected = emission->GetComponent(0, b) / (1.0 - diffuse->GetComponent(0, b));
      worst = std::max(worst, std::fabs(radiance->GetComponent(p, b) / expected - 1.0));
    }
  }
  std::cout << "furnace field: largest |vertex / (Le / (1 - rho)) - 1| = " << worst << "\n";
  Check(radiance && worst < 5e-3, "furnace: every vertex within 0.5% of Le / (1 - rho)");
  Check(mesh->GetPointData()->GetNormals() && mesh->GetPointData()->GetArray("SurfaceId") &&
      mesh->GetCellData()->GetArray("PatchId"),
    "the field carries Normals, SurfaceId and PatchId");
}

/// sRGB bytes of the radiance (as the image filter's RGB with exposure 1).
void AddColours(vtkPolyData* mesh)
{
  vtkDataArray* radiance = mesh->GetPointData()->GetArray("Radiance");
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("Colours");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(radiance->GetNumberOfTuples());
  for (vtkIdType p = 0; p < radiance->GetNumberOfTuples(); ++p)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double c = std::min(1.0, std::max(0.0, radiance->GetComponent(p, b)));
      const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
      colours->SetComponent(p, b, std::round(255.0 * encoded));
    }
  }
  mesh->GetPointData()->SetScalars(colours);
}
}

int TestIlluminationField(int argc, char* argv[])
{
  Furnace();

  RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 2);
  vtkNew<vtkIlluminationField> field;
  field->SetInputConnection(0, pipeline.Propagation->GetOutputPort(0));
  field->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
  field->Update();

  // The image filter's centre pixel (one sample: the centre ray) sees the tall block's front;
  // the field's vertex nearest that point has nearly the same radiance (a vertex is at most
  // half a quad away; the field varies slowly there).
  pipeline.Render->SetCameraName("main");
  pipeline.Render->SetWidth(33);
  pipeline.Render->SetHeight(33);
  pipeline.Render->SetSamplesPerPixel(1);
  pipeline.Render->Update();
  vtkImageData* image = pipeline.Render->GetOutput();
  const vtkIdType centre = 16 * 33 + 16;
  const double depth = image->GetPointData()->GetArray("Depth")->GetComponent(centre, 0);
  // The main camera looks along +z from (278, 273, -800).
  const double visible[3] = { 278.0, 273.0, -800.0 + depth };
  vtkPolyData* mesh = field->GetOutput();
  vtkIdType nearest = -1;
  double best = 1e300;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    const double d = std::hypot(x[0] - visible[0], x[1] - visible[1], x[2] - visible[2]);
    if (d < best)
    {
      best = d;
      nearest = p;
    }
  }
  for (int b = 0; b < 3; ++b)
  {
    const double pixel = image->GetPointData()->GetArray("Radiance")->GetComponent(centre, b);
    const double vertex = mesh->GetPointData()->GetArray("Radiance")->GetComponent(nearest, b);
    std::cout << "band " << b << ": centre pixel " << pixel << ", field " << vertex << " (" << best
              << " away)\n";
    Check(std::fabs(pixel / vertex - 1.0) < 0.02, "the field agrees with the image filter");
  }

  {
    vtkNew<vtkIlluminationField> bad;
    bad->SetInputConnection(0, pipeline.Subdivision->GetOutputPort(1));
    bad->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
    TestFailures::Add(
      FailureExpectation::Check(bad, { "Radiosity" }, "characteristic points without light"));
  }

  vtkNew<vtkPolyData> coloured;
  coloured->ShallowCopy(mesh);
  AddColours(coloured);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(coloured);
  mapper->SetColorModeToDirectScalars();
  mapper->SetScalarModeToUsePointData();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetLighting(false);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.0, 0.0, 0.0);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(278.0, 273.0, -800.0);
  camera->SetFocalPoint(278.0, 273.0, -799.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetViewAngle(39.3077);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderWindow> window;
  window->SetSize(200, 200);
  window->AddRenderer(renderer);
  window->Render();
  Check(ImageRegression::Check(window, argc, argv), "regression image");
  return TestFailures::ExitCode();
}
