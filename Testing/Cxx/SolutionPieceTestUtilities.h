// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SolutionPieceTestUtilities.h
 * @brief Test helper: rank r of K's piece of a whole solution (vtkSolutionPieces.h), cut here
 * with Core's RowShares::RowsOf, independently of the distributed filters that make pieces, so
 * that a test can hold a piece of any rank count on any number of processes.
 */
#ifndef SPHCOVER_SOLUTIONPIECETESTUTILITIES_H
#define SPHCOVER_SOLUTIONPIECETESTUTILITIES_H

#include "vtkSphericalCoverArrays.h"

#include "cover/SphericalCover.h"
#include "distributed/RowShares.h"
#include "math/RankShare.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>
#include <vector>

namespace SolutionPieceTestUtilities
{
/// Rank `rank` of `ranks`' piece of `whole`, cut with Core: the rows of its receivers and
/// their regions' incident radiance, marked as its share.
inline vtkSmartPointer<vtkPolyData> PieceOf(vtkPolyData* whole,
  const sphcover::SphericalCover& cover,
  int rank,
  int ranks)
{
  const std::vector<std::size_t> receivers =
    sphcover::RankShare::ItemsOf(rank, ranks, cover.PatchCount());
  auto piece = vtkSmartPointer<vtkPolyData>::New();
  piece->ShallowCopy(whole);
  vtkFieldData* fd = piece->GetFieldData();
  for (int a = fd->GetNumberOfArrays() - 1; a >= 0; --a)
  {
    const char* name = fd->GetAbstractArray(a)->GetName();
    if (vtkSphericalCoverArrays::IsCoverArray(name) || std::string(name) == "IncidentRadiance")
    {
      fd->RemoveArray(a);
    }
  }
  vtkSphericalCoverArrays::Store(sphcover::RowShares::RowsOf(cover, receivers), piece);
  vtkDataArray* incident = whole->GetFieldData()->GetArray("IncidentRadiance");
  vtkNew<vtkDoubleArray> own;
  own->SetName("IncidentRadiance");
  own->SetNumberOfComponents(3);
  for (const std::size_t e : sphcover::RowShares::KeptEntries(cover, receivers))
  {
    own->InsertNextTuple(incident->GetTuple(static_cast<vtkIdType>(e)));
  }
  fd->AddArray(own);
  vtkSphericalCoverArrays::MarkShare(piece, rank, ranks);
  return piece;
}
}

#endif
