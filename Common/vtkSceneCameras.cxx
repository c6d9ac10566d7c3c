// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSceneCameras.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformationDataObjectMetaDataKey.h>
#include <vtkStringArray.h>

#include <algorithm>

namespace names = vtkSphericalCoverArrayNames;

vtkInformationKeyMacro(vtkSceneCameras, SCENE_CAMERAS, DataObjectMetaData);

namespace
{
/// The number of cameras `fd` holds whole (a name and 12 parameters each).
vtkIdType CameraCount(vtkFieldData* fd, vtkStringArray*& cameraNames, vtkDataArray*& parameters)
{
  cameraNames =
    fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(names::CameraNames)) : nullptr;
  parameters = fd ? fd->GetArray(names::CameraParameters) : nullptr;
  if (!cameraNames || !parameters || parameters->GetNumberOfComponents() != 12)
  {
    return 0;
  }
  return std::min(cameraNames->GetNumberOfValues(), parameters->GetNumberOfTuples());
}
}

bool vtkSceneCameras::Find(vtkFieldData* fd, const std::string& name, sphcover::Camera& camera)
{
  vtkStringArray* cameraNames = nullptr;
  vtkDataArray* parameters = nullptr;
  const vtkIdType count = CameraCount(fd, cameraNames, parameters);
  for (vtkIdType k = 0; k < count; ++k)
  {
    if (name.empty() || cameraNames->GetValue(k) == name)
    {
      double p[12];
      parameters->GetTuple(k, p);
      camera.Name = cameraNames->GetValue(k);
      camera.Position = glm::dvec3(p[0], p[1], p[2]);
      camera.FocalPoint = glm::dvec3(p[3], p[4], p[5]);
      camera.ViewUp = glm::dvec3(p[6], p[7], p[8]);
      camera.ViewAngle = p[9];
      camera.Width = static_cast<int>(p[10]);
      camera.Height = static_cast<int>(p[11]);
      return true;
    }
  }
  return false;
}

std::vector<std::string> vtkSceneCameras::Names(vtkFieldData* fd)
{
  vtkStringArray* cameraNames = nullptr;
  vtkDataArray* parameters = nullptr;
  const vtkIdType count = CameraCount(fd, cameraNames, parameters);
  std::vector<std::string> result;
  for (vtkIdType k = 0; k < count; ++k)
  {
    result.push_back(cameraNames->GetValue(k));
  }
  return result;
}
