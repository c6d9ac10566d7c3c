// SPDX-License-Identifier: BSD-3-Clause
#include "scene/CameraPath.h"

#include "scene/CameraInput.h"
#include "scene/InputFile.h"
#include "scene/JsonInput.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <stdexcept>

namespace sphcover
{

std::vector<Camera> ParseCameraPath(const std::string& text, const std::string& path)
{
  const Json root = ParseJsonDocument(text, path);
  const JsonInput input(path);
  input.ExpectObject(root, "");
  input.CheckKeys(root, "", { "cameras" });
  const Json& cameras = input.Require(root, "", "cameras");
  if (!cameras.is_array())
  {
    input.Fail("/cameras", "expected an array of cameras");
  }
  if (cameras.empty())
  {
    input.Fail("/cameras", "no cameras: a path needs at least one");
  }
  if (cameras.size() > static_cast<size_t>(MaxPathCameras))
  {
    input.Fail("/cameras",
      std::to_string(cameras.size()) + " cameras: at most " + std::to_string(MaxPathCameras));
  }
  std::vector<Camera> walk;
  walk.reserve(cameras.size());
  for (size_t c = 0; c < cameras.size(); ++c)
  {
    walk.push_back(ParseCamera(input, cameras[c], Child("/cameras", c), false));
  }
  return walk;
}

std::vector<Camera> LoadCameraPath(const std::string& path)
{
  return ParseCameraPath(ReadInputFile(path), path);
}

std::vector<Camera> OrbitPath(const Camera& start, int count, const glm::dvec3& pivot)
{
  if (count < 1 || count > MaxPathCameras)
  {
    throw std::invalid_argument("an orbit has 1 to " + std::to_string(MaxPathCameras) +
      " cameras, not " + std::to_string(count));
  }
  const double upLength = glm::length(start.ViewUp);
  if (!(upLength > 0.0))
  {
    throw std::invalid_argument("the camera's view up is zero: no axis to orbit about");
  }
  const glm::dvec3 axis = start.ViewUp / upLength;
  // Rodrigues' rotation about the axis through the pivot.
  const auto turn = [&axis, &pivot](const glm::dvec3& point, double c, double s)
  {
    const glm::dvec3 arm = point - pivot;
    return pivot + arm * c + glm::cross(axis, arm) * s + axis * glm::dot(axis, arm) * (1.0 - c);
  };
  std::vector<Camera> cameras(static_cast<size_t>(count), start);
  for (int k = 0; k < count; ++k)
  {
    Camera& camera = cameras[static_cast<size_t>(k)];
    camera.Name = start.Name + "_orbit_" + std::to_string(k);
    if (k == 0)
    {
      continue; // the start itself, bit for bit (no rotation by a rounded zero angle)
    }
    const double angle = 2.0 * M_PI * k / count;
    camera.Position = turn(start.Position, std::cos(angle), std::sin(angle));
    camera.FocalPoint = turn(start.FocalPoint, std::cos(angle), std::sin(angle));
  }
  return cameras;
}

glm::dvec3 OrbitPivot(const Camera& start, const glm::dvec3& lower, const glm::dvec3& upper)
{
  const glm::dvec3 forward = glm::normalize(start.FocalPoint - start.Position);
  const double ahead = glm::dot(0.5 * (lower + upper) - start.Position, forward);
  return ahead > 0.0 && std::isfinite(ahead) ? start.Position + ahead * forward : start.FocalPoint;
}

} // namespace sphcover
