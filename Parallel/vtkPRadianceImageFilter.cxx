// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPRadianceImageFilter.h"

#include "vtkCoverDistribution.h"
#include "vtkCoverPatches.h"
#include "vtkHeldMessages.h"
#include "vtkLightPropagationSteps.h"
#include "vtkRankRenderer.h"
#include "vtkSMPParallelFor.h"
#include "vtkSolutionRenderer.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkStageProgress.h"

#include "render/RadianceRenderer.h"
#include "scene/Camera.h"

#include <vtkDataSet.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <exception>
#include <memory>
#include <string>
#include <utility>

vtkStandardNewMacro(vtkPRadianceImageFilter);

vtkPRadianceImageFilter::vtkPRadianceImageFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPRadianceImageFilter::~vtkPRadianceImageFilter()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkPRadianceImageFilter, Controller, vtkMultiProcessController);

int vtkPRadianceImageFilter::RequestData(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkMultiProcessController* controller = this->Controller;
  if (!controller || controller->GetNumberOfProcesses() <= 1)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkPolyData* illumination = vtkPolyData::GetData(inputVector[0], 0);
  // Collective, so it comes before any rank returns.
  const int pieces =
    vtkCoverDistribution::Count(controller, vtkSphericalCoverArrays::IsShare(illumination));
  if (pieces == 0)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const bool first = rank == 0;
  vtkDataSet* patchesInput = vtkCoverPatches::Find(this, inputVector);
  std::string problem;
  if (pieces != ranks)
  {
    problem = "some ranks' inputs are pieces of a solution kept in pieces and some not";
  }
  else
  {
    // Of these ranks, each its own (as vtkPLightPropagationFilter checks a share of the rows).
    const std::pair<int, int> piece = vtkLightPropagationSteps::RowShareOf(illumination);
    if (piece != std::make_pair(rank, ranks))
    {
      problem = "this rank's input is " + vtkLightPropagationSteps::ShareName(piece) +
        " of a solution kept in pieces, not " +
        vtkLightPropagationSteps::ShareName({ rank, ranks });
    }
  }
  if (problem.empty() && !patchesInput)
  {
    problem = "no patches: connect the patches (vtkIntervalSubdivisionFilter's output 0) to "
              "port 1 (Patches) unless a Spherical Cover is upstream of the illumination";
  }
  problem = vtkCoverDistribution::Agree(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot render: " << problem << ".");
    return 0;
  }

  // Every rank's renderer of its piece over rank 0's patches (the others' pieces of the scene
  // may be empty, as under pvbatch); rank 0's view.
  auto patches = vtkSmartPointer<vtkDataSet>::Take(patchesInput->NewInstance());
  if (first)
  {
    patches->ShallowCopy(patchesInput);
  }
  vtkCoverDistribution::BroadcastFromFirst(controller, patches);
  std::unique_ptr<sphcover::RadianceRenderer> renderer;
  sphcover::Camera camera;
  sphcover::RenderSettings settings;
  try
  {
    renderer = vtkSolutionRenderer::New(illumination, patches, problem, true);
    if (renderer && first)
    {
      problem = this->ViewOf(inputVector, illumination, patches, camera, settings);
    }
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  problem = vtkCoverDistribution::Agree(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot render: " << problem << ".");
    return 0;
  }

  // Rank 0 renders while the others serve its view's pairs (vtkRankRenderer); then the ranks
  // agree on how it went, rank 0's warning (aborted) held until then.
  sphcover::RenderedImage image;
  {
    vtkHeldMessages held(this);
    vtkRankRenderer together(controller, *renderer);
    if (first)
    {
      try
      {
        vtkStageProgress progress(this, "Radiance Image: rendering", 0.0, 0.95);
        if (!together.Render(camera,
              settings,
              image,
              vtkSMPParallelFor::Make(),
              [&progress](double fraction) { return progress(fraction); }))
        {
          vtkWarningMacro("Rendering aborted.");
        }
      }
      catch (const std::exception& e)
      {
        vtkErrorMacro(<< "Cannot render: " << e.what());
      }
      together.Finish();
    }
    else
    {
      together.Serve(vtkSMPParallelFor::Make());
    }
    problem = held.First("");
  }
  problem = vtkCoverDistribution::Agree(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  if (first)
  {
    vtkSolutionRenderer::ToImageData(image, this->ExposureFactor, output);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPRadianceImageFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}
