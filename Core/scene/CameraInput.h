// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CameraInput.h
 * @brief The camera keys of the scene format (Data/scenes/FORMAT.md "cameras") read from JSON,
 * in one place for the two documents that hold cameras: a scene file's "cameras" and a camera
 * path's (CameraPath.h), so that their keys, bounds and messages are the same.
 *
 * Core-internal: it exposes nlohmann/json through JsonInput.h.
 */
#ifndef SPHCOVER_CAMERAINPUT_H
#define SPHCOVER_CAMERAINPUT_H

#include "scene/Camera.h"
#include "scene/JsonInput.h"

#include <string>

namespace sphcover
{

/// Largest image side a camera may ask for; larger is surely a typo and would exhaust memory.
constexpr int MaxImageSide = 1 << 15;

/// The camera object `j` at `pointer`: position, focal_point, view_up, view_angle, width and
/// height, and name (required when `nameRequired`; otherwise optional, "" when absent). Fails
/// through `input` at the first unknown key, missing key or bad value: a coordinate beyond
/// BezierPatch::MaxCoordinate, a view angle outside (0, 180), a size outside [1, MaxImageSide],
/// the focal point at the eye, a view up zero or parallel to the view direction.
Camera ParseCamera(const JsonInput& input,
  const Json& j,
  const std::string& pointer,
  bool nameRequired = true);

} // namespace sphcover

#endif
