// SPDX-License-Identifier: BSD-3-Clause
#include "scene/CameraInput.h"

#include "geometry/BezierPatch.h"

#include <glm/geometric.hpp>

namespace sphcover
{
namespace
{
/// A point, each coordinate within BezierPatch::MaxCoordinate (as the scene's points).
glm::dvec3 Point(const JsonInput& input, const Json& j, const std::string& pointer)
{
  const glm::dvec3 v = input.Vec3(j, pointer);
  for (size_t k = 0; k < 3; ++k)
  {
    input.Bounded(j[k], Child(pointer, k), BezierPatch::MaxCoordinate, "coordinate");
  }
  return v;
}
}

Camera ParseCamera(const JsonInput& input,
  const Json& j,
  const std::string& pointer,
  bool nameRequired)
{
  input.ExpectObject(j, pointer);
  input.CheckKeys(
    j, pointer, { "name", "position", "focal_point", "view_up", "view_angle", "width", "height" });
  Camera camera;
  if (nameRequired || j.contains("name"))
  {
    camera.Name = input.String(input.Require(j, pointer, "name"), Child(pointer, "name"));
  }
  camera.Position = Point(input, input.Require(j, pointer, "position"), Child(pointer, "position"));
  camera.FocalPoint =
    Point(input, input.Require(j, pointer, "focal_point"), Child(pointer, "focal_point"));
  camera.ViewUp = Point(input, input.Require(j, pointer, "view_up"), Child(pointer, "view_up"));
  camera.ViewAngle =
    input.Number(input.Require(j, pointer, "view_angle"), Child(pointer, "view_angle"));
  if (!(camera.ViewAngle > 0.0 && camera.ViewAngle < 180.0))
  {
    input.Fail(Child(pointer, "view_angle"), "must be in (0, 180)");
  }
  camera.Width = input.PositiveInteger(
    input.Require(j, pointer, "width"), Child(pointer, "width"), MaxImageSide);
  camera.Height = input.PositiveInteger(
    input.Require(j, pointer, "height"), Child(pointer, "height"), MaxImageSide);
  const glm::dvec3 direction = camera.FocalPoint - camera.Position;
  if (glm::length(direction) == 0.0)
  {
    input.Fail(Child(pointer, "focal_point"), "focal_point equals position");
  }
  if (glm::length(glm::cross(glm::normalize(direction), camera.ViewUp)) <
      1e-9 * glm::length(camera.ViewUp) ||
    glm::length(camera.ViewUp) == 0.0)
  {
    input.Fail(Child(pointer, "view_up"), "view_up is zero or parallel to the view direction");
  }
  return camera;
}

} // namespace sphcover
