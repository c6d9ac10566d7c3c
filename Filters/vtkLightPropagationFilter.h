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
 * and the form factors of the surfaces that see each other (Core's SurfaceFormFactors, sparse:
 * a scene of thousands of named parts has millions of pairs, few of which see each other), one
 * tuple per pair by the first surface then the second: `SurfaceFormFactorPairs` (2 ints, From
 * and To, indices of `SurfaceNames`) and `SurfaceFormFactorValues` (F). The figures need
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
 * input (the readers' other pieces in a parallel pipeline), the filter
 * produces empty outputs without a message; with a non-empty input there, it refuses with an
 * error (a piece of the scene would give a wrong illumination). An empty input on piece 0 is an
 * error, as in serial.
 *
 * One process: vtkPLightPropagationFilter (Parallel/) propagates on several together.
 */
#ifndef vtkLightPropagationFilter_h
#define vtkLightPropagationFilter_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for std::string

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
   * "Batches").
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

  /// Shots of the last update.
  vtkGetMacro(Shots, int);

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

  double ConvergenceTolerance = 1e-5;
  int MaximumShots = 0;
  int ShootingOrder = BRIGHTEST_FIRST;
  int ShotBatch = 16;
  bool BalanceExchanges = true;
  double MemoryLimit = 8192.0;
  int Shots = 0;

private:
  vtkLightPropagationFilter(const vtkLightPropagationFilter&) = delete;
  void operator=(const vtkLightPropagationFilter&) = delete;
};

#endif
