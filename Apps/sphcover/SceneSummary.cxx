// SPDX-License-Identifier: BSD-3-Clause
#include "SceneSummary.h"

#include "scene/Scene.h"

#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace sphcover
{
namespace
{
std::string Triple(const glm::dvec3& v)
{
  std::ostringstream s;
  s << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return s.str();
}

std::string Describe(const Material& m)
{
  std::ostringstream s;
  s << MaterialTypeName(m.Type);
  switch (m.Type)
  {
    case MaterialType::Diffuse:
      s << "  reflectance " << Triple(m.Diffuse);
      break;
    case MaterialType::Mirror:
      s << "  reflectance " << Triple(m.Specular);
      break;
    case MaterialType::Phong:
      s << "  diffuse " << Triple(m.Diffuse) << " specular " << Triple(m.Specular) << " exponent "
        << m.PhongExponent;
      break;
    case MaterialType::Tabulated:
      s << "  table " << m.TableFile;
      break;
  }
  if (m.IsTransmitter())
  {
    s << "  transmittance " << Triple(m.Transmittance);
  }
  if (m.DiffuseTexture)
  {
    s << "  texture " << m.TextureFile << " (" << m.DiffuseTexture->Width() << "x"
      << m.DiffuseTexture->Height() << ", " << TextureEncodingName(m.TextureFileEncoding) << ")";
  }
  if (m.IsEmitter())
  {
    s << "  emission " << Triple(m.Emission);
  }
  return s.str();
}
}

void PrintSceneSummary(const Scene& scene, std::ostream& os)
{
  os << "Scene: " << scene.SourceFile << "\n";

  // Per named entry: patch count, degree histogram, materials used.
  struct EntryStats
  {
    size_t Patches = 0;
    size_t Triangles = 0;
    std::map<std::pair<int, int>, size_t> Degrees;
    std::map<int, size_t> MaterialUse;
  };
  std::vector<EntryStats> entries(scene.SurfaceNames.size());
  for (const Surface& surface : scene.Surfaces)
  {
    EntryStats& e = entries[static_cast<size_t>(surface.NameIndex)];
    ++e.Patches;
    e.Triangles += surface.IsTriangle ? 1 : 0;
    ++e.Degrees[{ surface.Patch.DegreeU(), surface.Patch.DegreeV() }];
    ++e.MaterialUse[surface.MaterialIndex];
  }
  os << "Surfaces: " << scene.SurfaceNames.size() << " named, " << scene.Surfaces.size()
     << " patches\n";
  size_t width = 4;
  for (const std::string& name : scene.SurfaceNames)
  {
    width = std::max(width, name.size());
  }
  os << "  " << std::left << std::setw(static_cast<int>(width)) << "name"
     << "  patches  degrees"
     << "             material\n";
  for (size_t k = 0; k < entries.size(); ++k)
  {
    std::ostringstream degrees;
    bool first = true;
    for (const auto& d : entries[k].Degrees)
    {
      degrees << (first ? "" : ", ") << d.second << "x(" << d.first.first << "," << d.first.second
              << ")";
      first = false;
    }
    if (entries[k].Triangles > 0)
    {
      degrees << " [" << entries[k].Triangles << " triangles]";
    }
    std::ostringstream materials;
    first = true;
    for (const auto& m : entries[k].MaterialUse)
    {
      materials << (first ? "" : ", ") << scene.Materials[static_cast<size_t>(m.first)].Name;
      first = false;
    }
    os << "  " << std::left << std::setw(static_cast<int>(width)) << scene.SurfaceNames[k] << "  "
       << std::setw(7) << entries[k].Patches << "  " << std::setw(18) << degrees.str() << "  "
       << materials.str() << "\n";
  }

  os << "Materials: " << scene.Materials.size() << "\n";
  for (const Material& m : scene.Materials)
  {
    os << "  " << m.Name << ": " << Describe(m) << "\n";
  }

  os << "Cameras: " << scene.Cameras.size() << "\n";
  for (const Camera& c : scene.Cameras)
  {
    os << "  " << c.Name << ": position " << Triple(c.Position) << " focal point "
       << Triple(c.FocalPoint) << " view up " << Triple(c.ViewUp) << " view angle " << c.ViewAngle
       << " size " << c.Width << "x" << c.Height << "\n";
  }

  glm::dvec3 lower;
  glm::dvec3 upper;
  scene.Bounds(lower, upper);
  os << "Bounds: " << Triple(lower) << " to " << Triple(upper) << "\n";
  os << "Settings: theta_bins=" << scene.Settings.ThetaBins
     << " phi_bins=" << scene.Settings.PhiBins << " max_level=" << scene.Settings.MaxLevel
     << " tolerance=" << scene.Settings.Tolerance
     << " min_patch_size=" << scene.Settings.MinPatchSize << "\n";
}

} // namespace sphcover
