// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CameraPath.h
 * @brief A walk-through's cameras (`sphcover walk`): read from a camera path file, or an orbit
 * around a camera. After the solve every view is cheap (paper §1, §5.3), so a path of many
 * cameras is rendered from one solution.
 *
 * A camera path file is one JSON object with one key, `cameras`, a non-empty array of cameras
 * in the scene format's keys (Data/scenes/FORMAT.md "cameras"; `name` optional):
 *
 *   {"cameras": [{"position": [278, 273, -800], "focal_point": [278, 273, 0],
 *                 "view_up": [0, 1, 0], "view_angle": 39.3, "width": 512, "height": 512}, ...]}
 *
 * Its mistakes are reported as a scene's are: one InputError naming the file, the JSON pointer
 * (or line and column of a syntax error) and the problem.
 */
#ifndef SPHCOVER_CAMERAPATH_H
#define SPHCOVER_CAMERAPATH_H

#include "scene/Camera.h"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace sphcover
{

/// Largest number of cameras of a path (and of an orbit): a frame takes at least milliseconds
/// and a file, so a million is days of frames and surely a mistake.
constexpr int MaxPathCameras = 1000000;

/// The cameras of the camera path file at `path`, in its order. Throws InputError.
std::vector<Camera> LoadCameraPath(const std::string& path);

/// The cameras of a path given as text; `path` names it in messages. Throws InputError.
std::vector<Camera> ParseCameraPath(const std::string& text, const std::string& path);

/**
 * `count` cameras (1 to MaxPathCameras) on a full circle around `pivot`: camera k is `start`
 * with its position and focal point turned by 360 k / count degrees about the axis through
 * `pivot` along the view up (the view up, view angle and size kept), so the first is `start`
 * exactly and every camera looks at the axis as `start` does, from the same distance and
 * height. Named `<start's name>_orbit_<k>`. Throws std::invalid_argument for a count outside
 * [1, MaxPathCameras] or a zero view up.
 */
std::vector<Camera> OrbitPath(const Camera& start, int count, const glm::dvec3& pivot);

/**
 * The pivot of an orbit of `start` through a scene within `lower` .. `upper` (its bounds): the
 * point of the view axis nearest the bounds' centre, so that the orbit circles the scene
 * (a camera's focal point may be a unit ahead of the eye, as the Cornell box's, which would
 * turn the camera on the spot); the focal point when that point is not ahead of the eye.
 */
glm::dvec3 OrbitPivot(const Camera& start, const glm::dvec3& lower, const glm::dvec3& upper);

} // namespace sphcover

#endif
