// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSphericalCoverArrays.h"

#include "vtkNamedArrays.h"
#include "vtkSphericalCoverArrayNames.h"

#include "cover/SphericalCover.h"

#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkPointData.h>
#include <vtkTypeUInt16Array.h>
#include <vtkTypeUInt32Array.h>
#include <vtkTypeUInt64Array.h>
#include <vtkTypeUInt8Array.h>

#include <cstring>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
/// Copies `values` into a new array of the matching VTK type, then lets them go.
template<typename ArrayType, typename Value>
vtkSmartPointer<ArrayType> RawArray(const char* name, int components, std::vector<Value>& values)
{
  const size_t tuples = values.size();
  auto array = vtkNamedArrays::New<ArrayType>(name, components, static_cast<vtkIdType>(tuples));
  if (tuples > 0)
  {
    std::memcpy(array->GetPointer(0), values.data(), tuples * sizeof(Value));
  }
  std::vector<Value>().swap(values);
  return array;
}

/// The raw values of a field array of exactly this type and component count, or false.
template<typename ArrayType, typename Value>
bool ReadRaw(vtkFieldData* fd, const char* name, int components, std::vector<Value>& values)
{
  auto* array = ArrayType::SafeDownCast(fd->GetAbstractArray(name));
  if (!array || array->GetNumberOfComponents() != components)
  {
    return false;
  }
  const size_t tuples = static_cast<size_t>(array->GetNumberOfTuples());
  values.resize(tuples);
  static_assert(sizeof(Value) % sizeof(typename ArrayType::ValueType) == 0, "layout");
  if (tuples > 0)
  {
    std::memcpy(values.data(), array->GetPointer(0), tuples * sizeof(Value));
  }
  return true;
}
}

void vtkSphericalCoverArrays::Store(const sphcover::SphericalCover& cover, vtkDataSet* output)
{
  Store(cover.ExportArrays(), output);
}

void vtkSphericalCoverArrays::Store(sphcover::SphericalCover::Arrays arrays, vtkDataSet* output)
{
  vtkFieldData* fd = output->GetFieldData();
  auto grid = vtkNamedArrays::Int(names::CoverGrid, 6, 1);
  const int gridValues[6] = { arrays.ThetaBins,
    arrays.PhiBins,
    arrays.SamplesTheta,
    arrays.SamplesPhi,
    arrays.Fill,
    arrays.UnoccludedKnown ? 1 : 0 };
  const char* gridNames[6] = {
    "ThetaBins", "PhiBins", "SamplesTheta", "SamplesPhi", "Fill", "UnoccludedKnown"
  };
  for (int k = 0; k < 6; ++k)
  {
    grid->SetComponentName(k, gridNames[k]);
    grid->SetComponent(0, k, gridValues[k]);
  }
  fd->AddArray(grid);
  fd->AddArray(RawArray<vtkTypeUInt64Array>(names::CoverRowOffsets, 1, arrays.RowOffsets));
  fd->AddArray(RawArray<vtkTypeUInt32Array>(names::CoverEntries, 2, arrays.Entries));
  fd->AddArray(RawArray<vtkFloatArray>(names::CoverUnoccluded, 1, arrays.Unoccluded));
  fd->AddArray(RawArray<vtkTypeUInt16Array>(names::CoverStrips, 3, arrays.Strips));
  fd->AddArray(RawArray<vtkFloatArray>(names::CoverStripDepths, 1, arrays.StripDepths));
  if (!arrays.Measures.empty())
  {
    fd->AddArray(RawArray<vtkFloatArray>(names::CoverMeasures, 1, arrays.Measures));
  }
  if (!arrays.Layers.empty())
  {
    fd->AddArray(RawArray<vtkTypeUInt8Array>(names::CoverLayers, 1, arrays.Layers));
    fd->AddArray(RawArray<vtkFloatArray>(names::CoverFilters, 1, arrays.Filters));
    fd->AddArray(RawArray<vtkFloatArray>(names::CoverTransmittances, 1, arrays.Transmittances));
  }
}

std::string vtkSphericalCoverArrays::Load(vtkDataSet* input,
  sphcover::SphericalCover& cover,
  bool share)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  vtkDataArray* grid = fd ? fd->GetArray(names::CoverGrid) : nullptr;
  vtkDataArray* area = input ? input->GetPointData()->GetArray(names::Area) : nullptr;
  if (!grid || grid->GetNumberOfComponents() != 6 || grid->GetNumberOfTuples() != 1 || !area)
  {
    return "the input holds no spherical cover (run vtkSphericalCoverFilter first)";
  }
  if (!share && fd->GetAbstractArray(names::CoverRowShare))
  {
    return "the input holds one rank's share of a spherical cover's rows (CoverRowShare: "
           "vtkSphericalCoverFilter with GatherRows off, or a solution kept in pieces, "
           "vtkLightPropagationFilter with GatherSolution off), which only the light propagation "
           "takes; gather the rows (GatherRows and GatherSolution on) or join the pieces";
  }
  sphcover::SphericalCover::Arrays arrays;
  arrays.ThetaBins = static_cast<int>(grid->GetComponent(0, 0));
  arrays.PhiBins = static_cast<int>(grid->GetComponent(0, 1));
  arrays.SamplesTheta = static_cast<int>(grid->GetComponent(0, 2));
  arrays.SamplesPhi = static_cast<int>(grid->GetComponent(0, 3));
  arrays.Fill = static_cast<int>(grid->GetComponent(0, 4));
  arrays.UnoccludedKnown = grid->GetComponent(0, 5) != 0.0;
  if (!ReadRaw<vtkTypeUInt64Array>(fd, names::CoverRowOffsets, 1, arrays.RowOffsets) ||
    !ReadRaw<vtkTypeUInt32Array>(fd, names::CoverEntries, 2, arrays.Entries) ||
    !ReadRaw<vtkFloatArray>(fd, names::CoverUnoccluded, 1, arrays.Unoccluded) ||
    !ReadRaw<vtkTypeUInt16Array>(fd, names::CoverStrips, 3, arrays.Strips) ||
    !ReadRaw<vtkFloatArray>(fd, names::CoverStripDepths, 1, arrays.StripDepths))
  {
    return "the cover's field arrays are missing or of the wrong type";
  }
  // Measured regions (SphericalCover.h) are optional: without them, the cells' measures.
  if (fd->GetAbstractArray(names::CoverMeasures) &&
    !ReadRaw<vtkFloatArray>(fd, names::CoverMeasures, 1, arrays.Measures))
  {
    return "the cover's field array " + std::string(names::CoverMeasures) +
      " is not a float array of one component";
  }
  // Panes (SphericalCover.h, "Panes"): the three arrays together or none.
  if (fd->GetAbstractArray(names::CoverLayers) || fd->GetAbstractArray(names::CoverFilters) ||
    fd->GetAbstractArray(names::CoverTransmittances))
  {
    if (!ReadRaw<vtkTypeUInt8Array>(fd, names::CoverLayers, 1, arrays.Layers) ||
      !ReadRaw<vtkFloatArray>(fd, names::CoverFilters, 1, arrays.Filters) ||
      !ReadRaw<vtkFloatArray>(fd, names::CoverTransmittances, 1, arrays.Transmittances))
    {
      return "the cover's pane arrays (" + std::string(names::CoverLayers) + ", " +
        names::CoverFilters + ", " + names::CoverTransmittances +
        ") are incomplete or of the wrong type";
    }
  }
  arrays.Areas.resize(static_cast<size_t>(area->GetNumberOfTuples()));
  for (vtkIdType k = 0; k < area->GetNumberOfTuples(); ++k)
  {
    arrays.Areas[static_cast<size_t>(k)] = area->GetComponent(k, 0);
  }
  return cover.ImportArrays(std::move(arrays));
}

bool vtkSphericalCoverArrays::IsCoverArray(const char* name)
{
  if (!name)
  {
    return false;
  }
  for (const char* cover : { names::CoverGrid,
         names::CoverRowOffsets,
         names::CoverEntries,
         names::CoverUnoccluded,
         names::CoverStrips,
         names::CoverStripDepths,
         names::CoverMeasures,
         names::CoverLayers,
         names::CoverFilters,
         names::CoverTransmittances })
  {
    if (std::strcmp(name, cover) == 0)
    {
      return true;
    }
  }
  return false;
}

void vtkSphericalCoverArrays::MarkShare(vtkDataObject* output, int rank, int ranks)
{
  auto marker = vtkNamedArrays::Int(names::CoverRowShare, 2, 1);
  marker->SetComponent(0, 0, rank);
  marker->SetComponent(0, 1, ranks);
  output->GetFieldData()->AddArray(marker);
}

bool vtkSphericalCoverArrays::IsShare(vtkDataObject* data)
{
  return data && data->GetFieldData()->GetAbstractArray(names::CoverRowShare);
}
