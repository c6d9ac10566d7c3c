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

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLMultiBlockDataWriter.h>

#include <iostream>

namespace sphcover_cli
{
int RunSolve(const Options& options)
{
  CheckOutputPath("-o", options.Output, { ".vtm" }, "solution");
  CheckOutputPath("--report", options.Report, { ".json" }, "report");
  Solution solution;
  solution.Read(options);
  solution.Solve(options);
  if (options.Rank > 0)
  {
    return 0; // rank 0 writes and prints (main.cxx)
  }
  if (!options.Report.empty())
  {
    WriteTextAtomically(SolutionReport(solution).dump(2) + "\n", options.Report);
  }
  if (!options.Output.empty())
  {
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(2);
    blocks->SetBlock(0, solution.Subdivision->GetOutput());
    blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "Patches");
    blocks->SetBlock(1, solution.Propagation->GetOutput());
    blocks->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "Illumination");
    vtkNew<vtkXMLMultiBlockDataWriter> writer;
    WriteXmlAtomically(writer, blocks, options.Output);
  }
  std::cout << "patches: " << solution.Subdivision->GetOutput()->GetNumberOfCells() << "\n"
            << "seconds: read " << solution.ReadSeconds << ", subdivide "
            << solution.SubdivideSeconds << ", cover " << solution.CoverSeconds << ", propagate "
            << solution.PropagateSeconds << " (" << solution.Propagation->GetShots() << " shots)\n";
  return 0;
}
}
