// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPRadianceImageFilter
 * @brief vtkRadianceImageFilter on the K processes of a controller (MPI under pvbatch,
 * pvserver and `mpiexec sphcover`): it also renders a solution kept in pieces
 * (vtkPLightPropagationFilter's GatherSolution off) on the ranks that hold the pieces.
 *
 * When every rank's input is its piece of a solution (field array `CoverRowShare` = (r, K)),
 * every rank builds the renderer of its piece with rank 0's patches (broadcast: under pvbatch
 * the other ranks' pieces of the scene are empty); rank 0 traces the view and lists the (point,
 * out cell) pairs of the directional part it reads, each rank evaluates those of its own points
 * from its rows, and rank 0 renders with all of them (vtkRankRenderer, paper §5.3.1). Rank 0's
 * output is the image, the serial one bit for bit; the other ranks' outputs are empty images.
 * No rank holds the whole cover. A failure on any rank is one error on every rank.
 *
 * Any other input (a whole solution, the gathered one on rank 0 and empty pieces on the
 * others) is rendered as vtkRadianceImageFilter renders it, as is every input on one process.
 * Every rank must update the filter together (as pvbatch --symmetric and pvserver do).
 */
#ifndef vtkPRadianceImageFilter_h
#define vtkPRadianceImageFilter_h

#include "SphericalCoverParallelModule.h" // for export macro
#include "vtkRadianceImageFilter.h"

class vtkMultiProcessController;

class SPHERICALCOVERPARALLEL_EXPORT vtkPRadianceImageFilter : public vtkRadianceImageFilter
{
public:
  static vtkPRadianceImageFilter* New();
  vtkTypeMacro(vtkPRadianceImageFilter, vtkRadianceImageFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The processes that render a solution kept in pieces together; nullptr or one process: this
   * process alone. Default is vtkMultiProcessController::GetGlobalController() at construction.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkPRadianceImageFilter();
  ~vtkPRadianceImageFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkMultiProcessController* Controller = nullptr;

private:
  vtkPRadianceImageFilter(const vtkPRadianceImageFilter&) = delete;
  void operator=(const vtkPRadianceImageFilter&) = delete;
};

#endif
