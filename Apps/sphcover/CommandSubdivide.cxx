// SPDX-License-Identifier: BSD-3-Clause
// sphcover subdivide SCENE -o patches.vtm: the interval subdivision (paper §4), its patches and
// characteristic points written as a multiblock file for ParaView.
#include "Commands.h"
#include "Options.h"
#include "OutputFiles.h"
#include "Pipeline.h"

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLMultiBlockDataWriter.h>

#include <iostream>

namespace sphcover_cli
{
int RunSubdivide(const Options& options)
{
  CheckOutputPath("-o", options.Output, { ".vtm" }, "subdivision");
  Solution solution;
  solution.Read(options);
  solution.Subdivide(options);
  vtkUnstructuredGrid* patches = solution.Subdivision->GetOutput();
  auto* points = vtkPolyData::SafeDownCast(solution.Subdivision->GetOutputDataObject(1));

  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, patches);
  blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "Patches");
  blocks->SetBlock(1, points);
  blocks->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "CharacteristicPoints");
  vtkNew<vtkXMLMultiBlockDataWriter> writer;
  WriteXmlAtomically(writer, blocks, options.Output);

  std::cout << "patches: " << patches->GetNumberOfCells() << "\n"
            << "characteristic points: " << points->GetNumberOfPoints() << "\n"
            << "pair tests: " << solution.Subdivision->GetPairTests() << "\n"
            << "seconds: " << solution.SubdivideSeconds << "\n"
            << "written: " << options.Output << "\n";
  return 0;
}
}
