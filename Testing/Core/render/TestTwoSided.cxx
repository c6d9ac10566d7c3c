// SPDX-License-Identifier: BSD-3-Clause
// Two-sided surfaces (Data/scenes/FORMAT.md "two_sided": the surface sends and receives light on
// both sides): the loader makes one the patch and its reversed copy, each side gets its own
// hemispheres in the cover (paper §3.3), emits, receives and reflects on its own in the
// propagation (§3.5), and is seen from its own half-space in the render (§5.3). A white furnace
// holding a two-sided plate then stays uniform, with the energy balanced, by both fills, and a
// camera under the plate sees the analytic radiance on its back side.
#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"
#include "math/Constants.h"
#include "propagation/ExchangeBalance.h"
#include "propagation/LightPropagation.h"
#include "render/RadianceRenderer.h"
#include "scene/SceneLoader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// furnace_two_sided.scene: the unit cube (rho 0.5, Le 1) with a two-sided plate of the same
/// material at z = 0.5 over [0.2, 0.8]^2, its front up. Analytic: L = Le / (1 - rho) = 2 on
/// every side of every surface, the plate's two sides included.
constexpr double Analytic = 2.0;

/// The uniform split, its cover by `fill` with the scene's two-sided surfaces, the propagation
/// (balanced, as the pipeline runs it by default, or as built) run to equilibrium.
struct TwoSidedFurnace
{
  Scene Environment;
  std::vector<Patch> Patches;
  SphericalCover Cover;
  std::vector<Material> Materials;
  std::unique_ptr<LightPropagation> Propagation;

  TwoSidedFurnace(RBufferFill fill, int split, bool balanced = true)
    : Environment(LoadSceneFile(ScenePath("furnace_two_sided.scene")))
    , Patches(SplitScene(this->Environment, split))
  {
    SphericalCoverOptions options;
    options.Fill = fill;
    for (const Surface& surface : this->Environment.Surfaces)
    {
      options.FillOptions.TwoSidedSurfaces.push_back(surface.TwoSided);
    }
    if (!this->Cover.Build(this->Patches, options, ThreadedFor(2)))
    {
      throw std::runtime_error("cover not built");
    }
    this->Materials = LightPropagation::MaterialsOfPatches(this->Environment, this->Patches);
    this->Propagation = std::make_unique<LightPropagation>(this->Cover, this->Materials);
    if (balanced)
    {
      this->Propagation->SetExchangeFactors(ExchangeBalance(this->Cover).EntryFactors());
    }
    PropagationSettings settings;
    settings.ConvergenceTolerance = 1e-8;
    if (!this->Propagation->Run(settings))
    {
      throw std::runtime_error("propagation did not converge");
    }
  }

  /// The area-weighted exitant radiance (band 0) of each scene surface.
  std::vector<double> SurfaceRadiance() const
  {
    std::vector<double> sum(this->Environment.Surfaces.size(), 0.0);
    std::vector<double> area(this->Environment.Surfaces.size(), 0.0);
    for (size_t i = 0; i < this->Patches.size(); ++i)
    {
      const size_t s = static_cast<size_t>(this->Patches[i].SurfaceIndex);
      sum[s] += this->Patches[i].Area * this->Propagation->ExitantRadiance(i).x;
      area[s] += this->Patches[i].Area;
    }
    for (size_t s = 0; s < sum.size(); ++s)
    {
      sum[s] /= area[s];
    }
    return sum;
  }
};

const char* FillName(RBufferFill fill)
{
  return fill == RBufferFill::RayCasting ? "ray fill" : "projection fill";
}
}

TEST(TwoSided, LoaderMakesATwoSidedSurfaceItsTwoSides)
{
  const Scene scene = LoadSceneFile(ScenePath("furnace_two_sided.scene"));
  // 6 walls, then the plate as the patch and its reversed copy, both of the entry's name.
  ASSERT_EQ(scene.Surfaces.size(), 8u);
  ASSERT_EQ(scene.SurfaceNames.size(), 7u);
  for (size_t s = 0; s < 6; ++s)
  {
    EXPECT_FALSE(scene.Surfaces[s].TwoSided);
  }
  const Surface& front = scene.Surfaces[6];
  const Surface& back = scene.Surfaces[7];
  EXPECT_TRUE(front.TwoSided);
  EXPECT_TRUE(back.TwoSided);
  EXPECT_EQ(front.NameIndex, 6);
  EXPECT_EQ(back.NameIndex, 6);
  EXPECT_EQ(front.MaterialIndex, back.MaterialIndex);
  EXPECT_NEAR(front.Patch.Normal(0.5, 0.5).z, 1.0, 1e-12);
  EXPECT_NEAR(back.Patch.Normal(0.5, 0.5).z, -1.0, 1e-12);
  // The same place: the copy's corners are the plate's.
  for (const double u : { 0.0, 1.0 })
  {
    for (const double v : { 0.0, 1.0 })
    {
      const glm::dvec3 p = front.Patch.Evaluate(u, v);
      bool found = false;
      for (const double a : { 0.0, 1.0 })
      {
        for (const double b : { 0.0, 1.0 })
        {
          found = found || glm::length(back.Patch.Evaluate(a, b) - p) < 1e-15;
        }
      }
      EXPECT_TRUE(found) << "corner (" << u << ", " << v << ")";
    }
  }
}

TEST(TwoSided, WhiteFurnaceWithATwoSidedPlateIsUniformAndBalanced)
{
  // A closed furnace of uniform emission Le and reflectance rho has L = Le / (1 - rho)
  // everywhere: the plate's sides included, and every wall whatever side of the plate it sees.
  // Both sides of the plate emit, so the power emitted is pi Le times the walls' area plus
  // twice the plate's, and at equilibrium all of it is absorbed.
  for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
  {
    const TwoSidedFurnace asBuilt(fill, 4, false);
    double worstAsBuilt = 0.0;
    for (size_t i = 0; i < asBuilt.Patches.size(); ++i)
    {
      worstAsBuilt = std::max(
        worstAsBuilt, std::fabs(asBuilt.Propagation->ExitantRadiance(i).x / Analytic - 1.0));
    }
    std::printf("[ TwoSided ] %s, exchange as built: worst point %.2e, imbalance %.2e\n",
      FillName(fill),
      worstAsBuilt,
      asBuilt.Propagation->Energy().RelativeImbalance);
    // The cover alone closes the furnace: every direction from every side meets a side facing it.
    EXPECT_LT(worstAsBuilt, 5e-3) << FillName(fill);
    EXPECT_LT(asBuilt.Propagation->Energy().RelativeImbalance, 5e-3) << FillName(fill);
    const TwoSidedFurnace furnace(fill, 4);
    const std::vector<double> radiance = furnace.SurfaceRadiance();
    double worstPoint = 0.0;
    for (size_t i = 0; i < furnace.Patches.size(); ++i)
    {
      worstPoint =
        std::max(worstPoint, std::fabs(furnace.Propagation->ExitantRadiance(i).x / Analytic - 1.0));
    }
    const EnergyBalance energy = furnace.Propagation->Energy();
    std::printf("[ TwoSided ] furnace with a two-sided plate, %s (%zu points):",
      FillName(fill),
      furnace.Patches.size());
    for (size_t s = 0; s < radiance.size(); ++s)
    {
      std::printf(" %s%s %.4f",
        furnace.Environment
          .SurfaceNames[static_cast<size_t>(furnace.Environment.Surfaces[s].NameIndex)]
          .c_str(),
        s == 7 ? " (back)" : "",
        radiance[s]);
    }
    std::printf("; worst point %.2e; emitted %.5f W, absorbed %.5f W, imbalance %.2e\n",
      worstPoint,
      energy.Emitted.x,
      energy.Absorbed.x,
      energy.RelativeImbalance);
    for (size_t s = 0; s < radiance.size(); ++s)
    {
      EXPECT_NEAR(radiance[s] / Analytic, 1.0, 5e-3) << FillName(fill) << ", surface " << s;
    }
    EXPECT_LT(worstPoint, 5e-3) << FillName(fill);
    // Le pi (6 + 2 x 0.36): the plate emits from both sides.
    EXPECT_NEAR(energy.Emitted.x, Pi * (6.0 + 2.0 * 0.36), 1e-9) << FillName(fill);
    EXPECT_LT(energy.RelativeImbalance, 5e-3) << FillName(fill);
  }
}

TEST(TwoSided, TheBackOfThePlateSeenByACameraHasTheAnalyticRadiance)
{
  // The scene's camera lies under the plate and looks up at its back side: each pixel on the
  // plate shows the radiance of the plate's lower side (the reversed copy's front), L = 2.
  const TwoSidedFurnace furnace(RBufferFill::RayCasting, 4);
  std::vector<glm::dvec3> exitant;
  for (size_t i = 0; i < furnace.Patches.size(); ++i)
  {
    exitant.push_back(furnace.Propagation->ExitantRadiance(i));
  }
  std::vector<bool> twoSided;
  for (const Surface& surface : furnace.Environment.Surfaces)
  {
    twoSided.push_back(surface.TwoSided);
  }
  const RadianceRenderer renderer(furnace.Patches,
    CharacteristicPointInterpolator::OfPatches(furnace.Patches),
    exitant,
    twoSided);
  ASSERT_FALSE(furnace.Environment.Cameras.empty());
  Camera camera = furnace.Environment.Cameras.front();
  camera.Width = 48;
  camera.Height = 48;
  RenderSettings settings;
  settings.SamplesPerPixel = 4;
  RenderedImage image;
  ASSERT_TRUE(renderer.Render(camera, settings, image));
  size_t plate = 0;
  double worstPlate = 0.0;
  double worst = 0.0;
  for (size_t p = 0; p < image.SurfaceId.size(); ++p)
  {
    ASSERT_GE(image.SurfaceId[p], 0) << "pixel " << p << " sees nothing";
    const double error = std::fabs(image.Radiance[3 * p] / Analytic - 1.0);
    worst = std::max(worst, error);
    // The upper side (surface 6) faces away from the camera: never the visible surface.
    EXPECT_NE(image.SurfaceId[p], 6) << "pixel " << p;
    if (image.SurfaceId[p] == 7)
    {
      ++plate;
      worstPlate = std::max(worstPlate, error);
    }
  }
  // The centre pixel looks straight up at the plate's lower side, 0.45 away.
  const size_t centre = static_cast<size_t>((camera.Height / 2) * camera.Width + camera.Width / 2);
  EXPECT_EQ(image.SurfaceId[centre], 7);
  EXPECT_NEAR(image.Depth[centre], 0.45, 1e-3);
  std::printf("[ TwoSided ] camera under the plate: %zu of %zu pixels on its back side, worst "
              "|L / 2 - 1| there %.2e, over the image %.2e\n",
    plate,
    image.SurfaceId.size(),
    worstPlate,
    worst);
  EXPECT_GT(plate, image.SurfaceId.size() / 4);
  EXPECT_LT(worstPlate, 5e-3);
  EXPECT_LT(worst, 5e-3);
}
