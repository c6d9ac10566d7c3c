// SPDX-License-Identifier: BSD-3-Clause
#include "vtkRadianceImageFilter.h"

#include "vtkCoverPatches.h"
#include "vtkIlluminationAdapter.h"
#include "vtkSMPParallelFor.h"
#include "vtkSceneCameras.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkStageProgress.h"
#include "vtkSurfaceGridAdapter.h"

#include "render/CharacteristicPointInterpolator.h"
#include "render/RadianceRenderer.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationDataObjectMetaDataKey.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <set>
#include <sstream>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkRadianceImageFilter);

namespace
{
/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1], as a byte.
unsigned char EncodeSRGB(double linear)
{
  const double c = std::clamp(linear, 0.0, 1.0);
  const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(255.0 * encoded));
}

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

/// The radiance image of the patches lit by `lit` seen by `camera` (paper §5.3), reporting
/// progress up to 0.95; false, with a warning or the error reported, when the inputs do not
/// belong to one solution, the rendering was aborted or failed.
bool RenderImage(vtkRadianceImageFilter* self,
  std::vector<sphcover::Patch> patches,
  vtkIlluminationAdapter::Illumination& lit,
  const sphcover::Camera& camera,
  const sphcover::RenderSettings& settings,
  sphcover::RenderedImage& image)
{
  try
  {
    // Every patch's surface must hold characteristic points, or the two inputs do not belong
    // to one solution.
    std::set<int> missing;
    for (const sphcover::Patch& patch : patches)
    {
      if (!lit.Interpolator.HasPoints(patch.SurfaceIndex))
      {
        missing.insert(patch.SurfaceIndex);
      }
    }
    if (!missing.empty())
    {
      vtkErrorWithObjectMacro(self,
        << "Cannot render: surface " << *missing.begin()
        << " of the patches has no characteristic point in the illumination; the "
           "two inputs do not come from one solution.");
      return false;
    }
    sphcover::RadianceRenderer renderer(std::move(patches),
      std::move(lit.Interpolator),
      std::move(lit.ExitantRadiance),
      std::move(lit.TwoSidedSurface));
    if (!lit.Direct.Empty())
    {
      // The lamps' direct light from its nodes, the rest interpolated (DirectIrradiance.h).
      renderer.SetDirectLight(std::move(lit.Direct));
    }
    if (!lit.Textures.empty())
    {
      // Textured surfaces: the texture at each visible point (paper §5.4).
      renderer.SetSurfaceTextures(std::move(lit.Textures));
    }
    if (lit.Directional)
    {
      // Non-diffuse surfaces: the BRDF toward the eye applied to the interpolated incident
      // radiance E of the cover (paper §5.3.1).
      renderer.SetDirectionalIllumination(std::move(*lit.Directional));
    }
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

/// The output image: per pixel Radiance, Depth and SurfaceId, and as its scalars the RGB bytes
/// of the exposed radiance, sRGB-encoded.
void WriteImage(const sphcover::RenderedImage& image, double exposure, vtkImageData* output)
{
  const vtkIdType pixels = static_cast<vtkIdType>(image.Width) * image.Height;
  output->Initialize();
  output->SetExtent(0, image.Width - 1, 0, image.Height - 1, 0, 0);
  output->SetSpacing(1.0, 1.0, 1.0);
  output->SetOrigin(0.0, 0.0, 0.0);
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName(names::Radiance);
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(pixels);
  std::copy(image.Radiance.begin(), image.Radiance.end(), radiance->GetPointer(0));
  vtkNew<vtkFloatArray> depth;
  depth->SetName(names::Depth);
  depth->SetNumberOfTuples(pixels);
  std::copy(image.Depth.begin(), image.Depth.end(), depth->GetPointer(0));
  vtkNew<vtkIntArray> surface;
  surface->SetName(names::SurfaceId);
  surface->SetNumberOfTuples(pixels);
  std::copy(image.SurfaceId.begin(), image.SurfaceId.end(), surface->GetPointer(0));
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName(names::RGB);
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(pixels);
  unsigned char* bytes = rgb->GetPointer(0);
  for (size_t k = 0; k < image.Radiance.size(); ++k)
  {
    bytes[k] = EncodeSRGB(exposure * image.Radiance[k]);
  }
  output->GetPointData()->AddArray(radiance);
  output->GetPointData()->AddArray(depth);
  output->GetPointData()->AddArray(surface);
  output->GetPointData()->SetScalars(rgb);
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

int vtkRadianceImageFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* illumination = vtkPolyData::GetData(inputVector[0], 0);
  vtkDataSet* patchesInput = vtkCoverPatches::Find(this, inputVector);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!illumination || !patchesInput)
  {
    vtkErrorMacro(<< "Cannot render: connect the illumination (vtkLightPropagationFilter's "
                     "output 0) to port 0 and, unless a Spherical Cover is upstream of it, the "
                     "patches (vtkIntervalSubdivisionFilter's output 0) to port 1 (Patches).");
    return 0;
  }
  vtkIlluminationAdapter::Illumination lit;
  std::string problem;
  if (!vtkIlluminationAdapter::Read(illumination, lit, problem))
  {
    vtkErrorMacro(<< "Cannot render: " << problem << ".");
    return 0;
  }

  sphcover::Scene scene;
  std::vector<sphcover::Patch> patches;
  if (!vtkSurfaceGridAdapter::ToPatches(patchesInput, scene, patches, problem))
  {
    vtkErrorMacro(<< "Cannot render: the patches on port 1 cannot be used: " << problem);
    return 0;
  }

  sphcover::Camera camera;
  if (!this->CameraName.empty())
  {
    if (!vtkSceneCameras::Find(illumination->GetFieldData(), this->CameraName, camera) &&
      !vtkSceneCameras::Find(patchesInput->GetFieldData(), this->CameraName, camera))
    {
      vtkErrorMacro(<< "Cannot render: no camera named '" << this->CameraName << "'; "
                    << CameraList(illumination->GetFieldData()) << ".");
      return 0;
    }
  }
  else
  {
    camera = PoseOf(this->Position,
      this->FocalPoint,
      this->ViewUp,
      this->ViewAngle,
      illumination->GetFieldData(),
      patchesInput->GetFieldData());
  }
  // The size announced by RequestInformation, from the same pipeline information.
  this->ImageSize(inputVector, camera.Width, camera.Height);
  const sphcover::RenderSettings settings = RenderSettingsOf(this);
  if (!(this->Exposure > 0.0 && std::isfinite(this->Exposure)))
  {
    vtkErrorMacro(<< "Cannot render: Exposure " << this->Exposure
                  << " is not a finite number > 0 (the image would be black or undefined).");
    return 0;
  }
  problem = sphcover::CheckCamera(camera, settings);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot render: " << problem << ".");
    return 0;
  }

  sphcover::RenderedImage image;
  if (!RenderImage(this, std::move(patches), lit, camera, settings, image))
  {
    return 0;
  }
  WriteImage(image, this->Exposure, output);
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
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB\n";
  os << indent << "MaximumSamples: " << this->MaximumSamples << "\n";
}
