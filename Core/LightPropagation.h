// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LightPropagation.h
 * @brief Progressive propagation of light over the spherical cover (paper §5, §5.1), for
 * diffuse surfaces, with incident radiance stored per region h_ij of every hemisphere H_i
 * (paper §3.1 decision 4) rather than exitant radiance per patch.
 *
 * State, per band (RGB):
 *  - E_e, the incident radiance of every entry e = (i, j) of the cover: the radiance P_i
 *    receives through h_ij, which is the exitant radiance of Q_j toward P_i;
 *  - the unshot exitant radiance dL_j of every patch: what Q_j has reflected (or emits) but
 *    not yet sent to the hemispheres that contain it.
 *
 * A shot (§5.1 "Remove the brightest characteristic point ... For all hemispherical
 * tessellations H_j with P_i in H_j ... update the radiance function entry associated with
 * h_ji") takes the shooter j's unshot radiance dL_j and walks column j of the cover: for every
 * receiver i whose hemisphere holds Q_j (entry e),
 *     E_e += dL_j,   dL_i += rho_i / pi * dL_j * Omega_e,
 * where Omega_e is the projected (cosine-weighted) solid angle of h_ij. For a diffuse shooter
 * the exitant radiance is the same in every direction (§3.5.1), so it is evaluated once per
 * shot and a shot costs O(column size) updates (§5.2: "I can be computed only once and then
 * used for all updates. eta in this case, now becomes O(N)").
 *
 * Derived quantities of patch i (row i of the cover):
 *  - irradiance        E_i = sum_{e in row i} E_e Omega_e                       (W m^-2);
 *  - exitant radiance  L_i = Le_i + rho_i / pi * E_i                            (W m^-2 sr^-1);
 *  - brightness (§5)   B_i = rho_i * E_i + pi * Le_i = pi * L_i                 (W m^-2):
 *    the paper's B = (k_d + k_s) int E cos dw + int eps cos dw with k_s = 0 (diffuse) and the
 *    emission eps = Le uniform over the hemisphere, so int eps cos dw = pi Le. It is the
 *    radiosity (exitant flux density) of the patch, per band.
 * L_i includes the light still unshot at P_i (as in progressive radiosity), so it is the
 * current estimate of the equilibrium, not only what has already been propagated.
 *
 * Shooting order and convergence. The unshot power of patch j is
 *     U_j = pi * A_j * (dL_j,r + dL_j,g + dL_j,b)   (W, summed over the bands),
 * the flux it would send out in one shot. BrightestFirst shoots the patch of largest U_j (ties
 * to the lowest index; the paper's "brightest characteristic point", measured by its unshot
 * change, which is what SPEC §4.4 allows); FixedOrder cycles through the patches in index
 * order and shoots whatever each has (a patch with nothing unshot is passed over). Both stop
 * when max_j U_j / W_e < ConvergenceTolerance, W_e = sum_j pi A_j (Le_j,r + Le_j,g + Le_j,b)
 * the emitted power (the paper's "appreciable change" of §5.1, made relative), or after
 * MaximumShots shots. Everything runs in the calling thread in a fixed order: the results are
 * deterministic.
 *
 * Limitations of this increment:
 *  - Diffuse reflection only. A Phong material is propagated as diffuse with its Diffuse
 *    reflectance (its specular lobe is dropped: that light is lost, not redistributed); mirror
 *    and tabulated materials are rejected (std::invalid_argument). The per-entry storage of E
 *    is already what the directional reflectances of §3.5 need; their shots evaluate I toward
 *    each receiver instead of once.
 *  - The shooter is found by a scan of the N patches per shot (O(N), the same order as a
 *    worst-case column), not by a priority queue.
 *  - Two-sided surfaces are handled as the cover handles them (one hemisphere per point).
 */
#ifndef SPHCOVER_LIGHTPROPAGATION_H
#define SPHCOVER_LIGHTPROPAGATION_H

#include "Material.h"
#include "ParallelFor.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace sphcover
{

class SphericalCover;
struct Patch;
struct Scene;

enum class ShootingOrder
{
  /// The patch with the largest unshot power (paper §5: "starting from the brightest").
  BrightestFirst = 0,
  /// The patches in index order, cyclically.
  FixedOrder = 1
};

struct PropagationSettings
{
  /// Stop when the unshot power (summed over all points) relative to the emitted power falls
  /// below this: no later update can then change anything by more.
  double ConvergenceTolerance = 1e-4;
  /// Most shots in one Run call (0: no limit other than convergence).
  std::size_t MaximumShots = 0;
  ShootingOrder Order = ShootingOrder::BrightestFirst;
};

/// One shot of the convergence history.
struct ShotRecord
{
  /// Index of the shot since construction (or Reset).
  std::size_t Shot = 0;
  std::size_t Shooter = 0;
  /// Unshot power the shooter sent, W summed over the bands (its U_j before the shot).
  double ShotPower = 0.0;
  /// ShotPower / emitted power (the "MaxChange" of SPEC §4.4 for BrightestFirst).
  double RelativeChange = 0.0;
  /// max_j U_j / emitted power after the shot: the convergence measure.
  double MaxUnshotRelative = 0.0;
  /// sum_j U_j after the shot, W.
  double UnshotEnergy = 0.0;
  /// Entries updated by the shot (the size of the shooter's column, §5.2).
  std::size_t ReceiverUpdates = 0;
  /// Wall-clock seconds of propagation since construction (or Reset), at the end of the shot.
  double Seconds = 0.0;
};

/// Power per band, W: emitted sum_i pi A_i Le_i, absorbed sum_i A_i (1 - rho_i) E_i, and what
/// is still unshot sum_i pi A_i dL_i.
struct EnergyBalance
{
  glm::dvec3 Emitted{ 0.0 };
  glm::dvec3 Absorbed{ 0.0 };
  glm::dvec3 Unshot{ 0.0 };
  /// max over the bands that emit of |Emitted - Absorbed| / Emitted: 0 at equilibrium in a
  /// closed scene; in an open scene it also counts the light that escapes.
  double RelativeImbalance = 0.0;
};

class LightPropagation
{
public:
  /**
   * @param cover the spherical cover of the patches (kept by reference: it must outlive this
   * object and not change).
   * @param reflectance diffuse reflectance rho per patch and band, in [0, 1].
   * @param emission emitted radiance Le per patch and band, >= 0 (W m^-2 sr^-1).
   * Throws std::invalid_argument when a size differs from the cover's patch count or a value
   * is out of range. Per-patch arrays are what a VTK filter holds as point data.
   */
  LightPropagation(const SphericalCover& cover,
    std::vector<glm::dvec3> reflectance,
    std::vector<glm::dvec3> emission);
  /// As above from one material per patch (see MaterialsOfPatches); throws
  /// std::invalid_argument for mirror and tabulated materials (see the file comment).
  LightPropagation(const SphericalCover& cover, const std::vector<Material>& materialOfPatch);

  /// The material of every patch: Scene::Materials of its surface.
  static std::vector<Material> MaterialsOfPatches(const Scene& scene,
    const std::vector<Patch>& patches);

  /// Back to the start: E = 0, unshot radiance = emission, no history.
  void Reset();

  /**
   * Shoots until converged (true), MaximumShots shots were made in this call (false) or
   * `progress` returned false (false; the state is consistent, a later Run continues).
   * Progress is 1 - UnshotEnergy / (UnshotEnergy at the start of the call), clamped to be
   * non-decreasing (in a discretised cover the unshot energy can rise slightly, reciprocity
   * being approximate), and 1 once converged. Throws std::invalid_argument for a negative
   * tolerance.
   */
  bool Run(const PropagationSettings& settings = {}, const ProgressCallback& progress = nullptr);

  /// One shot of patch `shooter`'s unshot radiance (§5.1); returns the entries updated.
  std::size_t Shoot(std::size_t shooter);

  /// Whether max_j U_j / emitted power < tolerance (true when nothing is emitted).
  bool Converged(double tolerance) const;

  // --- results ---------------------------------------------------------------------------------
  std::size_t PatchCount() const { return this->Rho.size(); }
  /// Incident radiance E_e of entry e of the cover (RGB, W m^-2 sr^-1).
  const glm::dvec3& IncidentRadiance(std::size_t entry) const { return this->Incident[entry]; }
  const std::vector<glm::dvec3>& IncidentRadiances() const { return this->Incident; }
  /// sum over row i of E_e Omega_e (W m^-2 per band).
  glm::dvec3 Irradiance(std::size_t patch) const;
  /// Le_i + rho_i / pi * Irradiance(i).
  glm::dvec3 ExitantRadiance(std::size_t patch) const;
  /// rho_i * Irradiance(i) + pi * Le_i (paper §5; see the file comment).
  glm::dvec3 Brightness(std::size_t patch) const;
  const glm::dvec3& UnshotRadiance(std::size_t patch) const { return this->Unshot[patch]; }
  /// U_j of the file comment.
  double UnshotPower(std::size_t patch) const;
  /// sum_j U_j.
  double UnshotEnergy() const;
  /// Emitted power summed over the bands, W.
  double EmittedPower() const { return this->TotalEmitted; }
  EnergyBalance Energy() const;
  const std::vector<ShotRecord>& History() const { return this->Shots; }
  const glm::dvec3& Reflectance(std::size_t patch) const { return this->Rho[patch]; }
  const glm::dvec3& Emission(std::size_t patch) const { return this->Le[patch]; }

private:
  /// The patch of largest unshot power (lowest index on ties), and that power.
  std::size_t Brightest(double& power) const;

  const SphericalCover& Cover;
  std::vector<glm::dvec3> Rho;
  std::vector<glm::dvec3> Le;
  /// Omega_e of every entry, computed once from the strips.
  std::vector<double> EntryOmega;
  std::vector<glm::dvec3> Incident;
  std::vector<glm::dvec3> Unshot;
  double TotalEmitted = 0.0;
  std::vector<ShotRecord> Shots;
  double ElapsedSeconds = 0.0;
  /// Next patch FixedOrder considers.
  std::size_t NextInOrder = 0;
};

} // namespace sphcover

#endif
