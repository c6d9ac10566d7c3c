// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkScenePieces.h
 * @brief The piece policy of every reader and filter: the whole scene is piece 0.
 *
 * Global illumination cannot be split by space: every hemisphere of the spherical cover sees
 * every surface of the scene (paper §3.3) and every characteristic point may shoot light to
 * every other (paper §5.1). A piece of the scene would give a plausible but wrong result, so
 * the stages never work on one:
 *  - the readers deliver the whole scene as piece 0 and an empty dataset as every other piece
 *    (they read nothing there);
 *  - a filter asked for a piece > 0 whose input is empty produces an empty output, silently:
 *    under `mpiexec -n N pvbatch --symmetric` (or a parallel pvserver) rank 0 computes and the
 *    other ranks idle, and ParaView gathers the same totals as in serial;
 *  - a filter asked for a piece > 0 whose input is not empty refuses with an error (a
 *    distributed mesh reader split the scene; merge it first);
 *  - an empty input on piece 0 stays the filter's own error, as in serial.
 * Under MPI the stages also share the work itself among the ranks (rows of the cover, shots:
 * vtkSphericalCoverFilter, vtkLightPropagationFilter). One exception to the rule above: the
 * spherical cover with GatherRows off gives every rank its share of the rows (field array
 * CoverRowShare), a non-empty piece > 0 that the light propagation takes and every other
 * filter refuses.
 */
#ifndef vtkScenePieces_h
#define vtkScenePieces_h

#include <vtkDataSet.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <sstream>
#include <string>

namespace vtkScenePieces
{
/// The piece requested of the algorithm's first output (0 when no piece was requested).
inline int RequestedPiece(vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector ? outputVector->GetInformationObject(0) : nullptr;
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()))
  {
    return 0;
  }
  return info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
}

/// The number of pieces requested of the algorithm's first output (1 when none was requested).
inline int RequestedPieces(vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector ? outputVector->GetInformationObject(0) : nullptr;
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
  {
    return 1;
  }
  return info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
}

/// What a filter does with its input on the requested piece.
enum class Role
{
  WholeScene,  ///< piece 0: compute (an empty input is the filter's own error)
  IdlePiece,   ///< piece > 0, empty input: empty output, no message
  PartialScene ///< piece > 0 with data: refuse (PartialSceneError)
};

inline Role Classify(vtkInformationVector* outputVector, vtkDataObject* input)
{
  if (RequestedPiece(outputVector) == 0)
  {
    return Role::WholeScene;
  }
  vtkDataSet* dataSet = vtkDataSet::SafeDownCast(input);
  const bool empty =
    !input || (dataSet && dataSet->GetNumberOfPoints() == 0 && dataSet->GetNumberOfCells() == 0);
  return empty ? Role::IdlePiece : Role::PartialScene;
}

/// The error of Role::PartialScene, naming the piece.
inline std::string PartialSceneError(vtkInformationVector* outputVector)
{
  std::ostringstream message;
  message << "piece " << RequestedPiece(outputVector) << " of " << RequestedPieces(outputVector)
          << " received part of the scene, but global illumination needs the whole scene in "
             "piece 0 (every hemisphere sees every surface): read the scene with the Patch "
             "Scene Reader, which gives it whole to piece 0, or merge the pieces first";
  return message.str();
}
}

#endif
