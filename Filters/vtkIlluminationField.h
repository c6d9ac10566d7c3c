// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkIlluminationField
 * @brief The illumination over all surfaces as a lit mesh, for interactive walk-throughs in
 * ParaView's own render view (Documentation/Pipeline.md#inspection-filters): the view-independent
 * result of the method (paper §2.5, §5.3) shown without ray casting a new image for every view.
 *
 * Inputs as vtkRadianceImageFilter: port 0 the illumination (vtkLightPropagationFilter's first
 * output), port 1 the patches (vtkIntervalSubdivisionFilter's first output). Every patch is
 * tessellated into Resolution x Resolution quads on the exact Bezier patch; every vertex gets
 * the brightness of paper §5.3.2 at its (surface, u, v): the bilinear interpolation of the
 * exitant radiance of the characteristic points around it, extrapolated near the edges (§3.4
 * Fig. 6), clamped at zero.
 *
 * Output (vtkPolyData): quads with point data `Radiance` (float RGB, W m^-2 sr^-1), `Normals`
 * (front side) and `SurfaceId`, and cell data `PatchId`. Colour by `Radiance` (magnitude or a
 * band) or, for the true colours, map it to RGB with a calculator. Non-diffuse surfaces show
 * their emission plus diffuse part (the view-dependent part of §5.3.1 needs the eye).
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

protected:
  vtkIlluminationField();
  ~vtkIlluminationField() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Resolution = 8;

private:
  vtkIlluminationField(const vtkIlluminationField&) = delete;
  void operator=(const vtkIlluminationField&) = delete;
};

#endif
