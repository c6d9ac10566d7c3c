// SPDX-License-Identifier: BSD-3-Clause
// The walk-through's fast primary rays (issue 41, paper §5.3): the eye rays of 4 x 4 pixel tiles
// cast as Embree packets and refined from the closed-form point on flat quadrilaterals give the
// image of one ray at a time refined from the triangle's point (RenderSettings::FastPrimaryRays
// off: the renderer before issue 41) within the tolerance of
// Documentation/notes/walk-through.md (2026-12-07): the same visible surface in every pixel,
// radiance within 1e-9 of the image's largest value, depth within 1e-9 of the pixel's; on the
// Cornell box, on a box with a mirror, phong and tabulated walls (the directional part of
// §5.3.1, through the caches kept across frames) and on a two-sided surface (the packets'
// filter); the images are the same bit for bit on 1 and 2 threads, and frames rendered after
// others (warm caches) equal a fresh renderer's.
#include "render/RadianceRenderer.h"

#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"
#include "propagation/LightPropagation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// A smooth, distinct radiance per characteristic point: the comparison is between two ways of
/// rendering the same values, so they need not be a solution.
std::vector<glm::dvec3> SyntheticRadiance(const std::vector<Patch>& patches)
{
  std::vector<glm::dvec3> radiance;
  for (const Patch& patch : patches)
  {
    radiance.emplace_back(patch.Domain.CenterU() + 0.1 * patch.SurfaceIndex,
      patch.Domain.CenterV(),
      1.0 + 0.01 * patch.SurfaceIndex);
  }
  return radiance;
}

/// The renderer of a scene split `split` x `split`: with the propagated directional
/// illumination (paper §5.3.1) when `directional`, else with SyntheticRadiance.
std::unique_ptr<RadianceRenderer> MakeRenderer(const Scene& scene, int split, bool directional)
{
  const std::vector<Patch> patches = SplitScene(scene, split);
  std::vector<bool> twoSided;
  for (const Surface& surface : scene.Surfaces)
  {
    twoSided.push_back(surface.TwoSided);
  }
  if (!directional)
  {
    return std::make_unique<RadianceRenderer>(patches,
      CharacteristicPointInterpolator::OfPatches(patches),
      SyntheticRadiance(patches),
      twoSided);
  }
  DirectionalIllumination illumination;
  EXPECT_TRUE(illumination.Cover.Build(patches));
  const std::vector<Material> materials = LightPropagation::MaterialsOfPatches(scene, patches);
  std::vector<glm::dvec3> exitant;
  {
    LightPropagation propagation(illumination.Cover, materials);
    for (const Patch& patch : patches)
    {
      illumination.Frames.push_back(HemisphereFrame::OfPatch(patch));
    }
    propagation.SetFrames(illumination.Frames);
    EXPECT_TRUE(propagation.Run());
    for (size_t i = 0; i < patches.size(); ++i)
    {
      exitant.push_back(propagation.ExitantRadiance(i));
    }
    illumination.IncidentRadiance = propagation.IncidentRadiances();
  }
  illumination.Materials = materials;
  auto renderer = std::make_unique<RadianceRenderer>(
    patches, CharacteristicPointInterpolator::OfPatches(patches), exitant, twoSided);
  renderer->SetDirectionalIllumination(std::move(illumination));
  return renderer;
}

/// Three cameras of a short orbit-like move from the scene's first camera, at 37 x 29 pixels
/// (not multiples of the tile side: partial tiles at the right and top).
std::vector<Camera> Walk(const Scene& scene)
{
  std::vector<Camera> cameras;
  const Camera first = scene.Cameras.front();
  for (int k = 0; k < 3; ++k)
  {
    Camera camera = first;
    camera.Width = 37;
    camera.Height = 29;
    const glm::dvec3 view = camera.FocalPoint - camera.Position;
    const glm::dvec3 side = glm::normalize(glm::cross(view, camera.ViewUp));
    camera.Position += (0.08 * k) * glm::length(view) * side;
    cameras.push_back(camera);
  }
  return cameras;
}

void ExpectWithinTolerance(const RenderedImage& reference,
  const RenderedImage& image,
  const std::string& what)
{
  ASSERT_EQ(reference.Radiance.size(), image.Radiance.size());
  double largest = 0.0;
  for (const float value : reference.Radiance)
  {
    largest = std::max(largest, static_cast<double>(std::fabs(value)));
  }
  ASSERT_GT(largest, 0.0) << what;
  size_t differing = 0;
  for (size_t p = 0; p < reference.SurfaceId.size(); ++p)
  {
    EXPECT_EQ(reference.SurfaceId[p], image.SurfaceId[p]) << what << ", pixel " << p;
    EXPECT_NEAR(reference.Depth[p], image.Depth[p], 1e-9 * std::fabs(reference.Depth[p]) + 1e-30)
      << what << ", pixel " << p;
    for (size_t c = 0; c < 3; ++c)
    {
      const double a = reference.Radiance[3 * p + c];
      const double b = image.Radiance[3 * p + c];
      EXPECT_NEAR(a, b, 1e-9 * largest) << what << ", pixel " << p << " band " << c;
      differing += a != b ? 1 : 0;
    }
  }
  // Most values are the same bits (Documentation/notes/walk-through.md, 2026-12-07).
  EXPECT_LE(differing, reference.Radiance.size() / 100) << what;
}

void ExpectIdentical(const RenderedImage& a, const RenderedImage& b, const std::string& what)
{
  EXPECT_EQ(a.Radiance, b.Radiance) << what;
  EXPECT_EQ(a.Depth, b.Depth) << what;
  EXPECT_EQ(a.SurfaceId, b.SurfaceId) << what;
}
}

TEST(PacketRendering, PacketsEqualSingleRaysWithinToleranceAndThreadCountIndependent)
{
  struct Case
  {
    const char* Scene;
    int Split;
    bool Directional;
  };
  // Split 2 for the propagated box: its cover and propagation dominate the test's time.
  for (const Case& c : { Case{ "cornell_box.scene", 3, false },
         Case{ "mixed_box.scene", 2, true },
         Case{ "furnace_two_sided.scene", 3, false } })
  {
    const Scene scene = LoadSceneFile(ScenePath(c.Scene));
    ASSERT_FALSE(scene.Cameras.empty()) << c.Scene;
    std::unique_ptr<RadianceRenderer> renderer = MakeRenderer(scene, c.Split, c.Directional);
    ASSERT_EQ(renderer->HasDirectionalIllumination(), c.Directional);
    const std::vector<Camera> cameras = Walk(scene);
    for (const int samples : { 1, 3 })
    {
      RenderSettings fast;
      fast.SamplesPerPixel = samples;
      RenderSettings reference = fast;
      reference.FastPrimaryRays = false;
      for (size_t k = 0; k < cameras.size(); ++k)
      {
        const std::string what = std::string(c.Scene) + ", camera " + std::to_string(k) + ", spp " +
          std::to_string(samples);
        RenderedImage single;
        RenderedImage packets;
        RenderedImage twoThreads;
        ASSERT_TRUE(renderer->Render(cameras[k], reference, single));
        ASSERT_TRUE(renderer->Render(cameras[k], fast, packets));
        ASSERT_TRUE(renderer->Render(cameras[k], fast, twoThreads, ThreadedFor(2)));
        ExpectWithinTolerance(single, packets, what);
        ExpectIdentical(packets, twoThreads, what + ", 1 vs 2 threads");
        if (c.Directional && k + 1 == cameras.size())
        {
          // This renderer's caches hold the earlier frames' pairs: a fresh renderer's frame is
          // the same bits (the caches hold exact values).
          std::unique_ptr<RadianceRenderer> fresh = MakeRenderer(scene, c.Split, true);
          RenderedImage cold;
          ASSERT_TRUE(fresh->Render(cameras[k], fast, cold, ThreadedFor(2)));
          ExpectIdentical(cold, packets, what + ", warm vs cold caches");
        }
      }
    }
  }
}
