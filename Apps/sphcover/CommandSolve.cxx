// SPDX-License-Identifier: BSD-3-Clause
// sphcover solve SCENE [-o solution.vtm] [--report report.json]: the method up to equilibrium
// (paper §4, §3.3, §5.1). The solution's illumination carries the scene's fingerprint (the
// reader's, passed on by every stage), so that `render --solution` can tell a solution of
// another (or an edited) scene.
#include "Commands.h"
#include "Options.h"
#include "OutputFiles.h"
#include "Pipeline.h"
#include "Report.h"

#include "vtkSolutionPieces.h"

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiPieceDataSet.h>
#include <vtkMultiProcessController.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLMultiBlockDataWriter.h>
#include <vtkXMLPMultiBlockDataWriter.h>

#include <iostream>

namespace sphcover_cli
{
namespace
{
/// The solution file's blocks: 0 the patches, 1 the illumination (rank 0's), and, written in
/// pieces (every rank its piece of the solution), 2 `CoverShares`: per rank its share of the
/// cover and its regions' radiance (vtkSolutionPieces), each rank's piece on that rank alone.
vtkSmartPointer<vtkMultiBlockDataSet> SolutionBlocks(Solution& solution, const Options& options)
{
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  vtkPolyData* illumination = solution.Propagation->GetOutput();
  const bool pieces = vtkSolutionPieces::IsPiece(illumination);
  blocks->SetNumberOfBlocks(pieces ? 3 : 2);
  blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "Patches");
  blocks->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "Illumination");
  if (!pieces)
  {
    blocks->SetBlock(0, solution.Subdivision->GetOutput());
    blocks->SetBlock(1, illumination);
    return blocks;
  }
  vtkNew<vtkPolyData> points;
  vtkNew<vtkPolyData> share;
  vtkSolutionPieces::Split(illumination, points, share);
  if (options.Rank == 0)
  {
    blocks->SetBlock(0, solution.Subdivision->GetOutput());
    blocks->SetBlock(1, points);
  }
  vtkNew<vtkMultiPieceDataSet> shares;
  shares->SetNumberOfPieces(static_cast<unsigned>(options.Ranks));
  shares->SetPiece(static_cast<unsigned>(options.Rank), share);
  blocks->SetBlock(2, shares);
  blocks->GetMetaData(2u)->Set(vtkCompositeDataSet::NAME(), "CoverShares");
  return blocks;
}
}

int RunSolve(const Options& options)
{
  CheckOutputPath("-o", options.Output, { ".vtm" }, "solution");
  CheckOutputPath("--report", options.Report, { ".json" }, "report");
  Solution solution;
  solution.Read(options);
  // Under mpiexec each rank keeps its piece of the solution and writes it: no rank holds the
  // whole cover.
  solution.Solve(options, false);
  if (!options.Output.empty())
  {
    vtkSmartPointer<vtkMultiBlockDataSet> blocks = SolutionBlocks(solution, options);
    if (options.Ranks > 1)
    {
      vtkNew<vtkXMLPMultiBlockDataWriter> writer;
      writer->SetController(vtkMultiProcessController::GetGlobalController());
      WriteXmlAtomicallyOnRanks(
        writer, blocks, options.Output, vtkMultiProcessController::GetGlobalController());
    }
    else
    {
      vtkNew<vtkXMLMultiBlockDataWriter> writer;
      WriteXmlAtomically(writer, blocks, options.Output);
    }
  }
  if (options.Rank > 0)
  {
    return 0; // rank 0 reports and prints (main.cxx)
  }
  if (!options.Report.empty())
  {
    WriteTextAtomically(SolutionReport(solution).dump(2) + "\n", options.Report);
  }
  std::cout << "patches: " << solution.Subdivision->GetOutput()->GetNumberOfCells() << "\n"
            << "seconds: read " << solution.ReadSeconds << ", subdivide "
            << solution.SubdivideSeconds << ", cover " << solution.CoverSeconds << ", propagate "
            << solution.PropagateSeconds << " (" << solution.Propagation->GetShots() << " shots)\n";
  return 0;
}
}
