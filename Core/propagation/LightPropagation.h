// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LightPropagation.h
 * @brief Progressive propagation of light over the spherical cover (paper §5, §5.1), for the four
 * reflectance kinds of §3.5 (diffuse, ideal mirror, phong, tabulated), with incident radiance
 * stored per region h_ij of every hemisphere H_i (paper §3.1 decision 4).
 *
 * State, per band: E_e, the incident radiance of every entry e = (i, j) of the cover (what P_i
 * receives through h_ij: the exitant radiance of Q_j toward P_i), and what each patch has
 * received but not yet shot: the uniform dL_j (emission, Lambertian reflection) and, for a
 * non-diffuse patch, dE_e per entry of its row.
 *
 * A shot of patch j (§5.1) walks column j of the cover: every receiver i whose hemisphere holds
 * Q_j gets E_e += I_ji and dL_i += k_d,i / pi f_e Omega_e I_ji (and dE_e += I_ji when
 * non-diffuse), Omega_e the projected solid angle of h_ij and f_e its exchange factor
 * (SetExchangeFactors; 1 without). A Lambertian shooter's I_ji = dL_j is the same toward every
 * receiver (§5.2). A non-diffuse shooter adds its weight table's reflection of dE averaged over
 * the region h_ji (ReflectanceWeights, §3.5 "general reflectance"), summed by strip pairs or over
 * the whole-hemisphere grid (DirectionalMethod, the same sum); a receiver without h_ji gets the
 * radiance toward the cell of P_i - P_j (SetFrames) or the hemisphere's mean.
 *
 * Receivers' views (with frames, SetFrames): a non-diffuse j sends i its exitant radiance
 * averaged over the directions in which P_i sees Q_j, not over h_ji: the samples of h_ij taken
 * into H_j and turned around (a mirror: the dE of the mirror cell of each), so a small receiver
 * sees a lamp's image through the whole of Q_j (§3.1, §5.1; the incident light stays P_j's).
 * Found once; a receiver whose samples all lie behind Q_j's plane is served by h_ji as above.
 * Automatic shoots such a patch through the grid (every cell at once).
 *
 * Order and convergence: BrightestFirst shoots the patch of largest unshot power U_j (§5 "the
 * brightest"; ties to the lowest index), FixedOrder cycles through the patches; both stop when
 * sum_j U_j falls below ConvergenceTolerance times the emitted power, or after MaximumShots. All
 * in the calling thread, in a fixed order: the results are deterministic.
 *
 * Batches (PropagationSettings::ShotBatch): BrightestFirst may shoot up to B patches at a time,
 * the brightest and the next ones whose U_j is at least BatchPowerFraction of its U_j, in order
 * of U_j (ties to the lowest index). Every member's unshot light is taken and, for a non-diffuse
 * one, reflected (its DirectionalShot) before any column is walked; the columns are then walked
 * in the batch's order. Light a member receives from another in the same batch stays unshot for
 * a later batch. The batch depends on the state alone, never on the ranks: under MPI the owners
 * of a batch's non-diffuse shooters reflect them at the same time, with one exchange per batch.
 * B = 1 is §5's order, one shot at a time.
 *
 * Panes (paper §5.4; SphericalCover.h "Panes"): an entry seen through panes receives the
 * shooter's radiance times its filter (E_e is what arrives, filtered); a pane's own unshot light
 * is only what it reflects, what it lets through having reached the points behind it through
 * their filtered entries of the same shot. Its power balance counts the transmitted part as
 * not absorbed: absorbed = E - reflected - T E.
 *
 * Results per patch: Irradiance E_i = sum_{e in row i} f_e E_e Omega_e; ExitantRadiance, the
 * Lambertian part Le + k_d / pi E_i; Brightness (§5's B), the flux density emitted and reflected
 * into the whole hemisphere; ExitantRadianceToward, the exitant radiance toward any direction
 * (§5.3.1); Energy, the power balance.
 *
 * Complexity: a shot costs O(column j) updates, plus for a non-diffuse shooter O(strips of row j x
 * in-strips with unshot light) by strip pairs or O(D log PhiBins) by the grid (D cells per
 * hemisphere) and O(view items), plus the O(N) scan for the next shooter. Memory: BytesPerEntry
 * per entry, BytesPerPatch per patch (the entries' state in column order, the order a shot
 * walks) and the views (ViewBytesPerCell per cell of the regions of non-diffuse sources).
 * Derivations, measurements and the variants tried: Documentation/notes/propagation.md.
 */
#ifndef SPHCOVER_LIGHTPROPAGATION_H
#define SPHCOVER_LIGHTPROPAGATION_H

#include "cover/HemisphereGrid.h"
#include "math/ParallelFor.h"
#include "math/RankShare.h"
#include "reflectance/DirectionalReflection.h"
#include "reflectance/Reflectance.h"
#include "reflectance/ReflectanceWeights.h"
#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
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
  /// Most patches shot at a time by BrightestFirst (see the file comment; at least 1). The
  /// results differ with it, within the tolerance; never with the ranks.
  std::size_t ShotBatch = 1;
};

/// One shot of the convergence history.
struct ShotRecord
{
  /// Index of the shot since construction (or Reset).
  std::size_t Shot = 0;
  std::size_t Shooter = 0;
  /// Unshot power the shooter sent, W summed over the bands (its U_j before the shot).
  double ShotPower = 0.0;
  /// ShotPower / emitted power (the "MaxChange" of Documentation/Pipeline.md#light-propagation for
  /// BrightestFirst).
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
  /// Receivers i whose region h_ji is null (see the file comment): served by their view of the
  /// shooter where they have one, else as the file comment says.
  std::size_t Fallbacks = 0;
  /// Of those, the ones served by the mean exitant radiance (no frames, or the direction
  /// below the shooter's tangent plane, and no view).
  std::size_t MeanFallbacks = 0;
  /// Wall-clock seconds of propagation since construction (or Reset), at the end of the shot.
  double Seconds = 0.0;
};

/// Power per band, W: emitted sum_i pi A_i Le_i, absorbed sum_i A_i (E_i - reflected_i)
/// (reflected_i = rho_i E_i for a diffuse patch, sum_e E_e a_e Omega_e more otherwise: see
/// UnshotPower), and what is still unshot (U_j per band).
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
  /// Bytes of the receivers' views (SetFrames) per cell of a region h_ij of a non-diffuse
  /// source j, as EstimateBytes counts them: a view holds an item of 8 bytes per cell of H_j its
  /// samples fall in, at most one per sample, 1.8 per cell of h_ij as measured
  /// (Documentation/notes/propagation.md, 2026-12-07).
  static constexpr std::size_t ViewBytesPerCell = 16;
  /// Bytes per patch that the state holds whatever the materials and the cover: a diffuse
  /// patch's reflectance, emission, unshot radiance, model and power (a floor, for refusing a
  /// scene before the cover's entries are known).
  static constexpr std::size_t LeastBytesPerPatch =
    3 * sizeof(glm::dvec3) + sizeof(int) + sizeof(double);
  /// An estimate of the propagation's memory for the cover and one material per patch: the
  /// state above, the receivers' views (ViewBytesPerCell, with frames) and the weight tables
  /// (PointReflectances::EstimateBytes), computed without allocating, so that a caller can
  /// refuse before constructing.
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

  /// Whether this rank holds the patch's row and results: every patch, unless the propagation
  /// is shared among ranks (distributed/SharedPropagation.h).
  bool Owns(std::size_t patch) const { return this->Share.Owns(patch); }

  /// Back to the start: E = 0, unshot radiance = emission, no history.
  void Reset();

  /// How non-diffuse shots sum their weight tables (default Automatic). The methods agree up
  /// to rounding; forcing one is for measuring and testing them.
  void SetDirectionalMethod(DirectionalMethod method) { this->Method = method; }
  DirectionalMethod GetDirectionalMethod() const { return this->Method; }
  /// Automatic takes the grid when the strip pairs exceed this many per cell of the grid: the
  /// grid's cost in strip pairs, as measured (Documentation/notes/propagation.md).
  static constexpr double GridCostInPairs = 5.0;
  /// A batch's members after the brightest have at least this fraction of its unshot power.
  static constexpr double BatchPowerFraction = 0.5;

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

  /// One shot of patch `shooter`'s unshot radiance (§5.1); returns the entries updated. Not
  /// under a share (std::logic_error): there Run's batches are collective.
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
  /// into the whole hemisphere + pi Le otherwise (paper §5).
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
  /// U_j = pi A_j sum_b dL_j,b (+ A_j sum_e sum_b dE_e,b a_e Omega_e for a non-diffuse patch,
  /// a_e Omega_e = sum_{c in h_je} Omega_c (a(c) - k_d) the table's albedo over the entry): the
  /// power the next shot of patch j sends out, W summed over the bands.
  double UnshotPower(std::size_t patch) const { return this->Power[patch]; }
  /// sum_j U_j.
  double UnshotEnergy() const;
  /// Emitted power summed over the bands, W.
  double EmittedPower() const { return this->TotalEmitted; }
  /// Under a share: collective, the sums over every rank's patches (the same on every rank).
  EnergyBalance Energy() const;
  /**
   * The lamps' light at every point as the cover's regions carry it, per band (W m^-2): the
   * direct irradiance E_d,i = sum over the entries e = (i, j) of lamp patches j of m_e Le_j,
   * plus, with `firstBounce`, its first Lambertian reflection sum_e m_e k_d,j / pi E_d,j
   * (m_e = f_e Omega_e, the measure the propagation counts the region with). This is the part
   * of Irradiance() that DirectIrradianceNodes computes finer, on the patches' nodes: a
   * renderer that adds the nodes takes this off the points' values, so that the cover's
   * coarser version of the same light is not counted twice. `lampPatch`: per patch whether it
   * is a lamp. Throws std::invalid_argument when its size is not PatchCount().
   */
  std::vector<glm::dvec3> LampIrradiance(const std::vector<bool>& lampPatch,
    bool firstBounce) const;
  const std::vector<ShotRecord>& History() const { return this->Shots; }
  /// The Lambertian reflectance k_d of patch i (rho for diffuse, the diffuse part of phong, 0
  /// for mirror and tabulated).
  const glm::dvec3& Reflectance(std::size_t patch) const { return this->Rho[patch]; }
  const glm::dvec3& Emission(std::size_t patch) const { return this->Le[patch]; }

private:
  /// A patch chosen to shoot, with what the ranks that do not own it need to know of it.
  struct Candidate
  {
    std::size_t Shooter = 0;
    /// U_j when chosen.
    double Power = 0.0;
    /// Its unshot radiance dL_j, and whether its shot is directional (has unshot dE).
    glm::dvec3 Increment{ 0.0 };
    bool Directional = false;
  };
  /// A non-diffuse shot (DirectionalShot's results): the radiance toward each entry of the
  /// shooter's row and what serves the receivers without one (the grid's exitant radiance, or
  /// the in-strips and their coupled rows), the mean over the hemisphere. Another rank's shot
  /// holds only what this rank's receivers read (ShareDirectionalShots).
  struct InStrip
  {
    int Begin;
    int End;
    glm::dvec3 Radiance;
  };
  struct DirectionalShotData
  {
    glm::dvec3 Mean{ 0.0 };
    /// Summed through the grid (the record's GridShot).
    bool Grid = false;
    /// GridOut holds the radiance toward the cells the receivers without h_ji need: a grid
    /// shot's, or one received from another rank (ShareDirectionalShots).
    bool ByCell = false;
    std::size_t WeightEvaluations = 0;
    std::vector<glm::dvec3> Out;
    std::vector<glm::dvec3> GridOut;
    std::vector<std::vector<InStrip>> In;
    std::vector<std::vector<int>> Coupled;
  };
  /// The patch of largest unshot power (lowest index on ties), that power, and the sum of all
  /// (UnshotEnergy), in one scan.
  std::size_t Brightest(double& power, double& total) const;
  /// The next batch from this rank's patches (the brightest `best` of power `largest`): up to
  /// `size` of them, of power >= BatchPowerFraction x largest, by SelectBatch.
  std::vector<Candidate> LocalBatch(std::size_t best, double largest, std::size_t size) const;
  /// The batch of `candidates`: those of power > 0 and >= BatchPowerFraction x `largest`, by
  /// decreasing power (lowest index on ties), the first `size`.
  static void SelectBatch(std::vector<Candidate>& candidates, double largest, std::size_t size);
  /// Shoots the batch (see the file comment); one record per member, without what the scan
  /// after it measures.
  std::vector<ShotRecord> ShootBatch(const std::vector<Candidate>& batch);
  /// U_j from Unshot and DirectionalUnshot (what Power holds).
  double PowerOf(std::size_t patch) const;
  /// Whether patch j's next shot is directional: non-diffuse, with unshot dE.
  bool ShootsDirectionally(std::size_t patch) const
  {
    return this->ModelOfPatch[patch] >= 0 && this->DirectionalUnshot[patch] > 0.0;
  }
  /// Run's steps: the next patch of FixedOrder that has unshot power; the final check of E_e.
  std::size_t NextInFixedOrder();
  void CheckIncidentFinite() const;
  // The non-diffuse shots (DirectionalShot.cxx).
  /// Sets up the non-diffuse machinery (models, weight tables, transposed entries).
  void SetUpModels(const std::vector<Material>& materialOfPatch);
  /// What orders a row's entries (CompareEntryKeys): for rows another rank holds.
  struct EntryKey
  {
    uint32_t Source;
    uint32_t Layer;
    glm::vec3 Filter;
  };
  /// ColumnBack: for every entry (i, j) of column j the position of (j, i) in row j, if any;
  /// row j from `remoteRows[j]` where that is not empty (the keys of another rank's row).
  void MatchTransposedEntries(const std::vector<std::vector<EntryKey>>& remoteRows = {});
  /**
   * What a propagation shared among ranks adds to Run's batches (SharePropagation in
   * distributed/SharedPropagation.h installs it; none: the propagation is serial, and every
   * patch is this rank's). Each call is collective: every rank makes it at the same point.
   */
  class BatchHook
  {
  public:
    virtual ~BatchHook() = default;
    /// Run's scan before every batch: this rank's batch of its own patches (LocalBatch), its
    /// largest power and unshot energy, whether it stops and the last batch's counts (none
    /// before the first batch) joined into the batch of all the ranks' (SelectBatch), the
    /// largest power and the total unshot energy, the counts summed into `records`; false when
    /// some rank stops.
    virtual bool JoinScan(std::vector<Candidate>& batch,
      double& largest,
      double& unshot,
      std::size_t size,
      bool stop,
      std::vector<ShotRecord>* records) = 0;
    /// ShootBatch's non-diffuse shots, each computed by its shooter's owner into `data[m]` (m
    /// the member), given to every rank as far as its receivers read them. `ok`: this rank's
    /// succeeded.
    virtual void ShareDirectionalShots(const std::vector<Candidate>& batch,
      const std::vector<bool>& directional,
      std::vector<DirectionalShotData>& data,
      bool ok) = 0;
    /// SetFrames changed what the receivers without a region h_ji read (EncodeFallbacks).
    virtual void FallbacksChanged() = 0;
  };
  friend class SharedPropagation;
  bool Shared() const { return this->Hook != nullptr; }
  /// ColumnAlbedoMeasure: a_e Omega_e of every entry of a non-diffuse row.
  void ComputeAlbedoMeasures();
  /// Exitant radiance of non-diffuse patch j (from its unshot dE, which it takes) averaged over
  /// each entry of row j, by the cheaper method, with the mean over the hemisphere, into `shot`.
  void DirectionalShot(std::size_t shooter, DirectionalShotData& shot);
  /// Moves the shooter's unshot dE into shot.In, as in-strips by row.
  void TakeUnshotInStrips(std::size_t shooter, DirectionalShotData& shot);
  /// shot.Coupled from shot.In; returns the strip pairs of a strip-pair shot.
  std::size_t CoupleInRows(std::size_t shooter,
    const ReflectanceWeights& table,
    DirectionalShotData& shot);
  /// The two methods of DirectionalShot, on the in-strips it collected.
  void ShotByStripPairs(std::size_t shooter,
    const ReflectanceWeights& table,
    std::size_t pairs,
    DirectionalShotData& shot);
  void ShotByGrid(std::size_t shooter, const ReflectanceWeights& table, DirectionalShotData& shot);
  /// The exitant radiance of directional shot `shot` toward a receiver without h_ji, whose
  /// ColumnBack code is `code`; counts a mean fallback into `meanFallbacks`.
  glm::dvec3 TowardReceiver(std::size_t shooter,
    uint32_t code,
    const DirectionalShotData& shot,
    std::size_t& meanFallbacks) const;
  /// Sets the ColumnBack codes of the receivers without h_ji from the frames, and the
  /// receivers' views of the mirrors (BuildReceiverViews).
  void EncodeFallbacks();
  /// Whether patch j serves its receivers by their views (every non-diffuse patch).
  bool ServedByViews(std::size_t patch) const;
  /// ViewBegin, Views and ViewCellsOf from the frames (none without): see the file comment.
  void BuildReceiverViews();
  /// Where the view of column position k of column j starts in Views, and ends at the next
  /// position's start (ViewBegin); a position without one starts where it ends.
  std::size_t ViewStart(std::size_t j, std::size_t k) const;
  /// Whether column position k of column j (a receiver of a non-diffuse patch) has a view.
  bool HasView(std::size_t j, std::size_t k) const;
  /// The exitant radiance of directional shot `shot` of patch j averaged over the view of its
  /// column position k, from shot.GridOut at the view's cells (FillViewCells, a grid shot, or
  /// another rank's, ShareDirectionalShots).
  glm::dvec3 ViewRadiance(std::size_t j, std::size_t k, const DirectionalShotData& shot) const;
  /// A strip-pair shot of a patch served by views: shot.GridOut at ViewCellsOf[shooter], as
  /// TowardReceiver gives them.
  void FillViewCells(std::size_t shooter, DirectionalShotData& shot) const;
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
  /// Per column position the entry's filter (SphericalCover::Filter: the panes in front of its
  /// source), when the cover has panes; else empty.
  std::vector<glm::dvec3> ColumnFilter;
  /// `radiance` as column position k's receiver sees it (times the entry's filter).
  glm::dvec3 Filtered(std::size_t k, const glm::dvec3& radiance) const
  {
    return this->ColumnFilter.empty() ? radiance : radiance * this->ColumnFilter[k];
  }
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
  /// A cell of the shooter's hemisphere in a receiver's view (BuildReceiverViews), with its
  /// share of the view (the shares of a view sum to 1).
  struct ViewCell
  {
    uint32_t Cell;
    float Weight;
  };
  /// Per patch the start in ViewBegin of its column's view starts (NoView: not served by
  /// views); ViewBegin holds ColumnEnd - ColumnBegin + 1 starts per such column, the view of a
  /// position being Views[start, next start), by cell. All empty without frames or non-diffuse
  /// patches.
  static constexpr std::size_t NoView = ~std::size_t(0);
  std::vector<std::size_t> ViewColumn;
  std::vector<std::size_t> ViewBegin;
  std::vector<ViewCell> Views;
  /// Per patch served by views: the cells its column's views read, sorted, each once.
  std::vector<std::vector<uint32_t>> ViewCellsOf;
  /// dE_e of the file comment.
  std::vector<glm::dvec3> UnshotIncident;
  /// The directional part of U_j (W, summed over the bands), kept up to date by the shots.
  std::vector<double> DirectionalUnshot;
  /// U_j of every patch, updated with Unshot and DirectionalUnshot: the scan for the brightest
  /// reads one array.
  std::vector<double> Power;
  /// The directional shots of the current batch, one per member (kept from batch to batch for
  /// their buffers).
  std::vector<DirectionalShotData> BatchShots;
  /// Scratch of ShotByGrid: unshot incident radiance per cell and per row the prefix sums of
  /// the exitant radiance over the columns.
  std::vector<glm::dvec3> GridIn;
  std::vector<glm::dvec3> GridPrefix;
  ReflectanceWeights::Scratch ReflectScratch;
  DirectionalMethod Method = DirectionalMethod::Automatic;
  std::vector<HemisphereFrame> Frames;
  /// The ranks, which say this rank's receivers (RankShare::Owns; every patch without a
  /// share), and the hook of a shared propagation (none: serial).
  RankShare Share;
  std::unique_ptr<BatchHook> Hook;
};

} // namespace sphcover

#endif
