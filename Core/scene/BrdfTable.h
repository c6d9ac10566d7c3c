// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BrdfTable.h
 * @brief A tabulated isotropic BRDF f(theta_in, theta_out, delta_phi) per RGB band, read from
 * the `.brdf.csv` format of Data/scenes/FORMAT.md (section "BRDF tables"): the measured or
 * precomputed "general reflectance" of paper §3.5 from which the weight tables w(out, in-cell)
 * are built.
 *
 * Isotropy (the BRDF depends on the azimuths only through delta_phi = phi_out - phi_in) and the
 * symmetry f(delta_phi) = f(-delta_phi) of isotropic surfaces let the table cover
 * delta_phi in [0, 180] degrees only. The values lie on a full rectilinear grid (every
 * combination of the listed theta_in, theta_out and delta_phi values exactly once) and are
 * interpolated trilinearly; outside the listed range an angle is clamped to the nearest
 * listed value.
 */
#ifndef SPHCOVER_BRDFTABLE_H
#define SPHCOVER_BRDFTABLE_H

#include <glm/vec3.hpp>

#include <istream>
#include <string>
#include <vector>

namespace sphcover
{

class BrdfTable
{
public:
  /**
   * Parses the CSV text; `displayName` names the file in messages. Throws InputError
   * (`<file>: line L: <problem>`) for a bad header, a row that is not 6 finite numbers, an
   * angle out of range, a negative value, a duplicate or missing grid point, or a table whose
   * directional albedo exceeds 1 (the last is reported without a line).
   */
  static BrdfTable Parse(std::istream& in, const std::string& displayName);
  /// Throws InputError ("cannot open file") if the file cannot be read.
  static BrdfTable Load(const std::string& path);

  /// f in sr^-1 per band; angles in radians, theta in [0, pi/2], deltaPhi in [-pi, pi] or any
  /// value (taken as |deltaPhi| folded into [0, pi]).
  glm::dvec3 Evaluate(double thetaIn, double thetaOut, double deltaPhi) const;

  /// The grid (radians, ascending).
  const std::vector<double>& ThetaIn() const { return this->ThetaInValues; }
  const std::vector<double>& ThetaOut() const { return this->ThetaOutValues; }
  const std::vector<double>& DeltaPhi() const { return this->DeltaPhiValues; }

  /**
   * Directional albedo a(theta) = integral over the incoming hemisphere of
   * f(theta_in, theta, dphi) cos(theta_in) dw_in, by a midpoint rule in (sin^2 theta_in, dphi)
   * on `thetaSteps` x `phiSteps` points (exact for a constant f).
   */
  glm::dvec3 Albedo(double thetaOut, int thetaSteps = 90, int phiSteps = 180) const;

private:
  std::vector<double> ThetaInValues;
  std::vector<double> ThetaOutValues;
  std::vector<double> DeltaPhiValues;
  /// Index (a * |ThetaOut| + b) * |DeltaPhi| + c.
  std::vector<glm::dvec3> Values;
};

} // namespace sphcover

#endif
