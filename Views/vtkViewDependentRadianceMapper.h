// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkViewDependentRadianceMapper
 * @brief A composite polydata mapper that, before each render, rewrites its Illumination Field
 * input's `DisplayRGB` for the renderer's camera (paper §5.3: the solution's radiance toward the
 * eye), so that camera moves show mirrors and glossy surfaces without a pipeline execution.
 *
 * Render reads the active camera's position and calls vtkViewDependentRadiance::Update on every
 * polydata leaf of its input that has `SurfaceId` and `UV` (vtkViewDependentRadiance::
 * CanEvaluate); Update does nothing when neither the eye nor the exposure changed, and else
 * evaluates only the vertices whose radiance depends on the eye. Then the superclass draws the
 * rewritten colours. Without an evaluator (or one without a solution) the input is drawn as
 * given. The input is modified in place: it must be this mapper's own copy of the data (as
 * ParaView's delivered geometry is), not a pipeline's output that other consumers read.
 *
 * The colouring is fixed: the point array `DisplayRGB` as direct colours. Its setters
 * (ScalarVisibility, ScalarMode, ColorMode, ArrayName, ArrayAccessMode) are ignored, so that a
 * representation's colouring properties, applied before every render, neither change the colours
 * nor touch the mapper's modification time (which would rebuild its buffers every frame).
 *
 * @warning The evaluator keeps the state of one field: an input of several leaves is drawn
 * correctly but re-evaluated in full every frame.
 */
#ifndef vtkViewDependentRadianceMapper_h
#define vtkViewDependentRadianceMapper_h

#include "SphericalCoverViewsModule.h" // for export macro
#include "vtkCompositePolyDataMapper2.h"
#include "vtkSmartPointer.h"          // for the evaluator
#include "vtkViewDependentRadiance.h" // for the wrappers of the evaluator's accessors

class SPHERICALCOVERVIEWS_EXPORT vtkViewDependentRadianceMapper : public vtkCompositePolyDataMapper2
{
public:
  static vtkViewDependentRadianceMapper* New();
  vtkTypeMacro(vtkViewDependentRadianceMapper, vtkCompositePolyDataMapper2);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The evaluator, holding the solution, called before each render; null draws the input as
  /// given. Default is null.
  void SetEvaluator(vtkViewDependentRadiance* evaluator);
  vtkViewDependentRadiance* GetEvaluator() const { return this->Evaluator; }

  ///@{
  /** Exposure of the colours in stops, as vtkIlluminationField's ExposureStops. Default is 0. */
  vtkSetMacro(ExposureStops, double);
  vtkGetMacro(ExposureStops, double);
  ///@}

  /// Updates the input's colours for the renderer's camera, then draws.
  void Render(vtkRenderer* renderer, vtkActor* actor) override;

  ///@{
  /// Ignored: the colouring is fixed (see the class comment).
  void SetScalarVisibility(vtkTypeBool) override {}
  void SetScalarMode(int) override {}
  void SetColorMode(int) override {}
  void SetArrayName(const char*) override {}
  void SetArrayAccessMode(int) override {}
  ///@}

protected:
  vtkViewDependentRadianceMapper();
  ~vtkViewDependentRadianceMapper() override;

  vtkSmartPointer<vtkViewDependentRadiance> Evaluator;
  double ExposureStops = 0.0;

private:
  vtkViewDependentRadianceMapper(const vtkViewDependentRadianceMapper&) = delete;
  void operator=(const vtkViewDependentRadianceMapper&) = delete;
};

#endif
