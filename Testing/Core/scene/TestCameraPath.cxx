// SPDX-License-Identifier: BSD-3-Clause
// Camera paths of `sphcover walk` (Core/scene/CameraPath.h): the scene format's camera keys with
// the name optional, every mistake one InputError at its JSON pointer, and the orbit: its first
// camera is the start bit for bit, every eye and focal point at the start's distance from the
// axis and height along the view up, evenly spaced on their circles; its pivot on the view
// axis next to the scene's centre.
#include "scene/CameraPath.h"
#include "scene/InputError.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace sphcover;

namespace
{
const std::string Good = R"({"position": [1, 2, 3], "focal_point": [1, 2, 4], "view_up": [0, 1, 0],
  "view_angle": 40, "width": 64, "height": 48})";

std::string ErrorOf(const std::string& text)
{
  try
  {
    ParseCameraPath(text, "walk.json");
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "no error";
}
}

TEST(CameraPath, ReadsTheScenesCameraKeysWithTheNameOptional)
{
  const std::vector<Camera> cameras =
    ParseCameraPath(R"({"cameras": [)" + Good + R"(, {"name": "second", "position": [0, 0, 0],
      "focal_point": [0, 0, -1], "view_up": [1, 0, 0], "view_angle": 90, "width": 8,
      "height": 9}]})",
      "walk.json");
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0].Name, "");
  EXPECT_EQ(cameras[0].Position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(cameras[0].FocalPoint, glm::dvec3(1, 2, 4));
  EXPECT_EQ(cameras[0].ViewAngle, 40.0);
  EXPECT_EQ(cameras[0].Width, 64);
  EXPECT_EQ(cameras[0].Height, 48);
  EXPECT_EQ(cameras[1].Name, "second");
  EXPECT_EQ(cameras[1].ViewUp, glm::dvec3(1, 0, 0));
  EXPECT_EQ(cameras[1].Height, 9);
}

TEST(CameraPath, ErrorsNameTheFileAndTheJsonPointer)
{
  EXPECT_EQ(
    ErrorOf(R"({"cameras": []})"), "walk.json: /cameras: no cameras: a path needs at least one");
  EXPECT_EQ(ErrorOf(R"([])"), "walk.json: /: expected an object");
  EXPECT_EQ(ErrorOf(R"({})"), "walk.json: /: missing key 'cameras'");
  EXPECT_EQ(ErrorOf(R"({"cameras": {}})"), "walk.json: /cameras: expected an array of cameras");
  EXPECT_EQ(ErrorOf(R"({"cameras": [], "speed": 1})"), "walk.json: /speed: unknown key 'speed'");
  EXPECT_EQ(ErrorOf(R"({"cameras": [)" + Good + R"(, {"position": [0, 0, 0]}]})"),
    "walk.json: /cameras/1: missing key 'focal_point'");
  EXPECT_EQ(ErrorOf(R"({"cameras": [{"position": [0, 0, 0], "focal_point": [0, 0, 0],
    "view_up": [0, 1, 0], "view_angle": 40, "width": 64, "height": 48}]})"),
    "walk.json: /cameras/0/focal_point: focal_point equals position");
  EXPECT_EQ(ErrorOf(R"({"cameras": [{"position": [0, 0, 0], "focal_point": [0, 0, 1],
    "view_up": [0, 1, 0], "view_angle": 40, "width": 64.0, "height": 48}]})")
              .substr(0, 34),
    "walk.json: /cameras/0/width: expec");
  EXPECT_EQ(ErrorOf(R"({"cameras": [)").substr(0, 19), "walk.json: line 1, ");
}

TEST(CameraPath, AnOrbitCirclesTheFocalPointAboutTheViewUp)
{
  Camera start;
  start.Name = "main";
  start.Position = glm::dvec3(3.0, 2.5, -4.0);
  start.FocalPoint = glm::dvec3(0.5, 1.0, 0.25);
  start.ViewUp = glm::dvec3(0.0, 2.0, 0.0);
  const int count = 7;
  const glm::dvec3 pivot(-1.0, 7.0, 2.0);
  const std::vector<Camera> orbit = OrbitPath(start, count, pivot);
  ASSERT_EQ(orbit.size(), static_cast<size_t>(count));
  EXPECT_EQ(orbit[0].Position, start.Position); // bit for bit: the walk's first frame
  EXPECT_EQ(orbit[0].FocalPoint, start.FocalPoint);
  const glm::dvec3 up(0.0, 1.0, 0.0);
  for (int k = 0; k < count; ++k)
  {
    const Camera& camera = orbit[static_cast<size_t>(k)];
    EXPECT_EQ(camera.Name, "main_orbit_" + std::to_string(k));
    EXPECT_EQ(camera.ViewUp, start.ViewUp);
    const double expected = std::remainder(2.0 * M_PI * k / count, 2.0 * M_PI);
    for (const auto& [before, after] : { std::pair(start.Position, camera.Position),
           std::pair(start.FocalPoint, camera.FocalPoint) })
    {
      const glm::dvec3 arm0 = before - pivot;
      const glm::dvec3 arm = after - pivot;
      EXPECT_NEAR(glm::length(arm), glm::length(arm0), 1e-12);
      EXPECT_NEAR(glm::dot(arm, up), glm::dot(arm0, up), 1e-12);
      // The signed angle from the start's arm about the view up, in the plane across it.
      const glm::dvec3 a = arm0 - glm::dot(arm0, up) * up;
      const glm::dvec3 b = arm - glm::dot(arm, up) * up;
      const double angle = std::atan2(glm::dot(glm::cross(a, b), up), glm::dot(a, b));
      EXPECT_NEAR(angle, expected, 1e-12) << "camera " << k;
    }
  }
  EXPECT_THROW(OrbitPath(start, 0, pivot), std::invalid_argument);
  EXPECT_THROW(OrbitPath(start, MaxPathCameras + 1, pivot), std::invalid_argument);
}

TEST(CameraPath, TheOrbitsPivotIsOnTheViewAxisNextToTheScenesCentre)
{
  Camera cornell; // the Cornell box's camera: its focal point a unit ahead of the eye
  cornell.Position = glm::dvec3(278.0, 273.0, -800.0);
  cornell.FocalPoint = glm::dvec3(278.0, 273.0, -799.0);
  const glm::dvec3 pivot =
    OrbitPivot(cornell, glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(556.0, 548.8, 559.2));
  EXPECT_NEAR(pivot.x, 278.0, 1e-12);
  EXPECT_NEAR(pivot.y, 273.0, 1e-12);
  EXPECT_NEAR(pivot.z, 279.6, 1e-9);
  // A scene behind the camera: its focal point.
  EXPECT_EQ(OrbitPivot(cornell, glm::dvec3(0.0, 0.0, -2000.0), glm::dvec3(1.0, 1.0, -1900.0)),
    cornell.FocalPoint);
}
