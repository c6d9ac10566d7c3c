// SPDX-License-Identifier: BSD-3-Clause
// vtkPRadianceImageFilter under `mpiexec -n 2` refuses what it cannot render: a solution whose
// pieces are on some ranks only (rank 0 holds a piece, rank 1 the whole solution), and pieces of
// another rank count (each rank a piece of 3). Each is one clear error on every rank, the same
// on both (the ranks agree before any returns), a failed request and an empty image; no rank
// waits for another that has returned (CTest's timeout would catch the hang). The pieces are cut
// from the serial solution with Core (SolutionPieceTestUtilities.h), so the test holds pieces
// of any rank count on 2 processes; the pieces of 2 then render the serial image, so the
// refusals are the filter's, not the pieces'. Skipped (77) on other than 2 processes.
#include "FailureExpectation.h"
#include "RenderTestPipeline.h"
#include "SolutionPieceTestUtilities.h"
#include "TestFailures.h"

#include "vtkPRadianceImageFilter.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/SphericalCover.h"

#include <vtkCommunicator.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMPIController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTrivialProducer.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using TestFailures::Check;

/// The distributed render of `illumination` (this rank's input) over the pipeline's patches.
struct DistributedRender
{
  vtkNew<vtkTrivialProducer> Input;
  vtkNew<vtkPRadianceImageFilter> Render;

  DistributedRender(RenderTestPipeline::Pipeline& pipeline,
    vtkPolyData* illumination,
    vtkMultiProcessController* controller)
  {
    this->Input->SetOutput(illumination);
    this->Render->SetController(controller);
    this->Render->SetInputConnection(0, this->Input->GetOutputPort());
    this->Render->SetPatchesConnection(pipeline.Subdivision->GetOutputPort(0));
    this->Render->SetWidth(32);
    this->Render->SetHeight(24);
    this->Render->SetSamplesPerPixel(1);
  }
};

/// The refusal of `illumination` on this rank: one error with `fragments`, a failed request,
/// an empty image. Returns the error's text ("" when there was not exactly one).
std::string Refused(RenderTestPipeline::Pipeline& pipeline,
  vtkPolyData* illumination,
  vtkMultiProcessController* controller,
  const std::vector<std::string>& fragments,
  const std::string& what)
{
  DistributedRender render(pipeline, illumination, controller);
  std::string message;
  TestFailures::Add(FailureExpectation::Check(render.Render, fragments, what, &message));
  Check(render.Render->GetOutput()->GetNumberOfPoints() == 0, what + ": the image is empty");
  return message;
}

/// Whether every rank's error says the same (rank 0's broadcast, compared on each rank), past
/// VTK's "vtkPRadianceImageFilter (address): " that differs between processes.
bool SameOnEveryRank(vtkMultiProcessController* controller, const std::string& error)
{
  const std::size_t start = error.find("): ");
  const std::string text = start == std::string::npos ? error : error.substr(start + 3);
  long long length = static_cast<long long>(text.size());
  controller->Broadcast(&length, 1, 0);
  std::string first(static_cast<std::size_t>(length), ' ');
  if (controller->GetLocalProcessId() == 0)
  {
    first = text;
  }
  if (length > 0)
  {
    controller->Broadcast(&first[0], static_cast<vtkIdType>(length), 0);
  }
  int same = first == text ? 1 : 0;
  int all = 0;
  controller->AllReduce(&same, &all, 1, vtkCommunicator::MIN_OP);
  return all == 1;
}

bool SameValues(vtkDataArray* a, vtkDataArray* b)
{
  return a && b && a->GetNumberOfValues() == b->GetNumberOfValues() &&
    a->GetDataType() == b->GetDataType() &&
    std::memcmp(a->GetVoidPointer(0),
      b->GetVoidPointer(0),
      static_cast<size_t>(a->GetNumberOfValues()) * static_cast<size_t>(a->GetDataTypeSize())) == 0;
}
}

int TestPRadianceImageFilterRefusals(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  if (ranks != 2)
  {
    std::cout << "SKIPPED: run under mpiexec -n 2 (" << ranks << " process(es))\n";
    controller->Finalize();
    return 77;
  }
  const std::string me = "rank " + std::to_string(rank) + ": ";
  {
    // The serial solution on each rank alone (the serial filters take no controller).
    RenderTestPipeline::Pipeline pipeline("cornell_box.scene", 1, 8, 32);
    pipeline.Propagation->Update();
    vtkPolyData* whole = pipeline.Propagation->GetOutput();
    sphcover::SphericalCover cover;
    Check(vtkSphericalCoverArrays::Load(whole, cover).empty(), me + "the solution's cover loads");

    // Pieces on some ranks only: rank 0 a piece of 2, rank 1 the whole solution.
    vtkSmartPointer<vtkPolyData> mixed = rank == 0
      ? SolutionPieceTestUtilities::PieceOf(whole, cover, 0, 2)
      : vtkSmartPointer<vtkPolyData>(whole);
    const std::string someRanks = Refused(pipeline,
      mixed,
      controller,
      { "Cannot render", "some ranks' inputs are pieces", "and some not" },
      me + "pieces on rank 0 only");
    Check(SameOnEveryRank(controller, someRanks),
      me + "pieces on rank 0 only: one error, the same on both ranks");

    // Pieces of another rank count: each rank's piece of 3 on 2 ranks. Rank 0 gives the message
    // (the lowest rank that fails: both do).
    const std::string otherCount = Refused(pipeline,
      SolutionPieceTestUtilities::PieceOf(whole, cover, rank, 3),
      controller,
      { "Cannot render", "rank 0 of 3's share", "not rank 0 of 2's share", "(rank 0 of 2)" },
      me + "pieces of 3 ranks on 2");
    Check(SameOnEveryRank(controller, otherCount),
      me + "pieces of 3 on 2: one error, the same on both ranks");

    // The control: the pieces of 2 render, rank 0 the serial image, without an error.
    DistributedRender pieces(
      pipeline, SolutionPieceTestUtilities::PieceOf(whole, cover, rank, 2), controller);
    Check(pieces.Render->GetExecutive()->Update() == 1, me + "the pieces of 2 render");
    pipeline.Render->SetWidth(32);
    pipeline.Render->SetHeight(24);
    pipeline.Render->SetSamplesPerPixel(1);
    pipeline.Render->Update();
    vtkImageData* image = pieces.Render->GetOutput();
    if (rank == 0)
    {
      Check(SameValues(image->GetPointData()->GetArray("Radiance"),
              pipeline.Render->GetOutput()->GetPointData()->GetArray("Radiance")),
        me + "the pieces of 2 give the serial image");
    }
    else
    {
      Check(image->GetNumberOfPoints() == 0, me + "only rank 0 holds the image");
    }
  }
  // Every rank's verdict: a failure on one rank fails the test on all.
  int failures = TestFailures::Count();
  int total = 0;
  controller->AllReduce(&failures, &total, 1, vtkCommunicator::SUM_OP);
  controller->Finalize();
  return total == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
