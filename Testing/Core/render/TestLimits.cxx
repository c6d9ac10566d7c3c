// SPDX-License-Identifier: BSD-3-Clause
// The limits that keep a run from never finishing, exhausting memory or writing non-finite
// results: settings bounds, the subdivision's budgets, the cover's and the propagation's memory
// estimates (made without allocating), the renderer's budgets, Embree's coordinate range, the
// scene fingerprint.
#include "cover/HemisphereGrid.h"
#include "cover/RayCastFill.h"
#include "cover/SphericalCover.h"
#include "propagation/LightPropagation.h"
#include "reflectance/DirectionalReflection.h"
#include "render/RadianceRenderer.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"
#include "scene/SettingsOverride.h"
#include "subdivision/IntervalSubdivision.h"
#include "subdivision/SubdivisionCriteria.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>

using namespace sphcover;

namespace
{
const Scene& Cornell()
{
  static const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene");
  return scene;
}

/// The finest subdivision the settings allow: without a budget it would not end in any
/// reasonable time.
SubdivisionSettings Finest()
{
  SubdivisionSettings settings;
  settings.MaxLevel = MaxSubdivisionLevel;
  std::fill(std::begin(settings.Tolerance), std::end(settings.Tolerance), MinimumTolerance);
  return settings;
}
}

TEST(Limits, MaxLevelAndToleranceBounds)
{
  SubdivisionSettings settings;
  settings.MaxLevel = MaxSubdivisionLevel;
  EXPECT_EQ(settings.Problem(), "");
  settings.MaxLevel = MaxSubdivisionLevel + 1;
  EXPECT_NE(settings.Problem().find("at most 32"), std::string::npos);
  settings = SubdivisionSettings();
  settings.Tolerance[0] = 1e-12;
  EXPECT_NE(settings.Problem().find("SelfShadowingTolerance"), std::string::npos);
  // The bound is where the parameter domain runs out of doubles: 3^-32 is still several steps
  // of the doubles below 1 (2^-53), 3^-33 less than two.
  double width = 1.0;
  for (int level = 0; level < MaxSubdivisionLevel; ++level)
  {
    width /= 3.0;
  }
  EXPECT_GT(width, 4.0 * 0x1p-53);
  EXPECT_LT(width / 3.0, 2.0 * 0x1p-53);
  // The scene file's settings block and --set say the same.
  EXPECT_THROW(OverrideSetting(SceneSettings(), "max_level=33"), std::exception);
  EXPECT_THROW(OverrideSetting(SceneSettings(), "tolerance=1e-10"), std::exception);
  EXPECT_EQ(OverrideSetting(SceneSettings(), "max_level=32").MaxLevel, 32);
}

TEST(Limits, SubdivisionStopsAtItsPatchBudget)
{
  SubdivisionSettings settings = Finest();
  settings.MaximumPatches = 500;
  IntervalSubdivision subdivision(Cornell(), settings);
  try
  {
    subdivision.Run();
    FAIL() << "the subdivision did not stop at its budget";
  }
  catch (const std::length_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("500 patches"), std::string::npos) << e.what();
  }
  // Refused before splitting: the patches of the last sweep are within the budget.
  EXPECT_LE(subdivision.Patches().size(), 500u);
}

TEST(Limits, SubdivisionRefusesASweepBeyondItsPairTestBudget)
{
  SubdivisionSettings settings = Finest();
  settings.MaximumPairTests = 100000;
  IntervalSubdivision subdivision(Cornell(), settings);
  EXPECT_THROW(subdivision.Run(), std::length_error);
  EXPECT_LE(subdivision.Statistics().PairTests, settings.MaximumPairTests);
  // The default subdivision of the Cornell box is well within the default budgets.
  IntervalSubdivision defaults(Cornell(), SubdivisionSettings());
  EXPECT_TRUE(defaults.Run());
}

TEST(Limits, CoverRefusesAnOversizedGridWithoutAllocating)
{
  SphericalCoverOptions options;
  options.ThetaBins = 4096;
  options.PhiBins = 16384;
  // 2^26 cells x 9 samples: over 19 GiB of R-buffer per thread.
  EXPECT_GT(SphericalCover::WorkingBytesPerThread(options), std::size_t(19) << 30);
  // Every thread holds its own R-buffer.
  EXPECT_GE(
    SphericalCover::WorkingBytes(options, 4), 4 * SphericalCover::WorkingBytesPerThread(options));
  const auto start = std::chrono::steady_clock::now();
  const std::string problem = SphericalCover::MemoryProblem(
    std::vector<Patch>(), options, 2, std::size_t(8192) * 1024 * 1024);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(problem.find("4096 x 16384"), std::string::npos) << problem;
  EXPECT_NE(problem.find("R-buffers"), std::string::npos) << problem;
  // Computed, not allocated: far below the seconds an allocation of gigabytes takes.
  EXPECT_LT(seconds, 0.01);
  // The default grid fits.
  EXPECT_EQ(SphericalCover::MemoryProblem(
              std::vector<Patch>(), SphericalCoverOptions(), 64, std::size_t(8192) * 1024 * 1024),
    "");
  // A grid whose cells overflow int indices is refused before anything is built.
  options.ThetaBins = 65535;
  options.PhiBins = 65535;
  EXPECT_THROW(SphericalCover::MemoryProblem(std::vector<Patch>(), options, 1, ~std::size_t(0)),
    std::invalid_argument);
}

TEST(Limits, WeightTableEstimateGrowsAsThetaSquaredPhi)
{
  const std::size_t small = ReflectanceWeights::EstimateBytes(32, 128);
  EXPECT_LT(small, std::size_t(16) << 20);
  EXPECT_EQ(ReflectanceWeights::EstimateBytes(64, 128), 4 * small);
  // The largest grid the settings allow with one glossy material: tens of TB, refused by the
  // propagation's MemoryLimit before anything is built.
  Material glossy;
  glossy.Type = MaterialType::Phong;
  glossy.Diffuse = glm::dvec3(0.3);
  glossy.Specular = glm::dvec3(0.3);
  glossy.PhongExponent = 20;
  Material white;
  const std::vector<Material> materials = { white, glossy, glossy };
  EXPECT_GT(PointReflectances::EstimateBytes(4096, 16384, materials), std::size_t(1) << 44);
  EXPECT_EQ(PointReflectances::EstimateBytes(32, 128, materials), small);
  EXPECT_EQ(PointReflectances::EstimateBytes(32, 128, { white }), 0u);
}

TEST(Limits, RendererBudgets)
{
  Camera camera;
  camera.Position = glm::dvec3(0, 0, 5);
  camera.Width = 32768;
  camera.Height = 32768;
  RenderSettings settings;
  settings.SamplesPerPixel = 4096;
  settings.MemoryLimitBytes = ~std::size_t(0);
  EXPECT_NE(CheckCamera(camera, settings).find("budget"), std::string::npos);
  camera.Width = camera.Height = 512;
  settings.SamplesPerPixel = 4;
  EXPECT_EQ(CheckCamera(camera, settings), "");
  camera.Position = glm::dvec3(0, 0, 1e19);
  EXPECT_NE(CheckCamera(camera, settings).find("ray casting"), std::string::npos);
}

TEST(Limits, RayCastingRefusesCoordinatesEmbreeAbortsOn)
{
  const BezierPatch far(
    1, 1, { { 0, 0, 2e18 }, { 1e18, 0, 2e18 }, { 0, 1e18, 2e18 }, { 1e18, 1e18, 2e18 } });
  std::vector<Patch> patches;
  patches.emplace_back(0, UVRect::Unit(), 0, far);
  EXPECT_NE(RayCastCoordinateProblem(RayCastPatches(patches)).find("Embree"), std::string::npos);
  const HemisphereGrid grid(8, 16);
  EXPECT_THROW(RayCastFiller(patches, grid, RBufferFillOptions()), std::invalid_argument);
  const BezierPatch near(1, 1, { { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 } });
  patches.clear();
  patches.emplace_back(0, UVRect::Unit(), 0, near);
  EXPECT_EQ(RayCastCoordinateProblem(RayCastPatches(patches)), "");
}

TEST(Limits, PropagationFailsOnNonFiniteEnergy)
{
  // The Cornell box's lamp emitting 1e308: its power pi x area x Le overflows.
  Scene scene = Cornell();
  for (Material& material : scene.Materials)
  {
    if (material.Emission.x > 0.0)
    {
      material.Emission = glm::dvec3(1e308);
    }
  }
  SubdivisionSettings coarse;
  coarse.MaxLevel = 0;
  IntervalSubdivision subdivision(scene, coarse);
  subdivision.Run();
  const std::vector<Patch> patches = subdivision.Patches();
  SphericalCoverOptions options;
  options.ThetaBins = 8;
  options.PhiBins = 32;
  SphericalCover cover;
  cover.Build(patches, options);
  LightPropagation propagation(cover, LightPropagation::MaterialsOfPatches(scene, patches));
  EXPECT_THROW(propagation.Run(), std::overflow_error);
}

TEST(Limits, FingerprintTellsScenesApart)
{
  Scene scene = Cornell();
  const std::string original = Fingerprint(scene);
  EXPECT_EQ(original.size(), 16u);
  EXPECT_EQ(Fingerprint(Cornell()), original);
  // Cameras do not count: a solution renders through any camera.
  scene.Cameras.clear();
  EXPECT_EQ(Fingerprint(scene), original);
  scene.Settings.MaxLevel += 1;
  EXPECT_NE(Fingerprint(scene), original);
  scene = Cornell();
  scene.Materials[0].Diffuse.x *= 0.5;
  EXPECT_NE(Fingerprint(scene), original);
}
