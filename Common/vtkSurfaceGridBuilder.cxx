// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfaceGridBuilder.h"

#include "vtkNamedArrays.h"
#include "vtkSceneSettingsArray.h"
#include "vtkSphericalCoverArrayNames.h"

#include "geometry/BezierPatch.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkHigherOrderQuadrilateral.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

namespace names = vtkSphericalCoverArrayNames;

int vtkSurfaceGridBuilder::VTKPointIndex(int i, int j, int degreeU, int degreeV)
{
  const int order[3] = { degreeU, degreeV, 0 };
  return vtkHigherOrderQuadrilateral::PointIndexFromIJK(i, j, order);
}

bool vtkSurfaceGridBuilder::IsTriangle(const sphcover::BezierPatch& patch)
{
  return patch.DegreeU() == 1 && patch.DegreeV() == 1 &&
    patch.ControlPoint(1, 1) == patch.ControlPoint(0, 1);
}

void vtkSurfaceGridBuilder::BuildCells(const std::vector<const sphcover::BezierPatch*>& patches,
  vtkUnstructuredGrid* output)
{
  const vtkIdType numberOfCells = static_cast<vtkIdType>(patches.size());
  vtkIdType numberOfPoints = 0;
  for (const sphcover::BezierPatch* patch : patches)
  {
    numberOfPoints +=
      IsTriangle(*patch) ? 3 : static_cast<vtkIdType>(patch->ControlPoints().size());
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(numberOfPoints);
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(numberOfCells, numberOfPoints);
  vtkNew<vtkUnsignedCharArray> types;
  types->SetNumberOfValues(numberOfCells);
  auto degrees = vtkNamedArrays::Int(names::HigherOrderDegrees, 3, numberOfCells);

  std::vector<vtkIdType> ids;
  vtkIdType nextPoint = 0;
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    const sphcover::BezierPatch& patch = *patches[static_cast<size_t>(c)];
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    if (IsTriangle(patch))
    {
      // Stored as (P00, P10, P11, P01 = P11): the triangle is P00, P10, P11.
      ids = { nextPoint, nextPoint + 1, nextPoint + 2 };
      points->SetPoint(nextPoint, &patch.ControlPoint(0, 0)[0]);
      points->SetPoint(nextPoint + 1, &patch.ControlPoint(1, 0)[0]);
      points->SetPoint(nextPoint + 2, &patch.ControlPoint(1, 1)[0]);
      types->SetValue(c, VTK_TRIANGLE);
    }
    else
    {
      ids.resize(static_cast<size_t>((m + 1) * (n + 1)));
      for (int j = 0; j <= n; ++j)
      {
        for (int i = 0; i <= m; ++i)
        {
          const vtkIdType id = nextPoint + VTKPointIndex(i, j, m, n);
          points->SetPoint(id, &patch.ControlPoint(i, j)[0]);
        }
      }
      for (size_t k = 0; k < ids.size(); ++k)
      {
        ids[k] = nextPoint + static_cast<vtkIdType>(k);
      }
      // A bilinear patch's VTK ordering (corners counter-clockwise) is VTK_QUAD's.
      types->SetValue(c, (m == 1 && n == 1) ? VTK_QUAD : VTK_BEZIER_QUADRILATERAL);
    }
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    nextPoint += static_cast<vtkIdType>(ids.size());
    const int degree[3] = { m, n, 0 };
    degrees->SetTypedTuple(c, degree);
  }
  output->SetPoints(points);
  output->SetCells(types, cells);
  output->GetCellData()->SetHigherOrderDegrees(degrees);
}

void vtkSurfaceGridBuilder::BuildCharacteristicPoints(const std::vector<sphcover::Patch>& patches,
  vtkPolyData* output)
{
  const vtkIdType count = static_cast<vtkIdType>(patches.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(count);
  vtkNew<vtkCellArray> vertices;
  vertices->AllocateExact(count, count);
  auto patchId = vtkNamedArrays::Int(names::PatchId, 1, count);
  auto area = vtkNamedArrays::Double(names::Area, 1, count);
  for (vtkIdType p = 0; p < count; ++p)
  {
    const sphcover::Patch& patch = patches[static_cast<size_t>(p)];
    points->SetPoint(p, &patch.Point[0]);
    vertices->InsertNextCell(1, &p);
    patchId->SetValue(p, static_cast<int>(p));
    area->SetValue(p, patch.Area);
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetVerts(vertices);
  output->GetPointData()->AddArray(patchId);
  output->GetPointData()->AddArray(area);
}

void vtkSurfaceGridBuilder::AddMaterialArrays(const sphcover::Scene& scene,
  const std::vector<int>& surfaceOfCell,
  vtkUnstructuredGrid* output)
{
  const vtkIdType numberOfCells = static_cast<vtkIdType>(surfaceOfCell.size());
  auto surfaceNameId = vtkNamedArrays::Int(names::SurfaceNameId, 1, numberOfCells);
  auto materialId = vtkNamedArrays::Int(names::MaterialId, 1, numberOfCells);
  auto materialType = vtkNamedArrays::Int(names::MaterialType, 1, numberOfCells);
  auto twoSided = vtkNamedArrays::Int(names::TwoSided, 1, numberOfCells);
  auto emission = vtkNamedArrays::Double(names::Emission, 3, numberOfCells);
  auto diffuse = vtkNamedArrays::Double(names::Diffuse, 3, numberOfCells);
  auto specular = vtkNamedArrays::Double(names::Specular, 3, numberOfCells);
  auto exponent = vtkNamedArrays::Double(names::PhongExponent, 1, numberOfCells);
  auto transmittance = vtkNamedArrays::Double(names::Transmittance, 3, numberOfCells);
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    const sphcover::Surface& surface =
      scene.Surfaces[static_cast<size_t>(surfaceOfCell[static_cast<size_t>(c)])];
    const sphcover::Material& material =
      scene.Materials[static_cast<size_t>(surface.MaterialIndex)];
    surfaceNameId->SetValue(c, surface.NameIndex);
    materialId->SetValue(c, surface.MaterialIndex);
    materialType->SetValue(c, static_cast<int>(material.Type));
    twoSided->SetValue(c, surface.TwoSided ? 1 : 0);
    emission->SetTuple(c, &material.Emission[0]);
    diffuse->SetTuple(c, &material.Diffuse[0]);
    specular->SetTuple(c, &material.Specular[0]);
    exponent->SetValue(c, material.PhongExponent);
    transmittance->SetTuple(c, &material.Transmittance[0]);
  }
  vtkCellData* cd = output->GetCellData();
  cd->AddArray(surfaceNameId);
  cd->AddArray(materialId);
  cd->AddArray(materialType);
  cd->AddArray(twoSided);
  cd->AddArray(emission);
  cd->AddArray(diffuse);
  cd->AddArray(specular);
  cd->AddArray(exponent);
  cd->AddArray(transmittance);
}

void vtkSurfaceGridBuilder::AddTextureCoordinates(
  const std::vector<const sphcover::BezierPatch*>& patches,
  vtkUnstructuredGrid* output)
{
  // The points as BuildCells lays them out: each cell its own, a triangle's P00, P10, P11.
  auto tcoords = vtkNamedArrays::Double(names::TextureCoordinates, 2, output->GetNumberOfPoints());
  vtkIdType nextPoint = 0;
  for (const sphcover::BezierPatch* patch : patches)
  {
    if (IsTriangle(*patch))
    {
      const double corners[3][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 } };
      for (int k = 0; k < 3; ++k)
      {
        tcoords->SetTypedTuple(nextPoint + k, corners[k]);
      }
      nextPoint += 3;
      continue;
    }
    const int m = patch->DegreeU();
    const int n = patch->DegreeV();
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= m; ++i)
      {
        const double uv[2] = { static_cast<double>(i) / m, static_cast<double>(j) / n };
        tcoords->SetTypedTuple(nextPoint + VTKPointIndex(i, j, m, n), uv);
      }
    }
    nextPoint += static_cast<vtkIdType>((m + 1) * (n + 1));
  }
  output->GetPointData()->SetTCoords(tcoords);
}

void vtkSurfaceGridBuilder::Build(const sphcover::Scene& scene, vtkUnstructuredGrid* output)
{
  output->Initialize();
  std::vector<const sphcover::BezierPatch*> patches;
  std::vector<int> surfaceOfCell;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    patches.push_back(&scene.Surfaces[s].Patch);
    surfaceOfCell.push_back(static_cast<int>(s));
  }
  BuildCells(patches, output);
  auto surfaceId = vtkNamedArrays::Int(names::SurfaceId, 1, static_cast<vtkIdType>(patches.size()));
  for (size_t s = 0; s < patches.size(); ++s)
  {
    surfaceId->SetValue(static_cast<vtkIdType>(s), static_cast<int>(s));
  }
  output->GetCellData()->AddArray(surfaceId);
  AddTextureCoordinates(patches, output);
  AddMaterialArrays(scene, surfaceOfCell, output);
  AddFieldData(scene, output);
}

void vtkSurfaceGridBuilder::AddFieldData(const sphcover::Scene& scene, vtkUnstructuredGrid* output)
{
  vtkFieldData* fd = output->GetFieldData();
  auto surfaceNames =
    vtkNamedArrays::String(names::SurfaceNames, static_cast<vtkIdType>(scene.SurfaceNames.size()));
  for (size_t k = 0; k < scene.SurfaceNames.size(); ++k)
  {
    surfaceNames->SetValue(static_cast<vtkIdType>(k), scene.SurfaceNames[k]);
  }
  fd->AddArray(surfaceNames);

  const vtkIdType numberOfMaterials = static_cast<vtkIdType>(scene.Materials.size());
  auto materialNames = vtkNamedArrays::String(names::MaterialNames, numberOfMaterials);
  auto materialTypes = vtkNamedArrays::String(names::MaterialTypeNames, numberOfMaterials);
  auto materialFiles = vtkNamedArrays::String(names::MaterialFiles, numberOfMaterials);
  auto textures = vtkNamedArrays::String(names::MaterialTextures, numberOfMaterials);
  auto textureEncodings =
    vtkNamedArrays::String(names::MaterialTextureEncodings, numberOfMaterials);
  for (vtkIdType k = 0; k < numberOfMaterials; ++k)
  {
    const sphcover::Material& material = scene.Materials[static_cast<size_t>(k)];
    materialNames->SetValue(k, material.Name);
    materialTypes->SetValue(k, sphcover::MaterialTypeName(material.Type));
    materialFiles->SetValue(k, material.TableFile);
    textures->SetValue(k, material.TextureFile);
    textureEncodings->SetValue(k, sphcover::TextureEncodingName(material.TextureFileEncoding));
  }
  fd->AddArray(materialNames);
  fd->AddArray(materialTypes);
  fd->AddArray(materialFiles);
  fd->AddArray(textures);
  fd->AddArray(textureEncodings);

  const vtkIdType numberOfCameras = static_cast<vtkIdType>(scene.Cameras.size());
  auto cameraNames = vtkNamedArrays::String(names::CameraNames, numberOfCameras);
  auto cameraParameters = vtkNamedArrays::Double(names::CameraParameters, 12, numberOfCameras);
  const char* cameraComponents[12] = { "PositionX",
    "PositionY",
    "PositionZ",
    "FocalPointX",
    "FocalPointY",
    "FocalPointZ",
    "ViewUpX",
    "ViewUpY",
    "ViewUpZ",
    "ViewAngle",
    "Width",
    "Height" };
  for (int k = 0; k < 12; ++k)
  {
    cameraParameters->SetComponentName(k, cameraComponents[k]);
  }
  for (vtkIdType k = 0; k < numberOfCameras; ++k)
  {
    const sphcover::Camera& camera = scene.Cameras[static_cast<size_t>(k)];
    cameraNames->SetValue(k, camera.Name);
    const double values[12] = { camera.Position.x,
      camera.Position.y,
      camera.Position.z,
      camera.FocalPoint.x,
      camera.FocalPoint.y,
      camera.FocalPoint.z,
      camera.ViewUp.x,
      camera.ViewUp.y,
      camera.ViewUp.z,
      camera.ViewAngle,
      double(camera.Width),
      double(camera.Height) };
    cameraParameters->SetTuple(k, values);
  }
  fd->AddArray(cameraNames);
  fd->AddArray(cameraParameters);

  fd->AddArray(vtkSceneSettingsArray::New(scene.Settings));

  auto sourceFile = vtkNamedArrays::String(names::SourceFile, 1);
  sourceFile->SetValue(0, scene.SourceFile);
  fd->AddArray(sourceFile);

  // Passed on by every stage: vtkLightPropagationFilter converts its powers to watts with it.
  auto unit = vtkNamedArrays::String(names::SceneUnit, 1);
  unit->SetValue(0, scene.Unit.Name);
  fd->AddArray(unit);
  auto metres = vtkNamedArrays::Double(names::SceneUnitMetres, 1, 1);
  metres->SetValue(0, scene.Unit.Metres);
  fd->AddArray(metres);

  // Passed on by every stage, so that a solution written to a file names the scene it was
  // solved from (sphcover render --solution refuses another one).
  auto fingerprint = vtkNamedArrays::String(names::SceneFingerprint, 1);
  fingerprint->SetValue(0, sphcover::Fingerprint(scene));
  fd->AddArray(fingerprint);
}
