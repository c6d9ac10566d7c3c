// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSphericalCoverFilter
 * @brief The spherical cover of paper §3.3: for every characteristic point P_i the hemisphere
 * H_i as a (theta, phi) grid filled as an R-buffer (§4.2.5), stored as strips per source patch.
 *
 * Input: the patches (vtkIntervalSubdivisionFilter's first output, or any surface dataset,
 * then one patch per surface). Each patch's characteristic point is its parametric centre.
 *
 * The R-buffer of H_i is filled either by projecting every candidate patch into (theta, phi)
 * with a depth test, as the paper does, or by casting rays through the cells with Embree
 * against a tessellation of the exact patches; several samples per cell classify each cell
 * by coverage. Patches fully below the tangent plane of P_i are skipped before any work.
 *
 * The grid: ThetaBins and PhiBins default to SCENE_SETTING (-1), which takes the grid the
 * patches were subdivided for (the input's field data `SubdivisionSettings`), else the scene's
 * (`SceneSettings`), else 32 x 128; any other value is the user's and wins. The grid used is
 * the output's `CoverGrid`.
 *
 * Output 0 (vtkPolyData): the characteristic points with point data `Normals`, `Tangents`
 * (phi = 0), `Area`, `PatchId`, `SurfaceId`, `CoveredProjectedSolidAngle` (pi inside a closed
 * scene), `VisibleSources` and the material arrays of the patches; field data: the input's
 * and the cover itself (vtkSphericalCoverArrays), which VTK's XML writers save bit for bit.
 *
 * Output 1 (vtkTable): the strips, `Receiver`, `Source`, `Theta` (row), `PhiBegin`, `PhiEnd`
 * (columns, end exclusive), `R` (mean distance); empty when GenerateStripTable is off.
 *
 * Before the cover is built, the patches may be refined (Refinement, sphcover::CoverRefinement):
 * the points are then those of the refined patches, each with the cell data of the input patch
 * it was cut from (UVRange, Level and SplitReason its own), `PatchId` numbering the refined
 * patches and `InputPatchId` the input cell it was cut from. What of paper §4.3 is done: the
 * R-buffer criterion of §4.2.5 from the receiver side (patches straddling an enclosure
 * boundary, the default), Step 3 from the source side (REFINEMENT_FULL: substantially hidden
 * or disconnected images, ternary splits within the level limit of note 2, rounds until no
 * patch asks), and Step 5's replacement of a split patch by all its pieces. Not done: the
 * interpolation of hemispheres at new characteristic points (§3.4, Step 5, note 5); every
 * refined patch gets its own R-buffer, which keeps every hemisphere exact (covered once, pi in
 * a closed scene) where interpolated rows would not be.
 *
 * Before building, the memory the cover needs is estimated; above MemoryLimit (MiB) the
 * filter refuses with an error.
 *
 * @warning Rows are built in parallel (vtkSMPTools); the result does not depend on the number
 * of threads.
 *
 * One process: vtkPSphericalCoverFilter (Parallel/) builds the rows on several.
 *
 * Pieces (vtkScenePieces.h): the whole scene is piece 0. Asked for a piece > 0 with an empty
 * input (the readers' other pieces in a parallel pipeline), the filter
 * produces empty outputs without a message; with a non-empty input there, it refuses with an
 * error (a piece of the scene would give a wrong illumination). An empty input on piece 0 is an
 * error, as in serial.
 */
#ifndef vtkSphericalCoverFilter_h
#define vtkSphericalCoverFilter_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class SPHERICALCOVERFILTERS_EXPORT vtkSphericalCoverFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkSphericalCoverFilter* New();
  vtkTypeMacro(vtkSphericalCoverFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The default of ThetaBins and PhiBins: the grid of the input's settings is used.
  enum
  {
    SCENE_SETTING = -1
  };

  enum FillMethods
  {
    PROJECTION = 0,
    RAY_CASTING = 1
  };

  ///@{
  /**
   * Cells of the hemisphere grid in theta (polar, 1 to 4096) and phi (azimuth, 1 to 16384;
   * 0 fails the request), or SCENE_SETTING, the default: the input's (see above).
   */
  vtkSetClampMacro(ThetaBins, int, SCENE_SETTING, 4096);
  vtkGetMacro(ThetaBins, int);
  vtkSetClampMacro(PhiBins, int, SCENE_SETTING, 16384);
  vtkGetMacro(PhiBins, int);
  ///@}

  ///@{
  /**
   * Samples per cell along theta and along phi (SamplesPerCell^2 in all): cells are classified
   * by coverage. Default is 3.
   */
  vtkSetClampMacro(SamplesPerCell, int, 1, 16);
  vtkGetMacro(SamplesPerCell, int);
  ///@}

  ///@{
  /** How the R-buffer is filled: PROJECTION (the paper's) or RAY_CASTING (Embree, with
   * adaptive sampling: the same error on the Cornell box at about a third of the cover's
   * time, Documentation/notes/time-to-accuracy.md). Default is RAY_CASTING. */
  vtkSetClampMacro(FillMethod, int, PROJECTION, RAY_CASTING);
  vtkGetMacro(FillMethod, int);
  void SetFillMethodToProjection() { this->SetFillMethod(PROJECTION); }
  void SetFillMethodToRayCasting() { this->SetFillMethod(RAY_CASTING); }
  ///@}

  ///@{
  /**
   * Measure the regions of the scene's lamps (bright emitters, Core's BrightEmitters.h) on the
   * lamp instead of in cells (SphericalCover.h, "Measured regions"; ray casting only): each
   * point's direct light is then integrated over the lamp with one shadow ray per node, not
   * counted to about 10 % in cells. Off: every region is its cells' measure (the paper's).
   * Default is on.
   */
  vtkSetMacro(MeasureLamps, bool);
  vtkGetMacro(MeasureLamps, bool);
  vtkBooleanMacro(MeasureLamps, bool);
  ///@}

  ///@{
  /**
   * Interpolate the hemispheres of the points that lie between two neighbours on a flat
   * surface from theirs, row by row, casting rays only where the neighbours' interpolations
   * disagree (paper §3.4 and §4.3 note 5; Core's HemisphereInterpolation.h; ray casting only).
   * Off (the default): every hemisphere is computed (Documentation/notes/
   * interpolated-hemispheres.md says why it is not the default yet).
   */
  vtkSetMacro(InterpolateHemispheres, bool);
  vtkGetMacro(InterpolateHemispheres, bool);
  vtkBooleanMacro(InterpolateHemispheres, bool);
  ///@}

  ///@{
  /**
   * Nodes along each side of every patch at which the lamps' direct irradiance (and its first
   * bounce, DirectBounceRays) is computed
   * (Core's DirectIrradiance.h: the output's point array DirectIrradiance): the render and the
   * illumination field then interpolate the sharp direct light from these nodes and only the
   * smooth rest between the characteristic points. Odd, 3 to 33; 0: none (every point's
   * light interpolated alike, the paper's §5.3.2). Scenes without a bright emitter get none.
   * Default is 9, of which only the 3 x 3 (a patch's corners, edge midpoints and centre) are
   * computed where the light is bilinear (DirectNodesTolerance).
   */
  vtkSetMacro(DirectIrradianceNodes, int);
  vtkGetMacro(DirectIrradianceNodes, int);
  ///@}

  ///@{
  /**
   * Rays per side (g x g in all, cosine-weighted) with which the first bounce of the lamps'
   * direct light is gathered at every node of DirectIrradianceNodes and added to it (Core's
   * DirectIrradiance.h): near concave edges and contact shadows the once-reflected light
   * changes below a patch too. 0 to 256; 0: the direct light only. Default is 32.
   */
  vtkSetClampMacro(DirectBounceRays, int, 0, 256);
  vtkGetMacro(DirectBounceRays, int);
  ///@}

  ///@{
  /**
   * Where the nodes beyond a patch's 3 x 3 are computed (Core's DirectIrradianceOptions::
   * RefinementTolerance): at patches whose 3 x 3 direct light departs from the bilinear
   * interpolation of their corners by more than this fraction of the larger of the patch's
   * brightest node and the scene's mean (a shadow's edge or a patch of light crosses them);
   * elsewhere the finer nodes are interpolated. 0: at every patch. Default is 0.05.
   */
  vtkSetClampMacro(DirectNodesTolerance, double, 0.0, 1.0);
  vtkGetMacro(DirectNodesTolerance, double);
  ///@}

  ///@{
  /**
   * Back sides of surfaces hide what lies behind them (opaque surfaces). Off: the paper's
   * culling of back-facing patches, which makes them transparent. Default is on.
   */
  vtkSetMacro(BackFacesOcclude, bool);
  vtkGetMacro(BackFacesOcclude, bool);
  vtkBooleanMacro(BackFacesOcclude, bool);
  ///@}

  ///@{
  /**
   * Fill output 1, the table of every strip (for ParaView's spreadsheet view). It is as large
   * as the cover's strips again (24 bytes a strip: 69 MB for the teapot room at max_level=3)
   * and stays in memory with the pipeline's outputs: a pipeline that only propagates and renders
   * (the sphcover command line) turns it off. Default is on.
   */
  vtkSetMacro(GenerateStripTable, bool);
  vtkGetMacro(GenerateStripTable, bool);
  vtkBooleanMacro(GenerateStripTable, bool);
  ///@}

  enum RefinementModes
  {
    REFINEMENT_OFF = 0,
    /// Receiver side only: patches straddling an enclosure boundary, and patches across the
    /// horizon of a nearby surface (CoverRefinement.h).
    REFINEMENT_ENCLOSURES = 1,
    /// Enclosure boundaries, then paper §4.3 Step 3 from the source side (every hemisphere
    /// analysed once per level; several cover builds' worth of time).
    REFINEMENT_FULL = 2
  };

  ///@{
  /**
   * The R-buffer refinement of paper §4.2.5 / §4.3 Steps 3 and 5 before the cover is built
   * (sphcover::CoverRefinement): REFINEMENT_OFF, REFINEMENT_ENCLOSURES (patches part of which
   * lies inside a closed solid or under a surface turned away, such as the floor along a
   * block's footprint, or within one patch width of such a boundary, are split; costs a few
   * hundred rays per patch; and patches across which, or within one patch width of which, the
   * plane of a surface in front of them within two patch sizes passes, so that part of them
   * sees that surface and part does not, such as the red wall along the plane of a block's top;
   * box and plane tests) or REFINEMENT_FULL (then also
   * patches substantially hidden or disconnected in some hemisphere). The output then has one
   * point per refined patch. Default is REFINEMENT_ENCLOSURES.
   */
  vtkSetClampMacro(Refinement, int, REFINEMENT_OFF, REFINEMENT_FULL);
  vtkGetMacro(Refinement, int);
  ///@}

  ///@{
  /**
   * How many ternary levels the refinement may split below the deepest input patch (paper §4.3
   * note 2's limit). Default is 3.
   */
  vtkSetClampMacro(RefinementLevels, int, 0, 12);
  vtkGetMacro(RefinementLevels, int);
  ///@}

  ///@{
  /** Largest memory the cover may take, in MiB; a bigger estimate is refused. Default 8192. */
  vtkSetClampMacro(MemoryLimit, double, 0.0, 1.0e9);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  /**
   * Wall seconds of the last execution's stages on this process: the R-buffer refinement, the
   * rows of the cover and the direct light's nodes. Measurements, not
   * part of the output (which stays the same from run to run).
   */
  const double* GetStageSeconds() const { return this->StageSeconds; }
  /// For RequestData's steps; does not modify the filter.
  void RecordStageSeconds(int stage, double seconds) { this->StageSeconds[stage] = seconds; }

protected:
  vtkSphericalCoverFilter();
  ~vtkSphericalCoverFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int ThetaBins = SCENE_SETTING;
  int PhiBins = SCENE_SETTING;
  int SamplesPerCell = 3;
  int FillMethod = RAY_CASTING;
  bool BackFacesOcclude = true;
  bool GenerateStripTable = true;
  bool MeasureLamps = true;
  bool InterpolateHemispheres = false;
  int DirectIrradianceNodes = 9;
  int DirectBounceRays = 32;
  double DirectNodesTolerance = 0.05;
  double MemoryLimit = 8192.0;
  int Refinement = REFINEMENT_ENCLOSURES;
  int RefinementLevels = 3;
  double StageSeconds[3] = { 0.0, 0.0, 0.0 };

private:
  vtkSphericalCoverFilter(const vtkSphericalCoverFilter&) = delete;
  void operator=(const vtkSphericalCoverFilter&) = delete;
};

#endif
