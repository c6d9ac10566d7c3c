// SPDX-License-Identifier: BSD-3-Clause
#include "SceneCamera.h"

#include "vtkSceneCameras.h"

#include <vtkDataObject.h>

#include <stdexcept>

namespace sphcover_cli
{
sphcover::Camera SceneCamera(vtkDataObject* surfaces,
  const std::string& name,
  const std::string& scene)
{
  sphcover::Camera camera;
  if (vtkSceneCameras::Find(surfaces->GetFieldData(), name, camera))
  {
    return camera;
  }
  std::string list;
  for (const std::string& known : vtkSceneCameras::Names(surfaces->GetFieldData()))
  {
    list += (list.empty() ? "'" : ", '") + known + "'";
  }
  throw std::runtime_error(scene + ": " +
    (name.empty() ? std::string("the scene has no camera") : "no camera named '" + name + "'") +
    (list.empty() ? std::string() : " (cameras: " + list + ")"));
}
}
