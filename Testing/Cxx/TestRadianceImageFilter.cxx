// SPDX-License-Identifier: BSD-3-Clause
// vtkRadianceImageFilter (paper §5.3, Documentation/Pipeline.md#rendering):
// - white furnace (Documentation/Verification.md#correctness-references), flat and curved, diffuse
// and the tabulated clay, seen from the
//   scenes' cameras inside: every pixel's Radiance within 0.5% of Le / (1 - rho);
// - consistency with the solution: the back wall of the Cornell box seen head-on (the view
//   axis along its normal, so every pixel covers the same wall area) has a mean Radiance equal
//   to the area-weighted mean exitant radiance of its characteristic points (what the solve
//   report gives) within 1%;
// - the output arrays and the image size; RGB is the sRGB encoding of ExposureFactor * Radiance;
// - without camera properties, the scene's first camera at its size; a property set wins;
// - bad input: raw surfaces without illumination, an unknown camera, bad camera properties,
//   an image beyond the memory limit, non-diffuse points without IncidentRadiance, corrupt
//   DirectIrradiance nodes and CoverLampIrradiance: one clear error each.
#include "FailureExpectation.h"
#include "RenderTestPipeline.h"
#include "TestFailures.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using TestFailures::Check;

/// `albedo`: the walls' directional albedo per band, for a tabulated BRDF (the reader's Diffuse
/// otherwise).
void Furnace(const char* scene, int maxLevel, const double* albedo = nullptr)
{
  RenderTestPipeline::Pipeline pipeline(scene, maxLevel, 32, 128);
  pipeline.Propagation->SetConvergenceTolerance(1e-6);
  pipeline.Render->SetCameraName("inside");
  pipeline.Render->SetWidth(48);
  pipeline.Render->SetHeight(40);
  pipeline.Render->Update();
  vtkImageData* image = pipeline.Render->GetOutput();
  vtkDataArray* radiance = image->GetPointData()->GetArray("Radiance");
  vtkDataArray* surface = image->GetPointData()->GetArray("SurfaceId");
  Check(radiance && surface && image->GetNumberOfPoints() == 48 * 40, "furnace: the image");
  if (!radiance || !surface)
  {
    return;
  }
  // Le / (1 - rho) of the furnace material, from the reader's cell data.
  vtkDataArray* emission = pipeline.Reader->GetOutput()->GetCellData()->GetArray("Emission");
  vtkDataArray* diffuse = pipeline.Reader->GetOutput()->GetCellData()->GetArray("Diffuse");
  double worst = 0.0;
  for (vtkIdType p = 0; p < image->GetNumberOfPoints(); ++p)
  {
    Check(surface->GetComponent(p, 0) >= 0, "furnace: every pixel sees the enclosure");
    for (int b = 0; b < 3; ++b)
    {
      const double a = albedo ? albedo[b] : diffuse->GetComponent(0, b);
      const double expected = emission->GetComponent(0, b) / (1.0 - a);
      worst = std::max(worst, std::fabs(radiance->GetComponent(p, b) / expected - 1.0));
    }
  }
  std::cout << scene << ": largest |pixel / (Le / (1 - rho)) - 1| = " << worst << "\n";
  Check(worst < 5e-3, std::string(scene) + ": every pixel within 0.5% of Le / (1 - rho)");
  if (albedo)
  {
    // Non-diffuse points need the cover's incident radiance: without it, one clear error.
    vtkNew<vtkPolyData> withoutE;
    withoutE->ShallowCopy(pipeline.Propagation->GetOutput());
    vtkNew<vtkFieldData> fields;
    fields->ShallowCopy(withoutE->GetFieldData());
    fields->RemoveArray("IncidentRadiance");
    withoutE->SetFieldData(fields);
    vtkNew<vtkTrivialProducer> producer;
    producer->SetOutput(withoutE);
    vtkNew<vtkRadianceImageFilter> render;
    render->SetInputConnection(0, producer->GetOutputPort());
    render->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
    render->SetCameraName("inside");
    render->SetWidth(8);
    render->SetHeight(8);
    TestFailures::Add(FailureExpectation::Check(
      render, { "non-diffuse", "IncidentRadiance" }, "non-diffuse points without E"));
  }
}

void BadDirectIrradiance(RenderTestPipeline::Pipeline& pipeline);

void CornellBackWall()
{
  // The scene's own subdivision depth: the pixels' mean is the integral of the interpolated
  // field (§5.3.2), the solution's the area-weighted sum of the patches' values; the two differ
  // by the discretisation (about -4% at MaxLevel 2, -2% at 3, -1% at 4, -0.6..-0.9% at 5, the
  // wall's field being steep toward the lamp and the corners).
  RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 5);
  // In front of the blocks (their largest z is 472) and looking along the back wall's normal:
  // every pixel then covers the same area of the wall (solid angle cos^3 a, area t^2 / cos a,
  // t = d / cos a). The wide angle takes in the whole wall; one sample per pixel (the centre)
  // makes the pixel mean the midpoint rule over the wall.
  pipeline.Render->SetPosition(278.0, 274.4, 480.0);
  pipeline.Render->SetFocalPoint(278.0, 274.4, 559.2);
  pipeline.Render->SetViewUp(0.0, 1.0, 0.0);
  pipeline.Render->SetViewAngle(150.0);
  pipeline.Render->SetWidth(300);
  pipeline.Render->SetHeight(300);
  pipeline.Render->SetSamplesPerPixel(1);
  pipeline.Render->Update();
  vtkPolyData* lit = pipeline.Propagation->GetOutput();
  const int backWall = 2; // Data/scenes/cornell_box.scene's third surface
  vtkDataArray* surfaceOfPoint = lit->GetPointData()->GetArray("SurfaceId");
  vtkDataArray* area = lit->GetPointData()->GetArray("Area");
  vtkDataArray* radiosity = lit->GetPointData()->GetArray("Radiosity");
  double expected[3] = { 0.0, 0.0, 0.0 };
  double wallArea = 0.0;
  for (vtkIdType i = 0; i < lit->GetNumberOfPoints(); ++i)
  {
    if (surfaceOfPoint->GetComponent(i, 0) == backWall)
    {
      wallArea += area->GetComponent(i, 0);
      for (int b = 0; b < 3; ++b)
      {
        expected[b] += area->GetComponent(i, 0) * radiosity->GetComponent(i, b);
      }
    }
  }
  vtkImageData* image = pipeline.Render->GetOutput();
  vtkDataArray* radiance = image->GetPointData()->GetArray("Radiance");
  vtkDataArray* surface = image->GetPointData()->GetArray("SurfaceId");
  double mean[3] = { 0.0, 0.0, 0.0 };
  vtkIdType pixels = 0;
  for (vtkIdType p = 0; p < image->GetNumberOfPoints(); ++p)
  {
    if (surface->GetComponent(p, 0) == backWall)
    {
      ++pixels;
      for (int b = 0; b < 3; ++b)
      {
        mean[b] += radiance->GetComponent(p, b);
      }
    }
  }
  Check(pixels > 250 * 250, "Cornell: the back wall fills most of the frame");
  for (int b = 0; b < 3; ++b)
  {
    expected[b] /= wallArea;
    mean[b] /= static_cast<double>(pixels);
    std::cout << "Cornell back wall, band " << b << ": pixels " << mean[b] << ", solution "
              << expected[b] << " (" << 100.0 * (mean[b] / expected[b] - 1.0) << "%)\n";
    Check(std::fabs(mean[b] / expected[b] - 1.0) < 0.01,
      "Cornell: the back wall's mean pixel radiance is its mean exitant radiance within 1%");
  }
  // RGB is sRGB(ExposureFactor * Radiance), clamped.
  pipeline.Render->SetExposureFactor(2.0);
  pipeline.Render->Update();
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetArray("RGB"));
  radiance = image->GetPointData()->GetArray("Radiance");
  Check(rgb && rgb->GetNumberOfComponents() == 3, "RGB: 3 unsigned char components");
  Check(image->GetPointData()->GetScalars() == rgb, "RGB: the image's scalars");
  Check(vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Depth")) != nullptr,
    "Depth: float");
  for (vtkIdType p = 0; rgb && p < image->GetNumberOfPoints(); p += 97)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double c = std::min(1.0, 2.0 * radiance->GetComponent(p, b));
      const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
      Check(std::fabs(rgb->GetComponent(p, b) - 255.0 * encoded) <= 0.5 + 1e-9,
        "RGB: sRGB encoding of ExposureFactor * Radiance");
    }
  }
  BadDirectIrradiance(pipeline);
}

/// The lamps' direct light from corrupt nodes (a solution file edited or damaged): a wrong
/// number of components, a negative or NaN value, or no Diffuse to reflect it give one clear
/// error each.
void BadDirectIrradiance(RenderTestPipeline::Pipeline& pipeline)
{
  vtkPolyData* lit = pipeline.Propagation->GetOutput();
  vtkDataArray* nodes = lit->GetPointData()->GetArray("DirectIrradiance");
  Check(nodes && nodes->GetNumberOfComponents() == 243,
    "Cornell: the cover's DirectIrradiance, the default 9 x 9 nodes of 3 bands");
  if (!nodes)
  {
    return;
  }
  auto corrupt = [&](const char* what, const std::vector<std::string>& words, auto edit)
  {
    vtkNew<vtkPolyData> bad;
    bad->ShallowCopy(lit); // its own point data, sharing the arrays
    edit(bad->GetPointData());
    vtkNew<vtkTrivialProducer> producer;
    producer->SetOutput(bad);
    vtkNew<vtkRadianceImageFilter> render;
    render->SetInputConnection(0, producer->GetOutputPort());
    render->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
    render->SetWidth(8);
    render->SetHeight(8);
    TestFailures::Add(FailureExpectation::Check(render, words, what));
  };
  corrupt("DirectIrradiance of 12 components",
    { "DirectIrradiance", "12 components" },
    [&](vtkPointData* pd)
    {
      vtkNew<vtkFloatArray> wrong;
      wrong->SetName("DirectIrradiance");
      wrong->SetNumberOfComponents(12);
      wrong->SetNumberOfTuples(lit->GetNumberOfPoints());
      wrong->Fill(0.0);
      pd->AddArray(wrong);
    });
  for (const double value : { -1.0, std::nan("") })
  {
    corrupt("a negative or NaN DirectIrradiance",
      { "DirectIrradiance of point 7", "negative or not a finite number" },
      [&](vtkPointData* pd)
      {
        vtkNew<vtkFloatArray> copy;
        copy->DeepCopy(nodes);
        copy->SetComponent(7, 4, value);
        pd->AddArray(copy);
      });
  }
  corrupt("DirectIrradiance without Diffuse",
    { "DirectIrradiance", "no point array Diffuse" },
    [&](vtkPointData* pd) { pd->RemoveArray("Diffuse"); });

  // The cover's version of the nodes' light, which the render takes off the points.
  vtkDataArray* coverPart = lit->GetPointData()->GetArray("CoverLampIrradiance");
  Check(coverPart && coverPart->GetNumberOfComponents() == 3,
    "Cornell: the propagation's CoverLampIrradiance, 3 bands");
  if (!coverPart)
  {
    return;
  }
  corrupt("CoverLampIrradiance of 2 components",
    { "CoverLampIrradiance", "2 components, not 3" },
    [&](vtkPointData* pd)
    {
      vtkNew<vtkDoubleArray> wrong;
      wrong->SetName("CoverLampIrradiance");
      wrong->SetNumberOfComponents(2);
      wrong->SetNumberOfTuples(lit->GetNumberOfPoints());
      wrong->Fill(0.0);
      pd->AddArray(wrong);
    });
  for (const double value : { -1.0, std::nan("") })
  {
    corrupt("a negative or NaN CoverLampIrradiance",
      { "CoverLampIrradiance of point 5", "negative or not a finite number" },
      [&](vtkPointData* pd)
      {
        vtkNew<vtkDoubleArray> copy;
        copy->DeepCopy(coverPart);
        copy->SetComponent(5, 1, value);
        pd->AddArray(copy);
      });
  }
}

/// Centre pixel's depth (the image has an odd or even size: the pixel right of the centre).
double CentreDepth(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  return image->GetPointData()->GetArray("Depth")->GetComponent(
    static_cast<vtkIdType>(dims[1] / 2) * dims[0] + dims[0] / 2, 0);
}

/// With the camera properties at their defaults, the scene's first camera at its size (known
/// before the inputs execute, from the reader's pipeline information): the image of that camera
/// named; a property set wins, the others stay the camera's.
void SceneCamera()
{
  RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 0);
  pipeline.Render->SetSamplesPerPixel(1);
  pipeline.Render->Update();
  vtkNew<vtkImageData> byDefault;
  byDefault->DeepCopy(pipeline.Render->GetOutput());
  int dims[3];
  byDefault->GetDimensions(dims);
  Check(dims[0] == 512 && dims[1] == 512, "no camera property: camera 'main''s 512 x 512");
  pipeline.Render->SetCameraName("main");
  pipeline.Render->SetWidth(512);
  pipeline.Render->SetHeight(512);
  pipeline.Render->Update();
  vtkDataArray* named = pipeline.Render->GetOutput()->GetPointData()->GetArray("Radiance");
  vtkDataArray* unnamed = byDefault->GetPointData()->GetArray("Radiance");
  bool same = named && unnamed && named->GetNumberOfTuples() == unnamed->GetNumberOfTuples();
  for (vtkIdType k = 0; same && k < 3 * named->GetNumberOfTuples(); ++k)
  {
    same = named->GetComponent(k / 3, k % 3) == unnamed->GetComponent(k / 3, k % 3);
  }
  Check(same, "no camera property: the image of camera 'main' named");

  // The user's view and width win; the height, view up and view angle stay the camera's.
  pipeline.Render->SetCameraName("");
  pipeline.Render->SetWidth(64);
  pipeline.Render->SetHeight(0);
  pipeline.Render->SetPosition(278.0, 273.0, -400.0);
  pipeline.Render->SetFocalPoint(278.0, 273.0, -399.0);
  pipeline.Render->Update();
  vtkImageData* moved = pipeline.Render->GetOutput();
  moved->GetDimensions(dims);
  Check(dims[0] == 64 && dims[1] == 512, "Width 64 set: 64 x 512 (the camera's height)");
  // The centre ray runs along +z in both views: 400 closer to the back wall.
  const double closer = CentreDepth(byDefault) - CentreDepth(moved);
  std::cout << "scene camera: centre depth " << CentreDepth(byDefault) << ", moved 400 closer "
            << CentreDepth(moved) << "\n";
  Check(std::fabs(closer - 400.0) < 1.0, "Position and FocalPoint set: the user's view");
}

void BadInput()
{
  {
    // Raw surfaces (the reader's output) on port 0: no illumination to render.
    vtkNew<vtkPatchSceneReader> reader;
    reader->SetFileName(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene");
    vtkNew<vtkIntervalSubdivisionFilter> subdivision;
    subdivision->SetInputConnection(reader->GetOutputPort());
    subdivision->SetMaxLevel(0);
    vtkNew<vtkRadianceImageFilter> render;
    render->SetInputConnection(0, subdivision->GetOutputPort(1));
    render->SetPatchesConnection(subdivision->GetOutputPort(0));
    TestFailures::Add(FailureExpectation::Check(
      render, { "Radiosity", "vtkLightPropagationFilter" }, "characteristic points without light"));
  }
  RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 0);
  pipeline.Render->SetWidth(16);
  pipeline.Render->SetHeight(16);
  pipeline.Render->SetCameraName("nonexistent");
  TestFailures::Add(
    FailureExpectation::Check(pipeline.Render, { "nonexistent", "'main'" }, "unknown camera"));
  pipeline.Render->SetCameraName("main");
  pipeline.Render->Update();
  Check(pipeline.Render->GetOutput()->GetNumberOfPoints() == 256, "the scene's camera renders");
  pipeline.Render->SetCameraName("");
  // 0, the default, is the scene camera's view angle; 180 and below 0 are errors.
  pipeline.Render->SetViewAngle(180.0);
  TestFailures::Add(
    FailureExpectation::Check(pipeline.Render, { "view angle" }, "180 degrees view angle"));
  pipeline.Render->SetViewAngle(-30.0);
  TestFailures::Add(
    FailureExpectation::Check(pipeline.Render, { "view angle" }, "negative view angle"));
  pipeline.Render->SetViewAngle(30.0);
  pipeline.Render->SetViewUp(0.0, 0.0, -1.0); // parallel to the default view direction
  TestFailures::Add(
    FailureExpectation::Check(pipeline.Render, { "parallel" }, "view up along the view"));
  pipeline.Render->SetViewUp(0.0, 1.0, 0.0);
  pipeline.Render->SetWidth(-1); // 0 is the scene camera's width
  TestFailures::Add(FailureExpectation::Check(pipeline.Render, { "-1x16" }, "width -1"));
  pipeline.Render->SetWidth(100000);
  pipeline.Render->SetHeight(100000);
  TestFailures::Add(FailureExpectation::Check(pipeline.Render, { "MiB", "limit" }, "huge image"));
  pipeline.Render->SetWidth(16);
  pipeline.Render->SetHeight(16);
  pipeline.Render->SetSamplesPerPixel(0);
  TestFailures::Add(FailureExpectation::Check(pipeline.Render, { "samples" }, "no samples"));
}
}

int TestRadianceImageFilter(int, char*[])
{
  Furnace("furnace_box.scene", 2);
  Furnace("furnace_sphere.scene", 1);
  // The tabulated clay (Data/brdf/README.md: directional albedo (0.75, 0.55, 0.35) in every
  // direction): uniform only if the directional part of paper §5.3.1 is rendered.
  const double clay[3] = { 0.75, 0.55, 0.35 };
  Furnace("furnace_clay.scene", 1, clay);
  CornellBackWall();
  SceneCamera();
  BadInput();
  return TestFailures::ExitCode();
}
