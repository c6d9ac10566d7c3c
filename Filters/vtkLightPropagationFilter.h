// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkLightPropagationFilter
 * @brief Progressive propagation of light over the spherical cover until equilibrium (paper
 * §5.1): the brightest characteristic point shoots its unshot light to every point whose
 * hemisphere contains it (the cover's column, §5.2), updating their incident radiance.
 *
 * Input: the cover points of vtkSphericalCoverFilter (with the material arrays `Diffuse`,
 * `Emission`, `MaterialType`, `Specular`, `PhongExponent`, `MaterialId`, the field array
 * `MaterialFiles` for tabulated BRDFs, and the cover in field data). Any other input (another
 * dataset type, points without a cover) is refused with one error.
 *
 * Incident radiance E is stored per region h_ij of the hemispheres (paper §3.1 decision 4),
 * three bands. All four reflectance kinds of paper §3.5 are propagated (Core's
 * LightPropagation and Reflectance): diffuse in closed form, ideal mirror, phong (diffuse part
 * plus energy-conserving lobe) and tabulated BRDFs (Data/scenes/FORMAT.md, "BRDF tables") by
 * precomputed weight tables w(out, in-cell). A table that cannot be read fails the request.
 *
 * Output 0 (vtkPolyData): the cover points with point data `Irradiance` (3, W m^-2),
 * `Radiosity` (3, the Lambertian exitant radiance Le + k_d / pi E, W m^-2 sr^-1: all of it for
 * a diffuse point, the diffuse part of a phong point, Le for mirror and tabulated points),
 * `Brightness` (3, the measure of paper §5: the flux density the point emits and reflects into
 * its whole hemisphere, W m^-2; pi times the exitant radiance for a diffuse point; for the
 * others pi Le + sum over its regions of E times the region's albedo-weighted projected solid
 * angle, i.e. (k_d + k_s) int E cos dw for phong) and, in field data,
 * `IncidentRadiance` (3 per entry of the cover: the incident radiance of every region h_ij,
 * in the cover's entry order), `EnergyBalance` (emitted, absorbed W per band),
 * `PropagationStatistics` (Shots) and the solution's figures (Core's
 * SolutionFigures, what `sphcover solve --report` prints): `SolutionStatistics`
 * (CharacteristicPoints, Strips, RelativeImbalance) and, per entry of `SurfaceNames`,
 * `SurfaceArea`, `SurfaceMeanIrradiance` (3), `SurfaceMeanExitantRadiance` (3, of Radiosity)
 * and `SurfaceFormFactors` (one component per name: row a, from surface a). The figures need
 * the points' `SurfaceNameId` and the field array `SurfaceNames` (every reader's scene has
 * them); without them they are left out, and an id that is not an index of the names is an
 * error.
 *
 * Output 1 (vtkTable): the convergence history, `Shot`, `Shooter`, `MaxChange` (the power
 * shot relative to the emitted power), `UnshotEnergy` (W), `Seconds`.
 *
 * MaximumShots stops early, so a ParaView user can watch the light spread.
 *
 * Pieces (vtkScenePieces.h): the whole scene is piece 0. Asked for a piece > 0 with an empty
 * input (the readers' other pieces, as under `mpiexec -n N pvbatch --symmetric`), the filter
 * produces empty outputs without a message; with a non-empty input there, it refuses with an
 * error (a piece of the scene would give a wrong illumination). An empty input on piece 0 is an
 * error, as in serial.
 *
 * Processes (Controller, by default the global controller): when every one of K > 1 processes
 * holds the whole cover (a VTK pipeline whose every rank holds piece 0), each rank keeps the
 * rows of its receivers r, r + K, ... (dealt round the ranks one by one, so that each rank has
 * a K-th of every surface and of each batch's shooters); when rank 0 holds the cover and the
 * others empty pieces (pvbatch, pvserver, `mpiexec sphcover`), rank 0 deals each rank those
 * rows (the other ranks never hold the whole cover); when every rank holds its share of the
 * cover (the field array `CoverRowShare` of vtkSphericalCoverFilter with GatherRows off, as
 * `mpiexec sphcover` builds it), each propagates its rows as they are, no rank holding the
 * whole cover until rank 0 gathers it for the solution once the propagation's state is gone.
 * Either way the K ranks then balance the
 * exchange (ExchangeBalance under a share: each its own rows, the factors the whole cover's bit
 * for bit) and propagate together (sphcover::SharePropagation), and the results are
 * gathered: on every rank in the first case, on rank 0 alone in the others (it writes the
 * solution, the others keep empty outputs, as above), or kept in pieces (GatherSolution off:
 * each rank its own rows' regions, below). So the outputs are the serial ones (the
 * per-patch values and the regions' incident radiances bit for bit; the energy sums up to the
 * order of addition). FixedOrder runs on each process alone, as described above. Every process
 * must update the filter together, as for vtkSphericalCoverFilter.
 */
#ifndef vtkLightPropagationFilter_h
#define vtkLightPropagationFilter_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for std::string
#include <vector> // for std::vector

class vtkMultiProcessController;
class vtkTable;

class SPHERICALCOVERFILTERS_EXPORT vtkLightPropagationFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkLightPropagationFilter* New();
  vtkTypeMacro(vtkLightPropagationFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ShootingOrders
  {
    BRIGHTEST_FIRST = 0,
    FIXED_ORDER = 1
  };

  ///@{
  /**
   * Equilibrium is reached when the unshot power (all points together) is below this fraction
   * of the emitted power. Default is 1e-5.
   */
  vtkSetClampMacro(ConvergenceTolerance, double, 0.0, 1.0);
  vtkGetMacro(ConvergenceTolerance, double);
  ///@}

  ///@{
  /** Stop after this many shots (0: until equilibrium). Default is 0. */
  vtkSetClampMacro(MaximumShots, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumShots, int);
  ///@}

  ///@{
  /**
   * Which point shoots next: BRIGHTEST_FIRST (the largest unshot power, paper §5) or
   * FIXED_ORDER (the points in turn). Default is BRIGHTEST_FIRST.
   */
  vtkSetClampMacro(ShootingOrder, int, BRIGHTEST_FIRST, FIXED_ORDER);
  vtkGetMacro(ShootingOrder, int);
  ///@}

  ///@{
  /**
   * Most points shot at a time by BRIGHTEST_FIRST: the brightest and the next ones with at least
   * half its unshot power, all taken before any is delivered (Core's LightPropagation,
   * "Batches"). Under MPI the ranks reflect a batch's mirror and glossy shooters at the same
   * time and exchange once per batch; the result depends on the batch, never on the ranks.
   * 1: the paper's order, one at a time. Default is 16.
   */
  vtkSetClampMacro(ShotBatch, int, 1, 4096);
  vtkGetMacro(ShotBatch, int);
  ///@}

  ///@{
  /**
   * Balance the cover's exchange before propagating (Core's ExchangeBalance): the radiance a
   * shot delivers through region h_ij is scaled by x_i y_j so that every point still gathers
   * exactly its covered projected solid angle (row sums) and every point delivers exactly what
   * its own hemisphere sends into the scene (column sums). A point-sampled cover is not exactly
   * reciprocal; balanced, the equilibrium of a closed scene conserves energy. Off: the cover's
   * exchange as built (the paper's method as such). Default is on.
   */
  vtkSetMacro(BalanceExchanges, bool);
  vtkGetMacro(BalanceExchanges, bool);
  vtkBooleanMacro(BalanceExchanges, bool);
  ///@}

  ///@{
  /**
   * Largest memory the propagation may take, in MiB (its state per region and the weight tables
   * of non-diffuse materials, which grow as ThetaBins^2 PhiBins); a larger estimate, made before
   * anything is allocated, is refused with an error. Default is 8192.
   */
  vtkSetClampMacro(MemoryLimit, double, 0.0, 1.0e9);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /**
   * Whether the solution is gathered when K > 1 ranks propagate together. On: rank 0's output
   * holds the whole solution (the whole cover and every region's IncidentRadiance; in a
   * pipeline whose every rank holds the whole cover, every rank's), the other ranks' outputs
   * are empty. Off: the solution is kept in pieces and no rank ever holds the whole cover:
   * every rank's output holds every point with the per-point arrays (the serial values) and
   * only its own rows (receivers r, r + K, ...) and their regions' IncidentRadiance, marked by
   * the field array `CoverRowShare` = (r, K) as vtkSphericalCoverFilter marks a share; rank 0's
   * holds the solution's figures too (summed from the ranks' rows, the serial ones bit for
   * bit). Filters that read a whole cover refuse such a piece; vtkSolutionPieces joins the K
   * pieces into the whole solution. Default is on; ignored on one process.
   */
  vtkSetMacro(GatherSolution, bool);
  vtkGetMacro(GatherSolution, bool);
  vtkBooleanMacro(GatherSolution, bool);
  ///@}

  /// Shots of the last update.
  vtkGetMacro(Shots, int);

  /**
   * When the last update propagated on K > 1 ranks: per rank, in rank order, 4 values: its
   * receivers, the entries of its rows, the estimated bytes of its propagation state
   * (LightPropagation::EstimateBytes of its rows) and the seconds of its shooting. Empty
   * otherwise. Measurements, not part of the output.
   */
  const std::vector<double>& GetRankFigures() const { return this->RankFigures; }

  /// The number of processes the last update propagated on together (1: this one alone).
  vtkGetMacro(RankCount, int);

  ///@{
  /**
   * The processes that propagate together (see above); nullptr or one process: this process
   * alone. Default is vtkMultiProcessController::GetGlobalController() at construction.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /**
   * Computes the solution's figures (see above) from the arrays of `illumination`, this
   * filter's output 0 or one read back from a file, and stores them in its field data.
   * Returns "" or the problem (then nothing is stored).
   */
  static std::string AddSolutionFigures(vtkPolyData* illumination);

protected:
  vtkLightPropagationFilter();
  ~vtkLightPropagationFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// Where the cover is when the ranks propagate together.
  enum class CoverHeld
  {
    EveryRank, ///< every rank's input holds the whole cover (or one process)
    FirstRank, ///< rank 0's; the others' `input` is its points without the cover
    Shares     ///< every rank's input holds its share (CoverRowShare)
  };
  /// RequestData's work: alone (`controller` null), or together with the controller's ranks,
  /// the cover `held` as said.
  int PropagateOnRanks(vtkMultiProcessController* controller,
    vtkPolyData* input,
    vtkPolyData* output,
    vtkTable* history,
    CoverHeld held = CoverHeld::EveryRank);
  /// RequestData's work when not every rank holds the cover: rank 0's (piece 0) propagated by
  /// every rank together, `role` (vtkScenePieces::Role) this rank's piece.
  int PropagateFromFirst(vtkMultiProcessController* controller,
    int role,
    vtkInformationVector* outputVector,
    vtkPolyData* input,
    vtkPolyData* output,
    vtkTable* history);

  double ConvergenceTolerance = 1e-5;
  int MaximumShots = 0;
  int ShootingOrder = BRIGHTEST_FIRST;
  int ShotBatch = 16;
  bool BalanceExchanges = true;
  bool GatherSolution = true;
  double MemoryLimit = 8192.0;
  int Shots = 0;
  vtkMultiProcessController* Controller = nullptr;
  std::vector<double> RankFigures;
  int RankCount = 1;

private:
  vtkLightPropagationFilter(const vtkLightPropagationFilter&) = delete;
  void operator=(const vtkLightPropagationFilter&) = delete;
};

#endif
