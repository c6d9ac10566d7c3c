// SPDX-License-Identifier: BSD-3-Clause
// Progressive light propagation over the spherical cover (paper §5.1, diffuse): the white
// furnace (Documentation/Verification.md#correctness-references) in a flat and a curved enclosure,
// energy balance, independence of the shooting order, Howell's parallel rectangles with one lamp,
// the O(column) cost of a shot (§5.2), progress, abort and the shot limit, and the material checks.
#include "propagation/LightPropagation.h"

#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"
#include "math/Constants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{

/// Largest relative deviation, over patches and bands, of the exitant radiance from the
/// furnace's Le / (1 - rho), both taken from the scene's material of each patch.
double WorstFurnaceError(const LightPropagation& propagation, const std::vector<Material>& m)
{
  double worst = 0.0;
  for (size_t i = 0; i < propagation.PatchCount(); ++i)
  {
    const glm::dvec3 expected = m[i].Emission / (glm::dvec3(1.0) - m[i].Diffuse);
    const glm::dvec3 got = propagation.ExitantRadiance(i);
    for (int b = 0; b < 3; ++b)
    {
      worst = std::max(worst, std::fabs(got[b] / expected[b] - 1.0));
    }
  }
  return worst;
}

/// The largest difference of two propagations' exitant radiances over the patches and bands,
/// with the largest radiance of `a` in `largest`.
double LargestExitantDifference(const LightPropagation& a,
  const LightPropagation& b,
  double& largest)
{
  double worst = 0.0;
  largest = 0.0;
  for (size_t i = 0; i < a.PatchCount(); ++i)
  {
    const glm::dvec3 x = a.ExitantRadiance(i);
    const glm::dvec3 y = b.ExitantRadiance(i);
    for (int k = 0; k < 3; ++k)
    {
      worst = std::max(worst, std::fabs(x[k] - y[k]));
      largest = std::max(largest, x[k]);
    }
  }
  return worst;
}
}

TEST(LightPropagation, WhiteFurnaceIsUniformInFlatAndCurvedEnclosures)
{
  // Documentation/Verification.md#correctness-references: a closed enclosure with uniform emission
  // Le and reflectance rho has radiance Le / (1 - rho) everywhere, whatever its shape.
  for (const char* name : { "furnace_box.scene", "furnace_sphere.scene" })
  {
    const bool sphere = std::string(name) == "furnace_sphere.scene";
    CoveredScene setup(name, Sanitized || sphere ? 2 : 3);
    for (const Material& material : setup.Materials)
    {
      ASSERT_EQ(material.Type, MaterialType::Diffuse);
      ASSERT_TRUE(material.IsEmitter());
    }
    LightPropagation propagation(setup.Cover, setup.Materials);
    PropagationSettings settings;
    settings.ConvergenceTolerance = 1e-6;
    ASSERT_TRUE(propagation.Run(settings));
    const double worst = WorstFurnaceError(propagation, setup.Materials);
    const std::vector<ShotRecord>& history = propagation.History();
    ASSERT_FALSE(history.empty());
    std::printf("[ Furnace  ] %s (%zu patches, %zu entries): %zu shots, %.2f us/shot, "
                "largest |L / (Le / (1 - rho)) - 1| = %.1e\n",
      name,
      setup.Patches.size(),
      setup.Cover.EntryCount(),
      history.size(),
      1e6 * history.back().Seconds / static_cast<double>(history.size()),
      worst);
    EXPECT_LT(worst, 5e-3) << name;
    EXPECT_LT(history.back().MaxUnshotRelative, settings.ConvergenceTolerance);
    // Brightness (§5) of a diffuse patch is pi times its exitant radiance.
    for (size_t i = 0; i < setup.Patches.size(); ++i)
    {
      const glm::dvec3 b = propagation.Brightness(i);
      const glm::dvec3 l = propagation.ExitantRadiance(i);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_NEAR(b[k], Pi * l[k], 1e-12 * b[k]);
      }
    }
  }
}

TEST(LightPropagation, ClosedBoxAbsorbsWhatItEmits)
{
  // At equilibrium in a closed scene every emitted watt is eventually absorbed:
  // sum_i pi A_i Le_i = sum_i A_i (1 - rho_i) E_i, per band.
  CoveredScene setup("furnace_box.scene", 3);
  LightPropagation propagation(setup.Cover, setup.Materials);
  const EnergyBalance before = propagation.Energy();
  EXPECT_DOUBLE_EQ(before.Absorbed.x, 0.0);
  EXPECT_NEAR(before.RelativeImbalance, 1.0, 1e-15);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-7;
  ASSERT_TRUE(propagation.Run(settings));
  const EnergyBalance after = propagation.Energy();
  // The emitted power from the patches' own areas and the scene's materials.
  glm::dvec3 emitted(0.0);
  for (size_t i = 0; i < setup.Patches.size(); ++i)
  {
    emitted += Pi * setup.Patches[i].Area * setup.Materials[i].Emission;
  }
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_NEAR(after.Emitted[b], emitted[b], 1e-9 * emitted[b]);
    EXPECT_NEAR(after.Absorbed[b], after.Emitted[b], 1e-3 * after.Emitted[b]) << "band " << b;
  }
  std::printf("[ Energy   ] furnace box: emitted %.6f %.6f %.6f W, absorbed %.6f %.6f %.6f W, "
              "relative imbalance %.1e\n",
    after.Emitted.x,
    after.Emitted.y,
    after.Emitted.z,
    after.Absorbed.x,
    after.Absorbed.y,
    after.Absorbed.z,
    after.RelativeImbalance);
  EXPECT_LT(after.RelativeImbalance, 1e-3);
  // The unshot energy shrinks as light is absorbed (every rho < 1).
  EXPECT_LT(propagation.History().back().UnshotEnergy, 1e-5 * propagation.EmittedPower());
}

TEST(LightPropagation, ShootingOrderDoesNotChangeTheEquilibrium)
{
  // The equilibrium is the solution of a linear system; the order in which unshot light is
  // propagated changes only the path to it. The Cornell box (open, coloured walls, one lamp)
  // gives a non-uniform solution, the furnace box a uniform one.
  for (const char* name : { "cornell_box.scene", "furnace_box.scene" })
  {
    CoveredScene setup(name, 2);
    LightPropagation brightest(setup.Cover, setup.Materials);
    LightPropagation fixed(setup.Cover, setup.Materials);
    ASSERT_TRUE(RunInBothOrders(brightest, fixed));
    double largest = 0.0;
    const double worst = LargestExitantDifference(brightest, fixed, largest);
    std::printf("[ Order    ] %s: brightest first %zu shots, fixed order %zu shots, largest "
                "difference %.1e of the largest radiance\n",
      name,
      brightest.History().size(),
      fixed.History().size(),
      worst / largest);
    EXPECT_LT(worst, 1e-4 * largest) << name;
    // The fixed order really is the index order: its first shots are patches 0, 1, 2, ...
    // whenever they have something to shoot (every furnace patch emits).
    if (std::string(name) == "furnace_box.scene")
    {
      for (size_t k = 0; k < setup.Patches.size(); ++k)
      {
        ASSERT_EQ(fixed.History()[k].Shooter, k);
      }
    }
    // Brightest first: the first shot is the brightest emitter (ties to the lowest index).
    size_t first = 0;
    for (size_t i = 1; i < setup.Patches.size(); ++i)
    {
      const double p = setup.Cover.PatchArea(i) *
        (setup.Materials[i].Emission.x + setup.Materials[i].Emission.y +
          setup.Materials[i].Emission.z);
      const double q = setup.Cover.PatchArea(first) *
        (setup.Materials[first].Emission.x + setup.Materials[first].Emission.y +
          setup.Materials[first].Emission.z);
      if (p > q)
      {
        first = i;
      }
    }
    EXPECT_EQ(brightest.History()[0].Shooter, first);
  }
}

TEST(LightPropagation, BatchesReachTheSameEquilibrium)
{
  // Shooting up to B patches at a time (PropagationSettings::ShotBatch) changes the path to the
  // equilibrium, not the equilibrium: the furnace stays uniform, the Cornell box's radiances
  // equal the one-at-a-time ones within the tolerance's reach, and every batch is the
  // brightest patch and the next ones of at least BatchPowerFraction of its power.
  for (const char* name : { "cornell_box.scene", "furnace_box.scene" })
  {
    CoveredScene setup(name, 2);
    PropagationSettings settings;
    settings.ConvergenceTolerance = 1e-7;
    LightPropagation single(setup.Cover, setup.Materials);
    ASSERT_TRUE(single.Run(settings));
    settings.ShotBatch = 16;
    LightPropagation batched(setup.Cover, setup.Materials);
    // Before the first batch: the powers it is chosen from.
    std::vector<double> power;
    for (size_t i = 0; i < setup.Patches.size(); ++i)
    {
      power.push_back(batched.UnshotPower(i));
    }
    ASSERT_TRUE(batched.Run(settings));
    double largest = 0.0;
    const double worst = LargestExitantDifference(single, batched, largest);
    std::printf("[ Batches  ] %s: one at a time %zu shots, batches of 16 %zu shots, largest "
                "difference %.1e of the largest radiance\n",
      name,
      single.History().size(),
      batched.History().size(),
      worst / largest);
    EXPECT_LT(worst, 1e-5 * largest) << name;
    if (std::string(name) == "furnace_box.scene")
    {
      EXPECT_LT(WorstFurnaceError(batched, setup.Materials), 5e-3);
    }
    // The first batch: the patches of largest power, in decreasing order (lowest index on
    // ties), as many as are at least half the largest, at most 16.
    std::vector<size_t> order(power.size());
    for (size_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::stable_sort(
      order.begin(), order.end(), [&power](size_t a, size_t b) { return power[a] > power[b]; });
    size_t members = 0;
    while (members < 16 && members < order.size() && power[order[members]] > 0.0 &&
      power[order[members]] >= LightPropagation::BatchPowerFraction * power[order[0]])
    {
      ++members;
    }
    ASSERT_GT(members, 0u);
    ASSERT_GE(batched.History().size(), members);
    for (size_t m = 0; m < members; ++m)
    {
      EXPECT_EQ(batched.History()[m].Shooter, order[m]) << name << " member " << m;
      EXPECT_EQ(batched.History()[m].ShotPower, power[order[m]]) << name << " member " << m;
    }
    // The batch's records share what the scan after it measured; the next batch's do not.
    EXPECT_EQ(batched.History()[members - 1].UnshotEnergy, batched.History()[0].UnshotEnergy);
    if (batched.History().size() > members)
    {
      EXPECT_NE(batched.History()[members].UnshotEnergy, batched.History()[0].UnshotEnergy);
    }
  }
}

TEST(LightPropagation, HowellParallelRectanglesWithOneLamp)
{
  // Lamp A (rho = 0, Le) facing white B (rho_B) across a gap, nothing else: B is lit only
  // directly, so its area-mean irradiance is pi Le F_BA, with F_BA the cover's form factor
  // (paper's cover, summed by SphericalCover::FormFactors) and close to Howell's closed form.
  CoveredScene setup("howell_parallel.scene", 4);
  const int lamp = setup.Environment.FindMaterial("lamp");
  const int white = setup.Environment.FindMaterial("white");
  ASSERT_GE(lamp, 0);
  ASSERT_GE(white, 0);
  const glm::dvec3 le = setup.Environment.Materials[lamp].Emission;
  const glm::dvec3 rhoB = setup.Environment.Materials[white].Diffuse;
  std::vector<int> group;
  for (const Patch& patch : setup.Patches)
  {
    group.push_back(setup.Environment.Surfaces[patch.SurfaceIndex].MaterialIndex == lamp ? 0 : 1);
  }
  const std::vector<double> f = setup.Cover.FormFactors(group, 2);
  const double fAB = f[0 * 2 + 1];
  const double fBA = f[1 * 2 + 0];

  LightPropagation propagation(setup.Cover, setup.Materials);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-12;
  ASSERT_TRUE(propagation.Run(settings));

  glm::dvec3 received[2]{ glm::dvec3(0.0), glm::dvec3(0.0) };
  double area[2]{ 0.0, 0.0 };
  for (size_t i = 0; i < setup.Patches.size(); ++i)
  {
    received[group[i]] += setup.Cover.PatchArea(i) * propagation.Irradiance(i);
    area[group[i]] += setup.Cover.PatchArea(i);
    if (group[i] == 0)
    {
      // The lamp reflects nothing: its radiance is its emission, whatever it receives.
      EXPECT_EQ(propagation.ExitantRadiance(i), le);
    }
  }
  const glm::dvec3 meanB = received[1] / area[1];
  const double howell = HowellParallel(1.0, 2.0, 1.0);
  std::printf("[ Howell   ] F_BA cover %.5f, Howell %.5f; mean irradiance of B %.5f W/m^2, "
              "pi Le F_BA %.5f\n",
    fBA,
    howell,
    meanB.x,
    Pi * le.x * fBA);
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_NEAR(meanB[b], Pi * le[b] * fBA, 1e-12 * meanB[b]);
  }
  EXPECT_NEAR(fBA, howell, 0.02 * howell);

  // The lamp receives back what B reflects. Counted from B's side with reciprocity: B patch j
  // sends pi A_j L_j F_jA to A, F_jA its own row's form factor to A (a different set of entries
  // of the cover than the lamp's rows that Irradiance sums), so the two agree to the cover's
  // reciprocity error.
  glm::dvec3 sentToLamp(0.0);
  for (size_t j = 0; j < setup.Patches.size(); ++j)
  {
    if (group[j] != 1)
    {
      continue;
    }
    double fjA = 0.0;
    for (size_t e = setup.Cover.EntryBegin(j); e < setup.Cover.EntryEnd(j); ++e)
    {
      if (group[setup.Cover.EntryAt(e).Source] == 0)
      {
        fjA += setup.Cover.ProjectedSolidAngle(e) / Pi;
      }
    }
    sentToLamp += Pi * setup.Cover.PatchArea(j) * propagation.ExitantRadiance(j) * fjA;
  }
  std::printf("[ Howell   ] power back on the lamp %.7f W (from B's rows %.7f W), F_AB %.5f\n",
    received[0].x,
    sentToLamp.x,
    fAB);
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_GT(received[0][b], 0.0);
    EXPECT_NEAR(received[0][b], sentToLamp[b], 0.02 * sentToLamp[b]);
  }

  // Single bounce: the light back on the lamp is proportional to rho_B.
  std::vector<glm::dvec3> reflectance;
  std::vector<glm::dvec3> emission;
  for (size_t i = 0; i < setup.Patches.size(); ++i)
  {
    reflectance.push_back(0.5 * setup.Materials[i].Diffuse);
    emission.push_back(setup.Materials[i].Emission);
  }
  LightPropagation darker(setup.Cover, reflectance, emission);
  ASSERT_TRUE(darker.Run(settings));
  glm::dvec3 receivedDarker(0.0);
  for (size_t i = 0; i < setup.Patches.size(); ++i)
  {
    if (group[i] == 0)
    {
      receivedDarker += setup.Cover.PatchArea(i) * darker.Irradiance(i);
    }
  }
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_GT(rhoB[b], 0.0);
    EXPECT_NEAR(receivedDarker[b], 0.5 * received[0][b], 1e-12 * received[0][b]);
  }
}

TEST(LightPropagation, LampIrradianceIsTheFirstTwoGenerationsOfTheLampsLight)
{
  // Lamp A (rho = 0) facing white B, nothing else: B receives only A's direct light, and A only
  // B's first reflection of it (A reflects nothing, B does not see itself). So the converged
  // Irradiance of progressive shooting is, at every patch, the lamps' direct light plus its
  // first bounce, which LampIrradiance sums in two sweeps over the columns instead.
  CoveredScene setup("howell_parallel.scene", 4);
  const int lamp = setup.Environment.FindMaterial("lamp");
  ASSERT_GE(lamp, 0);
  LightPropagation propagation(setup.Cover, setup.Materials);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-14;
  ASSERT_TRUE(propagation.Run(settings));
  std::vector<bool> lampPatch;
  for (const Patch& patch : setup.Patches)
  {
    lampPatch.push_back(setup.Environment.Surfaces[patch.SurfaceIndex].MaterialIndex == lamp);
  }
  const std::vector<glm::dvec3> direct = propagation.LampIrradiance(lampPatch, false);
  const std::vector<glm::dvec3> twoGenerations = propagation.LampIrradiance(lampPatch, true);
  ASSERT_EQ(direct.size(), setup.Patches.size());
  double lampReceived = 0.0;
  for (std::size_t i = 0; i < setup.Patches.size(); ++i)
  {
    const glm::dvec3 e = propagation.Irradiance(i);
    lampReceived += lampPatch[i] ? e.x : 0.0;
    for (int b = 0; b < 3; ++b)
    {
      EXPECT_NEAR(twoGenerations[i][b], e[b], 1e-9 * (1.0 + e[b])) << "patch " << i;
      EXPECT_NEAR(direct[i][b], lampPatch[i] ? 0.0 : e[b], 1e-9 * (1.0 + e[b])) << "patch " << i;
    }
  }
  EXPECT_GT(lampReceived, 0.0);
  EXPECT_THROW(propagation.LampIrradiance(std::vector<bool>(2, true), true), std::invalid_argument);
}

TEST(LightPropagation, AShotCostsOneColumn)
{
  // §5.2: a diffuse shot evaluates the shooter's radiance once and updates one entry per
  // hemisphere that contains it: exactly its column of the cover.
  CoveredScene setup("cornell_box.scene", 2);
  const size_t n = setup.Patches.size();
  // Column sizes counted from the rows (which hemispheres hold Q_j), not from the columns.
  std::vector<size_t> holders(n, 0);
  for (size_t i = 0; i < n; ++i)
  {
    for (size_t j = 0; j < n; ++j)
    {
      holders[j] += setup.Cover.FindEntry(i, j) >= 0 ? 1 : 0;
    }
  }
  LightPropagation propagation(setup.Cover, setup.Materials);
  PropagationSettings settings;
  settings.MaximumShots = 50;
  EXPECT_FALSE(propagation.Run(settings));
  ASSERT_EQ(propagation.History().size(), 50u);
  for (const ShotRecord& record : propagation.History())
  {
    EXPECT_EQ(record.ReceiverUpdates, holders[record.Shooter]) << "shot " << record.Shot;
  }

  // The first shot (the lamp's emission) changes exactly the entries of its column.
  LightPropagation fresh(setup.Cover, setup.Materials);
  const size_t shooter = propagation.History()[0].Shooter;
  EXPECT_EQ(fresh.Shoot(shooter), holders[shooter]);
  size_t changed = 0;
  for (size_t e = 0; e < setup.Cover.EntryCount(); ++e)
  {
    if (fresh.IncidentRadiance(e) != glm::dvec3(0.0))
    {
      ++changed;
      EXPECT_EQ(setup.Cover.EntryAt(e).Source, shooter);
      EXPECT_EQ(fresh.IncidentRadiance(e), setup.Materials[shooter].Emission);
    }
  }
  EXPECT_EQ(changed, holders[shooter]);
  EXPECT_EQ(fresh.UnshotRadiance(shooter), glm::dvec3(0.0));
}

TEST(LightPropagation, ProgressAbortAndShotLimit)
{
  CoveredScene setup("furnace_box.scene", 2);
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-6;

  // Abort after three reports: Run says so and has made exactly three shots.
  LightPropagation aborted(setup.Cover, setup.Materials);
  int calls = 0;
  EXPECT_FALSE(aborted.Run(settings, [&calls](double) { return ++calls < 3; }));
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(aborted.History().size(), 3u);

  // A shot limit stops early, also within a batch; a later Run continues from there to the
  // same equilibrium.
  LightPropagation limited(setup.Cover, setup.Materials);
  settings.MaximumShots = 5;
  settings.ShotBatch = 16;
  EXPECT_FALSE(limited.Run(settings));
  EXPECT_EQ(limited.History().size(), 5u);
  settings.ShotBatch = 1;
  EXPECT_FALSE(limited.Converged(settings.ConvergenceTolerance));
  settings.MaximumShots = 0;
  std::vector<double> fractions;
  EXPECT_TRUE(limited.Run(settings,
    [&fractions](double fraction)
    {
      fractions.push_back(fraction);
      return true;
    }));
  ASSERT_GE(fractions.size(), 2u);
  for (size_t k = 1; k < fractions.size(); ++k)
  {
    EXPECT_GE(fractions[k], fractions[k - 1]);
  }
  EXPECT_GE(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_LT(WorstFurnaceError(limited, setup.Materials), 5e-3);
  for (size_t k = 0; k < limited.History().size(); ++k)
  {
    EXPECT_EQ(limited.History()[k].Shot, k);
  }

  // Reset starts over: nothing received, the emission unshot again.
  limited.Reset();
  EXPECT_TRUE(limited.History().empty());
  EXPECT_EQ(limited.Irradiance(0), glm::dvec3(0.0));
  EXPECT_EQ(limited.UnshotRadiance(0), setup.Materials[0].Emission);
}

TEST(LightPropagation, RejectsWhatItCannotPropagate)
{
  CoveredScene setup("furnace_box.scene", 1);
  std::vector<Material> materials = setup.Materials;
  // Every kind is propagated (TestNonDiffusePropagation.cxx); values out of range are not.
  materials[2].Type = MaterialType::Mirror;
  materials[2].Specular = glm::dvec3(1.2);
  EXPECT_THROW(LightPropagation(setup.Cover, materials), std::invalid_argument);
  materials[2].Type = MaterialType::Phong;
  materials[2].Specular = glm::dvec3(0.5);
  EXPECT_THROW(LightPropagation(setup.Cover, materials), std::invalid_argument);
  materials[2].Type = MaterialType::Tabulated;
  materials[2].TableFile = std::string(SPHCOVER_DATA_DIR) + "/brdf/does_not_exist.brdf.csv";
  EXPECT_THROW(LightPropagation(setup.Cover, materials), std::runtime_error);
  // Phong keeps its diffuse part as the Lambertian reflectance (the Radiosity output).
  materials[2].Type = MaterialType::Phong;
  materials[2].Specular = glm::dvec3(0.1);
  LightPropagation phong(setup.Cover, materials);
  EXPECT_EQ(phong.Reflectance(2), materials[2].Diffuse);
  EXPECT_FALSE(phong.IsLambertian(2));
  EXPECT_TRUE(phong.IsLambertian(1));

  std::vector<glm::dvec3> rho(setup.Patches.size(), glm::dvec3(0.5));
  std::vector<glm::dvec3> le(setup.Patches.size(), glm::dvec3(1.0));
  EXPECT_THROW(LightPropagation(setup.Cover, std::vector<glm::dvec3>(1, glm::dvec3(0.5)), le),
    std::invalid_argument);
  rho[0].y = 1.5;
  EXPECT_THROW(LightPropagation(setup.Cover, rho, le), std::invalid_argument);
  rho[0].y = 0.5;
  le[1].z = -1.0;
  EXPECT_THROW(LightPropagation(setup.Cover, rho, le), std::invalid_argument);

  // Nothing emitted: converged at once, no shot.
  LightPropagation dark(setup.Cover, rho, std::vector<glm::dvec3>(setup.Patches.size()));
  EXPECT_TRUE(dark.Run());
  EXPECT_TRUE(dark.History().empty());
}
