// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Camera.h
 * @brief A pinhole camera as the scene file and VTK describe it.
 */
#ifndef SPHCOVER_CAMERA_H
#define SPHCOVER_CAMERA_H

#include <glm/vec3.hpp>

#include <string>

namespace sphcover
{

struct Camera
{
  std::string Name;
  glm::dvec3 Position{ 0.0, 0.0, 1.0 };
  glm::dvec3 FocalPoint{ 0.0 };
  glm::dvec3 ViewUp{ 0.0, 1.0, 0.0 };
  /// Vertical field of view in degrees (VTK's convention).
  double ViewAngle = 30.0;
  int Width = 512;
  int Height = 512;
};

} // namespace sphcover

#endif
