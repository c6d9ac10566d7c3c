// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSolutionRenderer.h"

#include "vtkIlluminationAdapter.h"
#include "vtkNamedArrays.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSurfaceGridAdapter.h"

#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace names = vtkSphericalCoverArrayNames;

std::unique_ptr<sphcover::RadianceRenderer> vtkSolutionRenderer::New(vtkPolyData* illumination,
  vtkDataSet* patchesInput,
  std::string& error,
  bool piece)
{
  vtkIlluminationAdapter::Illumination lit;
  if (!vtkIlluminationAdapter::Read(illumination, lit, error, true, piece))
  {
    return nullptr;
  }
  sphcover::Scene scene;
  std::vector<sphcover::Patch> patches;
  if (!vtkSurfaceGridAdapter::ToPatches(patchesInput, scene, patches, error))
  {
    error = "the patches cannot be used: " + error;
    return nullptr;
  }
  // Every patch's surface must hold characteristic points, or the two inputs do not belong to
  // one solution.
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
    error = "surface " + std::to_string(*missing.begin()) +
      " of the patches has no characteristic point in the illumination; the two inputs do not "
      "come from one solution";
    return nullptr;
  }
  std::vector<glm::dvec3> transmittance =
    vtkSurfaceGridAdapter::TransmittanceOfSurfaces(scene, patches);
  auto renderer = std::make_unique<sphcover::RadianceRenderer>(std::move(patches),
    std::move(lit.Interpolator),
    std::move(lit.ExitantRadiance),
    std::move(lit.TwoSidedSurface));
  // Panes (paper §5.4): what lies behind them shows through, scaled.
  renderer->SetSurfaceTransmittance(std::move(transmittance));
  if (!lit.Direct.Empty())
  {
    // The lamps' direct light from its nodes, the rest interpolated (DirectIrradiance.h).
    renderer->SetDirectLight(std::move(lit.Direct));
  }
  if (!lit.Textures.empty())
  {
    // Textured surfaces: the texture at each visible point (paper §5.4).
    renderer->SetSurfaceTextures(std::move(lit.Textures));
  }
  if (lit.Directional)
  {
    // Non-diffuse surfaces: the BRDF toward the eye applied to the interpolated incident
    // radiance E of the cover (paper §5.3.1).
    renderer->SetDirectionalIllumination(std::move(*lit.Directional));
  }
  return renderer;
}

unsigned char vtkSolutionRenderer::EncodeSRGB(double linear)
{
  const double c = std::clamp(linear, 0.0, 1.0);
  const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(255.0 * encoded));
}

void vtkSolutionRenderer::ToImageData(const sphcover::RenderedImage& image,
  double exposureFactor,
  vtkImageData* output)
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
    bytes[k] = EncodeSRGB(exposureFactor * image.Radiance[k]);
  }
  output->GetPointData()->AddArray(radiance);
  output->GetPointData()->AddArray(depth);
  output->GetPointData()->AddArray(surface);
  output->GetPointData()->SetScalars(rgb);
  // The samples that met more panes than the renderer follows (their light behind left out).
  auto paneLimit = vtkNamedArrays::Double(vtkSphericalCoverArrayNames::RenderPaneLimit, 2, 1);
  const double samples = static_cast<double>(image.SampleCount);
  paneLimit->SetComponent(0, 0, static_cast<double>(image.PaneLimitSamples));
  paneLimit->SetComponent(
    0, 1, samples > 0.0 ? static_cast<double>(image.PaneLimitSamples) / samples : 0.0);
  output->GetFieldData()->AddArray(paneLimit);
}
