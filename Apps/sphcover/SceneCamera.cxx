// SPDX-License-Identifier: BSD-3-Clause
#include "SceneCamera.h"

#include "vtkSceneCameras.h"

#include <vtkDataObject.h>

#include <stdexcept>
#include <string>

namespace sphcover_cli
{
void ParseSize(const std::string& text, int& width, int& height)
{
  const size_t x = text.find('x');
  size_t used1 = 0;
  size_t used2 = 0;
  try
  {
    if (x == std::string::npos)
    {
      throw std::invalid_argument(text);
    }
    width = std::stoi(text.substr(0, x), &used1);
    height = std::stoi(text.substr(x + 1), &used2);
  }
  catch (const std::exception&)
  {
    used1 = 0;
  }
  if (used1 == 0 || used1 != x || used2 != text.size() - x - 1 || width < 1 || height < 1)
  {
    throw std::runtime_error("--size '" + text + "': expected WIDTHxHEIGHT, e.g. 640x480");
  }
}

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
