// SPDX-License-Identifier: BSD-3-Clause
// vtkIntervalSubdivisionFilter:
// - a regression image (VTK-style baseline) of the paper's Fig. 9 situation: a doubly curved
//   patch seen from a point near it, its patches coloured by SplitReason with their edges;
// - bad properties and inputs give one clear error and a failed request, never a crash;
// - the patches keep the MaterialId and SurfaceNameId of their surfaces (the field arrays they
//   index are passed on).
#include "FailureExpectation.h"
#include "ImageRegression.h"
#include "vtkIntervalSubdivisionFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkSurfaceGridAdapter.h"

#include "scene/Scene.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataSetMapper.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkUnstructuredGrid.h>

#include <iostream>
#include <string>
#include <vector>

namespace
{
/// Updates the filter expecting a failure with one error that contains `fragment`.
int ExpectFailure(vtkIntervalSubdivisionFilter* filter, const std::string& fragment)
{
  return FailureExpectation::Check(filter, { fragment }, "vtkIntervalSubdivisionFilter");
}

/// The outlines of the patches: their exact boundary curves, sampled.
vtkSmartPointer<vtkPolyData> PatchOutlines(vtkUnstructuredGrid* patches)
{
  sphcover::Scene scene;
  std::string error;
  vtkSurfaceGridAdapter::ToScene(patches, true, scene, error);
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  constexpr int samples = 16;
  for (const sphcover::Surface& surface : scene.Surfaces)
  {
    std::vector<vtkIdType> ids;
    for (int side = 0; side < 4; ++side)
    {
      for (int k = 0; k < samples; ++k)
      {
        const double t = double(k) / samples;
        const double uv[4][2] = { { t, 0 }, { 1, t }, { 1 - t, 1 }, { 0, 1 - t } };
        const glm::dvec3 p = surface.Patch.Evaluate(uv[side][0], uv[side][1]);
        ids.push_back(points->InsertNextPoint(p.x, p.y, p.z));
      }
    }
    ids.push_back(ids.front());
    lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  auto outlines = vtkSmartPointer<vtkPolyData>::New();
  outlines->SetPoints(points);
  outlines->SetLines(lines);
  return outlines;
}
}

int TestIntervalSubdivisionFilter(int argc, char* argv[])
{
  int failures = 0;
  vtkNew<vtkPatchSceneReader> reader;
  reader->SetFileName(SPHCOVER_DATA_DIR "/scenes/fig9_dome.scene");

  // Bad properties.
  {
    vtkNew<vtkIntervalSubdivisionFilter> filter;
    filter->SetInputConnection(reader->GetOutputPort());
    filter->SetSphericalShapeTolerance(-0.5);
    failures += ExpectFailure(filter, "SphericalShapeTolerance must be");
    filter->SetSphericalShapeTolerance(0.02);
    // -1 is SCENE_SETTING (the scene's max_level); below it, an error.
    filter->SetMaxLevel(-2);
    failures += ExpectFailure(filter, "MaxLevel must be >= 0");
    filter->SetMaxLevel(2);
    filter->SetPhiBins(0);
    failures += ExpectFailure(filter, "PhiBins");
  }
  // Bad inputs: empty, and surfaces without the material arrays.
  {
    vtkNew<vtkUnstructuredGrid> empty;
    vtkNew<vtkIntervalSubdivisionFilter> filter;
    filter->SetInputData(empty);
    failures += ExpectFailure(filter, "no surfaces");

    reader->Update();
    vtkNew<vtkUnstructuredGrid> bare;
    bare->ShallowCopy(reader->GetOutput());
    bare->GetCellData()->RemoveArray("Diffuse");
    filter->SetInputData(bare);
    failures += ExpectFailure(filter, "lacks the material cell arrays");

    // A material kind the method does not know (vtkMaterialArrays names the cell).
    vtkNew<vtkUnstructuredGrid> unknownKind;
    unknownKind->DeepCopy(reader->GetOutput());
    unknownKind->GetCellData()->GetArray("MaterialType")->SetComponent(0, 0, 7.0);
    filter->SetInputData(unknownKind);
    failures += ExpectFailure(filter, "cell 0 has the unknown MaterialType 7");

    // Ids that index no material or name.
    for (const double id : { -1.0, 1e9 })
    {
      vtkNew<vtkUnstructuredGrid> badId;
      badId->DeepCopy(reader->GetOutput());
      badId->GetCellData()->GetArray("MaterialId")->SetComponent(0, 0, id);
      filter->SetInputData(badId);
      failures += ExpectFailure(filter, "cell 0: MaterialId");
    }
    vtkNew<vtkUnstructuredGrid> badName;
    badName->DeepCopy(reader->GetOutput());
    badName->GetCellData()->GetArray("SurfaceNameId")->SetComponent(0, 0, -3.0);
    filter->SetInputData(badName);
    failures += ExpectFailure(filter, "cell 0: SurfaceNameId -3 is not an index");
  }

  // The output's MaterialId and SurfaceNameId index the field arrays it passes on
  // (MaterialNames, MaterialFiles, SurfaceNames) as the input's do: each patch keeps the ids of
  // the surface it came from. In the teapot room the materials (sorted by name in the field data)
  // first appear in another order than their ids (the floor, id 1, comes first); when the
  // filter renumbered them by appearance, a tabulated material got another material's (empty)
  // table file downstream.
  {
    vtkNew<vtkPatchSceneReader> room;
    room->SetFileName(SPHCOVER_DATA_DIR "/scenes/teapot_room.scene");
    vtkNew<vtkIntervalSubdivisionFilter> filter;
    filter->SetInputConnection(room->GetOutputPort());
    filter->SetMaxLevel(2);
    filter->Update();
    vtkUnstructuredGrid* surfaces = room->GetOutput();
    vtkUnstructuredGrid* out = filter->GetOutput();
    vtkDataArray* surfaceOf = out->GetCellData()->GetArray("SurfaceId");
    int mismatches = 0;
    for (const char* idName : { "MaterialId", "SurfaceNameId" })
    {
      vtkDataArray* in = surfaces->GetCellData()->GetArray(idName);
      vtkDataArray* kept = out->GetCellData()->GetArray(idName);
      for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
      {
        const vtkIdType surface = static_cast<vtkIdType>(surfaceOf->GetComponent(c, 0));
        mismatches += kept->GetComponent(c, 0) != in->GetComponent(surface, 0) ? 1 : 0;
      }
    }
    std::cout << "teapot room: " << out->GetNumberOfCells() << " patches, " << mismatches
              << " ids not the input's\n";
    if (out->GetNumberOfCells() <= surfaces->GetNumberOfCells() || mismatches != 0)
    {
      std::cerr << "FAILED: the patches do not keep their surfaces' MaterialId and SurfaceNameId\n";
      ++failures;
    }
  }

  // The Fig. 9 dome with the scene's settings, coloured by SplitReason.
  vtkNew<vtkIntervalSubdivisionFilter> subdivision;
  subdivision->SetInputConnection(reader->GetOutputPort());
  subdivision->Update();
  vtkUnstructuredGrid* patches = subdivision->GetOutput();
  std::cout << patches->GetNumberOfCells() << " patches, " << subdivision->GetPairTests()
            << " pair tests\n";
  if (patches->GetNumberOfCells() <= 2 ||
    vtkPolyData::SafeDownCast(subdivision->GetOutputDataObject(1))->GetNumberOfPoints() !=
      patches->GetNumberOfCells())
  {
    std::cerr << "FAILED: the dome was not subdivided into patches and points\n";
    ++failures;
  }

  vtkNew<vtkLookupTable> reasons;
  reasons->SetNumberOfTableValues(6);
  reasons->SetTableRange(0, 5);
  const double colours[6][3] = { { 0.8, 0.8, 0.8 },
    { 0.85, 0.2, 0.2 },
    { 0.2, 0.45, 0.85 },
    { 0.25, 0.7, 0.3 },
    { 0.9, 0.65, 0.1 },
    { 0.6, 0.3, 0.7 } };
  for (int r = 0; r < 6; ++r)
  {
    reasons->SetTableValue(r, colours[r][0], colours[r][1], colours[r][2]);
  }
  // The exact curved patches (finely tessellated for display), their outlines, and the
  // receiver's characteristic point.
  vtkNew<vtkDataSetSurfaceFilter> surfaces;
  surfaces->SetInputConnection(subdivision->GetOutputPort(0));
  surfaces->SetNonlinearSubdivisionLevel(3);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(surfaces->GetOutputPort());
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray("SplitReason");
  mapper->SetLookupTable(reasons);
  mapper->SetScalarRange(0, 5);
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkNew<vtkPolyDataMapper> outlineMapper;
  outlineMapper->SetInputData(PatchOutlines(patches));
  outlineMapper->SetResolveCoincidentTopologyToPolygonOffset();
  vtkNew<vtkActor> outlineActor;
  outlineActor->SetMapper(outlineMapper);
  outlineActor->GetProperty()->SetColor(0.1, 0.1, 0.1);
  vtkNew<vtkSphereSource> eye;
  eye->SetCenter(1.6, 0.0, 0.65);
  eye->SetRadius(0.05);
  vtkNew<vtkPolyDataMapper> eyeMapper;
  eyeMapper->SetInputConnection(eye->GetOutputPort());
  vtkNew<vtkActor> eyeActor;
  eyeActor->SetMapper(eyeMapper);
  eyeActor->GetProperty()->SetColor(0.1, 0.1, 0.1);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->AddActor(outlineActor);
  renderer->AddActor(eyeActor);
  renderer->SetBackground(1, 1, 1);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(2.6, -3.2, 3.0);
  camera->SetFocalPoint(0.2, 0, 0.5);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->AddRenderer(renderer);
  window->Render();
  if (!ImageRegression::Check(window, argc, argv))
  {
    ++failures;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
