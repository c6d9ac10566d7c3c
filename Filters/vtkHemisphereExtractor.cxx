// SPDX-License-Identifier: BSD-3-Clause
#include "vtkHemisphereExtractor.h"

#include "vtkNamedArrays.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"

#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "math/Constants.h"

#include <vtkAlgorithmOutput.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDemandDrivenPipeline.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <cmath>
#include <exception>
#include <limits>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkHemisphereExtractor);

namespace
{
/// The bins of the cover held by `input` (its `CoverGrid` field array), false if it holds none.
bool CoverBins(vtkDataObject* input, int& thetaBins, int& phiBins)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  vtkDataArray* grid = fd ? fd->GetArray(names::CoverGrid) : nullptr;
  if (!grid || grid->GetNumberOfComponents() < 2 || grid->GetNumberOfTuples() != 1)
  {
    return false;
  }
  thetaBins = static_cast<int>(grid->GetComponent(0, 0));
  phiBins = static_cast<int>(grid->GetComponent(0, 1));
  return thetaBins > 0 && phiBins > 0;
}

/// A point-data vector array of `input` with 3 components and one tuple per cover point.
vtkDataArray* FrameArray(vtkDataSet* input, const char* name, vtkIdType count)
{
  vtkDataArray* array = input->GetPointData()->GetArray(name);
  return array && array->GetNumberOfComponents() == 3 && array->GetNumberOfTuples() == count
    ? array
    : nullptr;
}

/// The cover held by `input`, or why it holds none.
std::string LoadCover(vtkDataSet* input, sphcover::SphericalCover& cover)
{
  try
  {
    return vtkSphericalCoverArrays::Load(input, cover);
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
}

/// The cell arrays both outputs share, one value per cell of the cover's grid.
struct HemisphereCells
{
  vtkSmartPointer<vtkIntArray> Source;
  vtkSmartPointer<vtkIntArray> Surface;
  vtkSmartPointer<vtkIntArray> SurfaceName; // null when the input has no SurfaceNameId
  vtkSmartPointer<vtkFloatArray> Depth;
  vtkSmartPointer<vtkDoubleArray> Measure;

  void AddTo(vtkCellData* cd) const
  {
    cd->SetScalars(this->Source);
    cd->AddArray(this->Surface);
    if (this->SurfaceName)
    {
      cd->AddArray(this->SurfaceName);
    }
    cd->AddArray(this->Depth);
    cd->AddArray(this->Measure);
  }
};

/// The strips of every source of row `receiver` painted back into the grid's cells (source,
/// its surface and surface name, depth; no source: NoSource, -1, NaN), with each cell's
/// projected solid angle.
HemisphereCells PaintReceiverStrips(const sphcover::SphericalCover& cover,
  size_t receiver,
  vtkDataArray* surfaceOfPatch,
  vtkDataArray* nameOfPatch)
{
  const sphcover::HemisphereGrid& grid = cover.Grid();
  const vtkIdType cells = grid.CellCount();
  HemisphereCells out;
  out.Source = vtkNamedArrays::Int(names::Source, 1, cells);
  out.Surface = vtkNamedArrays::Int(names::SurfaceId, 1, cells);
  out.SurfaceName = nameOfPatch ? vtkNamedArrays::Int(names::SurfaceNameId, 1, cells) : nullptr;
  out.Depth = vtkNamedArrays::New<vtkFloatArray>(names::R, 1, cells);
  out.Measure = vtkNamedArrays::Double(names::ProjectedSolidAngle, 1, cells);
  out.Source->FillValue(sphcover::RBuffer::NoSource);
  out.Surface->FillValue(-1);
  if (out.SurfaceName)
  {
    out.SurfaceName->FillValue(-1);
  }
  out.Depth->FillValue(std::numeric_limits<float>::quiet_NaN());
  for (vtkIdType cell = 0; cell < cells; ++cell)
  {
    out.Measure->SetValue(cell, grid.CellMeasureOfCell(static_cast<int>(cell)));
  }
  for (size_t e = cover.EntryBegin(receiver); e < cover.EntryEnd(receiver); ++e)
  {
    const uint32_t j = cover.EntryAt(e).Source;
    const int surfaceId =
      surfaceOfPatch ? static_cast<int>(surfaceOfPatch->GetComponent(j, 0)) : -1;
    const int nameId = nameOfPatch ? static_cast<int>(nameOfPatch->GetComponent(j, 0)) : -1;
    for (size_t s = cover.StripBegin(e); s < cover.StripEnd(e); ++s)
    {
      const sphcover::SphericalCover::Strip& strip = cover.StripAt(s);
      for (int column = strip.PhiBegin; column < strip.PhiEnd; ++column)
      {
        const vtkIdType cell = grid.CellIndex(strip.Row, column);
        out.Source->SetValue(cell, static_cast<int>(j));
        out.Surface->SetValue(cell, surfaceId);
        if (out.SurfaceName)
        {
          out.SurfaceName->SetValue(cell, nameId);
        }
        out.Depth->SetValue(cell, cover.StripDepth(s));
      }
    }
  }
  return out;
}

/// Output 0: cell (column, row) of the image is the cover's cell row * PhiBins + column,
/// because VTK numbers an image's cells with x (phi) fastest.
void WriteCellImage(const sphcover::HemisphereGrid& grid,
  const HemisphereCells& cells,
  vtkImageData* image,
  vtkInformation* imageInfo)
{
  image->SetExtent(0, grid.PhiBins(), 0, grid.ThetaBins(), 0, 0);
  image->SetSpacing(grid.PhiStep(), grid.ThetaStep(), 1.0);
  image->SetOrigin(0.0, 0.0, 0.0);
  cells.AddTo(image->GetCellData());
  // The data pass may see a cover whose bins differ from what RequestInformation published
  // (when it could not read them); the extent of the data is the truth.
  imageInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), image->GetExtent(), 6);
}

/// The frame the cover was built in at characteristic point `id`. HemisphereFrame is the
/// Core's own convention (B = N x T, T re-orthogonalised), so the mesh cannot drift from it.
sphcover::HemisphereFrame FrameOfPoint(vtkDataSet* input,
  vtkDataArray* normals,
  vtkDataArray* tangents,
  vtkIdType id)
{
  double p[3];
  input->GetPoint(id, p);
  double n[3];
  double t[3];
  normals->GetTuple(id, n);
  tangents->GetTuple(id, t);
  const glm::dvec3 tangent(t[0], t[1], t[2]);
  return sphcover::HemisphereFrame::FromPartials(
    glm::dvec3(p[0], p[1], p[2]), glm::dvec3(n[0], n[1], n[2]), tangent, tangent);
}

/// Output 1: the 3-D hemisphere of `radius` around the frame's origin, one cell per cell of
/// the grid in the cover's order.
void BuildHemisphereMesh(const sphcover::HemisphereGrid& grid,
  const sphcover::HemisphereFrame& frame,
  double radius,
  const HemisphereCells& cells,
  vtkPolyData* mesh)
{
  const int thetaBins = grid.ThetaBins();
  const int phiBins = grid.PhiBins();
  // Points: the pole, then rows 1..ThetaBins of PhiBins points each (phi wraps around).
  const vtkIdType pointCount = 1 + static_cast<vtkIdType>(thetaBins) * phiBins;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(pointCount);
  auto pointNormals = vtkNamedArrays::Double(names::Normals, 3, pointCount);
  auto place = [&](vtkIdType id, const glm::dvec3& local)
  {
    const glm::dvec3 direction = frame.ToWorld(local);
    const glm::dvec3 x = frame.Origin + radius * direction;
    points->SetPoint(id, x.x, x.y, x.z);
    pointNormals->SetTuple3(id, direction.x, direction.y, direction.z);
  };
  place(0, glm::dvec3(0.0, 0.0, 1.0));
  auto pointOf = [phiBins](int row, int column) -> vtkIdType
  { return 1 + static_cast<vtkIdType>(row - 1) * phiBins + (column % phiBins); };
  for (int row = 1; row <= thetaBins; ++row)
  {
    for (int column = 0; column < phiBins; ++column)
    {
      place(pointOf(row, column),
        sphcover::HemisphereGrid::LocalDirection(grid.RowTheta(row), column * grid.PhiStep()));
    }
  }
  // Cells in the cover's order; counter-clockwise seen from outside (theta then phi), so their
  // normals point away from the centre like the point normals.
  const vtkIdType cellCount = grid.CellCount();
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(cellCount, 4 * cellCount);
  for (int row = 0; row < thetaBins; ++row)
  {
    for (int column = 0; column < phiBins; ++column)
    {
      if (row == 0)
      {
        const vtkIdType ids[3] = { 0, pointOf(1, column), pointOf(1, column + 1) };
        polys->InsertNextCell(3, ids);
      }
      else
      {
        const vtkIdType ids[4] = { pointOf(row, column),
          pointOf(row + 1, column),
          pointOf(row + 1, column + 1),
          pointOf(row, column + 1) };
        polys->InsertNextCell(4, ids);
      }
    }
  }
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetNormals(pointNormals);
  cells.AddTo(mesh->GetCellData());
}
}

vtkHemisphereExtractor::vtkHemisphereExtractor()
{
  // ParaView's status bar labels progress with this text, not the class name.
  this->SetProgressText("Hemisphere Extractor");
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkHemisphereExtractor::~vtkHemisphereExtractor() = default;

vtkImageData* vtkHemisphereExtractor::GetImageOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkPolyData* vtkHemisphereExtractor::GetMeshOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkHemisphereExtractor::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkHemisphereExtractor::FillOutputPortInformation(int port, vtkInformation* info)
{
  // The executive creates each output from its type name (REQUEST_DATA_OBJECT).
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

vtkTypeBool vtkHemisphereExtractor::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(request, inputVector, outputVector);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

int vtkHemisphereExtractor::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The image's extent is the cover's grid, which only the input's data knows. Bring the input
  // up to date now (a no-op when it already is; it reuses the previous pass's piece request, so
  // the later data pass finds it current and does not execute it again), then read the grid.
  vtkAlgorithmOutput* connection = this->GetInputConnection(0, 0);
  if (connection && connection->GetProducer())
  {
    connection->GetProducer()->Update(connection->GetIndex());
  }
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkDataObject* input = inInfo ? inInfo->Get(vtkDataObject::DATA_OBJECT()) : nullptr;

  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int thetaBins = 0;
  int phiBins = 0;
  if (CoverBins(input, thetaBins, phiBins))
  {
    const int extent[6] = { 0, phiBins, 0, thetaBins, 0, 0 };
    const double spacing[3] = { sphcover::TwoPi / phiBins, sphcover::HalfPi / thetaBins, 1.0 };
    const double origin[3] = { 0.0, 0.0, 0.0 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
    outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  }
  else
  {
    // No cover: an empty image; RequestData reports the problem (one message, one place).
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  }
  return 1;
}

int vtkHemisphereExtractor::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* mesh = vtkPolyData::GetData(outputVector, 1);
  image->Initialize();
  mesh->Initialize();

  // Pieces > 0 idle: the whole scene is piece 0 (vtkScenePieces.h).
  const vtkScenePieces::Role role = vtkScenePieces::Classify(outputVector, input);
  if (role != vtkScenePieces::Role::WholeScene)
  {
    if (role == vtkScenePieces::Role::PartialScene)
    {
      vtkErrorMacro(<< "Cannot extract a hemisphere: "
                    << vtkScenePieces::PartialSceneError(outputVector) << ".");
      return 0;
    }
    return 1;
  }

  if (this->Radius < 0.0 || !std::isfinite(this->Radius))
  {
    vtkErrorMacro(<< "Radius must be >= 0 (0: automatic), got " << this->Radius << ".");
    return 0;
  }
  sphcover::SphericalCover cover;
  const std::string problem = LoadCover(input, cover);
  if (!problem.empty())
  {
    vtkErrorMacro(<< "Cannot extract a hemisphere: " << problem << ".");
    return 0;
  }
  const vtkIdType count = static_cast<vtkIdType>(cover.PatchCount());
  if (this->PointId < 0 || this->PointId >= count)
  {
    vtkErrorMacro(<< "PointId " << this->PointId << " is out of range: the cover has " << count
                  << " characteristic points (0 to " << count - 1 << ").");
    return 0;
  }
  vtkDataArray* normals = FrameArray(input, names::Normals, count);
  vtkDataArray* tangents = FrameArray(input, names::Tangents, count);
  if (!normals || !tangents || input->GetNumberOfPoints() != count)
  {
    vtkErrorMacro(<< "Cannot extract a hemisphere: the input lacks the point arrays "
                  << names::Normals << " and " << names::Tangents
                  << " (3 components, one per characteristic point) of vtkSphericalCoverFilter.");
    return 0;
  }
  vtkDataArray* surfaceOfPatch = input->GetPointData()->GetArray(names::SurfaceId);
  // Surfaces loaded from one entry (the 32 Bezier surfaces of a .bpt teapot) share a name: the
  // name id colours a whole object alike.
  vtkDataArray* nameOfPatch = input->GetPointData()->GetArray(names::SurfaceNameId);

  const HemisphereCells cells =
    PaintReceiverStrips(cover, static_cast<size_t>(this->PointId), surfaceOfPatch, nameOfPatch);
  WriteCellImage(cover.Grid(), cells, image, outputVector->GetInformationObject(0));

  double radius = this->Radius;
  if (radius == 0.0)
  {
    radius = AutomaticRadiusFraction * input->GetLength();
    if (!(radius > 0.0))
    {
      radius = 1.0; // a single point has no extent to scale by
    }
  }
  BuildHemisphereMesh(
    cover.Grid(), FrameOfPoint(input, normals, tangents, this->PointId), radius, cells, mesh);
  return 1;
}

void vtkHemisphereExtractor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PointId: " << this->PointId << "\n";
  os << indent << "Radius: " << this->Radius << (this->Radius == 0.0 ? " (automatic)" : "") << "\n";
}
