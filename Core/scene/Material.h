// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Material.h
 * @brief Reflectance and emission of a surface (paper §3.5.1), one value per RGB band.
 */
#ifndef SPHCOVER_MATERIAL_H
#define SPHCOVER_MATERIAL_H

#include "scene/Texture.h"

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
  /// Transmittance per band (paper §5.4, a thin pane): the fraction of the light arriving on
  /// either side that leaves on the other in the same direction. Reflectance + transmittance
  /// <= 1 per band; a material that transmits makes its surfaces two-sided.
  glm::dvec3 Transmittance{ 0.0 };
  /// Absolute path of the texture PNG ("" for none): multiplies the diffuse reflectance over
  /// the surface's (u, v) (Texture.h).
  std::string TextureFile;
  TextureEncoding TextureFileEncoding = TextureEncoding::Srgb;
  /// The image read from TextureFile (null without a texture).
  std::shared_ptr<const Texture> DiffuseTexture;

  bool IsTransmitter() const
  {
    return this->Transmittance.x > 0 || this->Transmittance.y > 0 || this->Transmittance.z > 0;
  }

  bool IsEmitter() const
  {
    return this->Emission.x > 0 || this->Emission.y > 0 || this->Emission.z > 0;
  }
};

/**
 * The material a characteristic point carries in the propagation when its patch is `rect` of
 * its surface: a textured material's diffuse reflectance times the texture's mean over the
 * rectangle (paper §5.4, "convolving the texture maps ... with the surface reflectance map";
 * the subdivision's characterisability, §4.2.4, keeps the irradiance about constant over a
 * patch, so the patch reflects about its mean reflectance times its irradiance). Without a
 * texture, `material` itself.
 */
Material MaterialOverPatch(const Material& material, const UVRect& rect);

} // namespace sphcover

#endif
