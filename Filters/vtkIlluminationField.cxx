// SPDX-License-Identifier: BSD-3-Clause
#include "vtkIlluminationField.h"

#include "vtkCoverPatches.h"
#include "vtkIlluminationAdapter.h"
#include "vtkSMPParallelFor.h"
#include "vtkScenePieces.h"
#include "vtkSolutionRenderer.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkStageProgress.h"
#include "vtkSurfaceGridAdapter.h"

#include "render/BuriedPoints.h"
#include "render/RadianceRenderer.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
/// DisplayRGB: the radiance exposed by `scale` and sRGB-encoded, for display without a colour
/// map (ParaView's Map Scalars off).
vtkSmartPointer<vtkUnsignedCharArray> DisplayColours(vtkFloatArray* radiance, double scale)
{
  auto rgb = vtkSmartPointer<vtkUnsignedCharArray>::New();
  rgb->SetName(vtkSphericalCoverArrayNames::DisplayRGB);
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(radiance->GetNumberOfTuples());
  const float* in = radiance->GetPointer(0);
  unsigned char* out = rgb->GetPointer(0);
  for (vtkIdType k = 0; k < 3 * radiance->GetNumberOfTuples(); ++k)
  {
    // The encoding of vtkRadianceImageFilter's RGB: the field and the image show the same
    // colours.
    out[k] = vtkSolutionRenderer::EncodeSRGB(scale * in[k]);
  }
  return rgb;
}

/// The field's point arrays: position, Radiance, Normals, SurfaceId and UV, (n + 1)^2 points
/// per patch.
struct FieldPoints
{
  vtkNew<vtkPoints> Points;
  vtkNew<vtkFloatArray> Radiance;
  vtkNew<vtkFloatArray> Normals;
  vtkNew<vtkIntArray> SurfaceId;
  vtkNew<vtkDoubleArray> UV;

  explicit FieldPoints(vtkIdType count)
  {
    this->Points->SetDataTypeToDouble();
    this->Points->SetNumberOfPoints(count);
    this->Radiance->SetName(names::Radiance);
    this->Radiance->SetNumberOfComponents(3);
    this->Radiance->SetNumberOfTuples(count);
    this->Normals->SetName(names::Normals);
    this->Normals->SetNumberOfComponents(3);
    this->Normals->SetNumberOfTuples(count);
    this->SurfaceId->SetName(names::SurfaceId);
    this->SurfaceId->SetNumberOfTuples(count);
    this->UV->SetName(names::UV);
    this->UV->SetNumberOfComponents(2);
    this->UV->SetNumberOfTuples(count);
  }
};

/// Patch k's block of the field: its (n + 1) x (n + 1) parameter grid, each point with the
/// patch's position, normal and interpolated exitant radiance there (paper §5.3.2).
void SamplePatch(const sphcover::Patch& patch,
  size_t k,
  int n,
  const vtkIlluminationAdapter::Illumination& lit,
  FieldPoints& field)
{
  const vtkIdType perPatch = static_cast<vtkIdType>(n + 1) * (n + 1);
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      const double s = i == n ? 1.0 : static_cast<double>(i) / n;
      const double t = j == n ? 1.0 : static_cast<double>(j) / n;
      const vtkIdType id = static_cast<vtkIdType>(k) * perPatch + j * (n + 1) + i;
      const glm::dvec3 q = patch.Geometry.Evaluate(s, t);
      glm::dvec3 normal = glm::cross(patch.Geometry.PartialU(s, t), patch.Geometry.PartialV(s, t));
      const double length = glm::length(normal);
      normal = length > 0.0 ? normal / length : patch.Normal;
      const double u = patch.Domain.U0 + s * (patch.Domain.U1 - patch.Domain.U0);
      const double v = patch.Domain.V0 + t * (patch.Domain.V1 - patch.Domain.V0);
      // As the render (RadianceRenderer::SurfaceRadiance): the rest interpolated, the lamps'
      // direct light from its nodes.
      // A textured surface's texture at (u, v) (paper §5.4).
      const glm::dvec3 l = sphcover::TexturedRadiance(lit.Textures,
        patch.SurfaceIndex,
        u,
        v,
        sphcover::InterpolateRadiance(
          lit.Interpolator, lit.ExitantRadiance, patch.SurfaceIndex, u, v) +
          lit.Direct.At(lit.Interpolator, patch.SurfaceIndex, u, v));
      field.Points->SetPoint(id, q.x, q.y, q.z);
      field.Radiance->SetTypedTuple(id,
        std::array<float, 3>{
          static_cast<float>(l.x), static_cast<float>(l.y), static_cast<float>(l.z) }
          .data());
      field.Normals->SetTypedTuple(id,
        std::array<float, 3>{
          static_cast<float>(normal.x), static_cast<float>(normal.y), static_cast<float>(normal.z) }
          .data());
      field.SurfaceId->SetValue(id, patch.SurfaceIndex);
      field.UV->SetTypedComponent(id, 0, u);
      field.UV->SetTypedComponent(id, 1, v);
    }
  }
}

/// Every patch's block of the field, in ten batches reporting progress up to 0.9; false, with
/// a warning or the error reported, when aborted or failed.
bool SampleField(vtkIlluminationField* self,
  const std::vector<sphcover::Patch>& patches,
  int n,
  const vtkIlluminationAdapter::Illumination& lit,
  FieldPoints& field)
{
  try
  {
    // Each patch writes its own block of points: no shared state, any thread count.
    const sphcover::ParallelFor parallelFor = vtkSMPParallelFor::Make();
    const size_t batch = std::max<size_t>(1, patches.size() / 10);
    vtkStageProgress progress(self, "Illumination Field: interpolating", 0.0, 0.9);
    for (size_t first = 0; first < patches.size(); first += batch)
    {
      const size_t last = std::min(patches.size(), first + batch);
      parallelFor(last - first,
        [&](size_t begin, size_t end)
        {
          for (size_t k = first + begin; k < first + end; ++k)
          {
            SamplePatch(patches[k], k, n, lit, field);
          }
        });
      if (!progress(static_cast<double>(last) / static_cast<double>(patches.size())))
      {
        vtkWarningWithObjectMacro(self, "Illumination field aborted.");
        return false;
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(self, << "Cannot build the illumination field: " << e.what());
    return false;
  }
  return true;
}

/// The output: the field's points, n x n quads per patch with their PatchId; DisplayRGB (the
/// radiance times `scale`) the active scalars.
void WriteField(FieldPoints& field, vtkIdType patchCount, int n, double scale, vtkPolyData* output)
{
  const vtkIdType perPatch = static_cast<vtkIdType>(n + 1) * (n + 1);
  vtkNew<vtkCellArray> quads;
  quads->AllocateExact(patchCount * n * n, patchCount * n * n * 4);
  vtkNew<vtkIntArray> patchId;
  patchId->SetName(names::PatchId);
  patchId->SetNumberOfTuples(patchCount * n * n);
  vtkIdType cell = 0;
  for (vtkIdType k = 0; k < patchCount; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const vtkIdType v00 = k * perPatch + j * (n + 1) + i;
        // Counter-clockwise in (u, v): the quad's normal is the patch's front side.
        const vtkIdType quad[4] = { v00, v00 + 1, v00 + n + 2, v00 + n + 1 };
        quads->InsertNextCell(4, quad);
        patchId->SetValue(cell++, static_cast<int>(k));
      }
    }
  }
  output->Initialize();
  output->SetPoints(field.Points);
  output->SetPolys(quads);
  output->GetPointData()->AddArray(field.Radiance);
  output->GetPointData()->SetNormals(field.Normals);
  output->GetPointData()->AddArray(field.SurfaceId);
  output->GetPointData()->AddArray(field.UV);
  output->GetPointData()->SetScalars(DisplayColours(field.Radiance, scale));
  output->GetCellData()->AddArray(patchId);
}
}

vtkStandardNewMacro(vtkIlluminationField);

vtkIlluminationField::vtkIlluminationField()
{
  // ParaView's status bar labels progress with this text (vtkStageProgress.h).
  this->SetProgressText("Illumination Field");
  this->SetNumberOfInputPorts(2);
}

vtkIlluminationField::~vtkIlluminationField() = default;

int vtkIlluminationField::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkDataSet");
  if (port == 1)
  {
    // Unconnected: the patches upstream of the illumination (vtkCoverPatches.h).
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkIlluminationField::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* illumination = vtkPolyData::GetData(inputVector[0], 0);
  vtkDataSet* patchesInput = vtkCoverPatches::Find(this, inputVector);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  // Pieces > 0 idle: the whole solution is piece 0 (vtkScenePieces.h), as under
  // `mpiexec -n K pvbatch --symmetric`.
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, illumination);
  if (role != vtkScenePieces::Role::WholeScene)
  {
    output->Initialize();
    if (role == vtkScenePieces::Role::PartialScene)
    {
      vtkErrorMacro(<< "Cannot build the illumination field: "
                    << vtkScenePieces::PartialSceneError(outputVector) << ".");
      return 0;
    }
    return 1;
  }
  if (!illumination || !patchesInput)
  {
    vtkErrorMacro(<< "Cannot build the illumination field: connect the illumination "
                     "(vtkLightPropagationFilter's output 0) to port 0 and, unless a Spherical "
                     "Cover is upstream of it, the patches (vtkIntervalSubdivisionFilter's "
                     "output 0) to port 1 (Patches).");
    return 0;
  }
  vtkIlluminationAdapter::Illumination lit;
  std::string problem;
  // View-independent: the emission and diffuse part only (the directional part of paper
  // §5.3.1 needs the eye), so the cover and E are not read.
  if (!vtkIlluminationAdapter::Read(illumination, lit, problem, false))
  {
    vtkErrorMacro(<< "Cannot build the illumination field: " << problem << ".");
    return 0;
  }
  sphcover::Scene scene;
  std::vector<sphcover::Patch> patches;
  if (!vtkSurfaceGridAdapter::ToPatches(patchesInput, scene, patches, problem))
  {
    vtkErrorMacro(<< "Cannot build the illumination field: the patches on port 1 cannot be "
                     "used: "
                  << problem);
    return 0;
  }
  for (const sphcover::Patch& patch : patches)
  {
    if (!lit.Interpolator.HasPoints(patch.SurfaceIndex))
    {
      vtkErrorMacro(<< "Cannot build the illumination field: surface " << patch.SurfaceIndex
                    << " of the patches has no characteristic point in the illumination; the "
                       "two inputs do not come from one solution.");
      return 0;
    }
  }

  try
  {
    // As the render does (vtkRadianceImageFilter): no point takes after a buried one, and the
    // points' I less their direct light is what is interpolated (SamplePatch).
    lit.Interpolator.SetExcludedPoints(sphcover::BuriedPoints(lit.Interpolator, patches));
    lit.ExitantRadiance = lit.Direct.Rest(std::move(lit.ExitantRadiance));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Cannot build the illumination field: " << e.what());
    return 0;
  }

  const int n = this->Resolution;
  const vtkIdType perPatch = static_cast<vtkIdType>(n + 1) * (n + 1);
  const vtkIdType patchCount = static_cast<vtkIdType>(patches.size());
  FieldPoints field(patchCount * perPatch);
  if (!SampleField(this, patches, n, lit, field))
  {
    return 0;
  }
  WriteField(field, patchCount, n, std::exp2(this->ExposureStops), output);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkIlluminationField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "ExposureStops: " << this->ExposureStops << "\n";
}
