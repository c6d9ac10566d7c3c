// SPDX-License-Identifier: BSD-3-Clause
#include "SceneCamera.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <stdexcept>

namespace sphcover_cli
{
sphcover::Camera SceneCamera(vtkDataObject* surfaces,
  const std::string& name,
  const std::string& scene)
{
  vtkFieldData* fd = surfaces->GetFieldData();
  auto* names =
    vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkSphericalCoverArrayNames::CameraNames));
  vtkDataArray* parameters = fd->GetArray(vtkSphericalCoverArrayNames::CameraParameters);
  const vtkIdType count = names && parameters && parameters->GetNumberOfComponents() == 12
    ? std::min(names->GetNumberOfValues(), parameters->GetNumberOfTuples())
    : 0;
  for (vtkIdType k = 0; k < count; ++k)
  {
    if (name.empty() || names->GetValue(k) == name)
    {
      double p[12];
      parameters->GetTuple(k, p);
      sphcover::Camera camera;
      camera.Name = names->GetValue(k);
      camera.Position = glm::dvec3(p[0], p[1], p[2]);
      camera.FocalPoint = glm::dvec3(p[3], p[4], p[5]);
      camera.ViewUp = glm::dvec3(p[6], p[7], p[8]);
      camera.ViewAngle = p[9];
      camera.Width = static_cast<int>(p[10]);
      camera.Height = static_cast<int>(p[11]);
      return camera;
    }
  }
  std::string list;
  for (vtkIdType k = 0; k < count; ++k)
  {
    list += (list.empty() ? "'" : ", '") + names->GetValue(k) + "'";
  }
  throw std::runtime_error(scene + ": " +
    (name.empty() ? std::string("the scene has no camera") : "no camera named '" + name + "'") +
    (list.empty() ? std::string() : " (cameras: " + list + ")"));
}
}
