// SPDX-License-Identifier: BSD-3-Clause
// vtkSolutionPieces: a solution kept in pieces (vtkLightPropagationFilter with GatherSolution
// off, one piece per rank: every point, the rows of receivers r, r + K, ... and their regions'
// IncidentRadiance) split for writing and joined again gives the whole solution bit for bit, in
// any order of the shares; shares that do not make one solution are one error naming the share.
// The pieces are cut here from a serial solution with Core's RowsOf, the independent path (the
// ranks' own pieces are compared with the serial solution in ParaView.PluginParallel and
// CommandLine.MPI). GatherSolution off on one process leaves the solution whole.
#include "RenderTestPipeline.h"
#include "SolutionPieceTestUtilities.h"
#include "TestFailures.h"

#include "vtkPLightPropagationFilter.h"
#include "vtkSolutionPieces.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/SphericalCover.h"
#include "distributed/RowShares.h"
#include "math/RankShare.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using SolutionPieceTestUtilities::PieceOf;
using TestFailures::Check;

/// Whether the two arrays hold the same values, bit for bit (both missing: true).
bool SameValues(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b)
  {
    return !a && !b;
  }
  return a->GetDataType() == b->GetDataType() &&
    a->GetNumberOfComponents() == b->GetNumberOfComponents() &&
    a->GetNumberOfTuples() == b->GetNumberOfTuples() &&
    std::memcmp(a->GetVoidPointer(0),
      b->GetVoidPointer(0),
      static_cast<size_t>(a->GetNumberOfValues()) * static_cast<size_t>(a->GetDataTypeSize())) == 0;
}

/// Join's problem for `shares` of `points`, printed; "" when they join.
std::string JoinProblem(vtkPolyData* points, const std::vector<vtkPolyData*>& shares)
{
  vtkNew<vtkPolyData> joined;
  const std::string problem = vtkSolutionPieces::Join(points, shares, joined);
  std::cout << "join: " << (problem.empty() ? "joined" : problem) << "\n";
  return problem;
}
}

int TestSolutionPieces(int, char*[])
{
  RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 1, 8, 32);
  // The distributed filter on one process: nothing to keep apart.
  vtkNew<vtkPLightPropagationFilter> alone;
  alone->SetInputConnection(pipeline.Cover->GetOutputPort(0));
  alone->GatherSolutionOff();
  alone->Update();
  vtkPolyData* whole = alone->GetOutput();
  Check(!vtkSolutionPieces::IsPiece(whole) && whole->GetFieldData()->GetArray("IncidentRadiance"),
    "GatherSolution off on one process: the whole solution, not a piece");
  sphcover::SphericalCover cover;
  Check(vtkSphericalCoverArrays::Load(whole, cover).empty(), "the solution's cover loads");

  const int ranks = 3;
  std::vector<vtkSmartPointer<vtkPolyData>> pieces;
  std::vector<vtkSmartPointer<vtkPolyData>> points;
  std::vector<vtkSmartPointer<vtkPolyData>> shares;
  for (int r = 0; r < ranks; ++r)
  {
    pieces.push_back(PieceOf(whole, cover, r, ranks));
    points.push_back(vtkSmartPointer<vtkPolyData>::New());
    shares.push_back(vtkSmartPointer<vtkPolyData>::New());
    vtkSolutionPieces::Split(pieces.back(), points.back(), shares.back());
    Check(vtkSolutionPieces::IsPiece(pieces.back()) && vtkSolutionPieces::IsPiece(shares.back()) &&
        !vtkSolutionPieces::IsPiece(points.back()),
      "a piece and its share are marked, its points are not");
    Check(shares.back()->GetPointData()->GetNumberOfArrays() == 1 &&
        points.back()->GetNumberOfPoints() == whole->GetNumberOfPoints() &&
        !points.back()->GetFieldData()->GetArray("CoverEntries") &&
        !points.back()->GetFieldData()->GetArray("IncidentRadiance") &&
        shares.back()->GetFieldData()->GetArray("CoverEntries") &&
        shares.back()->GetFieldData()->GetArray("IncidentRadiance"),
      "Split: every point without the rows, the rows without the points");
  }
  // A piece is not a whole cover.
  sphcover::SphericalCover refused;
  const std::string problem = vtkSphericalCoverArrays::Load(pieces[1], refused);
  Check(problem.find("GatherSolution") != std::string::npos && refused.Empty(),
    "a piece of a solution is refused where a whole cover is read, naming GatherSolution: " +
      problem);

  // The shares in any order, with the points of any piece, join to the whole solution.
  vtkNew<vtkPolyData> joined;
  const std::string joinProblem =
    vtkSolutionPieces::Join(points[1], { shares[2], shares[0], shares[1] }, joined);
  Check(joinProblem.empty(), "the three shares join: " + joinProblem);
  vtkFieldData* a = joined->GetFieldData();
  vtkFieldData* b = whole->GetFieldData();
  int compared = 0;
  for (int k = 0; k < b->GetNumberOfArrays(); ++k)
  {
    vtkDataArray* expected = b->GetArray(k);
    if (!expected)
    {
      continue; // the string arrays (surface names, fingerprint) are the points' own
    }
    Check(SameValues(a->GetArray(expected->GetName()), expected),
      std::string("the joined solution's ") + expected->GetName() + " is the whole one's");
    ++compared;
  }
  Check(compared >= 8 && !a->GetArray("CoverRowShare") &&
      a->GetNumberOfArrays() == b->GetNumberOfArrays(),
    "the joined solution has the whole one's field arrays, and no share marker");
  Check(SameValues(joined->GetPointData()->GetArray("Radiosity"),
          whole->GetPointData()->GetArray("Radiosity")),
    "the joined solution's Radiosity is the whole one's");
  // A piece (rows and points together) is a share too.
  Check(JoinProblem(pieces[0], { pieces[0], pieces[1], pieces[2] }).empty(),
    "the pieces themselves join");

  // Shares that do not make one solution: one sentence naming the share.
  Check(JoinProblem(points[0], { shares[0], shares[2] }).find("not one of 2 ranks") !=
      std::string::npos,
    "a share missing is refused");
  Check(JoinProblem(points[0], { shares[0], shares[1], shares[1] }).find("there twice") !=
      std::string::npos,
    "a share given twice is refused");
  Check(JoinProblem(points[0], { shares[0], points[1], shares[2] }).find("not a share") !=
      std::string::npos,
    "something that is no share is refused");
  Check(JoinProblem(points[0], {}) == "no share of the cover", "no shares are refused");
  {
    vtkNew<vtkPolyData> shortened;
    shortened->ShallowCopy(shares[1]);
    vtkNew<vtkFieldData> fd;
    fd->ShallowCopy(shares[1]->GetFieldData());
    vtkNew<vtkDoubleArray> fewer;
    fewer->DeepCopy(fd->GetArray("IncidentRadiance"));
    fewer->SetNumberOfTuples(fewer->GetNumberOfTuples() - 1);
    fd->AddArray(fewer);
    shortened->SetFieldData(fd);
    Check(JoinProblem(points[0], { shares[0], shortened, shares[2] })
            .find("rank 1's share: its IncidentRadiance is not one RGB value per region") !=
        std::string::npos,
      "a share whose IncidentRadiance misses a region is refused");
  }
  {
    // Rank 1's share holding rank 0's rows too: a row in two shares.
    vtkSmartPointer<vtkPolyData> greedy = PieceOf(whole, cover, 0, 1);
    vtkSphericalCoverArrays::MarkShare(greedy, 1, 3);
    Check(
      JoinProblem(points[0], { shares[0], greedy, shares[2] }).find("in share 0 and in share 1") !=
        std::string::npos,
      "a row held by two shares is refused");
  }
  return TestFailures::ExitCode();
}
