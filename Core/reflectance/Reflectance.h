// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Reflectance.h
 * @brief The bidirectional reflectance R(theta_i, phi_i, theta_r, phi_r) of paper §3.5 for the
 * four material kinds, per RGB band, in the local frame of a hemisphere (z = normal, phi from
 * the tangent; HemisphereFrame). Directions point away from the surface: `in` toward where
 * the light comes from, `out` toward where it goes. Every model is isotropic: it depends on
 * theta_in, theta_out and delta_phi = phi_out - phi_in only.
 *
 *  - diffuse (§3.5.1): f = k_d / pi; directional albedo k_d.
 *  - mirror (§3.5.1): f = k_s delta(theta_r - theta_i) delta(phi_r - phi_i - pi) /
 *    (sin theta_i cos theta_i): all light from `in` leaves toward MirrorDirection(in), scaled
 *    by k_s; albedo k_s. Evaluate() returns 0 (the delta has no finite value): the renderer
 *    looks the incident radiance up in the mirror direction of the eye, and the propagation's
 *    weight tables put k_s on the mirror cell (ReflectanceWeights).
 *  - phong: f = k_d / pi + k_s c(theta_in) c(theta_out) cos^n(alpha), alpha the angle between
 *    `in` and the mirror direction of `out` (the "cos^n alpha" lobe around the mirror
 *    direction of §3.5.1), cos^n taken as 0 beyond 90 degrees. Energy-conserving
 *    normalization: c(theta) is the symmetric normalization that makes the lobe's directional
 *    albedo exactly 1 for every direction, so the material reflects exactly k_d + k_s of the
 *    light from any direction (FORMAT.md requires k_d + k_s <= 1) and f stays reciprocal
 *    (f(in, out) = f(out, in)). For a narrow lobe c(0)^2 is close to the familiar
 *    (n + 2) / (2 pi) (within 3% at n = 40); toward grazing angles, where the plain normalized
 *    lobe loses light below the horizon, c grows to make up for it. c is found once per
 *    material by symmetric (Sinkhorn) scaling of the lobe's kernel on 128 nodes in theta with
 *    512 azimuths (the albedo is then k_d + k_s within 1% of k_s for lobes wider than about
 *    two degrees, n up to ~ 500; the propagation's weight tables are normalized exactly
 *    anyway), and interpolated linearly in theta.
 *  - tabulated (§3.5 "general reflectance"): f from a BrdfTable (trilinear interpolation);
 *    albedo integrated numerically from the table.
 *
 * Albedo(theta) is the directional albedo integral f(in, out) cos(theta_in) dw_in for an
 * outgoing direction at polar angle theta: the share of a uniform incident radiance that
 * leaves toward `out`. For reciprocal BRDFs it is also the hemispherical reflectance of light
 * arriving from theta. The propagation normalizes its weight tables to it (ReflectanceWeights),
 * which keeps the white furnace exact.
 */
#ifndef SPHCOVER_REFLECTANCE_H
#define SPHCOVER_REFLECTANCE_H

#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <memory>
#include <vector>

namespace sphcover
{

class BrdfTable;

class Reflectance
{
public:
  /**
   * The BRDF of a material. A tabulated material uses material.Table, or reads
   * material.TableFile when Table is null (throws InputError when that fails). Throws
   * std::invalid_argument for values outside the ranges of Data/scenes/FORMAT.md.
   */
  explicit Reflectance(const Material& material);

  MaterialType Kind() const { return this->Type; }
  /// Lambertian only: the propagation's closed-form O(column) shot applies (paper §5.2).
  bool IsLambertian() const { return this->Type == MaterialType::Diffuse; }
  /// Ideal mirror: a delta BRDF, Evaluate() is 0.
  bool IsIdealMirror() const { return this->Type == MaterialType::Mirror; }
  /// k_d: the Lambertian part (diffuse, phong), 0 for mirror and tabulated.
  const glm::dvec3& LambertianReflectance() const { return this->KDiffuse; }
  /// k_s: the mirror reflectance or the phong lobe's weight, 0 otherwise.
  const glm::dvec3& SpecularReflectance() const { return this->KSpecular; }
  double PhongExponent() const { return this->Exponent; }

  /// f(in, out) in sr^-1 per band for unit local directions (0 when either lies below the
  /// tangent plane; 0 for the mirror's delta).
  glm::dvec3 Evaluate(const glm::dvec3& in, const glm::dvec3& out) const;
  /// The same in angles: theta in [0, pi/2], deltaPhi = phi_out - phi_in.
  glm::dvec3 Evaluate(double thetaIn, double thetaOut, double deltaPhi) const;
  /// Directional albedo for an outgoing polar angle theta (see the file comment).
  glm::dvec3 Albedo(double theta) const;
  /// The phong lobe's normalization c(theta) (1 for the other kinds).
  double LobeNormalization(double theta) const;

  /// The direction an ideal mirror reflects local direction `local` to: (-x, -y, z).
  static glm::dvec3 MirrorDirection(const glm::dvec3& local)
  {
    return { -local.x, -local.y, local.z };
  }

private:
  void NormalizeLobe();

  MaterialType Type = MaterialType::Diffuse;
  glm::dvec3 KDiffuse{ 0.0 };
  glm::dvec3 KSpecular{ 0.0 };
  double Exponent = 0.0;
  std::shared_ptr<const BrdfTable> Table;
  /// c at the nodes theta_k = (k + 1/2) (pi / 2) / nodes (phong).
  std::vector<double> LobeScale;
  /// Tabulated: Albedo at theta = k degrees, k = 0..90, interpolated in between.
  std::vector<glm::dvec3> AlbedoByDegree;
};

} // namespace sphcover

#endif
