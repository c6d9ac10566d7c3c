// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkIlluminationField
 * @brief The illumination over all surfaces as a lit mesh, for interactive walk-throughs in
 * ParaView's own render view (Documentation/Pipeline.md#inspection-filters): the view-independent
 * result of the method (paper §2.5, §5.3) shown without ray casting a new image for every view.
 *
 * Inputs as vtkRadianceImageFilter: port 0 the illumination (vtkLightPropagationFilter's first
 * output), port 1 the patches (vtkIntervalSubdivisionFilter's first output; optional: left
 * unconnected, the input of the vtkSphericalCoverFilter upstream of port 0, vtkCoverPatches.h).
 * Every patch is tessellated into Resolution x Resolution quads on the exact Bezier patch; every
 * vertex gets the brightness of paper §5.3.2 at its (surface, u, v): the bilinear interpolation of
 * the exitant radiance of the characteristic points around it, extrapolated near the edges (§3.4
 * Fig. 6), clamped at zero.
 *
 * Output (vtkPolyData): quads with point data `Radiance` (float RGB, W m^-2 sr^-1), `Normals`
 * (front side), `SurfaceId`, `UV` (the vertex's (u, v) in its surface's parameters, where
 * vtkViewDependentRadiance evaluates the view-dependent radiance) and, as the active scalars,
 * `DisplayRGB` (unsigned char RGB: the radiance times 2^ExposureStops, clamped to [0, 1] and
 * sRGB-encoded, as vtkRadianceImageFilter's `RGB`), and cell data `PatchId`. Show `DisplayRGB` with
 * Map Scalars off and lighting off (the colours are the light already) to see the true colours;
 * colour by `Radiance` for values. Non-diffuse surfaces show their emission plus diffuse part (the
 * view-dependent part of §5.3.1 needs the eye: ParaView's "View-Dependent Radiance"
 * representation of this output adds it for the render view's camera, vtkViewDependentRadiance).
 *
 * @warning Patches are tessellated in parallel (vtkSMPTools); the output does not depend on
 * the number of threads.
 */
#ifndef vtkIlluminationField_h
#define vtkIlluminationField_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

class SPHERICALCOVERFILTERS_EXPORT vtkIlluminationField : public vtkPolyDataAlgorithm
{
public:
  static vtkIlluminationField* New();
  vtkTypeMacro(vtkIlluminationField, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The patches (vtkIntervalSubdivisionFilter's first output) on port 1.
  void SetPatchesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /** Quads per patch along u and along v, 1 to 256. Default is 8. */
  vtkSetClampMacro(Resolution, int, 1, 256);
  vtkGetMacro(Resolution, int);
  ///@}

  ///@{
  /**
   * Exposure of `DisplayRGB` in photographic stops: the radiance is scaled by 2^ExposureStops
   * before the sRGB encoding, so radiance 2^-ExposureStops shows as white. -20 to 20. Default is
   * 0 (radiance 1 is white, as in vtkRadianceImageFilter at its default ExposureFactor 1: that
   * filter's exposure is a factor, this one a power of two).
   */
  vtkSetClampMacro(ExposureStops, double, -20.0, 20.0);
  vtkGetMacro(ExposureStops, double);
  ///@}

protected:
  vtkIlluminationField();
  ~vtkIlluminationField() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Resolution = 8;
  double ExposureStops = 0.0;

private:
  vtkIlluminationField(const vtkIlluminationField&) = delete;
  void operator=(const vtkIlluminationField&) = delete;
};

#endif
