// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DirectionalReflection.h
 * @brief The exitant radiance of a non-diffuse characteristic point toward one direction from
 * the incident radiance function E of its hemisphere (paper §3.5 "I(theta_r, phi_r) = sum_ij
 * w_ij e_ij"), the single implementation shared by the propagation
 * (LightPropagation::ExitantRadianceToward) and the final rendering (RadianceRenderer, paper
 * §5.3.1), and the BRDFs of the points that need it.
 *
 * Point i's row of the cover holds, per entry e = (i, j), the incident radiance E_e and the
 * strips of cells of region h_ij. Toward a local direction in the cell o (row, column of the
 * HemisphereGrid), the directional part of the exitant radiance is
 *     I_dir(o) = sum_e E_e sum_{strips s of e} sum_{c in s} w(o, c),
 * w the weight table of the point's BRDF without its Lambertian part (ReflectanceWeights): each
 * strip costs O(1) through the table's cumulative sums, so one evaluation costs O(strips of the
 * row) (the O(D) of paper §5.2 reduced by the run-length structure of the regions). For an
 * ideal mirror the table is k_s on the mirror cell, so I_dir(o) = k_s E of the region holding
 * the mirror cell of o (PhiBins even; odd: split over the two cells the mirror direction
 * borders). The Lambertian part Le + k_d / pi sum_e E_e Omega_e is not included: it is
 * the same toward every direction, and the propagation and the renderer already hold it
 * (`Radiosity`).
 */
#ifndef SPHCOVER_DIRECTIONALREFLECTION_H
#define SPHCOVER_DIRECTIONALREFLECTION_H

#include "reflectance/Reflectance.h"
#include "reflectance/ReflectanceWeights.h"
#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace sphcover
{

class HemisphereGrid;
class SphericalCover;

/// Whether two materials reflect alike (kind, reflectances, exponent, table): points with
/// equal reflectance share one Reflectance and one weight table.
bool SameReflectance(const Material& a, const Material& b);

/**
 * I_dir of the file comment: the directional (non-Lambertian) exitant radiance of point
 * `point` of `cover` toward the unit direction `localDirection` of its hemisphere frame
 * (HemisphereFrame::ToLocal, z along the normal), from the incident radiance `incident` of
 * every entry of the cover, through the weight table of the point's BRDF. 0 below the tangent
 * plane.
 */
glm::dvec3 DirectionalExitantRadiance(const SphericalCover& cover,
  const ReflectanceWeights& table,
  std::size_t point,
  const std::vector<glm::dvec3>& incident,
  const glm::dvec3& localDirection);

/// The same toward the cover grid's cell `cell` (what the value depends on: a direction above
/// the tangent plane in that cell gives this value bit for bit). Only the point's own row and
/// its entries' `incident` are read, so a share of the cover holding the row (a rank's rows)
/// gives the whole cover's value.
glm::dvec3 DirectionalExitantRadianceOfCell(const SphericalCover& cover,
  const ReflectanceWeights& table,
  std::size_t point,
  const std::vector<glm::dvec3>& incident,
  int cell);

/// The BRDF and weight table of every non-diffuse point, one per distinct reflectance.
class PointReflectances
{
public:
  PointReflectances() = default;
  /// Throws std::invalid_argument for values out of range and InputError when a tabulated
  /// material's table cannot be read (Reflectance).
  PointReflectances(const HemisphereGrid& grid, const std::vector<Material>& materialOfPoint);
  /// The bytes of the weight tables the constructor would build (one per distinct non-diffuse
  /// reflectance, ReflectanceWeights::EstimateBytes each), computed without building them.
  static std::size_t EstimateBytes(int thetaBins,
    int phiBins,
    const std::vector<Material>& materialOfPoint);

  /// Index of the point's model, -1 for a Lambertian point.
  int ModelOf(std::size_t point) const { return this->ModelOfPoint[point]; }
  bool IsLambertian(std::size_t point) const { return this->ModelOfPoint[point] < 0; }
  bool Empty() const { return this->Models.empty(); }
  /// nullptr for a Lambertian point.
  const Reflectance* Model(std::size_t point) const;
  const ReflectanceWeights* Table(std::size_t point) const;

private:
  std::vector<int> ModelOfPoint;
  std::vector<Reflectance> Models;
  std::vector<ReflectanceWeights> Tables;
};

} // namespace sphcover

#endif
