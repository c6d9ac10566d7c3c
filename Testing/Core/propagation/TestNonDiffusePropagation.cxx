// SPDX-License-Identifier: BSD-3-Clause
// Propagation with non-diffuse reflectance (paper §3.5, §5.1): white furnaces of mirror, phong
// and tabulated walls, flat and curved; the energy balance and the independence of the shooting
// order in a closed box of mixed materials; and a mirror carrying light to a patch that cannot
// see the lamp, against the image-source construction, also a small lamp's image seen by a small
// receiver through part of the mirror; the two summations of a directional shot (strip pairs,
// whole-hemisphere grid) agree.
#include "propagation/ExchangeBalance.h"
#include "propagation/LightPropagation.h"

#include "CoverTestUtilities.h"
#include "MaterialTestUtilities.h"
#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "math/Constants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{

/// The hemisphere frame of every patch's characteristic point.
std::vector<HemisphereFrame> FramesOf(const std::vector<Patch>& patches)
{
  std::vector<HemisphereFrame> frames;
  for (const Patch& patch : patches)
  {
    frames.push_back(HemisphereFrame::OfPatch(patch));
  }
  return frames;
}

/// The material of every patch from one material per surface (cycled when there are fewer
/// materials than surfaces).
std::vector<Material> MaterialsPerPatch(const std::vector<Patch>& patches,
  const std::vector<Material>& ofSurface)
{
  std::vector<Material> materials;
  for (const Patch& patch : patches)
  {
    materials.push_back(ofSurface.at(static_cast<size_t>(patch.SurfaceIndex) % ofSurface.size()));
  }
  return materials;
}

/// CoveredScene with the frames of its points and materials given per surface.
struct CoveredPatches : CoveredScene
{
  using CoveredScene::CoveredScene;

  std::vector<HemisphereFrame> Frames() const { return FramesOf(this->Patches); }

  std::vector<Material> PerPatch(const std::vector<Material>& ofSurface) const
  {
    return MaterialsPerPatch(this->Patches, ofSurface);
  }
};

/// The largest relative deviation from `expected` of the incident radiance of the cover's
/// entries (every region of every hemisphere).
double WorstFurnaceEntryError(const SphericalCover& cover,
  const LightPropagation& propagation,
  const glm::dvec3& expected)
{
  double worst = 0.0;
  for (size_t e = 0; e < cover.EntryCount(); ++e)
  {
    for (int b = 0; b < 3; ++b)
    {
      worst = std::max(worst, std::fabs(propagation.IncidentRadiance(e)[b] / expected[b] - 1.0));
    }
  }
  return worst;
}

/// The largest relative deviation from `expected` over the points' brightness / pi and their
/// exitant radiance toward the normal and one oblique direction (the white furnace checks).
double WorstFurnacePointError(const LightPropagation& propagation, const glm::dvec3& expected)
{
  const glm::dvec3 oblique = HemisphereGrid::LocalDirection(1.0, 2.0);
  double worst = 0.0;
  for (size_t i = 0; i < propagation.PatchCount(); ++i)
  {
    const glm::dvec3 values[3] = { propagation.Brightness(i) / Pi,
      propagation.ExitantRadianceToward(i, glm::dvec3(0.0, 0.0, 1.0)),
      propagation.ExitantRadianceToward(i, oblique) };
    for (const glm::dvec3& v : values)
    {
      for (int b = 0; b < 3; ++b)
      {
        worst = std::max(worst, std::fabs(v[b] / expected[b] - 1.0));
      }
    }
  }
  return worst;
}

/// The closed box of mixed materials of the energy and order tests: a diffuse lamp wall, a
/// mirror, two phong walls, the tabulated clay and a white wall.
std::vector<Material> MixedBox()
{
  return { Diffuse(glm::dvec3(0.5), glm::dvec3(1.0, 2.0, 3.0)),
    Mirror(glm::dvec3(0.9, 0.8, 0.7)),
    Phong(glm::dvec3(0.3, 0.2, 0.1), glm::dvec3(0.5, 0.4, 0.6), 30.0),
    Clay(),
    Diffuse(glm::dvec3(0.7, 0.6, 0.5)),
    Phong(glm::dvec3(0.1), glm::dvec3(0.8), 5.0) };
}
}

TEST(NonDiffusePropagation, WhiteFurnacesOfMirrorPhongAndTabulatedWalls)
{
  // A closed enclosure whose walls all emit Le and reflect with the same directional albedo a
  // (the same for every direction) is filled with radiance Le / (1 - a) in every direction,
  // whatever the BRDF's shape. Checked on every entry of the cover (the incident radiance of
  // every region of every hemisphere), on the brightness and toward two directions.
  const glm::dvec3 le(1.0);
  struct Case
  {
    const char* Scene;
    int Split;
    Material Walls;
    glm::dvec3 Albedo;
  };
  const std::vector<Case> cases = {
    { "furnace_box.scene", 3, Mirror(glm::dvec3(0.3, 0.6, 0.8), le), glm::dvec3(0.3, 0.6, 0.8) },
    { "furnace_box.scene",
      3,
      Phong(glm::dvec3(0.2, 0.3, 0.0), glm::dvec3(0.1, 0.3, 0.8), 20.0, le),
      glm::dvec3(0.3, 0.6, 0.8) },
    { "furnace_box.scene", 3, Clay(le), glm::dvec3(0.75, 0.55, 0.35) },
    { "furnace_sphere.scene",
      2,
      Phong(glm::dvec3(0.2, 0.3, 0.0), glm::dvec3(0.1, 0.3, 0.8), 20.0, le),
      glm::dvec3(0.3, 0.6, 0.8) },
    { "furnace_sphere.scene", 2, Mirror(glm::dvec3(0.3, 0.6, 0.8), le), glm::dvec3(0.3, 0.6, 0.8) },
  };
  for (const Case& c : cases)
  {
    CoveredPatches setup(c.Scene, Sanitized ? 2 : c.Split);
    const std::vector<Material> materials = setup.PerPatch({ c.Walls });
    LightPropagation propagation(setup.Cover, materials);
    PropagationSettings settings;
    settings.ConvergenceTolerance = 1e-6;
    ASSERT_TRUE(propagation.Run(settings));
    const glm::dvec3 expected = le / (glm::dvec3(1.0) - c.Albedo);
    const double worstEntry = WorstFurnaceEntryError(setup.Cover, propagation, expected);
    const double worstPoint = WorstFurnacePointError(propagation, expected);
    size_t fallbacks = 0;
    size_t weighted = 0;
    size_t gridShots = 0;
    for (const ShotRecord& record : propagation.History())
    {
      fallbacks += record.MeanFallbacks;
      weighted += record.WeightEvaluations;
      gridShots += record.GridShot ? 1 : 0;
    }
    std::printf("[ Furnace  ] %s, %s walls (%zu patches): %zu shots, %zu strip pairs, %zu grid "
                "shots, %zu mean fallbacks; largest error: entries %.1e, points %.1e\n",
      c.Scene,
      MaterialTypeName(c.Walls.Type),
      setup.Patches.size(),
      propagation.History().size(),
      weighted,
      gridShots,
      fallbacks,
      worstEntry,
      worstPoint);
    EXPECT_LT(worstEntry, 0.01) << c.Scene << " " << MaterialTypeName(c.Walls.Type);
    EXPECT_LT(worstPoint, 0.01) << c.Scene << " " << MaterialTypeName(c.Walls.Type);
    // The walls' weight tables were used (by strip pairs or the grid).
    EXPECT_GT(weighted + gridShots, 0u);
  }
}

TEST(NonDiffusePropagation, FurnacesThroughThePipelineWithTheExchangeBalanced)
{
  // The white furnaces of mirror, phong and tabulated walls as the propagation filter runs them
  // by default: the scene subdivided and refined at its own grid, the frames set and the exchange
  // balanced (ExchangeBalance). The furnace box with a cube inside (occlusion; pairs of points up
  // to 25% from reciprocal) and the curved sphere. Every point's brightness and exitant radiance
  // toward two directions, and the incident radiance of every region, within 1% of
  // Le / (1 - a); emitted = absorbed within 0.1%. (When
  // the balance scaled the stored radiance, which mirrors pass on, rather than the measure it
  // counts with, the mirror walls were 2.3% and 1.0% off.)
  const glm::dvec3 le(1.0);
  struct Case
  {
    Material Walls;
    glm::dvec3 Albedo;
  };
  const std::vector<Case> cases = {
    { Mirror(glm::dvec3(0.3, 0.6, 0.8), le), glm::dvec3(0.3, 0.6, 0.8) },
    { Phong(glm::dvec3(0.2, 0.3, 0.0), glm::dvec3(0.1, 0.3, 0.8), 20.0, le),
      glm::dvec3(0.3, 0.6, 0.8) },
    { Clay(le), glm::dvec3(0.75, 0.55, 0.35) },
  };
  std::vector<std::pair<const char*, Scene>> scenes = { { "furnace sphere",
    LoadSceneFile(ScenePath("furnace_sphere.scene")) } };
  if (!Sanitized)
  {
    scenes.emplace_back("furnace box with a cube inside", FurnaceBoxWithOccluder());
  }
  for (const auto& named : scenes)
  {
    const SceneSettingsPipeline run(named.second, 2, 3, false);
    const std::vector<HemisphereFrame> frames = FramesOf(run.After);
    const ExchangeBalance balance(run.Cover);
    for (const Case& c : cases)
    {
      const std::vector<Material> materials(run.After.size(), c.Walls);
      LightPropagation propagation(run.Cover, materials);
      propagation.SetFrames(frames);
      propagation.SetExchangeFactors(balance.EntryFactors());
      PropagationSettings settings;
      settings.ConvergenceTolerance = 1e-6;
      ASSERT_TRUE(propagation.Run(settings));
      const glm::dvec3 expected = le / (glm::dvec3(1.0) - c.Albedo);
      const double worst = std::max(WorstFurnacePointError(propagation, expected),
        WorstFurnaceEntryError(run.Cover, propagation, expected));
      const double imbalance = propagation.Energy().RelativeImbalance;
      std::printf("[ Furnace  ] %s (%zu points), %s walls, exchange balanced: largest error %.1e, "
                  "energy imbalance %.1e, %zu shots\n",
        named.first,
        run.After.size(),
        MaterialTypeName(c.Walls.Type),
        worst,
        imbalance,
        propagation.History().size());
      EXPECT_LT(worst, 0.01) << named.first << " " << MaterialTypeName(c.Walls.Type);
      EXPECT_LT(imbalance, 1e-3) << named.first << " " << MaterialTypeName(c.Walls.Type);
    }
  }
}

TEST(NonDiffusePropagation, ClosedMixedBoxAbsorbsWhatItEmits)
{
  // Energy: every emitted watt is absorbed at equilibrium, also when mirrors, phong lobes and
  // a tabulated BRDF redistribute it (absorbed = A (E - reflected into the hemisphere)).
  // A directional shot delivers A_i Omega(h_ij) I_ji to receiver i while the shooter's table
  // sends A_j Omega(h_ji) I_ji toward it: the two agree when the cover is reciprocal
  // (A_i Omega(h_ij) = A_j Omega(h_ji)). With one patch per wall every pair of walls is
  // symmetric, so the cover is reciprocal and the balance must hold. With the walls split,
  // point-sampled hemispheres of unequal neighbours are not reciprocal (up to 21% per pair in
  // the 2 x 2 box) and light goes missing (0.70% at 2 x 2, 0.49% at 6 x 6, 0.37% at 8 x 8): the
  // cover's discretisation error, which must fall as the patches shrink (diffuse shots weigh all
  // receivers alike and average it out).
  std::vector<double> splitImbalance;
  const std::vector<int> splits =
    Sanitized ? std::vector<int>{ 1, 3 } : std::vector<int>{ 1, 2, 6 };
  for (int split : splits)
  {
    CoveredPatches setup("furnace_box.scene", split);
    double reciprocity = 0.0;
    for (size_t i = 0; i < setup.Patches.size(); ++i)
    {
      for (size_t j = 0; j < setup.Patches.size(); ++j)
      {
        const double a = setup.Cover.PatchArea(i) * setup.Cover.ProjectedSolidAngle(i, j);
        const double b = setup.Cover.PatchArea(j) * setup.Cover.ProjectedSolidAngle(j, i);
        if (a > 0.0 || b > 0.0)
        {
          reciprocity = std::max(reciprocity, std::fabs(a - b) / std::max(a, b));
        }
      }
    }
    LightPropagation propagation(setup.Cover, setup.PerPatch(MixedBox()));
    PropagationSettings settings;
    settings.ConvergenceTolerance = 1e-8;
    ASSERT_TRUE(propagation.Run(settings));
    const EnergyBalance energy = propagation.Energy();
    std::printf("[ Energy   ] mixed box split %d: emitted %.6f %.6f %.6f W, absorbed %.6f %.6f "
                "%.6f W, relative imbalance %.1e, %zu shots; worst pair reciprocity %.1e\n",
      split,
      energy.Emitted.x,
      energy.Emitted.y,
      energy.Emitted.z,
      energy.Absorbed.x,
      energy.Absorbed.y,
      energy.Absorbed.z,
      energy.RelativeImbalance,
      propagation.History().size(),
      reciprocity);
    // With the exchange balanced (ExchangeBalance): a shot's power then arrives in full when its
    // radiance is the same toward every receiver (emission, Lambertian reflection); directional
    // shots and reflections keep an error of the order of how their radiance varies across the
    // cover's non-reciprocal pairs (LightPropagation).
    LightPropagation balanced(setup.Cover, setup.PerPatch(MixedBox()));
    balanced.SetExchangeFactors(ExchangeBalance(setup.Cover).EntryFactors());
    ASSERT_TRUE(balanced.Run(settings));
    std::printf("[ Energy   ] mixed box split %d, exchange balanced: relative imbalance %.1e\n",
      split,
      balanced.Energy().RelativeImbalance);
    if (split == 1)
    {
      ASSERT_LT(reciprocity, 1e-9);
      EXPECT_LT(energy.RelativeImbalance, 1e-3);
      EXPECT_LT(balanced.Energy().RelativeImbalance, 1e-3);
    }
    splitImbalance.push_back(balanced.Energy().RelativeImbalance);
    // Diffuse shooters keep the closed-form shot (§5.2): no weight table is touched.
    for (const ShotRecord& record : propagation.History())
    {
      if (propagation.IsLambertian(record.Shooter))
      {
        ASSERT_EQ(record.WeightEvaluations, 0u);
        ASSERT_FALSE(record.GridShot);
      }
    }
  }
  if (!Sanitized)
  {
    // 6 x 6 against 2 x 2: the discretisation error falls with the patch size.
    EXPECT_LT(splitImbalance[2], 0.8 * splitImbalance[1]);
  }
}

TEST(NonDiffusePropagation, ShootingOrderDoesNotChangeTheEquilibrium)
{
  // Brightest first and a fixed order reach the same equilibrium, with the cover's exchange as
  // built and balanced (the filter's default: the factors are fixed before the first shot, so
  // the propagation stays linear). The furnace box with a cube inside, split 2 x 2, in the mixed
  // materials: its cover is not balanced as built (the plain split box is, by symmetry).
  const std::vector<Patch> patches = SplitScene(FurnaceBoxWithOccluder(), 2);
  SphericalCover cover;
  ASSERT_TRUE(cover.Build(patches));
  const std::vector<Material> materials = MaterialsPerPatch(patches, MixedBox());
  const std::vector<HemisphereFrame> frames = FramesOf(patches);
  const ExchangeBalance balance(cover);
  double farthest = 0.0;
  for (double f : balance.EntryFactors())
  {
    farthest = std::max(farthest, std::fabs(f - 1.0));
  }
  ASSERT_GT(farthest, 1e-3) << "the balance has something to change";
  for (bool balanced : { false, true })
  {
    LightPropagation brightest(cover, materials);
    LightPropagation fixed(cover, materials);
    for (LightPropagation* propagation : { &brightest, &fixed })
    {
      propagation->SetFrames(frames);
      if (balanced)
      {
        propagation->SetExchangeFactors(balance.EntryFactors());
      }
    }
    ASSERT_TRUE(RunInBothOrders(brightest, fixed));
    double worst = 0.0;
    double largest = 0.0;
    for (size_t e = 0; e < cover.EntryCount(); ++e)
    {
      for (int k = 0; k < 3; ++k)
      {
        worst = std::max(
          worst, std::fabs(brightest.IncidentRadiance(e)[k] - fixed.IncidentRadiance(e)[k]));
        largest = std::max(largest, brightest.IncidentRadiance(e)[k]);
      }
    }
    double worstBrightness = 0.0;
    for (size_t i = 0; i < patches.size(); ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        worstBrightness = std::max(worstBrightness,
          std::fabs(brightest.Brightness(i)[k] - fixed.Brightness(i)[k]) /
            std::max(brightest.Brightness(i)[k], 1e-300));
      }
    }
    std::printf("[ Order    ] mixed box with a cube inside%s (largest |f - 1| %.1e): brightest "
                "first %zu shots, fixed order %zu shots, "
                "largest difference %.1e of the largest incident radiance, brightness %.1e\n",
      balanced ? ", exchange balanced" : "",
      balanced ? farthest : 0.0,
      brightest.History().size(),
      fixed.History().size(),
      worst / largest,
      worstBrightness);
    EXPECT_LT(worst, 1e-4 * largest);
    EXPECT_LT(worstBrightness, 1e-4);
  }
}

TEST(NonDiffusePropagation, GridAndStripPairShotsAgree)
{
  // The two ways a directional shot sums its weight table (DirectionalMethod): strip pairs
  // through the table's cumulative sums, and the whole hemisphere as a grid of cells through
  // ReflectanceWeights::Reflect (direct terms and Fourier transforms). They are the same sum
  // in another order, so the same shots must give the same equilibrium up to rounding, also
  // toward receivers without h_ji (frames given: the fallback toward the direction's cell).
  CoveredPatches setup("furnace_box.scene", 3);
  const std::vector<Material> materials = setup.PerPatch(MixedBox());
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-7;
  settings.Order = ShootingOrder::FixedOrder;
  std::vector<std::vector<glm::dvec3>> incident;
  std::size_t gridShots[3] = {};
  std::size_t pairShots[3] = {};
  const DirectionalMethod methods[3] = {
    DirectionalMethod::StripPairs, DirectionalMethod::Grid, DirectionalMethod::Automatic
  };
  std::size_t shots = 0;
  for (int m = 0; m < 3; ++m)
  {
    LightPropagation propagation(setup.Cover, materials);
    propagation.SetFrames(setup.Frames());
    propagation.SetDirectionalMethod(methods[m]);
    ASSERT_TRUE(propagation.Run(settings));
    for (const ShotRecord& record : propagation.History())
    {
      gridShots[m] += record.GridShot ? 1 : 0;
      pairShots[m] += record.WeightEvaluations > 0 ? 1 : 0;
    }
    incident.push_back(propagation.IncidentRadiances());
    if (m == 0)
    {
      shots = propagation.History().size();
    }
    // The fixed order shoots the same patches whatever the method.
    EXPECT_EQ(propagation.History().size(), shots);
  }
  EXPECT_EQ(gridShots[0], 0u);
  EXPECT_GT(pairShots[0], 0u);
  EXPECT_GT(gridShots[1], 0u);
  EXPECT_EQ(pairShots[1], 0u);
  for (int m : { 1, 2 })
  {
    double worst = 0.0;
    double largest = 0.0;
    for (size_t e = 0; e < setup.Cover.EntryCount(); ++e)
    {
      for (int k = 0; k < 3; ++k)
      {
        worst = std::max(worst, std::fabs(incident[0][e][k] - incident[m][e][k]));
        largest = std::max(largest, incident[0][e][k]);
      }
    }
    std::printf("[ Methods  ] mixed box split 3, %zu shots: strip pairs vs %s (%zu grid shots, "
                "%zu strip-pair shots): largest difference %.1e of the largest incident radiance\n",
      shots,
      m == 1 ? "grid" : "automatic",
      gridShots[m],
      pairShots[m],
      worst / largest);
    EXPECT_LT(worst, 1e-10 * largest);
  }
}

namespace
{
/// Projected solid angle of the square [-a, a]^2 in a plane parallel to the tangent plane at
/// distance d, centred under the point: four corner rectangles of the differential-area to
/// parallel-rectangle form factor (Howell C-2 style closed form), times pi.
double CentredSquare(double a, double d)
{
  const double x = a / d;
  const double y = a / d;
  const double corner = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                          y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
    (2.0 * Pi);
  return Pi * 4.0 * corner;
}
}

namespace
{
/// The materials of the mirror configurations below: surface 0 a mirror (k_s), 1 a black lamp
/// (Le), any other black.
std::vector<Material> MirrorLampReceiver(const std::vector<Patch>& patches,
  const glm::dvec3& ks,
  const glm::dvec3& le)
{
  std::vector<Material> materials;
  for (const Patch& patch : patches)
  {
    materials.push_back(patch.SurfaceIndex == 0 ? Mirror(ks)
        : patch.SurfaceIndex == 1               ? Diffuse(glm::dvec3(0.0), le)
                                                : Diffuse(glm::dvec3(0.0)));
  }
  return materials;
}

/// The mirror configuration below with a receiver of half-size `half`; returns the updates
/// served without h_ji.
std::size_t CheckMirrorCarriesLight(double half, bool frames)
{
  // A large lamp ceiling (z = 1, facing down, Le, black) over a flat mirror floor
  // [-1, 1]^2 (z = 0, k_s), and a small black receiver just under the ceiling
  // (z = 1 - eps, half-size 0.1, facing down). The receiver cannot see the lamp (it lies
  // behind it), only the mirror, in which it sees (image-source construction) the lamp's
  // mirror image at distance 2 - eps with radiance k_s Le, except where its own image hides it:
  //   E = k_s Le (Omega(mirror, half-size 1 at distance d) - Omega(own image, half-size 0.1 at
  //   distance 2 d)),  d = 1 - eps.
  // The lamp is large enough (half-size 2.5) that its image fills the whole mirror.
  const double eps = 1e-3;
  const double d = 1.0 - eps;
  const glm::dvec3 ks(0.8, 0.6, 0.4);
  const glm::dvec3 le(1.0, 2.0, 3.0);
  std::vector<Patch> patches;
  const int split = Sanitized ? 10 : 20;
  AppendSplit(patches, Parallelogram({ -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }), 0, split, split);
  AppendSplit(patches, Parallelogram({ -2.5, -2.5, 1 }, { 0, 5, 0 }, { 5, 0, 0 }), 1, 1, 1);
  AppendSplit(
    patches, Parallelogram({ -half, -half, d }, { 0, 2 * half, 0 }, { 2 * half, 0, 0 }), 2, 1, 1);
  EXPECT_LT(patches[static_cast<size_t>(split * split)].Normal.z, 0.0);
  EXPECT_LT(patches.back().Normal.z, 0.0);
  SphericalCover cover;
  EXPECT_TRUE(cover.Build(patches));
  const std::vector<Material> materials = MirrorLampReceiver(patches, ks, le);
  const size_t receiver = patches.size() - 1;
  // The receiver sees the mirror only: no entry of its row is the lamp.
  const size_t lamp = receiver - 1;
  EXPECT_LT(cover.FindEntry(receiver, lamp), 0);

  LightPropagation propagation(cover, materials);
  if (frames)
  {
    propagation.SetFrames(FramesOf(patches));
  }
  EXPECT_THROW(propagation.SetFrames(std::vector<HemisphereFrame>(2)), std::invalid_argument);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-9;
  EXPECT_TRUE(propagation.Run(settings));
  const double omega = CentredSquare(1.0, d) - CentredSquare(half, 2.0 * d);
  const glm::dvec3 expected = ks * le * omega;
  const glm::dvec3 got = propagation.Irradiance(receiver);
  size_t fallbacks = 0;
  for (const ShotRecord& record : propagation.History())
  {
    fallbacks += record.Fallbacks;
  }
  std::printf("[ Mirror   ] receiver half-size %g: irradiance %.5f %.5f %.5f, image-source value "
              "%.5f %.5f %.5f "
              "(%zu updates without h_ji)\n",
    half,
    got.x,
    got.y,
    got.z,
    expected.x,
    expected.y,
    expected.z,
    fallbacks);
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_NEAR(got[b], expected[b], 0.02 * expected[b]) << "band " << b;
  }
  // Without the mirror's reflection the receiver stays dark: the light really came through it.
  std::vector<Material> matte = materials;
  for (size_t i = 0; i < static_cast<size_t>(split * split); ++i)
  {
    matte[i] = Mirror(glm::dvec3(0.0));
  }
  LightPropagation dark(cover, matte);
  EXPECT_TRUE(dark.Run(settings));
  EXPECT_EQ(dark.Irradiance(receiver), glm::dvec3(0.0));
  return fallbacks;
}
}

TEST(NonDiffusePropagation, AMirrorCarriesLight)
{
  // The receiver large enough to hold cells of every mirror patch's hemisphere: the mirror
  // serves it by the regions h_ji.
  EXPECT_EQ(CheckMirrorCarriesLight(0.1, false), 0u);
  // A receiver 10x smaller wins no cell of most mirror patches' hemispheres (h_ji null): it is
  // served by the direction P_i - P_j in the mirror's frame (SetFrames), with the same
  // accuracy.
  EXPECT_GT(CheckMirrorCarriesLight(0.01, true), 0u);
}

namespace
{
/// Projected solid angle, seen from a point, of the rectangle [x0, x1] x [y0, y1] in a plane
/// parallel to the point's tangent plane at distance d, the point over the origin: the corner
/// rectangles' differential-area to parallel-rectangle form factors (odd in x and in y), by
/// inclusion and exclusion, times pi.
double ParallelRectangle(double x0, double x1, double y0, double y1, double d)
{
  const auto corner = [d](double x, double y)
  {
    const double a = x / d;
    const double b = y / d;
    return 0.5 *
      (a / std::sqrt(1 + a * a) * std::atan(b / std::sqrt(1 + a * a)) +
        b / std::sqrt(1 + b * b) * std::atan(a / std::sqrt(1 + b * b)));
  };
  return corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
}
} // namespace

namespace
{
/// The configuration of ASmallReceiverSeesTheLampsMirrorImageThroughTheMirror: the receiver's
/// irradiance by the propagation and by the image source, per band.
void MirrorImageOfASmallLamp(double d,
  double height,
  double lampX,
  double lampHalf,
  double receiverHalf,
  glm::dvec3& got,
  glm::dvec3& expected)
{
  const glm::dvec3 ks(0.9, 0.7, 0.5);
  const glm::dvec3 le(1.0, 2.0, 3.0);
  std::vector<Patch> patches;
  const int split = 20;
  AppendSplit(patches, Parallelogram({ -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }), 0, split, split);
  AppendSplit(patches,
    Parallelogram(
      { lampX - lampHalf, -lampHalf, height }, { 0, 2 * lampHalf, 0 }, { 2 * lampHalf, 0, 0 }),
    1,
    1,
    1);
  AppendSplit(patches,
    Parallelogram(
      { -receiverHalf, -receiverHalf, d }, { 0, 2 * receiverHalf, 0 }, { 2 * receiverHalf, 0, 0 }),
    2,
    1,
    1);
  SphericalCover cover;
  ASSERT_TRUE(cover.Build(patches));
  const std::vector<Material> materials = MirrorLampReceiver(patches, ks, le);
  const size_t receiver = patches.size() - 1;
  ASSERT_LT(patches[receiver].Normal.z, 0.0);
  ASSERT_LT(patches[receiver - 1].Normal.z, 0.0);
  ASSERT_LT(cover.FindEntry(receiver, receiver - 1), 0); // the lamp is out of its sight
  LightPropagation propagation(cover, materials);
  propagation.SetFrames(FramesOf(patches));
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-9;
  ASSERT_TRUE(propagation.Run(settings));
  got = propagation.Irradiance(receiver);
  // The image [lampX - a, lampX + a] x [-a, a] at distance d + H, averaged over 16 x 16 points
  // of the receiver (its own image, straight below, does not hide it here).
  double omega = 0.0;
  const int n = 16;
  for (int u = 0; u < n; ++u)
  {
    for (int v = 0; v < n; ++v)
    {
      const double x = receiverHalf * (2.0 * (u + 0.5) / n - 1.0);
      const double y = receiverHalf * (2.0 * (v + 0.5) / n - 1.0);
      omega += ParallelRectangle(
        lampX - lampHalf - x, lampX + lampHalf - x, -lampHalf - y, lampHalf - y, d + height);
    }
  }
  expected = ks * le * (omega / (n * n));
}
} // namespace

TEST(NonDiffusePropagation, ASmallReceiverSeesTheLampsMirrorImageThroughTheMirror)
{
  // A small lamp (half-size a, facing down at height H, off to the side) over a flat mirror
  // floor [-1, 1]^2 (k_s), and a small black receiver facing down at height d over the centre:
  // the lamp is behind the receiver's tangent plane, so all its light comes by the mirror, in
  // which it sees the lamp's mirror image (image-source construction) at distance d + H,
  // partly covering the mirror. Its irradiance is k_s Le times the image's projected solid
  // angle, averaged over the receiver. A receiver this small sees each mirror patch along a
  // pencil of directions from the mirror patch's characteristic point (h_ji): taking the
  // mirror's radiance along that pencil point-samples the image (paper §5.1 evaluates I in the
  // direction P_i - P_j); the receiver's view of the mirror (LightPropagation.h) averages it
  // over the whole of each mirror patch as the receiver sees it.
  // Receivers near the mirror under a far lamp (d / H <= 0.2): the mirror patches'
  // characteristic points then see nearly what the receiver sees through them (the rest of the
  // error: the parallax of P_j against the point of Q_j the receiver looks at, d / (d + H) of
  // the receiver's view of a mirror patch, and the cells of H_j). {d, H, lamp centre x, a,
  // receiver half-size}; the next to last, a receiver large enough to see the image through
  // the mirror patches' hemispheres' regions, passes either way.
  const double configs[][5] = { { 0.2, 2.0, 0.6, 0.4, 0.02 },
    { 0.3, 1.5, 0.5, 0.3, 0.02 },
    { 0.25, 2.0, 0.8, 0.5, 0.02 },
    { 0.2, 1.5, 0.4, 0.3, 0.02 },
    { 0.3, 2.0, 0.7, 0.35, 0.02 },
    { 0.2, 2.0, 0.5, 0.25, 0.05 },
    { 0.15, 1.5, 0.45, 0.3, 0.01 } };
  double meanError = 0.0;
  for (const auto& c : configs)
  {
    glm::dvec3 got;
    glm::dvec3 expected;
    MirrorImageOfASmallLamp(c[0], c[1], c[2], c[3], c[4], got, expected);
    std::printf("[ Image    ] d %g, H %g, lamp at x %g, half-size %g, receiver half-size %g: "
                "irradiance %.5f %.5f %.5f, image-source value %.5f %.5f %.5f (%+.2f %%)\n",
      c[0],
      c[1],
      c[2],
      c[3],
      c[4],
      got.x,
      got.y,
      got.z,
      expected.x,
      expected.y,
      expected.z,
      100.0 * (got.x / expected.x - 1.0));
    // Measured 2026-12-07: +2.5, +1.8, +3.1, +7.9, +4.0, -2.0, +1.9 %; the mirror's radiance
    // along h_ji instead: -59, +10, +42, -74, -48, -2.0, -100 %.
    for (int b = 0; b < 3; ++b)
    {
      EXPECT_NEAR(got[b], expected[b], 0.1 * expected[b]) << "band " << b << ", d " << c[0];
    }
    meanError += std::fabs(got.x / expected.x - 1.0) / static_cast<double>(std::size(configs));
  }
  EXPECT_LT(meanError, 0.05);
}
