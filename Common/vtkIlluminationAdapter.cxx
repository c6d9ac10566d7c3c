// SPDX-License-Identifier: BSD-3-Clause
#include "vtkIlluminationAdapter.h"

#include "vtkMaterialArrays.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include "math/Constants.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
/// What an irradiance read from a dataset must be.
bool IsFiniteAndNotNegative(double value)
{
  return std::isfinite(value) && value >= 0.0;
}
}

bool vtkIlluminationAdapter::Read(vtkPolyData* points,
  Illumination& illumination,
  std::string& error,
  bool directional,
  bool piece)
{
  illumination.Directional.reset();
  vtkPointData* pd = points->GetPointData();
  vtkDataArray* radiosity = pd->GetArray(names::Radiosity);
  vtkDataArray* surfaceId = pd->GetArray(names::SurfaceId);
  vtkDataArray* uvRange = pd->GetArray(names::UVRange);
  vtkDataArray* twoSided = pd->GetArray(names::TwoSided);
  if (!radiosity || radiosity->GetNumberOfComponents() != 3)
  {
    error = std::string("the input has no point array Radiosity (3 components); connect the "
                        "illuminated cover points (vtkLightPropagationFilter's output 0), not ") +
      (points->GetNumberOfPoints() == 0 ? "an empty dataset" : "points without illumination");
    return false;
  }
  if (!surfaceId || !uvRange || uvRange->GetNumberOfComponents() != 4)
  {
    error = "the input lacks the point arrays SurfaceId and UVRange (4 components) that place "
            "each characteristic point on its surface";
    return false;
  }
  const vtkIdType count = points->GetNumberOfPoints();
  std::vector<int> surfaceOfPoint(static_cast<size_t>(count));
  std::vector<sphcover::UVRect> domainOfPoint(static_cast<size_t>(count));
  illumination.ExitantRadiance.assign(static_cast<size_t>(count), glm::dvec3(0.0));
  illumination.TwoSidedSurface.clear();
  for (vtkIdType i = 0; i < count; ++i)
  {
    const size_t k = static_cast<size_t>(i);
    surfaceOfPoint[k] = static_cast<int>(surfaceId->GetComponent(i, 0));
    double r[4];
    uvRange->GetTuple(i, r);
    domainOfPoint[k] = sphcover::UVRect{ r[0], r[1], r[2], r[3] };
    radiosity->GetTuple(i, &illumination.ExitantRadiance[k][0]);
    if (surfaceOfPoint[k] >= 0)
    {
      const size_t s = static_cast<size_t>(surfaceOfPoint[k]);
      illumination.TwoSidedSurface.resize(std::max(illumination.TwoSidedSurface.size(), s + 1));
      illumination.TwoSidedSurface[s] = twoSided && twoSided->GetComponent(i, 0) != 0.0;
    }
  }
  try
  {
    illumination.Interpolator =
      sphcover::CharacteristicPointInterpolator(surfaceOfPoint, domainOfPoint);
  }
  catch (const std::exception& e)
  {
    error = e.what();
    return false;
  }
  if (!vtkIlluminationAdapter::ReadDirectIrradiance(points, illumination, error) ||
    !vtkIlluminationAdapter::ReadTextures(points, illumination, error))
  {
    return false;
  }
  return !directional ||
    vtkIlluminationAdapter::ReadDirectional(points, illumination, error, piece);
}

bool vtkIlluminationAdapter::ReadDirectIrradiance(vtkPolyData* points,
  Illumination& illumination,
  std::string& error)
{
  illumination.Direct = sphcover::DirectLight();
  vtkPointData* pd = points->GetPointData();
  vtkDataArray* nodes = pd->GetArray(names::DirectIrradiance);
  if (!nodes)
  {
    return true;
  }
  const int components = nodes->GetNumberOfComponents();
  const int side = static_cast<int>(std::lround(std::sqrt(components / 3.0)));
  if (components != 3 * side * side || side < 3 || side > 33 || side % 2 == 0)
  {
    error = "the point array DirectIrradiance has " + std::to_string(components) +
      " components, not 3 n^2 for an odd n from 3 to 33";
    return false;
  }
  vtkDataArray* diffuse = pd->GetArray(names::Diffuse);
  if (!diffuse || diffuse->GetNumberOfComponents() != 3)
  {
    error = "the points have DirectIrradiance but no point array Diffuse (3 components)";
    return false;
  }
  const vtkIdType count = points->GetNumberOfPoints();
  std::vector<float> values(static_cast<size_t>(count) * static_cast<size_t>(components));
  std::vector<glm::dvec3> reflectance(static_cast<size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      const double value = nodes->GetComponent(i, c);
      if (!IsFiniteAndNotNegative(value))
      {
        error =
          "DirectIrradiance of point " + std::to_string(i) + " is negative or not a finite number";
        return false;
      }
      values[static_cast<size_t>(i) * static_cast<size_t>(components) + static_cast<size_t>(c)] =
        static_cast<float>(value);
    }
    diffuse->GetTuple(static_cast<vtkIdType>(i), &reflectance[static_cast<size_t>(i)][0]);
  }
  // The cover's version of the nodes' light (vtkLightPropagationFilter), when the points have it.
  std::vector<glm::dvec3> coverPart;
  vtkDataArray* cover = pd->GetArray(names::CoverLampIrradiance);
  if (cover)
  {
    if (cover->GetNumberOfComponents() != 3)
    {
      error = "the point array CoverLampIrradiance has " +
        std::to_string(cover->GetNumberOfComponents()) + " components, not 3";
      return false;
    }
    coverPart.resize(static_cast<size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      glm::dvec3& value = coverPart[static_cast<size_t>(i)];
      cover->GetTuple(i, &value[0]);
      if (!IsFiniteAndNotNegative(value.x) || !IsFiniteAndNotNegative(value.y) ||
        !IsFiniteAndNotNegative(value.z))
      {
        error = "CoverLampIrradiance of point " + std::to_string(i) +
          " is negative or not a finite number";
        return false;
      }
    }
  }
  sphcover::DirectIrradianceNodes direct;
  direct.NodesPerSide = side;
  direct.Values = std::move(values);
  illumination.Direct = sphcover::DirectLight(
    std::move(direct), reflectance, static_cast<std::size_t>(count), coverPart);
  return true;
}

bool vtkIlluminationAdapter::ReadTextures(vtkPolyData* points,
  Illumination& illumination,
  std::string& error)
{
  illumination.Textures.clear();
  auto* files =
    vtkStringArray::SafeDownCast(points->GetFieldData()->GetAbstractArray(names::MaterialTextures));
  bool textured = false;
  for (vtkIdType m = 0; files && m < files->GetNumberOfValues() && !textured; ++m)
  {
    textured = !files->GetValue(m).empty();
  }
  if (!textured)
  {
    return true;
  }
  std::vector<sphcover::Material> materials;
  if (!vtkIlluminationAdapter::ReadMaterials(points, materials, error))
  {
    return false;
  }
  vtkDataArray* irradiance = points->GetPointData()->GetArray(names::Irradiance);
  if (!irradiance || irradiance->GetNumberOfComponents() != 3)
  {
    error = "the points have textured materials but no point array Irradiance (3 components)";
    return false;
  }
  vtkDataArray* surfaceId = points->GetPointData()->GetArray(names::SurfaceId);
  for (size_t k = 0; k < materials.size(); ++k)
  {
    const sphcover::Material& material = materials[k];
    const int surface = static_cast<int>(surfaceId->GetComponent(static_cast<vtkIdType>(k), 0));
    if (!material.DiffuseTexture || surface < 0)
    {
      continue;
    }
    // The untextured radiance, Le + k_d / pi E with the material's own k_d: the render
    // multiplies its reflected part by the texture at each visible point (paper §5.4).
    glm::dvec3 e;
    irradiance->GetTuple(static_cast<vtkIdType>(k), &e[0]);
    illumination.ExitantRadiance[k] = material.Emission + material.Diffuse / sphcover::Pi * e;
    const size_t s = static_cast<size_t>(surface);
    illumination.Textures.resize(std::max(illumination.Textures.size(), s + 1));
    illumination.Textures[s] =
      sphcover::SurfaceTexture{ material.DiffuseTexture, material.Emission };
  }
  return true;
}

bool vtkIlluminationAdapter::ApplyTextureMeans(vtkPolyData* points,
  std::vector<sphcover::Material>& materials,
  std::string& error)
{
  vtkDataArray* uvRange = points->GetPointData()->GetArray(names::UVRange);
  for (size_t k = 0; k < materials.size(); ++k)
  {
    if (!materials[k].DiffuseTexture)
    {
      continue;
    }
    if (!uvRange || uvRange->GetNumberOfComponents() != 4)
    {
      error = "the points have textured materials but no point array UVRange (4 components) "
              "that gives each point's patch";
      return false;
    }
    double r[4];
    uvRange->GetTuple(static_cast<vtkIdType>(k), r);
    materials[k] =
      sphcover::MaterialOverPatch(materials[k], sphcover::UVRect{ r[0], r[1], r[2], r[3] });
  }
  return true;
}

bool vtkIlluminationAdapter::ReadDirectional(vtkPolyData* points,
  Illumination& illumination,
  std::string& error,
  bool piece)
{
  illumination.Directional.reset();
  vtkDataArray* type = points->GetPointData()->GetArray(names::MaterialType);
  bool nonDiffuse = false;
  for (vtkIdType i = 0; type && i < points->GetNumberOfPoints() && !nonDiffuse; ++i)
  {
    nonDiffuse = type->GetComponent(i, 0) != 0.0;
  }
  if (!nonDiffuse)
  {
    return true; // every surface is Lambertian: Radiosity is all of it
  }
  auto directional = std::make_unique<sphcover::DirectionalIllumination>();
  if (!vtkIlluminationAdapter::ReadMaterials(points, directional->Materials, error))
  {
    return false;
  }
  if (!vtkIlluminationAdapter::ReadFrames(points, directional->Frames))
  {
    error = "the input has non-diffuse points but lacks the point arrays Normals and Tangents "
            "(3 components) of their hemisphere frames";
    return false;
  }
  const std::string problem = vtkSphericalCoverArrays::Load(points, directional->Cover, piece);
  if (!problem.empty())
  {
    error = "the input has non-diffuse points but no usable cover: " + problem;
    return false;
  }
  vtkDataArray* incident = points->GetFieldData()->GetArray(names::IncidentRadiance);
  const vtkIdType entries = static_cast<vtkIdType>(directional->Cover.EntryCount());
  if (!incident || incident->GetNumberOfComponents() != 3 ||
    incident->GetNumberOfTuples() != entries)
  {
    error = "the input has non-diffuse points but no field array IncidentRadiance with 3 "
            "components for each of the cover's " +
      std::to_string(entries) + " entries (vtkLightPropagationFilter's output 0 has it)";
    return false;
  }
  directional->IncidentRadiance.assign(static_cast<size_t>(entries), glm::dvec3(0.0));
  for (vtkIdType e = 0; e < entries; ++e)
  {
    incident->GetTuple(e, &directional->IncidentRadiance[static_cast<size_t>(e)][0]);
  }
  illumination.Directional = std::move(directional);
  return true;
}

bool vtkIlluminationAdapter::ReadFrames(vtkPolyData* points,
  std::vector<sphcover::HemisphereFrame>& frames)
{
  frames.clear();
  vtkDataArray* normals = points->GetPointData()->GetArray(names::Normals);
  vtkDataArray* tangents = points->GetPointData()->GetArray(names::Tangents);
  if (!normals || !tangents || normals->GetNumberOfComponents() != 3 ||
    tangents->GetNumberOfComponents() != 3)
  {
    return false;
  }
  const vtkIdType count = points->GetNumberOfPoints();
  frames.resize(static_cast<size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    sphcover::HemisphereFrame& frame = frames[static_cast<size_t>(i)];
    points->GetPoint(i, &frame.Origin[0]);
    normals->GetTuple(i, &frame.Normal[0]);
    tangents->GetTuple(i, &frame.Tangent[0]);
    frame.Bitangent = glm::cross(frame.Normal, frame.Tangent);
  }
  return true;
}

bool vtkIlluminationAdapter::ReadMaterials(vtkPolyData* points,
  std::vector<sphcover::Material>& materials,
  std::string& error)
{
  // One material per point, as the scene reader described it (vtkSurfaceGridBuilder).
  const vtkMaterialArrays arrays(points->GetPointData(), points->GetFieldData(), "point");
  if (!arrays.Check(error))
  {
    return false;
  }
  const vtkIdType count = points->GetNumberOfPoints();
  materials.assign(static_cast<size_t>(count), sphcover::Material());
  for (vtkIdType i = 0; i < count; ++i)
  {
    if (!arrays.Read(i, materials[static_cast<size_t>(i)], error))
    {
      return false;
    }
  }
  return true;
}
