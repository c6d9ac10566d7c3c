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
 * writes it to the point array `ViewRadiance` and its display bytes (times 2^Exposure,
 * sRGB-encoded, as the field's) to `DisplayRGB`, and marks both modified, so that a mapper
 * showing `DisplayRGB` shows the new view at its next render. On diffuse surfaces the value
 * is the field's `Radiance` itself (the same interpolation), whatever the eye.
 *
 * Status (issue 18, part b): the evaluation only. A ParaView representation or mapper that calls
 * Update from the render view's camera before each render is not written yet.
 *
 * @warning Vertices are evaluated in parallel (vtkSMPTools); the values do not depend on the
 * number of threads.
 */
#ifndef vtkViewDependentRadiance_h
#define vtkViewDependentRadiance_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for the renderer

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
   * Writes `ViewRadiance` and `DisplayRGB` of `field` (vtkIlluminationField's output) for an
   * eye at (x, y, z), exposure in stops as vtkIlluminationField's Exposure. False, with the
   * error reported and the field unchanged, without a solution or when the field lacks
   * `SurfaceId` or `UV`.
   */
  bool Update(vtkPolyData* field, double x, double y, double z, double exposure);

  /// Seconds the last Update took (its evaluation and the arrays' bytes).
  vtkGetMacro(LastUpdateSeconds, double);

protected:
  vtkViewDependentRadiance();
  ~vtkViewDependentRadiance() override;

  std::unique_ptr<sphcover::RadianceRenderer> Renderer;
  double LastUpdateSeconds = 0.0;

private:
  vtkViewDependentRadiance(const vtkViewDependentRadiance&) = delete;
  void operator=(const vtkViewDependentRadiance&) = delete;
};

#endif
