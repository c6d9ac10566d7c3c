// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSolutionPieces
 * @brief A solution kept in pieces (vtkLightPropagationFilter with GatherSolution off): split
 * for writing, and joined into the whole solution for the filters that read one.
 *
 * Rank r of K's piece is the illumination output with every characteristic point and its
 * per-point arrays, but only the rows of receivers r, r + K, ... of the cover and their
 * regions' IncidentRadiance, marked by the field array `CoverRowShare` = (r, K). Split parts it
 * into its points (what every piece holds alike, and on rank 0 the solution's figures) and its
 * share (the points with their `Area` alone, and in field data the cover's arrays,
 * IncidentRadiance and the marker), so that a solution file holds the illumination once and the
 * K shares beside it (`sphcover solve` under mpiexec: Documentation/Pipeline.md). Join is the
 * inverse: the points and every rank's share give the gathered solution, the one
 * GatherSolution on gives, bit for bit (RowShares::JoinRows, and each region's
 * IncidentRadiance from the share holding its row).
 */
#ifndef vtkSolutionPieces_h
#define vtkSolutionPieces_h

#include "SphericalCoverParallelModule.h" // for export macro

#include <string> // for the problem
#include <vector> // for the shares

class vtkPolyData;

class SPHERICALCOVERPARALLEL_EXPORT vtkSolutionPieces
{
public:
  /// Whether `data` is a piece or a share (it carries `CoverRowShare`).
  static bool IsPiece(vtkPolyData* data);

  /// `piece` into `points` (a shallow copy without the cover's arrays, IncidentRadiance and
  /// the marker) and `share` (those arrays in field data, with the points and their areas).
  static void Split(vtkPolyData* piece, vtkPolyData* points, vtkPolyData* share);

  /// Split's inverse for one rank: `points` with the share's arrays (`share`'s field data:
  /// the cover's, IncidentRadiance and the marker) into `piece`, shallow copies.
  static void Merge(vtkPolyData* points, vtkPolyData* share, vtkPolyData* piece);

  /**
   * The whole solution into `whole` from `points` (Split's points, or a piece) and the shares
   * of every rank, in any order: Split's shares or pieces. Returns "" or the problem, naming
   * the share ("share 2 of 3: ..."): a share missing, held twice or of another rank count, a
   * share's cover that does not load with the points (another grid, another point count), a
   * row held by two shares, an IncidentRadiance that is not one RGB value per region.
   */
  static std::string Join(vtkPolyData* points,
    const std::vector<vtkPolyData*>& shares,
    vtkPolyData* whole);
};

#endif
