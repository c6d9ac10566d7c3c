// SPDX-License-Identifier: BSD-3-Clause
#include "scene/Scene.h"

#include <glm/common.hpp>

#include <cstdint>
#include <cstdio>
#include <limits>

namespace sphcover
{

const char* MaterialTypeName(MaterialType type)
{
  switch (type)
  {
    case MaterialType::Diffuse:
      return "diffuse";
    case MaterialType::Mirror:
      return "mirror";
    case MaterialType::Phong:
      return "phong";
    case MaterialType::Tabulated:
      return "tabulated";
  }
  return "unknown";
}

Material MaterialOverPatch(const Material& material, const UVRect& rect)
{
  Material patchMaterial = material;
  if (material.DiffuseTexture)
  {
    patchMaterial.Diffuse = material.Diffuse * material.DiffuseTexture->Mean(rect);
  }
  return patchMaterial;
}

namespace
{
/// FNV-1a, 64 bits: deterministic across runs and platforms of one byte order.
struct Fnv1a
{
  uint64_t Hash = 14695981039346656037ull;
  void Bytes(const void* data, std::size_t size)
  {
    for (std::size_t k = 0; k < size; ++k)
    {
      this->Hash = (this->Hash ^ static_cast<const unsigned char*>(data)[k]) * 1099511628211ull;
    }
  }
  template<typename T>
  void Value(const T& value)
  {
    this->Bytes(&value, sizeof(T));
  }
  void Text(const std::string& text)
  {
    this->Value(text.size());
    this->Bytes(text.data(), text.size());
  }
  void Vector(const glm::dvec3& v)
  {
    this->Value(v.x);
    this->Value(v.y);
    this->Value(v.z);
  }
};
}

std::string Fingerprint(const Scene& scene)
{
  Fnv1a hash;
  hash.Value(scene.Surfaces.size());
  for (const Surface& surface : scene.Surfaces)
  {
    hash.Value(surface.Patch.DegreeU());
    hash.Value(surface.Patch.DegreeV());
    for (const glm::dvec3& point : surface.Patch.ControlPoints())
    {
      hash.Vector(point);
    }
    hash.Value(surface.NameIndex);
    hash.Value(surface.MaterialIndex);
    hash.Value(surface.TwoSided);
  }
  hash.Value(scene.Materials.size());
  for (const Material& material : scene.Materials)
  {
    hash.Text(material.Name);
    hash.Value(static_cast<int>(material.Type));
    hash.Vector(material.Diffuse);
    hash.Vector(material.Specular);
    hash.Value(material.PhongExponent);
    hash.Vector(material.Emission);
    hash.Text(material.TableFile);
    // Panes and textures enter only where present, so that other scenes keep their fingerprints.
    if (material.IsTransmitter())
    {
      hash.Vector(material.Transmittance);
    }
    if (!material.TextureFile.empty())
    {
      hash.Text(material.TextureFile);
      hash.Value(static_cast<int>(material.TextureFileEncoding));
    }
  }
  hash.Value(scene.SurfaceNames.size());
  for (const std::string& name : scene.SurfaceNames)
  {
    hash.Text(name);
  }
  hash.Value(scene.Settings.ThetaBins);
  hash.Value(scene.Settings.PhiBins);
  hash.Value(scene.Settings.MaxLevel);
  hash.Value(scene.Settings.Tolerance);
  hash.Value(scene.Settings.MinPatchSize);
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash.Hash));
  return text;
}

void Scene::Bounds(glm::dvec3& lower, glm::dvec3& upper) const
{
  lower = glm::dvec3(std::numeric_limits<double>::infinity());
  upper = glm::dvec3(-std::numeric_limits<double>::infinity());
  for (const Surface& surface : this->Surfaces)
  {
    for (const glm::dvec3& p : surface.Patch.ControlPoints())
    {
      lower = glm::min(lower, p);
      upper = glm::max(upper, p);
    }
  }
}

namespace
{
/// The units a scene may declare, with their lengths in metres (exact: the inch is 0.0254 m).
struct NamedUnit
{
  const char* Name;
  double Metres;
};
constexpr NamedUnit KnownUnits[] = { { "mm", 0.001 },
  { "cm", 0.01 },
  { "dm", 0.1 },
  { "m", 1.0 },
  { "km", 1000.0 },
  { "in", 0.0254 },
  { "ft", 0.3048 },
  { "yd", 0.9144 } };
}

bool FindLengthUnit(const std::string& name, LengthUnit& unit)
{
  for (const NamedUnit& known : KnownUnits)
  {
    if (name == known.Name)
    {
      unit.Name = known.Name;
      unit.Metres = known.Metres;
      return true;
    }
  }
  return false;
}

std::string LengthUnitNames()
{
  std::string names;
  for (const NamedUnit& known : KnownUnits)
  {
    names += (names.empty() ? "" : ", ") + std::string(known.Name);
  }
  return names;
}

int Scene::FindMaterial(const std::string& name) const
{
  for (size_t m = 0; m < this->Materials.size(); ++m)
  {
    if (this->Materials[m].Name == name)
    {
      return static_cast<int>(m);
    }
  }
  return -1;
}

} // namespace sphcover
