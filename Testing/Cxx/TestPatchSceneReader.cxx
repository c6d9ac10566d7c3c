// SPDX-License-Identifier: BSD-3-Clause
// The readers' output contract (Documentation/Pipeline.md#reader) on every scene and model shipped
// in Data/:
// - every scene reads; one cell per surface; the named cell and field arrays exist with the
//   right number of components;
// - the output converts back to the same Core scene (vtkSurfaceGridAdapter): control points
//   bit for bit, materials, names, triangle and two-sided flags;
// - every .bpt model reads with the patch count and bounds its source documents;
// - facts of the Cornell box: walls are VTK_QUADs, the box bounds, the official camera.
#include "TestFailures.h"
#include "vtkBPTReader.h"
#include "vtkPatchSceneReader.h"
#include "vtkSceneFileLoader.h"
#include "vtkSceneSettingsArray.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSurfaceGridAdapter.h"

#include "scene/Scene.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <string>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
using TestFailures::Check;

void CheckArrays(vtkUnstructuredGrid* grid, const std::string& file)
{
  vtkCellData* cd = grid->GetCellData();
  const std::pair<const char*, int> cellArrays[] = { { names::SurfaceId, 1 },
    { names::SurfaceNameId, 1 },
    { names::MaterialId, 1 },
    { names::MaterialType, 1 },
    { names::Emission, 3 },
    { names::Diffuse, 3 },
    { names::Specular, 3 },
    { names::PhongExponent, 1 },
    { names::TwoSided, 1 },
    { names::Transmittance, 3 },
    { names::HigherOrderDegrees, 3 } };
  for (const auto& array : cellArrays)
  {
    vtkDataArray* a = cd->GetArray(array.first);
    Check(a && a->GetNumberOfComponents() == array.second &&
        a->GetNumberOfTuples() == grid->GetNumberOfCells(),
      file + ": cell array " + array.first);
  }
  Check(
    cd->GetHigherOrderDegrees() != nullptr, file + ": HigherOrderDegrees is the degrees attribute");
  vtkFieldData* fd = grid->GetFieldData();
  for (const char* name : { names::SurfaceNames,
         names::MaterialNames,
         names::MaterialTypeNames,
         names::MaterialFiles,
         names::MaterialTextures,
         names::MaterialTextureEncodings,
         names::CameraNames,
         names::SourceFile })
  {
    Check(vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)) != nullptr,
      file + ": field array " + name);
  }
  vtkDataArray* cameras = fd->GetArray(names::CameraParameters);
  Check(cameras && cameras->GetNumberOfComponents() == 12, file + ": CameraParameters");
  vtkDataArray* settings = fd->GetArray(names::SceneSettings);
  Check(settings && settings->GetNumberOfComponents() == 5 && settings->GetNumberOfTuples() == 1,
    file + ": SceneSettings");
}

/// The texture coordinates (paper §5.4): every point of a cell is the surface at its
/// TextureCoordinates where the surface goes through its control point (the corners of every
/// cell, and every point of a bilinear one); every value in [0, 1].
void CheckTextureCoordinates(vtkUnstructuredGrid* grid, const std::string& file)
{
  vtkDataArray* tcoords = grid->GetPointData()->GetTCoords();
  Check(tcoords && std::string(tcoords->GetName()) == names::TextureCoordinates &&
      tcoords->GetNumberOfComponents() == 2 &&
      tcoords->GetNumberOfTuples() == grid->GetNumberOfPoints(),
    file + ": TextureCoordinates are the active TCoords, 2 per point");
  if (!tcoords)
  {
    return;
  }
  const sphcover::Scene scene = vtkSceneFileLoader::Load(file);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    vtkIdType count = 0;
    const vtkIdType* ids = nullptr;
    grid->GetCellPoints(c, count, ids);
    const sphcover::BezierPatch& patch = scene.Surfaces[static_cast<size_t>(c)].Patch;
    for (vtkIdType k = 0; k < count; ++k)
    {
      double uv[2];
      tcoords->GetTuple(ids[k], uv);
      Check(
        uv[0] >= 0 && uv[0] <= 1 && uv[1] >= 0 && uv[1] <= 1, file + ": a (u, v) outside [0, 1]");
      const bool corner = (uv[0] == 0 || uv[0] == 1) && (uv[1] == 0 || uv[1] == 1);
      if (corner)
      {
        double p[3];
        grid->GetPoint(ids[k], p);
        const glm::dvec3 q = patch.Evaluate(uv[0], uv[1]);
        Check(std::abs(p[0] - q.x) + std::abs(p[1] - q.y) + std::abs(p[2] - q.z) <=
            1e-9 * (1 + std::abs(q.x) + std::abs(q.y) + std::abs(q.z)),
          file + ": cell " + std::to_string(c) + "'s corner is not P at its TextureCoordinates");
      }
    }
  }
}

void CheckRoundTrip(vtkUnstructuredGrid* grid, const std::string& file)
{
  // The Core scene the reader converted, loaded again directly.
  const sphcover::Scene original = vtkSceneFileLoader::Load(file);
  sphcover::Scene back;
  std::string error;
  Check(vtkSurfaceGridAdapter::ToScene(grid, false, back, error), file + ": adapter: " + error);
  Check(back.Surfaces.size() == original.Surfaces.size(), file + ": adapter surface count");
  for (size_t s = 0; s < std::min(back.Surfaces.size(), original.Surfaces.size()); ++s)
  {
    const sphcover::Surface& a = original.Surfaces[s];
    const sphcover::Surface& b = back.Surfaces[s];
    Check(a.Patch.DegreeU() == b.Patch.DegreeU() && a.Patch.DegreeV() == b.Patch.DegreeV() &&
        a.Patch.ControlPoints() == b.Patch.ControlPoints(),
      file + ": control points of surface " + std::to_string(s));
    Check(a.IsTriangle == b.IsTriangle && a.TwoSided == b.TwoSided,
      file + ": flags of surface " + std::to_string(s));
    const sphcover::Material& ma = original.Materials[static_cast<size_t>(a.MaterialIndex)];
    const sphcover::Material& mb = back.Materials[static_cast<size_t>(b.MaterialIndex)];
    Check(ma.Name == mb.Name && ma.Type == mb.Type && ma.Diffuse == mb.Diffuse &&
        ma.Specular == mb.Specular && ma.Emission == mb.Emission &&
        ma.PhongExponent == mb.PhongExponent && ma.TableFile == mb.TableFile &&
        ma.Transmittance == mb.Transmittance && ma.TextureFile == mb.TextureFile &&
        ma.TextureFileEncoding == mb.TextureFileEncoding &&
        (ma.DiffuseTexture != nullptr) == (mb.DiffuseTexture != nullptr),
      file + ": material of surface " + std::to_string(s));
    Check(original.SurfaceNames[static_cast<size_t>(a.NameIndex)] ==
        back.SurfaceNames[static_cast<size_t>(b.NameIndex)],
      file + ": name of surface " + std::to_string(s));
  }
}

bool Near(double a, double b)
{
  return std::fabs(a - b) <= 1e-9 * std::max(1.0, std::fabs(b));
}
}

int TestPatchSceneReader(int, char*[])
{
  const std::string scenes = SPHCOVER_DATA_DIR "/scenes/";
  for (const char* name : { "cornell_box.scene",
         "cornell_box_meshes.scene",
         "teapot_room.scene",
         "furnace_box.scene",
         "furnace_sphere.scene",
         "howell_parallel.scene",
         "howell_perpendicular.scene",
         "textured_floor.scene" })
  {
    const std::string file = scenes + name;
    vtkNew<vtkPatchSceneReader> reader;
    reader->SetFileName(file.c_str());
    Check(reader->GetExecutive() && reader->GetExecutive()->Update() == 1, file + ": update");
    vtkUnstructuredGrid* grid = reader->GetOutput();
    Check(grid->GetNumberOfCells() > 0, file + ": has cells");
    CheckArrays(grid, file);
    CheckRoundTrip(grid, file);
    CheckTextureCoordinates(grid, file);
  }

  // Cornell box: the original geometry as quads, its bounds, the official camera.
  {
    vtkNew<vtkPatchSceneReader> reader;
    reader->SetFileName((scenes + "cornell_box.scene").c_str());
    reader->Update();
    vtkUnstructuredGrid* grid = reader->GetOutput();
    for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
    {
      Check(
        grid->GetCellType(c) == VTK_QUAD, "cornell_box: cell " + std::to_string(c) + " is a quad");
    }
    double b[6];
    grid->GetBounds(b);
    Check(Near(b[0], 0) && Near(b[1], 556) && Near(b[2], 0) && Near(b[3], 548.8) && Near(b[4], 0) &&
        Near(b[5], 559.2),
      "cornell_box: bounds (0,0,0)-(556,548.8,559.2)");
    vtkDataArray* camera = grid->GetFieldData()->GetArray(names::CameraParameters);
    double c[12];
    camera->GetTuple(0, c);
    Check(Near(c[0], 278) && Near(c[1], 273) && Near(c[2], -800) && Near(c[5], -799) &&
        Near(c[9], 39.3077),
      "cornell_box: official camera");
    vtkDataArray* emission = grid->GetCellData()->GetArray(names::Emission);
    int emitters = 0;
    for (vtkIdType k = 0; k < grid->GetNumberOfCells(); ++k)
    {
      emitters += emission->GetComponent(k, 0) > 0 ? 1 : 0;
    }
    Check(emitters == 1, "cornell_box: exactly one emitting surface (the light)");
  }

  // Every .bpt model: patch count and bounds as documented at its source (Data/models/README.md).
  struct Model
  {
    const char* File;
    vtkIdType Patches;
    double Bounds[6];
  };
  const Model models[] = {
    { "teapot.bpt", 32, { -3, 3.525, -2, 2, 0, 3.15 } },
    { "geonum2017/simple.bpt", 1, { 0, 3, 0, 3, 0, 3 } },
    { "geonum2017/wave.bpt", 1, { 0, 4, 0, 4, -2, 5 } },
    { "geonum2017/heart.bpt", 2, { -5.5, 5.5, -3, 5.5, -1, 1 } },
    { "geonum2017/sphere.bpt", 8, { -1, 1, -1, 1, -1, 1 } },
    { "geonum2017/teapot.bpt", 32, { -3, 3.525, -2, 2, 0, 3.15 } },
    { "geonum2017/teacup.bpt", 26, { -1, 1, 0, 0.954545, -1, 1 } },
    { "geonum2017/teaspoon.bpt", 16, { -0.142857, 0.142857, -1, 0.220982, -0.107143, 0.0892857 } },
  };
  for (const Model& model : models)
  {
    const std::string file = std::string(SPHCOVER_DATA_DIR "/models/") + model.File;
    vtkNew<vtkBPTReader> reader;
    reader->SetFileName(file.c_str());
    reader->Update();
    vtkUnstructuredGrid* grid = reader->GetOutput();
    Check(grid->GetNumberOfCells() == model.Patches, file + ": patch count");
    double b[6];
    grid->GetBounds(b);
    bool boundsOk = true;
    for (int k = 0; k < 6; ++k)
    {
      boundsOk = boundsOk && std::fabs(b[k] - model.Bounds[k]) < 1e-5;
    }
    Check(boundsOk, file + ": bounds");
  }

  // SceneSettings: the pane stack's settings block (min_patch_size included) reads back; a file
  // written before the setting (four components) reads with min_patch_size 0 and its other
  // values.
  {
    vtkNew<vtkPatchSceneReader> reader;
    reader->SetFileName((scenes + "pane_stack.scene").c_str());
    reader->Update();
    const sphcover::SceneSettings current =
      vtkSceneSettingsArray::Read(reader->GetOutput()->GetFieldData());
    Check(current.MinPatchSize == 0.5 && current.MaxLevel == 1 && current.ThetaBins == 8 &&
        current.PhiBins == 32 && current.Tolerance == 0.5,
      "min_patch_size reads back");
    vtkNew<vtkDoubleArray> older;
    older->SetName(vtkSphericalCoverArrayNames::SceneSettings);
    older->SetNumberOfComponents(4);
    const double values[4] = { 16, 64, 3, 0.1 };
    older->InsertNextTuple(values);
    vtkNew<vtkFieldData> fd;
    fd->AddArray(older);
    const sphcover::SceneSettings read = vtkSceneSettingsArray::Read(fd);
    Check(read.ThetaBins == 16 && read.PhiBins == 64 && read.MaxLevel == 3 &&
        read.Tolerance == 0.1 && read.MinPatchSize == 0.0,
      "four-component SceneSettings read with min_patch_size 0");
  }
  return TestFailures::ExitCode();
}
