// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPSphericalCoverFilter
 * @brief vtkSphericalCoverFilter on the K processes of a controller (MPI under pvbatch,
 * pvserver and `mpiexec sphcover`): the same cover, its rows built on all of them.
 *
 * With K > 1 ranks the receivers (characteristic points) are cut into K x 32 chunks of
 * consecutive receivers, of about equal estimated work (SphericalCover::EstimateRowCosts),
 * dealt round the ranks, and the row blocks are gathered in receiver order, so the cover is the
 * serial one bit for bit (rows are independent, paper §4.3). When the other ranks hold empty
 * pieces (pvbatch), rank 0's input is broadcast to them first; they help build and keep empty
 * outputs. The refinement's leaves and hemispheres (Steps 1 to 3) and the direct light's nodes
 * are shared among the ranks too. The output then carries the field array `CoverRankFigures`
 * (per rank: receivers, seconds, bytes of its rows).
 *
 * With GatherRows off the rows are not gathered: rank r builds and keeps the rows of receivers
 * r, r + K, ... (the light propagation's share, vtkPLightPropagationFilter), and every rank's
 * output holds every characteristic point but only its own rows (field array `CoverRowShare`),
 * so that no rank ever holds the whole cover before the propagation.
 *
 * Every rank must update the filter together (as pvbatch --symmetric, pvserver and mpiexec
 * sphcover do); a failure on any rank is one error on every rank. On one process, or with no
 * controller, the filter is vtkSphericalCoverFilter.
 */
#ifndef vtkPSphericalCoverFilter_h
#define vtkPSphericalCoverFilter_h

#include "SphericalCoverParallelModule.h" // for export macro
#include "vtkSphericalCoverFilter.h"

class vtkMultiProcessController;

class SPHERICALCOVERPARALLEL_EXPORT vtkPSphericalCoverFilter : public vtkSphericalCoverFilter
{
public:
  static vtkPSphericalCoverFilter* New();
  vtkTypeMacro(vtkPSphericalCoverFilter, vtkSphericalCoverFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Under K > 1 ranks: gather the rows built on the ranks into the whole cover on the ranks
   * that hold the whole scene (rank 0 under pvbatch, whose output ParaView shows). Off: each
   * rank keeps the rows of its receivers r, r + K, ... and outputs them with every
   * characteristic point, marked by the field array `CoverRowShare`: the input the light
   * propagation takes without any rank holding the whole cover (sphcover under mpiexec turns
   * it off). Other filters that read the cover need it gathered. Default is on; ignored on one
   * process.
   */
  vtkSetMacro(GatherRows, bool);
  vtkGetMacro(GatherRows, bool);
  vtkBooleanMacro(GatherRows, bool);
  ///@}

  ///@{
  /**
   * The processes the rows are built on; nullptr or one process: this process alone. Default
   * is vtkMultiProcessController::GetGlobalController() at construction.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkPSphericalCoverFilter();
  ~vtkPSphericalCoverFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool GatherRows = true;
  vtkMultiProcessController* Controller = nullptr;

private:
  vtkPSphericalCoverFilter(const vtkPSphericalCoverFilter&) = delete;
  void operator=(const vtkPSphericalCoverFilter&) = delete;
};

#endif
