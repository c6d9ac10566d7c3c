// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPLightPropagationFilter
 * @brief vtkLightPropagationFilter on the K processes of a controller (MPI under pvbatch,
 * pvserver and `mpiexec sphcover`): the same solution, the receivers' rows shared among them.
 *
 * When every one of K > 1 processes holds the whole cover (a VTK pipeline whose every rank holds
 * piece 0), each rank keeps the rows of its receivers r, r + K, ... (dealt round the ranks one by
 * one, so that each rank has a K-th of every surface and of each batch's shooters); when rank 0
 * holds the cover and the others empty pieces (pvbatch, pvserver, `mpiexec sphcover`), rank 0 deals
 * each rank those rows (the other ranks never hold the whole cover); when every rank holds its
 * share of the cover (the field array `CoverRowShare` of vtkSphericalCoverFilter with GatherRows
 * off, as `mpiexec sphcover` builds it), each propagates its rows as they are, no rank holding the
 * whole cover until rank 0 gathers it for the solution once the propagation's state is gone.
 * Either way the K ranks then balance the
 * exchange (ExchangeBalance under a share: each its own rows, the factors the whole cover's bit
 * for bit) and propagate together (LightPropagation::SetRankShare), and the results are
 * gathered: on every rank in the first case, on rank 0 alone in the others (it writes the
 * solution, the others keep empty outputs, as above), or kept in pieces (GatherSolution off:
 * each rank its own rows' regions, below). So the outputs are the serial ones (the
 * per-patch values and the regions' incident radiances bit for bit; the energy sums up to the
 * order of addition). Every process must update the filter together, as for
 * vtkPSphericalCoverFilter.
 *
 * On one process, with no controller, or in the FixedOrder, the filter is
 * vtkLightPropagationFilter.
 */
#ifndef vtkPLightPropagationFilter_h
#define vtkPLightPropagationFilter_h

#include "SphericalCoverParallelModule.h" // for export macro
#include "vtkLightPropagationFilter.h"

#include <vector> // for std::vector

class vtkMultiProcessController;
class vtkTable;

class SPHERICALCOVERPARALLEL_EXPORT vtkPLightPropagationFilter : public vtkLightPropagationFilter
{
public:
  static vtkPLightPropagationFilter* New();
  vtkTypeMacro(vtkPLightPropagationFilter, vtkLightPropagationFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Whether the solution is gathered when K > 1 ranks propagate together. On: rank 0's output
   * holds the whole solution (the whole cover and every region's IncidentRadiance; in a
   * pipeline whose every rank holds the whole cover, every rank's), the other ranks' outputs
   * are empty. Off: the solution is kept in pieces and no rank ever holds the whole cover:
   * every rank's output holds every point with the per-point arrays (the serial values) and
   * only its own rows (receivers r, r + K, ...) and their regions' IncidentRadiance, marked by
   * the field array `CoverRowShare` = (r, K) as vtkSphericalCoverFilter marks a share; rank 0's
   * holds the solution's figures too (summed from the ranks' rows, the serial ones bit for
   * bit). Filters that read a whole cover refuse such a piece; vtkSolutionPieces joins the K
   * pieces into the whole solution. Default is on; ignored on one process.
   */
  vtkSetMacro(GatherSolution, bool);
  vtkGetMacro(GatherSolution, bool);
  vtkBooleanMacro(GatherSolution, bool);
  ///@}

  /**
   * When the last update propagated on K > 1 ranks: per rank, in rank order, 4 values: its
   * receivers, the entries of its rows, the estimated bytes of its propagation state
   * (LightPropagation::EstimateBytes of its rows) and the seconds of its shooting. Empty
   * otherwise. Measurements, not part of the output.
   */
  const std::vector<double>& GetRankFigures() const { return this->RankFigures; }

  /// The number of processes the last update propagated on together (1: this one alone).
  vtkGetMacro(RankCount, int);

  ///@{
  /**
   * The processes that propagate together (see above); nullptr or one process: this process
   * alone. Default is vtkMultiProcessController::GetGlobalController() at construction.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

protected:
  vtkPLightPropagationFilter();
  ~vtkPLightPropagationFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Where the cover is when the ranks propagate together.
  enum class CoverHeld
  {
    EveryRank, ///< every rank's input holds the whole cover (or one process)
    FirstRank, ///< rank 0's; the others' `input` is its points without the cover
    Shares     ///< every rank's input holds its share (CoverRowShare)
  };
  /// RequestData's work on the controller's ranks together, the cover `held` as said.
  int PropagateOnRanks(vtkMultiProcessController* controller,
    vtkPolyData* input,
    vtkPolyData* output,
    vtkTable* history,
    CoverHeld held = CoverHeld::EveryRank);
  /// RequestData's work when not every rank holds the cover: rank 0's (piece 0) propagated by
  /// every rank together, `role` (vtkScenePieces::Role) this rank's piece.
  int PropagateFromFirst(vtkMultiProcessController* controller,
    int role,
    vtkInformationVector* outputVector,
    vtkPolyData* input,
    vtkPolyData* output,
    vtkTable* history);

  bool GatherSolution = true;
  vtkMultiProcessController* Controller = nullptr;
  std::vector<double> RankFigures;
  int RankCount = 1;

private:
  vtkPLightPropagationFilter(const vtkPLightPropagationFilter&) = delete;
  void operator=(const vtkPLightPropagationFilter&) = delete;
};

#endif
