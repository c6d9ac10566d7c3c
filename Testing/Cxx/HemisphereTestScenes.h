// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file HemisphereTestScenes.h
 * @brief Test helpers for vtkHemisphereExtractor: the pipeline reader -> subdivision -> cover
 * -> extractor for a scene, the characteristic point of a surface nearest a location, and the
 * regression view of one hemisphere (its (phi, theta) image above, the 3-D hemisphere in the
 * room below, both coloured by the SurfaceId (or SurfaceNameId) seen, with a fixed palette).
 */
#ifndef SPHCOVER_HEMISPHERETESTSCENES_H
#define SPHCOVER_HEMISPHERETESTSCENES_H

#include "vtkHemisphereExtractor.h"
#include "vtkIntervalSubdivisionFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkSphericalCoverFilter.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkDataSetMapper.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>

#include <limits>
#include <string>

namespace HemisphereTestScenes
{
/// The whole pipeline for one scene; the extractor is connected to the cover's first output.
struct Pipeline
{
  vtkNew<vtkPatchSceneReader> Reader;
  vtkNew<vtkIntervalSubdivisionFilter> Subdivision;
  vtkNew<vtkSphericalCoverFilter> Cover;
  vtkNew<vtkHemisphereExtractor> Extractor;

  Pipeline(const std::string& scene, int maxLevel)
  {
    this->Reader->SetFileName(scene.c_str());
    this->Subdivision->SetInputConnection(this->Reader->GetOutputPort());
    this->Subdivision->SetMaxLevel(maxLevel);
    this->Cover->SetInputConnection(this->Subdivision->GetOutputPort(0));
    this->Extractor->SetInputConnection(this->Cover->GetOutputPort(0));
  }
  vtkPolyData* CoverPoints()
  {
    return vtkPolyData::SafeDownCast(this->Cover->GetOutputDataObject(0));
  }
};

/// The index of `name` in the field array SurfaceNames (SurfaceId), -1 if absent.
inline int SurfaceIdOf(vtkDataObject* data, const std::string& name)
{
  auto* names =
    vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("SurfaceNames"));
  for (vtkIdType k = 0; names && k < names->GetNumberOfValues(); ++k)
  {
    if (names->GetValue(k) == name)
    {
      return static_cast<int>(k);
    }
  }
  return -1;
}

/// The characteristic point of surface `surfaceId` nearest `location`, -1 if none.
inline vtkIdType NearestPointOfSurface(vtkPolyData* points, int surfaceId, const double location[3])
{
  vtkDataArray* surface = points->GetPointData()->GetArray("SurfaceId");
  vtkIdType best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (vtkIdType i = 0; surface && i < points->GetNumberOfPoints(); ++i)
  {
    if (static_cast<int>(surface->GetComponent(i, 0)) != surfaceId)
    {
      continue;
    }
    double p[3];
    points->GetPoint(i, p);
    const double d = (p[0] - location[0]) * (p[0] - location[0]) +
      (p[1] - location[1]) * (p[1] - location[1]) + (p[2] - location[2]) * (p[2] - location[2]);
    if (d < bestDistance)
    {
      bestDistance = d;
      best = i;
    }
  }
  return best;
}

/**
 * One fixed colour per id 0..15 and black for -1 (nothing seen); the range is offset by
 * half a unit so that value v maps exactly to entry v + 1.
 */
inline vtkSmartPointer<vtkLookupTable> SurfaceColours()
{
  static const double colours[17][3] = { { 0.0, 0.0, 0.0 },
    { 0.85, 0.85, 0.80 },
    { 0.55, 0.55, 0.60 },
    { 0.95, 0.75, 0.45 },
    { 0.85, 0.15, 0.15 },
    { 0.15, 0.65, 0.20 },
    { 1.0, 0.95, 0.2 },
    { 0.25, 0.45, 0.90 },
    { 0.55, 0.75, 1.0 },
    { 0.10, 0.25, 0.55 },
    { 0.45, 0.85, 0.85 },
    { 0.60, 0.30, 0.75 },
    { 0.95, 0.45, 0.75 },
    { 0.85, 0.55, 0.15 },
    { 0.50, 0.30, 0.15 },
    { 0.70, 0.90, 0.45 },
    { 0.55, 0.10, 0.35 } };
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->SetNumberOfTableValues(17);
  table->SetTableRange(-1.5, 15.5);
  for (int k = 0; k < 17; ++k)
  {
    table->SetTableValue(k, colours[k][0], colours[k][1], colours[k][2]);
  }
  table->Build();
  return table;
}

inline void ColourBySurface(vtkMapper* mapper, vtkLookupTable* table, const char* array)
{
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray(array);
  mapper->SetLookupTable(table);
  mapper->UseLookupTableScalarRangeOn();
  mapper->ScalarVisibilityOn();
}

/**
 * Renders the extractor's current outputs into `window` (600 x 500): above, the (phi, theta)
 * image with phi growing to the right and the zenith (theta = 0) on top; below, the scene's
 * patches semi-transparent with the opaque 3-D hemisphere at the point, all coloured by the
 * cell array `array` (SurfaceId or SurfaceNameId), seen by the scene's
 * first camera (field data CameraParameters) with its view angle narrowed `zoom` times.
 */
inline void RenderHemisphere(Pipeline& pipeline,
  vtkRenderWindow* window,
  double zoom,
  const char* array = "SurfaceId")
{
  vtkSmartPointer<vtkLookupTable> table = SurfaceColours();

  vtkNew<vtkImageData> image;
  image->ShallowCopy(pipeline.Extractor->GetImageOutput());
  vtkNew<vtkDataSetMapper> imageMapper;
  imageMapper->SetInputData(image);
  ColourBySurface(imageMapper, table, array);
  vtkNew<vtkActor> imageActor;
  imageActor->SetMapper(imageMapper);
  imageActor->GetProperty()->LightingOff();
  vtkNew<vtkRenderer> imageRenderer;
  imageRenderer->SetViewport(0.0, 0.7, 1.0, 1.0);
  imageRenderer->SetBackground(1, 1, 1);
  imageRenderer->AddActor(imageActor);
  double bounds[6];
  image->GetBounds(bounds);
  const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0 };
  vtkCamera* flat = imageRenderer->GetActiveCamera();
  flat->ParallelProjectionOn();
  // From -z with view up -y: phi (x) grows to the right, theta (y) downwards.
  flat->SetFocalPoint(centre);
  flat->SetPosition(centre[0], centre[1], -10.0);
  flat->SetViewUp(0, -1, 0);
  flat->SetParallelScale(0.5 * (bounds[3] - bounds[2]) * 1.08);

  vtkNew<vtkDataSetSurfaceFilter> surfaces;
  surfaces->SetInputConnection(pipeline.Subdivision->GetOutputPort(0));
  surfaces->SetNonlinearSubdivisionLevel(2);
  vtkNew<vtkPolyDataMapper> sceneMapper;
  sceneMapper->SetInputConnection(surfaces->GetOutputPort());
  ColourBySurface(sceneMapper, table, array);
  vtkNew<vtkActor> sceneActor;
  sceneActor->SetMapper(sceneMapper);
  sceneActor->GetProperty()->SetOpacity(0.35);
  vtkNew<vtkPolyData> mesh;
  mesh->ShallowCopy(pipeline.Extractor->GetMeshOutput());
  vtkNew<vtkPolyDataMapper> meshMapper;
  meshMapper->SetInputData(mesh);
  ColourBySurface(meshMapper, table, array);
  vtkNew<vtkActor> meshActor;
  meshActor->SetMapper(meshMapper);
  meshActor->GetProperty()->SetAmbient(0.4);
  meshActor->GetProperty()->SetDiffuse(0.6);
  vtkNew<vtkRenderer> roomRenderer;
  roomRenderer->SetViewport(0.0, 0.0, 1.0, 0.7);
  roomRenderer->SetBackground(1, 1, 1);
  roomRenderer->AddActor(sceneActor);
  roomRenderer->AddActor(meshActor);
  roomRenderer->SetUseDepthPeeling(true);

  vtkDataArray* parameters = pipeline.CoverPoints()->GetFieldData()->GetArray("CameraParameters");
  vtkCamera* camera = roomRenderer->GetActiveCamera();
  double p[12];
  parameters->GetTuple(0, p);
  camera->SetPosition(p[0], p[1], p[2]);
  camera->SetFocalPoint(p[3], p[4], p[5]);
  camera->SetViewUp(p[6], p[7], p[8]);
  camera->SetViewAngle(p[9]);
  camera->Zoom(zoom);
  roomRenderer->ResetCameraClippingRange();

  window->SetSize(600, 500);
  window->SetAlphaBitPlanes(1);
  window->SetMultiSamples(0);
  window->AddRenderer(imageRenderer);
  window->AddRenderer(roomRenderer);
  window->Render();
}
}

#endif
