// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSolutionPieces.h"

#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/SphericalCover.h"
#include "distributed/RowShares.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>
#include <utility>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
/// Whether the field array `name` belongs to a share rather than to the points.
bool IsShareArray(const char* name)
{
  return vtkSphericalCoverArrays::IsCoverArray(name) ||
    (name &&
      (std::string(name) == names::IncidentRadiance || std::string(name) == names::CoverRowShare));
}

/// The (rank, rank count) of a share's marker; {-1, 0} when it has none or a malformed one.
std::pair<int, int> MarkerOf(vtkPolyData* share)
{
  vtkDataArray* marker = share ? share->GetFieldData()->GetArray(names::CoverRowShare) : nullptr;
  if (!marker || marker->GetNumberOfComponents() != 2 || marker->GetNumberOfTuples() != 1)
  {
    return { -1, 0 };
  }
  return { static_cast<int>(marker->GetComponent(0, 0)),
    static_cast<int>(marker->GetComponent(0, 1)) };
}
}

bool vtkSolutionPieces::IsPiece(vtkPolyData* data)
{
  return vtkSphericalCoverArrays::IsShare(data);
}

void vtkSolutionPieces::Split(vtkPolyData* piece, vtkPolyData* points, vtkPolyData* share)
{
  points->ShallowCopy(piece);
  share->Initialize();
  vtkFieldData* fd = points->GetFieldData();
  for (int a = fd->GetNumberOfArrays() - 1; a >= 0; --a)
  {
    if (IsShareArray(fd->GetAbstractArray(a)->GetName()))
    {
      fd->RemoveArray(a);
    }
  }
  // The points and their areas too, with which the rows load (and a dataset without points
  // is not written into a multiblock file).
  share->SetPoints(piece->GetPoints());
  share->GetPointData()->AddArray(piece->GetPointData()->GetArray(names::Area));
  vtkFieldData* from = piece->GetFieldData();
  for (int a = 0; a < from->GetNumberOfArrays(); ++a)
  {
    if (IsShareArray(from->GetAbstractArray(a)->GetName()))
    {
      share->GetFieldData()->AddArray(from->GetAbstractArray(a));
    }
  }
}

void vtkSolutionPieces::Merge(vtkPolyData* points, vtkPolyData* share, vtkPolyData* piece)
{
  piece->ShallowCopy(points);
  vtkFieldData* fd = share->GetFieldData();
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
  {
    if (IsShareArray(fd->GetAbstractArray(a)->GetName()))
    {
      piece->GetFieldData()->AddArray(fd->GetAbstractArray(a));
    }
  }
}

std::string vtkSolutionPieces::Join(vtkPolyData* points,
  const std::vector<vtkPolyData*>& shares,
  vtkPolyData* whole)
{
  const int count = static_cast<int>(shares.size());
  if (count == 0)
  {
    return "no share of the cover";
  }
  // The shares in rank order, each rank's once.
  std::vector<vtkPolyData*> byRank(shares.size(), nullptr);
  for (std::size_t s = 0; s < shares.size(); ++s)
  {
    const std::pair<int, int> marker = MarkerOf(shares[s]);
    const std::string name = "share " + std::to_string(s + 1) + " of " + std::to_string(count);
    if (marker.first < 0)
    {
      return name + ": not a share of a cover (no CoverRowShare of one rank and rank count)";
    }
    if (marker.second != count || marker.first >= count)
    {
      return name + ": rank " + std::to_string(marker.first) + " of " +
        std::to_string(marker.second) + "'s share, not one of " + std::to_string(count) +
        " ranks (a share is missing or from another solve)";
    }
    if (byRank[static_cast<std::size_t>(marker.first)])
    {
      return name + ": rank " + std::to_string(marker.first) + "'s share is there twice";
    }
    byRank[static_cast<std::size_t>(marker.first)] = shares[s];
  }

  // Each share's rows, loaded with the points' areas, and its regions' incident radiance.
  std::vector<sphcover::SphericalCover> covers(byRank.size());
  std::vector<vtkDataArray*> incident(byRank.size());
  std::size_t entries = 0;
  for (std::size_t r = 0; r < byRank.size(); ++r)
  {
    const std::string name = "rank " + std::to_string(r) + "'s share";
    vtkNew<vtkPolyData> rows;
    Merge(points, byRank[r], rows);
    vtkFieldData* fd = byRank[r]->GetFieldData();
    const std::string problem = vtkSphericalCoverArrays::Load(rows, covers[r], true);
    if (!problem.empty())
    {
      return name + ": " + problem;
    }
    incident[r] = fd->GetArray(names::IncidentRadiance);
    if (!incident[r] || incident[r]->GetNumberOfComponents() != 3 ||
      incident[r]->GetNumberOfTuples() != static_cast<vtkIdType>(covers[r].EntryCount()))
    {
      return name + ": its IncidentRadiance is not one RGB value per region of its rows (" +
        std::to_string(covers[r].EntryCount()) + ")";
    }
    entries += covers[r].EntryCount();
  }

  // Every region's incident radiance in the joined cover's order: receiver by receiver, from
  // the share that holds its row (JoinRows below refuses a row held twice).
  vtkSmartPointer<vtkDataArray> joined;
  joined.TakeReference(incident[0]->NewInstance());
  joined->SetName(names::IncidentRadiance);
  joined->SetNumberOfComponents(3);
  joined->SetNumberOfTuples(static_cast<vtkIdType>(entries));
  vtkIdType next = 0;
  const std::size_t receivers = covers[0].PatchCount();
  for (std::size_t i = 0; i < receivers; ++i)
  {
    for (std::size_t r = 0; r < covers.size(); ++r)
    {
      if (i >= covers[r].PatchCount())
      {
        continue; // another point count: JoinRows says so
      }
      for (std::size_t e = covers[r].EntryBegin(i);
           e < covers[r].EntryEnd(i) && next < joined->GetNumberOfTuples();
           ++e)
      {
        joined->SetTuple(next++, static_cast<vtkIdType>(e), incident[r]);
      }
    }
  }

  std::vector<sphcover::SphericalCover::Arrays> arrays;
  const sphcover::SphericalCoverOptions options = covers[0].Options();
  for (sphcover::SphericalCover& cover : covers)
  {
    arrays.push_back(std::move(cover).ExportArrays());
    cover = sphcover::SphericalCover();
  }
  sphcover::SphericalCover cover;
  const std::string problem = sphcover::RowShares::JoinRows(cover, std::move(arrays), options, {});
  if (!problem.empty())
  {
    return "the ranks' shares: " + problem;
  }
  whole->ShallowCopy(points);
  vtkFieldData* fd = whole->GetFieldData();
  for (int a = fd->GetNumberOfArrays() - 1; a >= 0; --a)
  {
    if (IsShareArray(fd->GetAbstractArray(a)->GetName()))
    {
      fd->RemoveArray(a);
    }
  }
  vtkSphericalCoverArrays::Store(std::move(cover).ExportArrays(), whole);
  fd->AddArray(joined);
  return std::string();
}
