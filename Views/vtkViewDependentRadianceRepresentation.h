// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkViewDependentRadianceRepresentation
 * @brief ParaView's "View-Dependent Radiance" representation of an Illumination Field: the
 * surfaces show the solution's radiance toward the render view's camera, mirrors and glossy
 * surfaces included, and follow every camera move without a pipeline execution (issue 18; the
 * paper's point, §1 and §5.3, that after the solve every view is cheap).
 *
 * A Surface representation (vtkGeometryRepresentationWithFaces) whose mapper is a
 * vtkViewDependentRadianceMapper. After the pipeline executes (RequestData), it checks that the
 * data shown is an Illumination Field output (`SurfaceId`, `UV`) and finds the solution the field
 * was made from (vtkViewDependentRadiance::SetSolutionFrom: the field's illumination and
 * patches); the mapper then evaluates, before each render, the radiance toward the camera's
 * position at the field's vertices (paper §5.3.1, interpolated as §5.3.2) and draws it as
 * `DisplayRGB` with the field's tone map (2^ExposureStops, clamped, sRGB), lighting off, whatever
 * the colouring and lighting properties say. On diffuse surfaces the colours are the Illumination
 * Field's own `DisplayRGB` for the same ExposureStops.
 *
 * Unusable input (not an Illumination Field output, or no solution upstream): one error per
 * pipeline update, and the data drawn as the Surface representation would with `DisplayRGB`.
 *
 * Always drawn at full resolution: the LOD geometry (decimated, its `SurfaceId` and `UV`
 * averaged) cannot be evaluated, so LOD is suppressed whatever SuppressLOD says.
 *
 * @warning The solution is read where the pipeline runs: in the built-in session and pvbatch
 * (and on a pvserver that renders). When a client renders geometry delivered from a server, the
 * client has no solution and shows the field's own (diffuse) colours.
 */
#ifndef vtkViewDependentRadianceRepresentation_h
#define vtkViewDependentRadianceRepresentation_h

#include "SphericalCoverViewsModule.h" // for export macro
#include "vtkGeometryRepresentationWithFaces.h"
#include "vtkNew.h"                   // for the evaluator
#include "vtkViewDependentRadiance.h" // for vtkNew

class SPHERICALCOVERVIEWS_EXPORT vtkViewDependentRadianceRepresentation
  : public vtkGeometryRepresentationWithFaces
{
public:
  static vtkViewDependentRadianceRepresentation* New();
  vtkTypeMacro(vtkViewDependentRadianceRepresentation, vtkGeometryRepresentationWithFaces);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Exposure in photographic stops, as vtkIlluminationField's ExposureStops: the radiance is
   * scaled by 2^ExposureStops before the sRGB encoding. -20 to 20. Default is 0.
   */
  void SetExposureStops(double stops);
  double GetExposureStops() const;
  ///@}

  /// LOD stays suppressed (see the class comment); the argument is ignored.
  void SetSuppressLOD(bool suppress) override;

  ///@{
  /// Ignored: the colours are the light already, drawn unlit (ambient 1, diffuse and specular 0).
  void SetAmbient(double) override {}
  void SetDiffuse(double) override {}
  void SetSpecular(double) override {}
  ///@}

protected:
  vtkViewDependentRadianceRepresentation();
  ~vtkViewDependentRadianceRepresentation() override;

  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkNew<vtkViewDependentRadiance> Evaluator;

private:
  vtkViewDependentRadianceRepresentation(const vtkViewDependentRadianceRepresentation&) = delete;
  void operator=(const vtkViewDependentRadianceRepresentation&) = delete;
};

#endif
