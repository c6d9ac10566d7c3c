// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LightPropagation.h
 * @brief Progressive propagation of light over the spherical cover (paper §5, §5.1), for
 * the four reflectance kinds of §3.5 (diffuse, ideal mirror, phong, tabulated), with incident
 * radiance stored per region h_ij of every hemisphere H_i (paper §3.1 decision 4) rather than
 * exitant radiance per patch. The diffuse case first; non-diffuse patches below.
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
 * where Omega_e is the projected (cosine-weighted) solid angle of h_ij (f_e Omega_e with the
 * exchange balanced, SetExchangeFactors; E_e itself is never scaled). For a diffuse shooter
 * the exitant radiance is the same in every direction (§3.5.1), so it is evaluated once per
 * shot and a shot costs O(column size) updates (§5.2: "I can be computed only once and then
 * used for all updates. eta in this case, now becomes O(N)").
 *
 * Derived quantities of a diffuse patch i (row i of the cover):
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
 * when sum_j U_j / W_e < ConvergenceTolerance, W_e = sum_j pi A_j (Le_j,r + Le_j,g + Le_j,b)
 * the emitted power (the paper's "appreciable change" of §5.1, made relative), or after
 * MaximumShots shots. Everything runs in the calling thread in a fixed order: the results are
 * deterministic.
 *
 * Non-diffuse reflection (paper §3.5, §5.1, §5.2). A patch whose material is not Lambertian
 * (mirror, phong, tabulated; see Reflectance) cannot turn what it receives into one exitant
 * radiance: its exitant radiance depends on the direction. Such a patch keeps, instead of a
 * reflected dL, the unshot incident radiance dE_e of every entry e of its row (what arrived
 * through h_ie since it last shot); its emission stays in dL (emission is uniform). When it
 * shoots, its exitant radiance toward receiver i is
 *     I_ji = dL_j + (1 / Omega(h_ji)) sum_{o in h_ji} Omega_o sum_c w(o, c) dE_c,
 * the weight table w(out, in-cell) of ReflectanceWeights (paper §3.5 "general reflectance";
 * the ideal mirror is the table with k_s on the mirror cell) averaged over the region h_ji
 * through which P_j sees Q_i: the cells in which the direction P_i - P_j of §5.1 lies. The
 * average over the region rather than the value at one direction is what keeps the energy:
 * summed over the regions of a closed scene, A_j sum_i Omega(h_ji) I_ji is exactly what the
 * weight table reflects. Receiver i gets A_i Omega(h_ij) I_ji, the same where the cover is
 * reciprocal (A_i Omega(h_ij) = A_j Omega(h_ji): the test's one-patch-per-wall box balances to
 * 1e-7). Point-sampled hemispheres of unequal neighbours are not reciprocal (up to 20-27% per
 * pair in the split furnace box). The balance (SetExchangeFactors, ExchangeBalance), fixed
 * before the first shot, gives every region h_ij the measure f_ij Omega_ij (f_ij = x_i y_j)
 * over which its radiance is gathered into irradiance and power: rows keep their covered
 * measure (the furnace stays exact) and columns deliver what the source's own hemisphere sends
 * (a diffuse shot into a closed scene arrives in full). E_e stays the radiance P_i sees (the
 * shooter's exitant radiance toward it, not scaled), and that is what a non-diffuse receiver
 * reflects through its weight table and what the renderer reads. A mirror thus passes on the
 * radiance it sees, and mirror and phong furnaces stay uniform with the balance on. (With E_e
 * scaled by f_e instead, light that crossed k mirrors carried the product of k factors: 2.3% off
 * in the furnace box with a cube inside, NonDiffusePropagation.
 * FurnacesThroughThePipelineWithTheExchangeBalanced.) A non-diffuse point's reflection is
 * counted over its cells' own measure (which the table conserves) and what it receives over the
 * balanced one. Both differ from an exchange that is exact pair by pair only through how the
 * radiance varies along a row or a column, so closed scenes with mirrors and glossy surfaces
 * keep an imbalance of a few tenths of a percent. It is the cover's discretisation error and
 * falls as the patches shrink: the mixed box split 2 x 2, 3 x 3, 4 x 4, 6 x 6, 8 x 8 loses 0.70,
 * 0.65, 0.57, 0.49, 0.37% (ClosedMixedBoxAbsorbsWhatItEmits asserts the fall); a finer grid at
 * the same patches does not help (the mixed box with a cube inside through `sphcover solve`:
 * 0.41, 0.29, 0.39% at 16 x 64, 32 x 128, 64 x 256). The
 * teapot room is off by 0.081% unrefined (1.26% as built) and 0.40% refined as the cover filter
 * does (0.18% as built; with the stored radiance scaled instead of the measure, 0.33% and 0.29%).
 * In the refined teapot room the balance itself cannot close: patches smaller than a cell as
 * seen from afar win few cells of other hemispheres, so their columns fall far short of their
 * rows (1010 of the 13461 points would need y_j > 4) and ExchangeBalance stops stalled. The
 * propagation stays linear, hence order independent; a closed Cornell box goes from 0.84% to
 * 6e-5 (ExchangeBalance.h). Tried and rejected: scaling each shot's delivered power to the sent
 * power (it breaks the furnace, 21% with mirrors, and the order independence); making
 * directional shots exact pair by pair by renormalising each weight table to the balanced
 * out-measures (the split mixed box then balances to 6e-8, but the mirror sphere through the
 * pipeline is 12.6% off the furnace value and the teapot room had not converged after 890902
 * shots, against 72066); re-emitting what a non-diffuse receiver gains or loses by the balanced
 * measure as a uniform radiance (no change: the refined teapot room 0.398%); a cover filled
 * with RBufferFillOptions::DiffuseRounding (the unrefined teapot room 0.22% balanced, 0.96% as
 * built); the rows of non-diffuse receivers left unscaled and the columns balanced through the
 * diffuse rows alone (the teapot room 0.41% unrefined, 0.42% refined).
 *
 * The sum over the table is taken in one of two ways (DirectionalMethod), the same sum in another
 * order (the test GridAndStripPairShotsAgree: 7e-15; the teapot room to 1e-3: incident radiance
 * within 1.1e-14, brightness 9e-14, shot for shot, BenchmarkLightPropagation --compare):
 *  - strip pairs: each (out strip of row j, in strip with unshot radiance) costs O(1)
 *    (cumulative sums of the table), so a shot costs O(strips of row j x strips with unshot
 *    light + column j), the O(D) per receiver of §5.2 reduced by the strips' run-length
 *    structure. Cheap while little of the hemisphere holds unshot light, but it grows with the
 *    product: ~1.2 million pairs per shot in the refined teapot room, where one propagation did
 *    not end in 10 minutes;
 *  - the grid: the unshot light is laid out over the D cells of the hemisphere, reflected
 *    toward every cell at once by ReflectanceWeights::Reflect (the mirror's delta cell by cell,
 *    other tables as circular correlations over phi by FFT, O(ThetaBins^2 PhiBins)), and
 *    averaged over every region h_ji from prefix sums along the rows, O(D log PhiBins +
 *    strips of row j + column j) whatever the strips. A receiver without h_ji reads its cell.
 * Automatic (the default) takes the grid when the strip pairs exceed GridCostInPairs per cell.
 * Where the cover has h_ij
 * but not h_ji (the two hemispheres are discretised independently: a small patch wins no cell
 * of a far shooter's hemisphere; 16% of the updates in the teapot room), the exitant radiance
 * toward the cell of the direction P_i - P_j is used when the frames of the characteristic
 * points are known (SetFrames; the cells are found once, EncodeFallbacks), else the hemisphere's
 * mean exitant radiance (sum over all cells of Omega_o I(o), over pi); ShotRecord counts those
 * updates. A receiver i updates its entry h_ij as before, adds rho_i Omega_e / pi of the increment
 * to dL_i (rho_i = k_d, the Lambertian part, 0 for mirror and tabulated) and, when non-diffuse, the
 * increment to dE_e. The Lambertian part of a phong surface thus travels in closed form with dL,
 * and the weight tables hold the rest of the BRDF (ReflectanceWeights). A Lambertian shooter keeps
 * the closed-form O(column) shot above (§5.2), even among non-diffuse patches.
 *
 * For a non-diffuse patch:
 *  - the unshot power is U_j = pi A_j sum_b dL_j + A_j sum_e sum_b dE_e,b a_e,b Omega_e, with
 *    a_e Omega_e = sum_{c in h_je} Omega_c (a(c) - k_d) the albedo-weighted measure of the
 *    entry (the table's part of the albedo): the
 *    power its next shot sends out (shooting order and convergence as above, on this U_j);
 *  - ExitantRadiance (the Radiosity output) is its Lambertian part Le + k_d / pi E (k_d = 0 for
 *    mirror and tabulated);
 *  - Brightness is pi Le + k_d E + sum_e E_e a_e Omega_e, the flux density it reflects and emits
 * into its whole hemisphere (for a diffuse patch rho E + pi Le as before): the paper's B = (k_d +
 * k_s) int E cos dw + int eps cos dw with the albedo per direction;
 *  - absorbed power A (E - (Brightness - pi Le)), E the irradiance over the balanced measures;
 *  - ExitantRadianceToward(i, direction) evaluates the BRDF toward any direction through the
 *    weight table at the direction's cell (paper §5.3.1: "E interpolated then the BRDF
 *    evaluated toward the eye"); the one implementation is DirectionalExitantRadiance, which
 *    the renderer uses too.
 *
 * Memory layout. The state of the entries (E, dE and the per-entry constants a shot reads) is
 * kept in column order, the order in which a shot walks column j: its entries lie all over the
 * rows, and in row order every update was a cache miss (91% of the column walk's time in the
 * teapot room). The rows are then gathered instead, only by a directional shooter (its own row,
 * prefetched) and for results (Irradiance, IncidentRadiances).
 *
 * Measured (BenchmarkLightPropagation, on a machine shared with other jobs, so wall times are
 * high and vary; processor time is steadier): the teapot room refined as the cover filter does
 * (--refine 3: 13461 patches, 11369 non-diffuse, 9.1 million entries) converges to 1e-5 in
 * 83959 shots, 18.0 s wall and 12.0 s of processor time: uniform shots 62 us (mean column
 * 4004), grid shots 384 us, strip-pair shots 227 us (8021 pairs). Before, `sphcover solve`
 * did not finish propagating it in 10 minutes; strip pairs alone cost 5.8 ms per directional
 * shot there (1.1 million pairs, column-ordered state already). Unrefined (9195
 * patches) to 1e-3: 248 s before (strip pairs, entries in row order), 6.9 s wall / 4.6 s
 * processor now, the same 35397 shots; to 1e-5: 70046 shots, 14.2 s wall / 9.4 s processor. The
 * Cornell box (diffuse only) to 1e-5: 5.7 s before, 1.3 s now (35429 shots); a uniform shot
 * costs 6.9 ns per update (57.7 ns in row order).
 *
 * Limitations: the shooter is found by a scan of the N patches per shot (O(N), the same order
 * as a worst-case column; one pass with the unshot sum), not by a priority queue: a heap would
 * pay O(log N) for each of a column's updates, more than the scan. A shot runs in the calling
 * thread: it takes 50 to 350 us, about what handing work to other threads costs, so threads
 * would gain little and, on a shared machine, wait for cores. Two-sided surfaces are handled as
 * the cover handles them (one hemisphere per point).
 */
#ifndef SPHCOVER_LIGHTPROPAGATION_H
#define SPHCOVER_LIGHTPROPAGATION_H

#include "cover/HemisphereGrid.h"
#include "math/ParallelFor.h"
#include "reflectance/DirectionalReflection.h"
#include "reflectance/Reflectance.h"
#include "reflectance/ReflectanceWeights.h"
#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
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

/// How a non-diffuse shot sums its weight table (the results agree up to rounding; see the file
/// comment).
enum class DirectionalMethod
{
  /// Per shot the cheaper of the two by the estimated cost.
  Automatic = 0,
  /// Strip pairs: O(out strips of the shooter's row x in strips with unshot light).
  StripPairs = 1,
  /// The whole hemisphere: the unshot light as a dense grid of cells, reflected by
  /// ReflectanceWeights::Reflect, then O(1) per out strip by prefix sums.
  Grid = 2
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
  /// Strip pairs (out strip, in strip) the weight table was summed over (0 for a Lambertian
  /// shooter and for a grid shot): the O(D)-like part of a non-diffuse shot.
  std::size_t WeightEvaluations = 0;
  /// Whether the shot reflected its unshot light through the whole-hemisphere grid
  /// (DirectionalMethod::Grid) rather than strip pairs.
  bool GridShot = false;
  /// Receivers i served without the region h_ji, which is null (see the file comment).
  std::size_t Fallbacks = 0;
  /// Of those, the ones served by the mean exitant radiance (no frames, or the direction
  /// below the shooter's tangent plane).
  std::size_t MeanFallbacks = 0;
  /// Wall-clock seconds of propagation since construction (or Reset), at the end of the shot.
  double Seconds = 0.0;
};

/// Power per band, W: emitted sum_i pi A_i Le_i, absorbed sum_i A_i (E_i - reflected_i)
/// (reflected_i = rho_i E_i for a diffuse patch, see the file comment otherwise), and what is
/// still unshot (U_j per band).
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
  /// As above from one material per patch (see MaterialsOfPatches), of any kind: patches with
  /// equal materials share one Reflectance and one weight table. Throws std::invalid_argument
  /// for values out of range and InputError when a tabulated material's table cannot be read.
  LightPropagation(const SphericalCover& cover, const std::vector<Material>& materialOfPatch);

  /// Bytes per entry and per patch of the propagation's state in the widest case (non-diffuse
  /// receivers: E, dE, measures, positions, albedo measures), with the exchange factors and a
  /// filter's output arrays.
  static constexpr std::size_t BytesPerEntry = 192;
  static constexpr std::size_t BytesPerPatch = 256;
  /// An estimate of the propagation's memory for the cover and one material per patch: the
  /// state above and the weight tables (PointReflectances::EstimateBytes), computed without
  /// allocating, so that a caller can refuse before constructing.
  static std::size_t EstimateBytes(const SphericalCover& cover,
    const std::vector<Material>& materialOfPatch);

  /// The material of every patch: Scene::Materials of its surface.
  static std::vector<Material> MaterialsOfPatches(const Scene& scene,
    const std::vector<Patch>& patches);

  /**
   * The hemisphere frame of every characteristic point (HemisphereFrame::OfPatch; the cover's
   * grid is laid out in these frames), or none. With them a non-diffuse shooter serves a
   * receiver whose region h_ji is null by the direction P_i - P_j (see the file comment).
   * Throws std::invalid_argument for a size other than 0 or PatchCount().
   */
  void SetFrames(std::vector<HemisphereFrame> frames);

  /**
   * Balance factors f_e of the entries (ExchangeBalance::EntryFactors, by entry index), or none
   * (empty: f_e = 1, the cover's exchange as built). Region h_ij then counts with the measure
   * f_e Omega_e in the irradiance (and so in every Lambertian reflection and in the energy): the
   * cover's hemispheres with the exchange made energy conserving. The stored incident radiance
   * E_e, which directional reflection and the renderer read, stays the shooter's radiance (see
   * the file comment). Resets the propagation. Throws std::invalid_argument for a size other
   * than 0 or the cover's entry count, or a factor that is negative or not finite.
   */
  void SetExchangeFactors(const std::vector<double>& entryFactors);
  bool HasExchangeFactors() const { return this->Balanced; }

  /// Back to the start: E = 0, unshot radiance = emission, no history.
  void Reset();

  /// How non-diffuse shots sum their weight tables (default Automatic). The methods agree up
  /// to rounding; forcing one is for measuring and testing them.
  void SetDirectionalMethod(DirectionalMethod method) { this->Method = method; }
  DirectionalMethod GetDirectionalMethod() const { return this->Method; }
  /// Automatic takes the grid when the strip pairs exceed this many per cell of the grid: the
  /// grid's cost in strip pairs (BenchmarkLightPropagation --compare on the refined teapot room:
  /// 200 to 300 us per grid shot, 5 ns per strip pair in large shots and more in small ones,
  /// D = 4096 cells).
  static constexpr double GridCostInPairs = 5.0;

  /**
   * Shoots until converged (true), MaximumShots shots were made in this call (false) or
   * `progress` returned false (false; the state is consistent, a later Run continues).
   * Progress is 1 - UnshotEnergy / (UnshotEnergy at the start of the call), clamped to be
   * non-decreasing (in a discretised cover the unshot energy can rise slightly, reciprocity
   * being approximate), and 1 once converged. Throws std::invalid_argument for a negative
   * tolerance, std::overflow_error when the emitted power, the unshot energy or (once
   * converged) an incident radiance is not finite.
   */
  bool Run(const PropagationSettings& settings = {}, const ProgressCallback& progress = nullptr);

  /// One shot of patch `shooter`'s unshot radiance (§5.1); returns the entries updated.
  std::size_t Shoot(std::size_t shooter);

  /// Whether max_j U_j / emitted power < tolerance (true when nothing is emitted).
  bool Converged(double tolerance) const;

  // --- results ---------------------------------------------------------------------------------
  std::size_t PatchCount() const { return this->Rho.size(); }
  /// Incident radiance E_e of entry e of the cover (RGB, W m^-2 sr^-1).
  const glm::dvec3& IncidentRadiance(std::size_t entry) const
  {
    return this->Incident[this->EntryPosition[entry]];
  }
  /// E_e of every entry, by entry index. Copied from the column-ordered state on the first call
  /// after a shot (O(entries)); not to be called concurrently with itself or
  /// ExitantRadianceToward before that copy exists.
  const std::vector<glm::dvec3>& IncidentRadiances() const;
  /// sum over row i of f_e E_e Omega_e (W m^-2 per band; f_e = 1 without exchange factors).
  glm::dvec3 Irradiance(std::size_t patch) const;
  /// Le_i + k_d / pi * Irradiance(i): the Lambertian exitant radiance (all of it for a diffuse
  /// patch; the diffuse part of phong; Le for mirror and tabulated).
  glm::dvec3 ExitantRadiance(std::size_t patch) const;
  /// Exitant flux density: rho_i * Irradiance(i) + pi * Le_i for a diffuse patch, reflected
  /// into the whole hemisphere + pi Le otherwise (paper §5; see the file comment).
  glm::dvec3 Brightness(std::size_t patch) const;
  /// Exitant radiance of patch i toward a unit direction in its hemisphere's local frame
  /// (HemisphereFrame::ToLocal; z along the normal): Le + sum_e sum_{c in h_ie} w(o, c) E_e,
  /// o the direction's cell, plus k_d / pi E (Le + rho / pi E for a diffuse patch); 0 below the
  /// tangent plane.
  glm::dvec3 ExitantRadianceToward(std::size_t patch, const glm::dvec3& localDirection) const;
  /// Whether patch i is Lambertian (shoots in closed form).
  bool IsLambertian(std::size_t patch) const { return this->ModelOfPatch[patch] < 0; }
  /// The BRDF of a non-diffuse patch (nullptr for a Lambertian one, whose BRDF is
  /// Reflectance(patch) / pi).
  const sphcover::Reflectance* ReflectanceModel(std::size_t patch) const;
  /// The weight table of a non-diffuse patch (nullptr for a Lambertian one).
  const ReflectanceWeights* Weights(std::size_t patch) const;
  /// Unshot incident radiance dE_e of entry e (non-diffuse receivers only; 0 otherwise).
  glm::dvec3 UnshotIncidentRadiance(std::size_t entry) const
  {
    return this->UnshotIncident.empty() ? glm::dvec3(0.0)
                                        : this->UnshotIncident[this->EntryPosition[entry]];
  }
  const glm::dvec3& UnshotRadiance(std::size_t patch) const { return this->Unshot[patch]; }
  /// U_j of the file comment.
  double UnshotPower(std::size_t patch) const { return this->Power[patch]; }
  /// sum_j U_j.
  double UnshotEnergy() const;
  /// Emitted power summed over the bands, W.
  double EmittedPower() const { return this->TotalEmitted; }
  EnergyBalance Energy() const;
  const std::vector<ShotRecord>& History() const { return this->Shots; }
  /// The Lambertian reflectance k_d of patch i (rho for diffuse, the diffuse part of phong, 0
  /// for mirror and tabulated).
  const glm::dvec3& Reflectance(std::size_t patch) const { return this->Rho[patch]; }
  const glm::dvec3& Emission(std::size_t patch) const { return this->Le[patch]; }

private:
  /// The patch of largest unshot power (lowest index on ties), that power, and the sum of all
  /// (UnshotEnergy), in one scan.
  std::size_t Brightest(double& power, double& total) const;
  /// U_j from Unshot and DirectionalUnshot (what Power holds).
  double PowerOf(std::size_t patch) const;
  /// Run's steps: the next patch of FixedOrder that has unshot power; one shot with its
  /// record (all but what the scan after it measures); the final check of E_e.
  std::size_t NextInFixedOrder();
  ShotRecord ShootAndRecord(std::size_t shooter);
  void CheckIncidentFinite() const;
  // The non-diffuse shots (DirectionalShot.cxx).
  /// Sets up the non-diffuse machinery (models, weight tables, transposed entries).
  void SetUpModels(const std::vector<Material>& materialOfPatch);
  /// ColumnBack: for every entry (i, j) of column j the position of (j, i) in row j, if any.
  void MatchTransposedEntries();
  /// ColumnAlbedoMeasure: a_e Omega_e of every entry of a non-diffuse row.
  void ComputeAlbedoMeasures();
  /// Exitant radiance of non-diffuse patch j (from its unshot dE) averaged over each entry of
  /// row j, into DirectionalOut, by the cheaper method; returns the mean over the hemisphere.
  glm::dvec3 DirectionalShot(std::size_t shooter);
  /// Moves the shooter's unshot dE into DirectionalIn, as in-strips by row.
  void TakeUnshotInStrips(std::size_t shooter);
  /// DirectionalCoupled from DirectionalIn; returns the strip pairs of a strip-pair shot.
  std::size_t CoupleInRows(std::size_t shooter, const ReflectanceWeights& table);
  /// The two methods of DirectionalShot, on the in-strips it collected.
  glm::dvec3 ShotByStripPairs(std::size_t shooter,
    const ReflectanceWeights& table,
    std::size_t pairs);
  glm::dvec3 ShotByGrid(std::size_t shooter, const ReflectanceWeights& table);
  /// The exitant radiance of the current directional shot toward a receiver without h_ji, whose
  /// ColumnBack code is `code`.
  glm::dvec3 TowardReceiver(std::size_t shooter, uint32_t code, const glm::dvec3& mean);
  /// Sets the ColumnBack codes of the receivers without h_ji from the frames.
  void EncodeFallbacks();
  /// sum_e E_e a_e Omega_e over row i (non-diffuse) or rho_i E_i (diffuse).
  glm::dvec3 Reflected(std::size_t patch) const;

  const SphericalCover& Cover;
  std::vector<glm::dvec3> Rho;
  std::vector<glm::dvec3> Le;
  /// Omega_e of every entry, computed once from the strips, by entry and in column order (the
  /// k-th element of the cover's columns: a shot walks column j, and reads its entries'
  /// data in one sweep instead of all over the rows).
  std::vector<double> EntryOmega;
  /// The measure each region's radiance counts with, in column order: f_e Omega_e with exchange
  /// factors (SetExchangeFactors), Omega_e without.
  std::vector<double> ColumnMeasure;
  bool Balanced = false;
  /// E_e in column order (EntryPosition), and by entry for IncidentRadiances.
  std::vector<glm::dvec3> Incident;
  mutable std::vector<glm::dvec3> IncidentByEntry;
  mutable bool IncidentByEntryValid = false;
  std::vector<glm::dvec3> Unshot;
  double TotalEmitted = 0.0;
  std::vector<ShotRecord> Shots;
  double ElapsedSeconds = 0.0;
  /// Next patch FixedOrder considers.
  std::size_t NextInOrder = 0;

  // Non-diffuse patches (see the file comment).
  /// Index into Reflectances, -1 for a Lambertian patch.
  std::vector<int> ModelOfPatch;
  PointReflectances Reflectances;
  static constexpr uint32_t NoEntry = 0xffffffffu;
  static constexpr uint32_t FallbackFlag = 0x80000000u;
  /// Position in column order of every entry.
  std::vector<uint32_t> EntryPosition;
  // Only when some patch is non-diffuse, all in column order (see ColumnMeasure):
  /// For the entry (i, j) at column position k: the position of the entry (j, i) within row j
  /// (an index of DirectionalOut); when h_ji is null, FallbackFlag | the cell of the direction
  /// P_i - P_j in H_j (frames known, EncodeFallbacks), or NoEntry (the mean).
  std::vector<uint32_t> ColumnBack;
  /// a_e Omega_e per band for entries of non-diffuse rows (0 otherwise).
  std::vector<glm::dvec3> ColumnAlbedoMeasure;
  /// dE_e of the file comment.
  std::vector<glm::dvec3> UnshotIncident;
  /// The directional part of U_j (W, summed over the bands), kept up to date by the shots.
  std::vector<double> DirectionalUnshot;
  /// U_j of every patch, updated with Unshot and DirectionalUnshot: the scan for the brightest
  /// reads one array.
  std::vector<double> Power;
  /// Scratch of DirectionalShot: radiance toward each entry of the shooter's row, the in-strips
  /// with unshot radiance by row, and per out row the coupled in rows that hold some.
  std::vector<glm::dvec3> DirectionalOut;
  struct InStrip
  {
    int Begin;
    int End;
    glm::dvec3 Radiance;
  };
  std::vector<std::vector<InStrip>> DirectionalIn;
  std::vector<std::vector<int>> DirectionalCoupled;
  /// Scratch of ShotByGrid: unshot incident radiance per cell, exitant radiance per cell, and
  /// per row the prefix sums of the exitant radiance over the columns.
  std::vector<glm::dvec3> GridIn;
  std::vector<glm::dvec3> GridOut;
  std::vector<glm::dvec3> GridPrefix;
  ReflectanceWeights::Scratch ReflectScratch;
  DirectionalMethod Method = DirectionalMethod::Automatic;
  /// Whether the current (last) directional shot went through the grid.
  bool GridShot = false;
  std::vector<HemisphereFrame> Frames;
  /// Statistics of the last Shoot, for its ShotRecord.
  std::size_t LastWeightEvaluations = 0;
  std::size_t LastFallbacks = 0;
  std::size_t LastMeanFallbacks = 0;
};

} // namespace sphcover

#endif
