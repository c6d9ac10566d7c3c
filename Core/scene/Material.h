// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Material.h
 * @brief Reflectance and emission of a surface (paper §3.5.1), one value per RGB band.
 */
#ifndef SPHCOVER_MATERIAL_H
#define SPHCOVER_MATERIAL_H

#include <glm/vec3.hpp>

#include <memory>
#include <string>

namespace sphcover
{

class BrdfTable;

/// The four reflectance kinds of paper §3.5: Lambertian, ideal mirror, shiny (a cos^n lobe
/// around the mirror direction, here the normalized Phong lobe plus a diffuse part) and a
/// general reflectance given by a weight table.
enum class MaterialType
{
  Diffuse = 0,
  Mirror = 1,
  Phong = 2,
  Tabulated = 3
};

const char* MaterialTypeName(MaterialType type);

struct Material
{
  /// The largest emitted radiance the readers accept, W m^-2 sr^-1 (the sun's disc is about
  /// 2e7). With coordinates within BezierPatch::MaxCoordinate, emission * area * pi summed
  /// over a scene stays below 1e50, far from overflowing a double (Data/scenes/FORMAT.md).
  static constexpr double MaxEmission = 1e12;

  std::string Name;
  MaterialType Type = MaterialType::Diffuse;
  /// Lambertian reflectance k_Lambert per band (diffuse, and the diffuse part of phong).
  glm::dvec3 Diffuse{ 0.0 };
  /// Specular reflectance k_specular per band (mirror, and the lobe of phong).
  glm::dvec3 Specular{ 0.0 };
  /// Exponent n of the normalized cos^n lobe (phong only).
  double PhongExponent = 0.0;
  /// Emitted radiance per band, W m^-2 sr^-1, uniform over the front hemisphere.
  glm::dvec3 Emission{ 0.0 };
  /// Absolute path of the BRDF table (tabulated only; format: Data/scenes/FORMAT.md).
  std::string TableFile;
  /// The table read from TableFile when the scene was loaded (tabulated only; may be null when
  /// the material was rebuilt from VTK arrays, and then Reflectance reads TableFile).
  std::shared_ptr<const BrdfTable> Table;

  bool IsEmitter() const
  {
    return this->Emission.x > 0 || this->Emission.y > 0 || this->Emission.z > 0;
  }
};

} // namespace sphcover

#endif
