// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSceneSettingsArray.h"

#include "vtkNamedArrays.h"
#include "vtkSphericalCoverArrayNames.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>

namespace names = vtkSphericalCoverArrayNames;

vtkSmartPointer<vtkDoubleArray> vtkSceneSettingsArray::New(const sphcover::SceneSettings& settings)
{
  auto array = vtkNamedArrays::Double(names::SceneSettings, 5, 1);
  array->SetComponentName(0, "theta_bins");
  array->SetComponentName(1, "phi_bins");
  array->SetComponentName(2, "max_level");
  array->SetComponentName(3, "tolerance");
  array->SetComponentName(4, "min_patch_size");
  const double values[5] = { double(settings.ThetaBins),
    double(settings.PhiBins),
    double(settings.MaxLevel),
    settings.Tolerance,
    settings.MinPatchSize };
  array->SetTuple(0, values);
  return array;
}

sphcover::SceneSettings vtkSceneSettingsArray::Read(vtkFieldData* fd)
{
  sphcover::SceneSettings settings;
  vtkDataArray* values = fd ? fd->GetArray(names::SceneSettings) : nullptr;
  // Four components in files written before min_patch_size (it is then 0).
  const int components = values ? values->GetNumberOfComponents() : 0;
  if (values && (components == 4 || components == 5) && values->GetNumberOfTuples() == 1)
  {
    settings.ThetaBins = static_cast<int>(values->GetComponent(0, 0));
    settings.PhiBins = static_cast<int>(values->GetComponent(0, 1));
    settings.MaxLevel = static_cast<int>(values->GetComponent(0, 2));
    settings.Tolerance = values->GetComponent(0, 3);
    settings.MinPatchSize = components == 5 ? values->GetComponent(0, 4) : 0.0;
  }
  return settings;
}
