// SPDX-License-Identifier: BSD-3-Clause
// The final rendering of paper §5.3: the white furnace renders uniform
// (Documentation/Verification.md#correctness-references); a linear field over a square seen head-on
// renders the analytic (u, v) of each pixel's visible point (camera conventions, visible surface,
// §5.3.2 interpolation and edge extrapolation), with the analytic depth; the image does not depend
// on the thread count; abort; bad cameras are refused with one clear message.
#include "math/Constants.h"
#include "render/RadianceRenderer.h"

#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"
#include "propagation/LightPropagation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// The unit square at z = 0 (front side +z), split 3 x 3, with the radiance (u, v, 1) of every
/// characteristic point: a linear field, which §5.3.2's interpolation reproduces exactly.
RadianceRenderer LinearSquare()
{
  std::vector<Patch> patches;
  AppendSplit(patches,
    Parallelogram(glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0)),
    0,
    3,
    3);
  std::vector<glm::dvec3> radiance;
  for (const Patch& patch : patches)
  {
    radiance.emplace_back(patch.Domain.CenterU(), patch.Domain.CenterV(), 1.0);
  }
  CharacteristicPointInterpolator interpolator =
    CharacteristicPointInterpolator::OfPatches(patches);
  return RadianceRenderer(patches, std::move(interpolator), radiance);
}

Camera HeadOn()
{
  Camera camera;
  camera.Position = glm::dvec3(0.5, 0.5, 2.0);
  camera.FocalPoint = glm::dvec3(0.5, 0.5, 0.0);
  camera.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
  camera.ViewAngle = 40.0;
  camera.Width = 48;
  camera.Height = 32;
  return camera;
}
}

TEST(RadianceRenderer, WhiteFurnaceRendersUniform)
{
  // Documentation/Verification.md#correctness-references: radiance Le / (1 - rho) everywhere in a
  // closed furnace, so on every pixel.
  for (const char* name : { "furnace_box.scene", "furnace_sphere.scene" })
  {
    const Scene scene = LoadSceneFile(ScenePath(name));
    const std::vector<Patch> patches = SplitScene(scene, 3);
    SphericalCover cover;
    ASSERT_TRUE(cover.Build(patches));
    const std::vector<Material> materials = LightPropagation::MaterialsOfPatches(scene, patches);
    LightPropagation propagation(cover, materials);
    PropagationSettings propagationSettings;
    propagationSettings.ConvergenceTolerance = 1e-6;
    ASSERT_TRUE(propagation.Run(propagationSettings));
    std::vector<glm::dvec3> exitant;
    for (size_t i = 0; i < patches.size(); ++i)
    {
      exitant.push_back(propagation.ExitantRadiance(i));
    }
    const RadianceRenderer renderer(
      patches, CharacteristicPointInterpolator::OfPatches(patches), exitant);
    ASSERT_FALSE(scene.Cameras.empty());
    Camera camera = scene.Cameras.front();
    camera.Width = 40;
    camera.Height = 30;
    RenderSettings settings;
    settings.SamplesPerPixel = 4;
    RenderedImage image;
    ASSERT_TRUE(renderer.Render(camera, settings, image));
    const Material& material = scene.Materials.front();
    const glm::dvec3 expected = material.Emission / (glm::dvec3(1.0) - material.Diffuse);
    double worst = 0.0;
    for (size_t p = 0; p < image.SurfaceId.size(); ++p)
    {
      ASSERT_GE(image.SurfaceId[p], 0) << name << ": pixel " << p << " sees nothing";
      for (int b = 0; b < 3; ++b)
      {
        worst = std::max(worst, std::fabs(image.Radiance[3 * p + b] / expected[b] - 1.0));
      }
    }
    std::printf("[ Furnace  ] %s: largest |pixel / (Le / (1 - rho)) - 1| = %.1e\n", name, worst);
    EXPECT_LT(worst, 5e-3) << name;
  }
}

TEST(RadianceRenderer, LinearFieldOnSquareMatchesAnalyticVisiblePoint)
{
  const RadianceRenderer renderer = LinearSquare();
  const Camera camera = HeadOn();
  RenderSettings settings;
  settings.SamplesPerPixel = 1; // the pixel centre
  RenderedImage image;
  ASSERT_TRUE(renderer.Render(camera, settings, image));
  const double halfHeight = std::tan(0.5 * camera.ViewAngle * Pi / 180.0);
  const double halfWidth = halfHeight * camera.Width / camera.Height;
  int inside = 0;
  int outside = 0;
  for (int j = 0; j < camera.Height; ++j)
  {
    for (int i = 0; i < camera.Width; ++i)
    {
      // The ray through the pixel centre meets z = 0 at eye + 2 (x, y, -1), row 0 at the bottom.
      const double x = (2.0 * (i + 0.5) / camera.Width - 1.0) * halfWidth;
      const double y = (2.0 * (j + 0.5) / camera.Height - 1.0) * halfHeight;
      const double u = 0.5 + 2.0 * x;
      const double v = 0.5 + 2.0 * y;
      const size_t p = static_cast<size_t>(j * camera.Width + i);
      const bool onSquare = u > 1e-6 && u < 1.0 - 1e-6 && v > 1e-6 && v < 1.0 - 1e-6;
      const bool offSquare = u < -1e-6 || u > 1.0 + 1e-6 || v < -1e-6 || v > 1.0 + 1e-6;
      if (onSquare)
      {
        ++inside;
        EXPECT_EQ(image.SurfaceId[p], 0);
        EXPECT_NEAR(image.Radiance[3 * p + 0], u, 1e-5) << i << ", " << j;
        EXPECT_NEAR(image.Radiance[3 * p + 1], v, 1e-5) << i << ", " << j;
        EXPECT_NEAR(image.Radiance[3 * p + 2], 1.0, 1e-6);
        EXPECT_NEAR(image.Depth[p], 2.0 * std::sqrt(1.0 + x * x + y * y), 1e-5);
      }
      else if (offSquare)
      {
        ++outside;
        EXPECT_EQ(image.SurfaceId[p], -1);
        EXPECT_EQ(image.Depth[p], -1.0f);
        EXPECT_EQ(image.Radiance[3 * p], 0.0f);
      }
    }
  }
  // The view holds the square and a margin around it.
  EXPECT_GT(inside, 200);
  EXPECT_GT(outside, 200);
  // Seen from behind, a one-sided surface is black but still the visible surface.
  Camera behind = camera;
  behind.Position.z = -2.0;
  ASSERT_TRUE(renderer.Render(behind, settings, image));
  const size_t centre = static_cast<size_t>((camera.Height / 2) * camera.Width + camera.Width / 2);
  EXPECT_EQ(image.SurfaceId[centre], 0);
  EXPECT_EQ(image.Radiance[3 * centre], 0.0f);
  EXPECT_NEAR(image.Depth[centre], 2.0, 0.01);
}

TEST(RadianceRenderer, ThreadIndependentAndAbortable)
{
  const RadianceRenderer renderer = LinearSquare();
  const Camera camera = HeadOn();
  RenderSettings settings;
  settings.SamplesPerPixel = 5;
  RenderedImage sequential;
  RenderedImage threaded;
  ASSERT_TRUE(renderer.Render(camera, settings, sequential));
  ASSERT_TRUE(renderer.Render(camera, settings, threaded, ThreadedFor(3)));
  EXPECT_EQ(sequential.Radiance, threaded.Radiance);
  EXPECT_EQ(sequential.Depth, threaded.Depth);
  EXPECT_EQ(sequential.SurfaceId, threaded.SurfaceId);
  int calls = 0;
  EXPECT_FALSE(renderer.Render(camera,
    settings,
    threaded,
    SequentialFor,
    [&calls](double)
    {
      ++calls;
      return false;
    }));
  EXPECT_EQ(calls, 1);
}

TEST(RadianceRenderer, AnEdgeAcrossARowOfPixelsCoversItsShareOnAverage)
{
  // The square's top edge (y = 1) crosses pixel row 9 of a 128 x 16 image 3/32 of a row above
  // the row's bottom, across every column: the row's mean coverage (band z of the square's
  // radiance is 1) is 3/32. With one sample pattern for all pixels, 16 samples would count one
  // sample below the edge in every pixel, 1/16 (the file comment of RadianceRenderer.h: a
  // pattern shifted per pixel).
  const RadianceRenderer renderer = LinearSquare();
  Camera camera;
  const double halfHeight = 0.1; // tan(view angle / 2)
  const double distance = 0.5;
  const double edgeRow = 9.0 + 3.0 / 32.0;
  const double y = 1.0 - (edgeRow / 8.0 - 1.0) * halfHeight * distance;
  camera.Position = glm::dvec3(0.5, y, distance);
  camera.FocalPoint = glm::dvec3(0.5, y, 0.0);
  camera.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
  camera.ViewAngle = 2.0 * std::atan(halfHeight) * 180.0 / Pi;
  camera.Width = 128;
  camera.Height = 16;
  RenderSettings settings;
  settings.SamplesPerPixel = 16;
  RenderedImage image;
  ASSERT_TRUE(renderer.Render(camera, settings, image));
  double coverage = 0.0;
  for (int i = 0; i < camera.Width; ++i)
  {
    const std::size_t pixel = 9 * static_cast<std::size_t>(camera.Width) + i;
    coverage += image.Radiance[3 * pixel + 2];
    // Every pixel counts one or two of its 16 samples: one per row stratum.
    EXPECT_TRUE(std::fabs(image.Radiance[3 * pixel + 2] - 1.0 / 16.0) < 1e-6 ||
      std::fabs(image.Radiance[3 * pixel + 2] - 2.0 / 16.0) < 1e-6)
      << "column " << i << ": " << image.Radiance[3 * pixel + 2];
  }
  coverage /= camera.Width;
  EXPECT_NEAR(coverage, 3.0 / 32.0, 0.008);
  // The rows below are covered, the rows above not.
  EXPECT_FLOAT_EQ(image.Radiance[3 * (8 * 128 + 64) + 2], 1.0f);
  EXPECT_FLOAT_EQ(image.Radiance[3 * (10 * 128 + 64) + 2], 0.0f);
}

TEST(RadianceRenderer, BadCamerasAreRefusedWithOneMessage)
{
  const RadianceRenderer renderer = LinearSquare();
  RenderSettings settings;
  RenderedImage image;
  struct Case
  {
    const char* Expected;
    Camera Bad;
  };
  std::vector<Case> cases;
  Camera c = HeadOn();
  c.ViewAngle = 0.0;
  cases.push_back({ "view angle", c });
  c = HeadOn();
  c.ViewAngle = -10.0;
  cases.push_back({ "view angle", c });
  c = HeadOn();
  c.ViewUp = glm::dvec3(0.0, 0.0, 3.0);
  cases.push_back({ "parallel", c });
  c = HeadOn();
  c.Width = 0;
  cases.push_back({ "image size", c });
  c = HeadOn();
  c.Height = -3;
  cases.push_back({ "image size", c });
  c = HeadOn();
  c.FocalPoint = c.Position;
  cases.push_back({ "focal point", c });
  c = HeadOn();
  c.Position.x = std::nan("");
  cases.push_back({ "finite", c });
  c = HeadOn();
  c.Width = 200000;
  c.Height = 200000;
  cases.push_back({ "MiB", c });
  for (const Case& bad : cases)
  {
    const std::string problem = CheckCamera(bad.Bad, settings);
    EXPECT_NE(problem.find(bad.Expected), std::string::npos) << problem;
    EXPECT_EQ(problem.find('\n'), std::string::npos);
    try
    {
      renderer.Render(bad.Bad, settings, image);
      ADD_FAILURE() << "no error for " << bad.Expected;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_EQ(problem, e.what());
    }
  }
  RenderSettings noSamples;
  noSamples.SamplesPerPixel = 0;
  EXPECT_NE(CheckCamera(HeadOn(), noSamples).find("samples"), std::string::npos);
  EXPECT_EQ(CheckCamera(HeadOn(), settings), "");
}
