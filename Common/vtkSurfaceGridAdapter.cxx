// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSurfaceGridAdapter.h"

#include "vtkMaterialArrays.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSurfaceGridBuilder.h"

#include "scene/Scene.h"
#include "scene/SceneLoader.h"
#include "subdivision/Patch.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkStringArray.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
std::string StringValue(vtkFieldData* fd, const char* name, vtkIdType index)
{
  auto* array = vtkStringArray::SafeDownCast(fd ? fd->GetAbstractArray(name) : nullptr);
  return (array && index >= 0 && index < array->GetNumberOfValues()) ? array->GetValue(index)
                                                                     : std::string();
}

/// Entry `index` of the field array `name`, or `fallback` followed by the index where it has
/// none.
std::string NameOrFallback(vtkFieldData* fd,
  const char* name,
  vtkIdType index,
  const std::string& fallback)
{
  const std::string text = StringValue(fd, name, index);
  return text.empty() ? fallback + std::to_string(index) : text;
}

/// Cell c's value of the id array `idName` as an index in [0, limit): false, with the error,
/// for a value that is negative, fractional, not a number or too large.
bool CellIndex(double value,
  vtkIdType limit,
  const char* idName,
  vtkIdType c,
  int& index,
  std::string& error)
{
  if (!(value >= 0.0 && value < static_cast<double>(limit)) || value != std::floor(value))
  {
    std::ostringstream text;
    text << "cell " << c << ": " << idName << " " << value << " is not an index in [0, " << limit
         << ")";
    error = text.str();
    return false;
  }
  index = static_cast<int>(value);
  return true;
}

/// The control points of a Bezier quadrilateral cell with `n` points, in the patch's row-major
/// order, and its degrees (from HigherOrderDegrees, or equal ones from the point count): false,
/// with the error, where the count does not match the degrees or a degree is out of range.
bool BezierControlPoints(vtkDataSet* input,
  vtkIdType c,
  vtkIdList* ids,
  vtkDataArray* degrees,
  std::vector<glm::dvec3>& control,
  int& du,
  int& dv,
  std::string& error)
{
  const vtkIdType n = ids->GetNumberOfIds();
  if (degrees && degrees->GetNumberOfComponents() >= 2)
  {
    du = static_cast<int>(degrees->GetComponent(c, 0));
    dv = static_cast<int>(degrees->GetComponent(c, 1));
  }
  else
  {
    // Without HigherOrderDegrees VTK assumes equal degrees from the point count.
    du = dv = static_cast<int>(std::lround(std::sqrt(double(n)))) - 1;
  }
  if (du < 1 || dv < 1 || du > sphcover::BezierPatch::MaxDegree ||
    dv > sphcover::BezierPatch::MaxDegree || (du + 1) * (dv + 1) != n)
  {
    error = "cell " + std::to_string(c) + ": Bezier quadrilateral with " + std::to_string(n) +
      " points does not match degrees " + std::to_string(du) + " x " + std::to_string(dv);
    return false;
  }
  control.resize(static_cast<size_t>(n));
  for (int j = 0; j <= dv; ++j)
  {
    for (int i = 0; i <= du; ++i)
    {
      glm::dvec3& p = control[static_cast<size_t>(j * (du + 1) + i)];
      input->GetPoint(ids->GetId(vtkSurfaceGridBuilder::VTKPointIndex(i, j, du, dv)), &p[0]);
    }
  }
  return true;
}

/// Cell c as a Bezier patch: a quad is bilinear, a triangle a bilinear patch with its last
/// corner repeated (`triangle` set), a Bezier quadrilateral keeps its degrees. False, with the
/// error, for another cell type, a point that is not finite or a patch with no area.
bool CellPatch(vtkDataSet* input,
  vtkIdType c,
  vtkIdList* ids,
  vtkDataArray* degrees,
  std::optional<sphcover::BezierPatch>& patch,
  bool& triangle,
  std::string& error)
{
  const int type = input->GetCellType(c);
  input->GetCellPoints(c, ids);
  const vtkIdType n = ids->GetNumberOfIds();
  auto point = [&](vtkIdType k)
  {
    glm::dvec3 p;
    input->GetPoint(ids->GetId(k), &p[0]);
    return p;
  };
  std::vector<glm::dvec3> control;
  int du = 1;
  int dv = 1;
  triangle = false;
  if (type == VTK_QUAD && n == 4)
  {
    control = { point(0), point(1), point(3), point(2) };
  }
  else if (type == VTK_TRIANGLE && n == 3)
  {
    control = { point(0), point(1), point(2), point(2) };
    triangle = true;
  }
  else if (type == VTK_BEZIER_QUADRILATERAL)
  {
    if (!BezierControlPoints(input, c, ids, degrees, control, du, dv, error))
    {
      return false;
    }
  }
  else
  {
    error = "cell " + std::to_string(c) + ": unsupported cell type " + std::to_string(type) +
      " (expected Bezier quadrilaterals, quads or triangles)";
    return false;
  }
  for (const glm::dvec3& p : control)
  {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    {
      error = "cell " + std::to_string(c) + ": a point is not finite";
      return false;
    }
  }
  patch.emplace(du, dv, std::move(control));
  if (sphcover::IsDegeneratePatch(*patch))
  {
    error = "cell " + std::to_string(c) + ": degenerate patch (no area)";
    return false;
  }
  return true;
}

/// The cell arrays and field arrays ToScene reads each cell's material and name from.
struct CellAttributes
{
  vtkFieldData* Fields;
  const vtkMaterialArrays& Materials;
  vtkDataArray* MaterialId;
  vtkDataArray* NameId;
  vtkIdType MaterialLimit;
  vtkIdType NameLimit;
};

/// Cell c's material index (its MaterialId), with the scene's materials grown to it by
/// placeholders; the first cell of a material reads it into the scene (`materialRead` marks
/// the ones read). False, with the error, for a bad id or material values.
bool CellMaterial(const CellAttributes& attributes,
  vtkIdType c,
  sphcover::Scene& scene,
  std::vector<char>& materialRead,
  int& materialIndex,
  std::string& error)
{
  if (!CellIndex(attributes.MaterialId->GetComponent(c, 0),
        attributes.MaterialLimit,
        names::MaterialId,
        c,
        materialIndex,
        error))
  {
    return false;
  }
  const std::size_t index = static_cast<std::size_t>(materialIndex);
  while (scene.Materials.size() <= index)
  {
    sphcover::Material placeholder;
    placeholder.Name = NameOrFallback(attributes.Fields,
      names::MaterialNames,
      static_cast<vtkIdType>(scene.Materials.size()),
      "material");
    scene.Materials.push_back(placeholder);
    materialRead.push_back(0);
  }
  if (!materialRead[index])
  {
    sphcover::Material material;
    if (!attributes.Materials.Read(c, material, error))
    {
      return false;
    }
    if (material.Name.empty())
    {
      material.Name = scene.Materials[index].Name;
    }
    scene.Materials[index] = material;
    materialRead[index] = 1;
  }
  return true;
}

/// Cell c's surface name index (its SurfaceNameId, 0 without the array), with the scene's
/// surface names grown to it. False, with the error, for a bad id.
bool CellSurfaceName(const CellAttributes& attributes,
  vtkIdType c,
  sphcover::Scene& scene,
  int& nameIndex,
  std::string& error)
{
  if (!CellIndex(attributes.NameId ? attributes.NameId->GetComponent(c, 0) : 0.0,
        attributes.NameLimit,
        names::SurfaceNameId,
        c,
        nameIndex,
        error))
  {
    return false;
  }
  while (scene.SurfaceNames.size() <= static_cast<std::size_t>(nameIndex))
  {
    scene.SurfaceNames.push_back(NameOrFallback(attributes.Fields,
      names::SurfaceNames,
      static_cast<vtkIdType>(scene.SurfaceNames.size()),
      "surface"));
  }
  return true;
}
}

bool vtkSurfaceGridAdapter::ToScene(vtkDataSet* input,
  bool allowDefaultMaterials,
  sphcover::Scene& scene,
  std::string& error)
{
  scene = sphcover::Scene();
  if (!input || input->GetNumberOfCells() == 0)
  {
    error = "the input has no surfaces (no cells)";
    return false;
  }
  vtkCellData* cd = input->GetCellData();
  vtkFieldData* fd = input->GetFieldData();
  const vtkMaterialArrays materials(cd, fd, "cell");
  vtkDataArray* nameId = cd->GetArray(names::SurfaceNameId);
  vtkDataArray* twoSided = cd->GetArray(names::TwoSided);
  vtkDataArray* degrees = cd->GetHigherOrderDegrees();

  const bool hasMaterials = cd->GetArray(names::MaterialId) && cd->GetArray(names::Diffuse) &&
    cd->GetArray(names::Specular) && cd->GetArray(names::Emission);
  if (!hasMaterials)
  {
    if (!allowDefaultMaterials)
    {
      error = std::string("the input lacks the material cell arrays (") + names::MaterialId + ", " +
        names::Diffuse + ", " + names::Specular + ", " + names::Emission +
        "); read scenes with vtkPatchSceneReader";
      return false;
    }
    sphcover::Material white;
    white.Name = "default";
    white.Diffuse = glm::dvec3(0.8);
    scene.Materials.push_back(white);
  }
  if (hasMaterials && !materials.Check(error))
  {
    return false;
  }

  // The input's MaterialId and SurfaceNameId index its field arrays (MaterialNames,
  // MaterialFiles, SurfaceNames), which the filters pass on to their outputs: the scene keeps
  // them as its indices, so that the ids written downstream still name the same entries. An id
  // no cell uses (cells removed in ParaView, say) gets a placeholder that no surface refers to.
  const vtkIdType numberOfCells = input->GetNumberOfCells();
  const auto idLimit = [&](const char* name)
  {
    auto* array = vtkStringArray::SafeDownCast(fd ? fd->GetAbstractArray(name) : nullptr);
    return numberOfCells + (array ? array->GetNumberOfValues() : 0);
  };
  const CellAttributes attributes{ fd,
    materials,
    cd->GetArray(names::MaterialId),
    nameId,
    idLimit(names::MaterialNames),
    idLimit(names::SurfaceNames) };
  std::vector<char> materialRead;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    std::optional<sphcover::BezierPatch> patch;
    bool triangle = false;
    if (!CellPatch(input, c, ids, degrees, patch, triangle, error))
    {
      return false;
    }
    int materialIndex = 0;
    if (hasMaterials && !CellMaterial(attributes, c, scene, materialRead, materialIndex, error))
    {
      return false;
    }
    int nameIndex = 0;
    if (!CellSurfaceName(attributes, c, scene, nameIndex, error))
    {
      return false;
    }

    sphcover::Surface surface(std::move(*patch), nameIndex, materialIndex);
    surface.IsTriangle = triangle;
    surface.TwoSided = twoSided && twoSided->GetComponent(c, 0) != 0.0;
    scene.Surfaces.push_back(std::move(surface));
  }
  scene.SourceFile = StringValue(fd, names::SourceFile, 0);
  return true;
}

bool vtkSurfaceGridAdapter::ToPatches(vtkDataSet* input,
  sphcover::Scene& scene,
  std::vector<sphcover::Patch>& patches,
  std::string& error)
{
  patches.clear();
  if (!ToScene(input, false, scene, error))
  {
    return false;
  }
  vtkCellData* cd = input->GetCellData();
  vtkDataArray* uvRange = cd->GetArray(names::UVRange);
  vtkDataArray* level = cd->GetArray(names::Level);
  vtkDataArray* surfaceId = cd->GetArray(names::SurfaceId);
  if (uvRange && uvRange->GetNumberOfComponents() != 4)
  {
    error = "the UVRange cell array must have 4 components";
    return false;
  }
  patches.reserve(scene.Surfaces.size());
  for (size_t c = 0; c < scene.Surfaces.size(); ++c)
  {
    const vtkIdType cell = static_cast<vtkIdType>(c);
    sphcover::UVRect domain = sphcover::UVRect::Unit();
    if (uvRange)
    {
      domain = { uvRange->GetComponent(cell, 0),
        uvRange->GetComponent(cell, 1),
        uvRange->GetComponent(cell, 2),
        uvRange->GetComponent(cell, 3) };
    }
    // The surface the patch is part of: the R-buffer's coverage vote and the ray fill's
    // crack-free tessellation group a surface's pieces together.
    const int surface =
      surfaceId ? static_cast<int>(surfaceId->GetComponent(cell, 0)) : static_cast<int>(c);
    patches.emplace_back(surface,
      domain,
      level ? static_cast<int>(level->GetComponent(cell, 0)) : 0,
      scene.Surfaces[c].Patch);
  }
  return true;
}

std::vector<glm::dvec3> vtkSurfaceGridAdapter::TransmittanceOfSurfaces(const sphcover::Scene& scene,
  const std::vector<sphcover::Patch>& patches)
{
  std::vector<glm::dvec3> transmittance;
  for (size_t k = 0; k < patches.size() && k < scene.Surfaces.size(); ++k)
  {
    const size_t surface = static_cast<size_t>(std::max(0, patches[k].SurfaceIndex));
    transmittance.resize(std::max(transmittance.size(), surface + 1), glm::dvec3(0.0));
    transmittance[surface] =
      scene.Materials[static_cast<size_t>(scene.Surfaces[k].MaterialIndex)].Transmittance;
  }
  return transmittance;
}
