// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkIntervalSubdivisionFilter
 * @brief The environment-dependent subdivision of paper §4: the patch list Q and its
 * characteristic points, by interval range tests over whole patches.
 *
 * Input: surfaces as vtkPatchSceneReader writes them (any dataset of Bezier quadrilaterals,
 * quads and triangles with the material cell arrays of Documentation/Pipeline.md#reader).
 *
 * Every pair (characteristic point P_i, patch Q_j) is tested against the criteria of paper
 * §4.2: self-shadowing (§4.2.1), hemispherical containment (§4.2.2), spherical shape (§4.2.3:
 * distance form for diffuse sources, normal form for the others) and characterisability
 * (§4.2.4), each with its own switch and tolerance. A patch that fails is split in three along
 * u or v (§4.3 note 3), exactly, until the criteria hold, MaxLevel is reached, or the patch
 * projects to about one cell of the ThetaBins x PhiBins grid (§4.3 note 2). Pairs fully below
 * the horizon or back-facing are classified, not split. The range estimates use Bernstein
 * (convex hull) bounds or natural interval arithmetic (RangeMethod). See
 * Core/subdivision/SubdivisionCriteria.h for the exact tests and tolerances.
 *
 * Settings of the scene: MaxLevel, ThetaBins, PhiBins and the four tolerances default to
 * SCENE_SETTING (-1), which takes the input's field data `SceneSettings` (max_level,
 * theta_bins, phi_bins, and tolerance for all four criteria), as the command line does, or
 * the scene file's defaults (5, 32, 128, 0.02) when the input has none. Any other value is the
 * user's and wins (a flag "was Set called" would not do: ParaView sets every property).
 *
 * Output 0 (vtkUnstructuredGrid): one cell per patch, its exact geometry (Bezier
 * quadrilateral, quad or triangle), cell data `SurfaceId`, `PatchId`, `Level`, `UVRange`
 * (u0, u1, v0, v1), `Area`, `SplitReason` (the criterion that caused the last split; names in
 * the field array `SplitReasonNames`), and the material arrays of the input. Field data: the
 * input's, plus `SubdivisionStatistics` (pair tests, sweeps) and `SubdivisionSettings` (the
 * values used; vtkSphericalCoverFilter takes its grid from them).
 *
 * Output 1 (vtkPolyData): the characteristic points, one vertex each, at the parametric centre
 * of each patch, with point data `Normals`, `PatchId`, `SurfaceId`, `UV`, `Area`, `Level`.
 *
 * @warning The work is parallel over receivers (vtkSMPTools); the result does not depend on the
 * number of threads.
 *
 * Pieces (vtkScenePieces.h): the whole scene is piece 0. Asked for a piece > 0 with an empty
 * input (the readers' other pieces in a parallel pipeline), the filter
 * produces empty outputs without a message; with a non-empty input there, it refuses with an
 * error (a piece of the scene would give a wrong illumination). An empty input on piece 0 is an
 * error, as in serial.
 */
#ifndef vtkIntervalSubdivisionFilter_h
#define vtkIntervalSubdivisionFilter_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class SPHERICALCOVERFILTERS_EXPORT vtkIntervalSubdivisionFilter
  : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIntervalSubdivisionFilter* New();
  vtkTypeMacro(vtkIntervalSubdivisionFilter, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The default of the scene's settings: the input's `SceneSettings` value is used.
  enum
  {
    SCENE_SETTING = -1
  };

  enum RangeMethods
  {
    BERNSTEIN = 0,
    NATURAL_INTERVAL = 1
  };

  ///@{
  /**
   * How ranges of the criteria's polynomials are bounded: Bernstein (convex-hull) bounds of the
   * exact sub-patch, or natural interval evaluation. Default is BERNSTEIN.
   */
  vtkSetClampMacro(RangeMethod, int, BERNSTEIN, NATURAL_INTERVAL);
  vtkGetMacro(RangeMethod, int);
  void SetRangeMethodToBernstein() { this->SetRangeMethod(BERNSTEIN); }
  void SetRangeMethodToNaturalInterval() { this->SetRangeMethod(NATURAL_INTERVAL); }
  ///@}

  ///@{
  /**
   * The deepest subdivision level (ternary splits from a surface), 0 to 32 (deeper patches are
   * narrower than the double precision of the parameter domain; another value fails the
   * request). Default is SCENE_SETTING: the scene's max_level (5 without one).
   */
  vtkSetMacro(MaxLevel, int);
  vtkGetMacro(MaxLevel, int);
  ///@}

  ///@{
  /**
   * No patch is split once its bounding box's diagonal is at most this fraction of the scene's
   * (0: no such limit; in [0, 1), another value fails the request): with a deep MaxLevel the
   * points go where the surfaces are large, instead of the same number to every surface.
   * Default is SCENE_SETTING: the scene's min_patch_size (0 without one).
   */
  vtkSetMacro(MinPatchSize, double);
  vtkGetMacro(MinPatchSize, double);
  ///@}

  ///@{
  /**
   * The budget of the subdivision: it fails with an error, before splitting, when a sweep would
   * make more than MaximumPatches patches or hold more than MemoryLimit MiB of patches (every
   * later stage grows with the patch count), and before or during a sweep when the pair tests,
   * its time, would exceed MaximumPairTests (1e9: 10 to 25 minutes on two threads). Defaults
   * are 1000000, 8192 and 1e9.
   */
  vtkSetClampMacro(MaximumPatches, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaximumPatches, int);
  vtkSetClampMacro(MemoryLimit, double, 0.0, 1.0e9);
  vtkGetMacro(MemoryLimit, double);
  vtkSetClampMacro(MaximumPairTests, double, 1.0, 1.0e18);
  vtkGetMacro(MaximumPairTests, double);
  ///@}

  ///@{
  /**
   * The (theta, phi) grid of the spherical cover: no patch is split once it projects to about
   * one cell. Defaults are SCENE_SETTING: the scene's theta_bins and phi_bins (32 and 128
   * without them).
   */
  vtkSetMacro(ThetaBins, int);
  vtkGetMacro(ThetaBins, int);
  vtkSetMacro(PhiBins, int);
  vtkGetMacro(PhiBins, int);
  ///@}

  ///@{
  /**
   * Self-shadowing criterion (paper §4.2.1): split a patch with a silhouette as seen from a
   * characteristic point. Tolerance in units of |N| d (a cosine). Defaults are on and
   * SCENE_SETTING (the scene's tolerance, 0.02 without one).
   */
  vtkSetMacro(SelfShadowing, bool);
  vtkGetMacro(SelfShadowing, bool);
  vtkBooleanMacro(SelfShadowing, bool);
  vtkSetMacro(SelfShadowingTolerance, double);
  vtkGetMacro(SelfShadowingTolerance, double);
  ///@}

  ///@{
  /**
   * Hemispherical containment criterion (paper §4.2.2): split a patch that straddles the
   * horizon of a characteristic point. Tolerance relative to the distance. Defaults are on and
   * SCENE_SETTING (the scene's tolerance, 0.02 without one).
   */
  vtkSetMacro(HemisphericalContainment, bool);
  vtkGetMacro(HemisphericalContainment, bool);
  vtkBooleanMacro(HemisphericalContainment, bool);
  vtkSetMacro(HemisphericalContainmentTolerance, double);
  vtkGetMacro(HemisphericalContainmentTolerance, double);
  ///@}

  ///@{
  /**
   * Spherical shape criterion (paper §4.2.3): split a source patch whose distance (diffuse) or
   * projected normal (other materials) varies by more than the relative tolerance as seen from
   * a characteristic point. Defaults are on and SCENE_SETTING (the scene's tolerance, 0.02
   * without one).
   */
  vtkSetMacro(SphericalShape, bool);
  vtkGetMacro(SphericalShape, bool);
  vtkBooleanMacro(SphericalShape, bool);
  vtkSetMacro(SphericalShapeTolerance, double);
  vtkGetMacro(SphericalShapeTolerance, double);
  ///@}

  ///@{
  /**
   * Characterisability criterion (paper §4.2.4): split a receiving patch whose normal varies
   * by more than the relative tolerance with respect to the direction to a source point.
   * Defaults are on and SCENE_SETTING (the scene's tolerance, 0.02 without one).
   */
  vtkSetMacro(Characterisability, bool);
  vtkGetMacro(Characterisability, bool);
  vtkBooleanMacro(Characterisability, bool);
  vtkSetMacro(CharacterisabilityTolerance, double);
  vtkGetMacro(CharacterisabilityTolerance, double);
  ///@}

  /// Sets all four tolerances (the scene file's single "tolerance").
  void SetTolerance(double tolerance);

  /// Pair tests of the last update (pairs whose criteria were range-tested).
  vtkGetMacro(PairTests, vtkIdType);

protected:
  vtkIntervalSubdivisionFilter();
  ~vtkIntervalSubdivisionFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int RangeMethod = BERNSTEIN;
  int MaxLevel = SCENE_SETTING;
  double MinPatchSize = SCENE_SETTING;
  int MaximumPatches = 1000000;
  double MemoryLimit = 8192.0;
  double MaximumPairTests = 1.0e9;
  int ThetaBins = SCENE_SETTING;
  int PhiBins = SCENE_SETTING;
  bool SelfShadowing = true;
  double SelfShadowingTolerance = SCENE_SETTING;
  bool HemisphericalContainment = true;
  double HemisphericalContainmentTolerance = SCENE_SETTING;
  bool SphericalShape = true;
  double SphericalShapeTolerance = SCENE_SETTING;
  bool Characterisability = true;
  double CharacterisabilityTolerance = SCENE_SETTING;
  vtkIdType PairTests = 0;

private:
  vtkIntervalSubdivisionFilter(const vtkIntervalSubdivisionFilter&) = delete;
  void operator=(const vtkIntervalSubdivisionFilter&) = delete;
};

#endif
