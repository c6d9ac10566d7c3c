// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkViewDependentRadiance
 * @brief The radiance of a solution toward an eye at every vertex of an illumination field:
 * the per-vertex evaluation a walk-through in a render view needs (issue 18), done in place on
 * the field's arrays, with no pipeline execution, whenever the camera moves.
 *
 * SetSolution builds the solution's renderer once (vtkSolutionRenderer: the interpolation of
 * paper §5.3.2 with the lamps' direct-light nodes and the directional part of §5.3.1). Update
 * then evaluates, at every vertex of a vtkIlluminationField output (its points, `SurfaceId`
 * and `UV`), the radiance of the front side toward the eye (RadianceRenderer::
 * SurfaceRadianceToward: the emission and diffuse part plus, on a non-diffuse surface, the BRDF
 * toward the eye applied to the incident radiance E of the stencil's characteristic points),
 * writes it to the point array `ViewRadiance` and its display bytes (times 2^ExposureStops,
 * sRGB-encoded, as the field's) to `DisplayRGB`, and marks both modified, so that a mapper
 * showing `DisplayRGB` shows the new view at its next render. On diffuse surfaces the value
 * is the field's `Radiance` itself (the same interpolation), whatever the eye.
 *
 * What a camera move costs (paper §1, §5.3: after the solve every view is cheap). The first
 * Update of a field evaluates every vertex and remembers which vertices depend on the eye
 * (RadianceRenderer::IsViewDependent: a non-diffuse point in the stencil) with what of their
 * radiance does not (RadianceRenderer::TowardTerms: the interpolation stencil, the lamps' direct
 * light); a later Update of the same field (same points, `SurfaceId` and `UV`) for another eye
 * evaluates only those vertices, from their terms, through one directional cache per thread kept
 * across Updates (a lazily filled table of I_dir per (point, eye cell), which does not depend on
 * the eye's position), and re-encodes only their bytes; the same eye and exposure again cost
 * nothing. The values are those of the uncached evaluation whatever the history.
 * vtkViewDependentRadianceRepresentation (plug-in) calls Update from the render view's camera
 * before every render.
 *
 * @warning Vertices are evaluated in parallel (vtkSMPTools); the values do not depend on the
 * number of threads. Not thread-safe itself: one Update at a time.
 */
#ifndef vtkViewDependentRadiance_h
#define vtkViewDependentRadiance_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for the renderer
#include <string> // for CanEvaluate's problem

class vtkAlgorithm;
class vtkDataSet;
class vtkPolyData;
namespace sphcover
{
class RadianceRenderer;
}

class SPHERICALCOVERFILTERS_EXPORT vtkViewDependentRadiance : public vtkObject
{
public:
  static vtkViewDependentRadiance* New();
  vtkTypeMacro(vtkViewDependentRadiance, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the renderer of the illumination (vtkLightPropagationFilter's first output) over
   * the patches (vtkIntervalSubdivisionFilter's first output). False, with the error reported
   * and no solution kept, when they cannot be used or do not come from one solution.
   */
  bool SetSolution(vtkPolyData* illumination, vtkDataSet* patches);

  /**
   * SetSolution from the pipeline that made a field: the nearest vtkIlluminationField at or
   * above `consumer` along first inputs (ParaView's stages in between included), its
   * illumination input and its patches (port 1, or those upstream, vtkCoverPatches). Does
   * nothing and returns true when that solution is the one already set and unchanged. False,
   * with one error, when there is no Illumination Field upstream or its solution is refused.
   * Call after the pipeline has executed (the inputs' data are read, not updated).
   */
  bool SetSolutionFrom(vtkAlgorithm* consumer);

  /// Whether a solution is set.
  bool HasSolution() const;

  /**
   * Writes `ViewRadiance` and `DisplayRGB` of `field` (vtkIlluminationField's output) for an
   * eye at (x, y, z), the exposure in stops as vtkIlluminationField's ExposureStops. False,
   * with the error reported and the field unchanged, without a solution or when the field lacks
   * `SurfaceId` or `UV`.
   */
  bool Update(vtkPolyData* field, double x, double y, double z, double exposureStops);

  /**
   * Whether `field` has what Update needs: `SurfaceId` and a 2-component `UV` point array. False
   * with the problem in one sentence in `problem`.
   */
  static bool CanEvaluate(vtkPolyData* field, std::string& problem);

  /// Seconds the last Update took (its evaluation and the arrays' bytes).
  vtkGetMacro(LastUpdateSeconds, double);

  /// Vertices the last Update evaluated (all on a field's first Update, then the view-dependent
  /// ones when the eye moved, none when nothing changed).
  vtkGetMacro(LastEvaluatedVertices, vtkIdType);

protected:
  vtkViewDependentRadiance();
  ~vtkViewDependentRadiance() override;

  std::unique_ptr<sphcover::RadianceRenderer> Renderer;
  double LastUpdateSeconds = 0.0;
  vtkIdType LastEvaluatedVertices = 0;

  /// What the Updates of one field share (see the class comment).
  struct FieldState;
  std::unique_ptr<FieldState> State;

private:
  vtkViewDependentRadiance(const vtkViewDependentRadiance&) = delete;
  void operator=(const vtkViewDependentRadiance&) = delete;
};

#endif
