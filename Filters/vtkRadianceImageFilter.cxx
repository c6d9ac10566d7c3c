// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRadianceImageFilter.h"

#include "vtkCoverPatches.h"
#include "vtkSMPParallelFor.h"
#include "vtkSceneCameras.h"
#include "vtkScenePieces.h"
#include "vtkSolutionRenderer.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkStageProgress.h"

#include "render/RadianceRenderer.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationDataObjectMetaDataKey.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <sstream>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkRadianceImageFilter);

namespace
{
/// The camera `name` (or the first) of the scene as the inputs' pipeline information carries
/// it, known before any data exists (vtkPatchSceneReader); false when they carry none.
bool FindCameraInformation(vtkInformationVector** inputVector,
  const std::string& name,
  sphcover::Camera& camera)
{
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* info = inputVector[port]->GetInformationObject(0);
    vtkDataObject* cameras = info ? info->Get(vtkSceneCameras::SCENE_CAMERAS()) : nullptr;
    if (cameras && vtkSceneCameras::Find(cameras->GetFieldData(), name, camera))
    {
      return true;
    }
  }
  return false;
}

std::string CameraList(vtkFieldData* fd)
{
  const std::vector<std::string> cameras = vtkSceneCameras::Names(fd);
  if (cameras.empty())
  {
    return "the scene has no cameras";
  }
  std::string list = "the scene's cameras are";
  for (std::size_t k = 0; k < cameras.size(); ++k)
  {
    list += (k == 0 ? " '" : ", '") + cameras[k] + "'";
  }
  return list;
}

/// The camera of the pose properties, used without CameraName: each left at its default is the
/// scene's first camera's (the former defaults without one); the view is the user's once
/// Position and FocalPoint differ.
sphcover::Camera PoseOf(const double position3[3],
  const double focalPoint3[3],
  const double viewUp3[3],
  double viewAngle,
  vtkFieldData* illumination,
  vtkFieldData* patches)
{
  sphcover::Camera scene;
  if (!vtkSceneCameras::Find(illumination, "", scene) && !vtkSceneCameras::Find(patches, "", scene))
  {
    scene.Position = glm::dvec3(0.0, 0.0, 1.0);
    scene.FocalPoint = glm::dvec3(0.0, 0.0, 0.0);
    scene.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
    scene.ViewAngle = 30.0;
  }
  const glm::dvec3 position(position3[0], position3[1], position3[2]);
  const glm::dvec3 focalPoint(focalPoint3[0], focalPoint3[1], focalPoint3[2]);
  const glm::dvec3 viewUp(viewUp3[0], viewUp3[1], viewUp3[2]);
  const bool ownView = position != focalPoint;
  const bool sceneOnly = !ownView && viewUp == glm::dvec3(0.0) && viewAngle == 0.0;
  sphcover::Camera camera;
  camera.Name = sceneOnly ? scene.Name : std::string();
  camera.Position = ownView ? position : scene.Position;
  camera.FocalPoint = ownView ? focalPoint : scene.FocalPoint;
  camera.ViewUp = viewUp != glm::dvec3(0.0) ? viewUp : scene.ViewUp;
  camera.ViewAngle = viewAngle != 0.0 ? viewAngle : scene.ViewAngle;
  return camera;
}

/// The renderer's budget from the filter's properties (MemoryLimit in MiB), clamped to what
/// size_t holds.
sphcover::RenderSettings RenderSettingsOf(vtkRadianceImageFilter* self)
{
  sphcover::RenderSettings settings;
  settings.SamplesPerPixel = self->GetSamplesPerPixel();
  settings.MemoryLimitBytes = static_cast<size_t>(
    std::min(self->GetMemoryLimit() * 1024.0 * 1024.0, static_cast<double>(SIZE_MAX / 2)));
  settings.MaximumSamples =
    static_cast<size_t>(std::min(self->GetMaximumSamples(), static_cast<double>(SIZE_MAX / 2)));
  return settings;
}

/// The radiance image of `camera` (paper §5.3), reporting progress up to 0.95; false, with a
/// warning or the error reported, when the rendering was aborted or failed.
bool RenderImage(vtkRadianceImageFilter* self,
  const sphcover::RadianceRenderer& renderer,
  const sphcover::Camera& camera,
  const sphcover::RenderSettings& settings,
  sphcover::RenderedImage& image)
{
  try
  {
    vtkStageProgress progress(self, "Radiance Image: rendering", 0.0, 0.95);
    const bool completed = renderer.Render(camera,
      settings,
      image,
      vtkSMPParallelFor::Make(),
      [&progress](double fraction) { return progress(fraction); });
    if (!completed)
    {
      vtkWarningWithObjectMacro(self, "Rendering aborted.");
      return false;
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << "Cannot render: " << e.what());
    return false;
  }
  return true;
}
}

vtkRadianceImageFilter::vtkRadianceImageFilter()
  : CameraNames(vtkStringArray::New())
{
  // ParaView's status bar labels progress with this text (vtkStageProgress.h).
  this->SetProgressText("Radiance Image");
  this->SetNumberOfInputPorts(2);
}

vtkRadianceImageFilter::~vtkRadianceImageFilter()
{
  this->CameraNames->Delete();
}

int vtkRadianceImageFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkDataSet");
  if (port == 1)
  {
    // Unconnected: the patches upstream of the illumination (vtkCoverPatches.h).
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

void vtkRadianceImageFilter::ImageSize(vtkInformationVector** inputVector,
  int& width,
  int& height) const
{
  width = this->Width;
  height = this->Height;
  if (width != 0 && height != 0)
  {
    return;
  }
  sphcover::Camera camera;
  if (!FindCameraInformation(inputVector, this->CameraName, camera))
  {
    camera.Width = 512;
    camera.Height = 512;
  }
  width = width != 0 ? width : camera.Width;
  height = height != 0 ? height : camera.Height;
}

int vtkRadianceImageFilter::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The cameras the scene announces, for ParaView's CameraName drop-down.
  this->CameraNames->Initialize();
  for (int port = 0; port < 2 && this->CameraNames->GetNumberOfValues() == 0; ++port)
  {
    vtkInformation* info = inputVector[port]->GetInformationObject(0);
    vtkDataObject* cameras = info ? info->Get(vtkSceneCameras::SCENE_CAMERAS()) : nullptr;
    for (const std::string& name :
      vtkSceneCameras::Names(cameras ? cameras->GetFieldData() : nullptr))
    {
      this->CameraNames->InsertNextValue(name);
    }
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int width = 0;
  int height = 0;
  this->ImageSize(inputVector, width, height);
  const int extent[6] = { 0, std::max(width, 1) - 1, 0, std::max(height, 1) - 1, 0, 0 };
  const double spacing[3] = { 1.0, 1.0, 1.0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  return 1;
}

std::string vtkRadianceImageFilter::ViewOf(vtkInformationVector** inputVector,
  vtkPolyData* illumination,
  vtkDataSet* patches,
  sphcover::Camera& camera,
  sphcover::RenderSettings& settings)
{
  if (!this->CameraName.empty())
  {
    if (!vtkSceneCameras::Find(illumination->GetFieldData(), this->CameraName, camera) &&
      !vtkSceneCameras::Find(patches->GetFieldData(), this->CameraName, camera))
    {
      return "no camera named '" + this->CameraName + "'; " +
        CameraList(illumination->GetFieldData());
    }
  }
  else
  {
    camera = PoseOf(this->Position,
      this->FocalPoint,
      this->ViewUp,
      this->ViewAngle,
      illumination->GetFieldData(),
      patches->GetFieldData());
  }
  // The size announced by RequestInformation, from the same pipeline information.
  this->ImageSize(inputVector, camera.Width, camera.Height);
  settings = RenderSettingsOf(this);
  if (!(this->ExposureFactor > 0.0 && std::isfinite(this->ExposureFactor)))
  {
    std::ostringstream text;
    text << "ExposureFactor " << this->ExposureFactor
         << " is not a finite number > 0 (the image would be black or undefined)";
    return text.str();
  }
  return sphcover::CheckCamera(camera, settings);
}

int vtkRadianceImageFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* illumination = vtkPolyData::GetData(inputVector[0], 0);
  vtkDataSet* patchesInput = vtkCoverPatches::Find(this, inputVector);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  // A piece of a solution kept in pieces holds some rows of the cover only, on every rank.
  if (vtkSphericalCoverArrays::IsShare(illumination))
  {
    output->Initialize();
    vtkErrorMacro(<< "Cannot render: the input is one rank's piece of a solution kept in pieces "
                     "(vtkPLightPropagationFilter's GatherSolution off), which holds only that "
                     "rank's rows of the cover; render it on the ranks that hold the pieces "
                     "(vtkPRadianceImageFilter) or gather the solution (GatherSolution on).");
    return 0;
  }
  // Pieces > 0 idle: the whole solution is piece 0 (vtkScenePieces.h), as under
  // `mpiexec -n K pvbatch --symmetric`, where rank 0 renders the image.
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, illumination);
  if (role != vtkScenePieces::Role::WholeScene)
  {
    output->Initialize();
    if (role == vtkScenePieces::Role::PartialScene)
    {
      vtkErrorMacro(<< "Cannot render: " << vtkScenePieces::PartialSceneError(outputVector) << ".");
      return 0;
    }
    return 1;
  }
  if (!illumination || !patchesInput)
  {
    vtkErrorMacro(<< "Cannot render: connect the illumination (vtkLightPropagationFilter's "
                     "output 0) to port 0 and, unless a Spherical Cover is upstream of it, the "
                     "patches (vtkIntervalSubdivisionFilter's output 0) to port 1 (Patches).");
    return 0;
  }
  // The solution's renderer (vtkSolutionRenderer: the same as a walk-through's, frame for
  // frame), then the one view.
  std::unique_ptr<sphcover::RadianceRenderer> renderer;
  std::string problem;
  try
  {
    renderer = vtkSolutionRenderer::New(illumination, patchesInput, problem);
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  if (!renderer)
  {
    vtkErrorMacro(<< "Cannot render: " << problem << ".");
    return 0;
  }

  sphcover::Camera camera;
  sphcover::RenderSettings settings;
  problem = this->ViewOf(inputVector, illumination, patchesInput, camera, settings);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot render: " << problem << ".");
    return 0;
  }

  sphcover::RenderedImage image;
  if (!RenderImage(this, *renderer, camera, settings, image))
  {
    return 0;
  }
  vtkSolutionRenderer::ToImageData(image, this->ExposureFactor, output);
  if (image.PaneLimitSamples > 0)
  {
    // Once per image, not per ray: the count is in the output's RenderPaneLimit.
    vtkWarningMacro(<< image.PaneLimitSamples << " of " << image.SampleCount
                    << " samples met more than " << sphcover::RadianceRenderer::MaxPanesPerSample
                    << " panes; the light behind them is left out (RenderPaneLimit).");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkRadianceImageFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CameraName: " << this->CameraName << "\n";
  os << indent << "Position: " << this->Position[0] << " " << this->Position[1] << " "
     << this->Position[2] << "\n";
  os << indent << "FocalPoint: " << this->FocalPoint[0] << " " << this->FocalPoint[1] << " "
     << this->FocalPoint[2] << "\n";
  os << indent << "ViewUp: " << this->ViewUp[0] << " " << this->ViewUp[1] << " " << this->ViewUp[2]
     << "\n";
  os << indent << "ViewAngle: " << this->ViewAngle << "\n";
  os << indent << "Width: " << this->Width << "\n";
  os << indent << "Height: " << this->Height << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "ExposureFactor: " << this->ExposureFactor << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "MaximumSamples: " << this->MaximumSamples << "\n";
}
