// SPDX-License-Identifier: BSD-3-Clause
// The lamps' direct irradiance at the nodes of every patch (Core/cover/DirectIrradiance.h):
// under a square lamp it is the analytic irradiance of a parallel rectangle (Howell's
// differential element to a parallel rectangle); a node on the edge where the floor meets a
// wall sees the lamp as a brute-force integral says (the wall does not shadow the node on it);
// an occluder that hides the lamp gives zero; the first bounce off an evenly lit floor is rho
// times its direct light; the nodes do not depend on the thread count; a scene without a
// bright emitter has none. The renderer keeps I at the characteristic points
// and adds the nodes' variation between them.
#include "cover/BrightEmitters.h"
#include "cover/DirectIrradiance.h"
#include "cover/RayCastFill.h"
#include "render/RadianceRenderer.h"

#include "CoverTestUtilities.h"
#include "distributed/InProcessRanks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
constexpr double LampHeight = 0.5;
const glm::dvec3 LampEmission(1.0, 2.0, 3.0);

/// The unit floor at z = 0 (front +z, surface 0, split 3 x 3), a lamp [0.25, 0.75]^2 at
/// z = LampHeight facing down (surface 1, split 3 x 3), a wall at x = 0 facing +x (surface 2)
/// and, with `occluder`, an opaque square [0.3, 0.7]^2 at z = 0.25 facing down (surface 3).
std::vector<Patch> LampOverFloor(bool occluder)
{
  std::vector<Patch> patches;
  AppendSplit(patches,
    Parallelogram(glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0)),
    0,
    3,
    3);
  AppendSplit(patches,
    Parallelogram(
      glm::dvec3(0.25, 0.25, LampHeight), glm::dvec3(0.0, 0.5, 0.0), glm::dvec3(0.5, 0.0, 0.0)),
    1,
    3,
    3);
  AppendSplit(patches,
    Parallelogram(glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0)),
    2,
    1,
    1);
  if (occluder)
  {
    AppendSplit(patches,
      Parallelogram(
        glm::dvec3(0.3, 0.3, 0.25), glm::dvec3(0.0, 0.4, 0.0), glm::dvec3(0.4, 0.0, 0.0)),
      3,
      1,
      1);
  }
  return patches;
}

std::vector<glm::dvec3> EmissionOf(const std::vector<Patch>& patches)
{
  std::vector<glm::dvec3> emission;
  for (const Patch& patch : patches)
  {
    emission.push_back(patch.SurfaceIndex == 1 ? LampEmission : glm::dvec3(0.0));
  }
  return emission;
}

DirectIrradianceNodes Compute(const std::vector<Patch>& patches,
  const ParallelFor& parallelFor = SequentialFor,
  int nodesPerSide = 3)
{
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  const std::vector<glm::dvec3> emission = EmissionOf(patches);
  DirectIrradianceOptions options;
  options.NodesPerSide = nodesPerSide;
  options.BounceRaysPerSide = 0; // the direct light alone (the bounce: FirstBounceOfAnEvenFloor)
  DirectIrradianceNodes nodes;
  EXPECT_TRUE(ComputeDirectIrradiance(
    patches, caster, BrightEmitters(patches, emission), emission, {}, options, nodes, parallelFor));
  return nodes;
}

/// Projected solid angle of a rectangle a x b parallel to the receiver at height c, seen from
/// the point under one of its corners: pi times Howell's configuration factor B-3.
double CornerProjectedSolidAngle(double a, double b, double c)
{
  const double x = a / c;
  const double y = b / c;
  const double sx = std::sqrt(1.0 + x * x);
  const double sy = std::sqrt(1.0 + y * y);
  return 0.5 * (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy));
}

/// The lamp's projected solid angle from the floor point p (normal +z) by the midpoint rule on
/// a fine grid, with the occluder of LampOverFloor when `occluder` (visibility by where the ray
/// crosses its plane): an independent integral.
double BruteForceProjectedSolidAngle(const glm::dvec3& p, bool occluder = false)
{
  const int n = 600;
  const double h = 0.5 / n;
  double sum = 0.0;
  for (int a = 0; a < n; ++a)
  {
    for (int b = 0; b < n; ++b)
    {
      const glm::dvec3 q(0.25 + (a + 0.5) * h, 0.25 + (b + 0.5) * h, LampHeight);
      const glm::dvec3 d = q - p;
      const double r2 = glm::dot(d, d);
      const glm::dvec3 crossing = p + d * ((0.25 - p.z) / d.z);
      if (occluder && crossing.x > 0.3 && crossing.x < 0.7 && crossing.y > 0.3 && crossing.y < 0.7)
      {
        continue;
      }
      sum += (d.z / std::sqrt(r2)) * (d.z / std::sqrt(r2)) / r2 * h * h;
    }
  }
  return sum;
}

/// The floor's patch holding (x, y) of the 3 x 3 split and its own (s, t) there.
std::size_t FloorPatch(double x, double y, double& s, double& t)
{
  const int a = std::min(2, static_cast<int>(x * 3.0));
  const int b = std::min(2, static_cast<int>(y * 3.0));
  s = x * 3.0 - a;
  t = y * 3.0 - b;
  return static_cast<std::size_t>(b * 3 + a);
}
}

TEST(DirectIrradiance, UnderTheLampItIsTheParallelRectanglesIrradiance)
{
  const std::vector<Patch> patches = LampOverFloor(false);
  const DirectIrradianceNodes nodes = Compute(patches);
  ASSERT_EQ(nodes.NodesPerSide, 3);
  ASSERT_EQ(nodes.Values.size(), patches.size() * 9 * 3);
  // The floor's centre is the centre node of its middle patch: four corners of 0.25 x 0.25.
  const double exact = 4.0 * CornerProjectedSolidAngle(0.25, 0.25, LampHeight);
  const glm::dvec3 centre = nodes.At(4, 0.5, 0.5);
  for (int band = 0; band < 3; ++band)
  {
    EXPECT_NEAR(centre[band] / (LampEmission[band] * exact), 1.0, 5e-3) << "band " << band;
  }
  // Under a corner of the lamp: one rectangle of 0.5 x 0.5 (the node of patch 4 at (0, 0)
  // lies at (1/3, 1/3), not under the corner; take patch 0's node (2, 2) at (1/3, 1/3) and
  // compare with the superposition of four rectangles from there).
  const double u = 1.0 / 3.0 - 0.25;
  const double w = 0.75 - 1.0 / 3.0;
  const double fromThird = CornerProjectedSolidAngle(w, w, LampHeight) +
    2.0 * CornerProjectedSolidAngle(w, u, LampHeight) + CornerProjectedSolidAngle(u, u, LampHeight);
  EXPECT_NEAR(nodes.At(0, 1.0, 1.0).x / (LampEmission.x * fromThird), 1.0, 5e-3);
  // The same point as a node of the neighbouring patches: one value on their shared corner.
  EXPECT_FLOAT_EQ(nodes.At(0, 1.0, 1.0).x, nodes.At(4, 0.0, 0.0).x);
  // The lamp does not light itself.
  for (std::size_t p = 9; p < 18; ++p)
  {
    EXPECT_EQ(nodes.At(p, 0.5, 0.5), glm::dvec3(0.0));
  }
}

/// A bowl z = BowlDepth (x^2 + y^2) over [-1, 1]^2, its inside (+z) the front: the biquadratic
/// patch with x = 2u - 1, y = 2v - 1 (x^2's Bernstein coefficients are 1, -1, 1).
constexpr double BowlDepth = 0.5;
BezierPatch Bowl()
{
  const double x[3] = { -1.0, 0.0, 1.0 };
  const double x2[3] = { 1.0, -1.0, 1.0 };
  std::vector<glm::dvec3> points;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      points.emplace_back(x[i], x[j], BowlDepth * (x2[i] + x2[j]));
    }
  }
  return BezierPatch(2, 2, points);
}

/// The projected solid angle of the whole bowl from its point at (s, t), by the midpoint rule
/// on a fine grid of the bowl's own parameters: the graph of a convex function sees all of
/// itself from above (the chord between two of its points runs above it), so no visibility.
double BowlSelfProjectedSolidAngle(const BezierPatch& bowl, double s, double t)
{
  const glm::dvec3 p = bowl.Evaluate(s, t);
  const glm::dvec3 np = bowl.Normal(s, t);
  const int n = 800;
  double sum = 0.0;
  for (int a = 0; a < n; ++a)
  {
    for (int b = 0; b < n; ++b)
    {
      const double u = (a + 0.5) / n;
      const double v = (b + 0.5) / n;
      const glm::dvec3 d = bowl.Evaluate(u, v) - p;
      const double r2 = glm::dot(d, d);
      const glm::dvec3 area = bowl.UnnormalizedNormal(u, v) / (static_cast<double>(n) * n);
      if (r2 > 0.0)
      {
        sum += std::max(0.0, glm::dot(d, np)) * std::max(0.0, -glm::dot(d, area)) / (r2 * r2);
      }
    }
  }
  return sum;
}

TEST(DirectIrradiance, AConcaveLampLightsItsOwnInside)
{
  // A bowl that emits, alone (issue 39 item 6): every node of it sees the rest of its inside.
  // The nodes left out the lamp's own surface, so its light on itself was in neither the
  // nodes nor (the cover's version being taken off) the render; a planar lamp's own nodes stay
  // dark (UnderTheLampItIsTheParallelRectanglesIrradiance).
  const BezierPatch bowl = Bowl();
  std::vector<Patch> patches;
  AppendSplit(patches, bowl, 0, 3, 3);
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  const std::vector<glm::dvec3> emission(patches.size(), LampEmission);
  DirectIrradianceOptions options;
  options.BounceRaysPerSide = 0;
  DirectIrradianceNodes nodes;
  ASSERT_TRUE(ComputeDirectIrradiance(patches, caster, { true }, emission, {}, options, nodes));
  ASSERT_EQ(nodes.NodesPerSide, 3);
  // Every node of the centre patch and of a corner patch, against the independent integral.
  double worst = 0.0;
  for (const std::size_t p : { std::size_t(0), std::size_t(4) })
  {
    const UVRect& domain = patches[p].Domain;
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 3; ++i)
      {
        const double s = domain.U0 + (domain.U1 - domain.U0) * i / 2.0;
        const double t = domain.V0 + (domain.V1 - domain.V0) * j / 2.0;
        const double exact = BowlSelfProjectedSolidAngle(bowl, s, t);
        ASSERT_GT(exact, 0.1) << "patch " << p << " node " << i << ", " << j;
        const glm::dvec3 value = nodes.At(p, i / 2.0, j / 2.0);
        for (int band = 0; band < 3; ++band)
        {
          const double ratio = value[band] / (LampEmission[band] * exact);
          worst = std::max(worst, std::fabs(ratio - 1.0));
          EXPECT_NEAR(ratio, 1.0, 0.02)
            << "patch " << p << " node " << i << ", " << j << " band " << band;
        }
      }
    }
  }
  RecordProperty("WorstRelativeError", std::to_string(worst));
}

TEST(DirectIrradiance, ANodeWhereTheFloorMeetsAWallIsLit)
{
  const std::vector<Patch> patches = LampOverFloor(false);
  const DirectIrradianceNodes nodes = Compute(patches);
  // (0, 0.5) on the floor lies on the wall's plane; the rays to the lamp leave the wall at once.
  double s;
  double t;
  const std::size_t patch = FloorPatch(0.0, 0.5, s, t);
  const double expected = BruteForceProjectedSolidAngle(glm::dvec3(0.0, 0.5, 0.0));
  ASSERT_GT(expected, 0.05);
  EXPECT_NEAR(nodes.At(patch, s, t).y / (LampEmission.y * expected), 1.0, 5e-3);
  // And the wall's own node at its foot, in the floor's plane, sees the lamp too.
  const glm::dvec3 wall = nodes.At(18, 0.5, 0.0);
  EXPECT_GT(wall.x, 0.0);
}

TEST(DirectIrradiance, AnOccluderCastsItsShadow)
{
  const DirectIrradianceNodes open = Compute(LampOverFloor(false));
  const DirectIrradianceNodes shaded = Compute(LampOverFloor(true));
  // Seen from the floor's centre the occluder (at half the lamp's height, 0.4 wide) covers
  // [0.1, 0.9]^2 of the lamp's plane: the whole lamp.
  EXPECT_EQ(shaded.At(4, 0.5, 0.5), glm::dvec3(0.0));
  // From the floor's corner (0, 0) the occluder hides part of the lamp only (its far corner
  // [0.6, 0.75]^2), and from (1/6, 1/6) more of it ([0.43, 0.75]^2): as the brute-force
  // integral says, to the quadrature's resolution of the shadow's edge (a ninth of the lamp).
  const double cornerOpen = open.At(0, 0.0, 0.0).z;
  const double cornerShaded = shaded.At(0, 0.0, 0.0).z;
  const double sixth = 1.0 / 6.0;
  for (const glm::dvec3& p : { glm::dvec3(0.0), glm::dvec3(sixth, sixth, 0.0) })
  {
    double s;
    double t;
    const std::size_t patch = FloorPatch(p.x, p.y, s, t);
    const double expectedOpen = BruteForceProjectedSolidAngle(p);
    const double expectedShaded = BruteForceProjectedSolidAngle(p, true);
    ASSERT_LT(expectedShaded, 0.97 * expectedOpen);
    EXPECT_NEAR(open.At(patch, s, t).z / LampEmission.z, expectedOpen, 5e-3 * expectedOpen);
    EXPECT_NEAR(shaded.At(patch, s, t).z / LampEmission.z, expectedShaded, 0.05 * expectedOpen)
      << "at (" << p.x << ", " << p.y << ")";
  }
  // The far corner (1, 1) is shaded alike (lamp and occluder are symmetric about the floor's
  // centre), up to a shadow ray through the occluder's edge.
  EXPECT_NEAR(shaded.At(8, 1.0, 1.0).z, cornerShaded, 0.02 * cornerOpen);
}

TEST(DirectIrradiance, IndependentOfThreadsAndBilinearBetweenNodes)
{
  const std::vector<Patch> patches = LampOverFloor(true);
  const DirectIrradianceNodes one = Compute(patches, SequentialFor, 5);
  const DirectIrradianceNodes two = Compute(patches, ThreadedFor(2), 5);
  ASSERT_EQ(one.Values, two.Values);
  // Between nodes the values are bilinear: at the middle of four nodes, their mean.
  const glm::dvec3 mean = 0.25 *
    (one.At(4, 0.25, 0.25) + one.At(4, 0.5, 0.25) + one.At(4, 0.25, 0.5) + one.At(4, 0.5, 0.5));
  const glm::dvec3 middle = one.At(4, 0.375, 0.375);
  for (int band = 0; band < 3; ++band)
  {
    EXPECT_NEAR(middle[band], mean[band], 1e-6 * (1.0 + mean[band]));
  }
}

// Under MPI the ranks compute the nodes in turn and join them (RankShare.h): the direct light and
// its first bounce (which reads the joined direct light at the nodes of other ranks) are the
// serial values bit for bit, whatever the number of ranks (run here as threads).
TEST(DirectIrradiance, SharedAmongRanksEqualsSerial)
{
  const std::vector<Patch> patches = LampOverFloor(true);
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  const std::vector<glm::dvec3> emission = EmissionOf(patches);
  const std::vector<glm::dvec3> diffuse(patches.size(), glm::dvec3(0.5, 0.4, 0.3));
  const std::vector<bool> lamps = BrightEmitters(patches, emission);
  DirectIrradianceOptions options;
  options.NodesPerSide = 5;
  options.BounceRaysPerSide = 8;
  DirectIrradianceNodes serial;
  ASSERT_TRUE(ComputeDirectIrradiance(patches, caster, lamps, emission, diffuse, options, serial));
  ASSERT_FALSE(serial.Empty());
  for (const int ranks : { 2, 3, 5 })
  {
    InProcessRanks world(ranks);
    std::vector<DirectIrradianceNodes> results(static_cast<std::size_t>(ranks));
    std::vector<int> completed(static_cast<std::size_t>(ranks), 0);
    world.Run(
      [&](const RankShare& share, int rank)
      {
        completed[static_cast<std::size_t>(rank)] = ComputeDirectIrradiance(patches,
          caster,
          lamps,
          emission,
          diffuse,
          options,
          results[static_cast<std::size_t>(rank)],
          SequentialFor,
          nullptr,
          share);
      });
    for (int rank = 0; rank < ranks; ++rank)
    {
      SCOPED_TRACE(testing::Message() << "rank " << rank << " of " << ranks);
      EXPECT_TRUE(completed[static_cast<std::size_t>(rank)]);
      EXPECT_EQ(results[static_cast<std::size_t>(rank)].NodesPerSide, serial.NodesPerSide);
      EXPECT_EQ(results[static_cast<std::size_t>(rank)].Values, serial.Values);
    }
  }
}

// A rank that aborts (its progress returns false) returns false; the others learn it at the
// join and throw RankShare::PeerFailure: no rank waits for ever.
TEST(DirectIrradiance, ARankThatAbortsStopsEveryRank)
{
  const std::vector<Patch> patches = LampOverFloor(false);
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  const std::vector<glm::dvec3> emission = EmissionOf(patches);
  const std::vector<bool> lamps = BrightEmitters(patches, emission);
  DirectIrradianceOptions options;
  options.BounceRaysPerSide = 0;
  InProcessRanks world(3);
  std::vector<std::string> outcome(3);
  world.Run(
    [&](const RankShare& share, int rank)
    {
      DirectIrradianceNodes nodes;
      try
      {
        const bool completed = ComputeDirectIrradiance(
          patches,
          caster,
          lamps,
          emission,
          {},
          options,
          nodes,
          SequentialFor,
          [rank](double) { return rank != 1; },
          share);
        outcome[static_cast<std::size_t>(rank)] = completed ? "completed" : "aborted";
      }
      catch (const RankShare::PeerFailure&)
      {
        outcome[static_cast<std::size_t>(rank)] = "peer failed";
      }
    });
  EXPECT_EQ(outcome, std::vector<std::string>({ "peer failed", "aborted", "peer failed" }));
}

TEST(DirectIrradiance, FirstBounceOfAnEvenFloor)
{
  // A 40 x 40 floor (rho 0.5, split 5 x 5) under a 20 x 20 lamp at height 1 (split 4 x 4), and
  // a small plate facing the floor at height 0.25 above (2, 2), between the floor's nodes: the
  // plate gets no direct light, and its first bounce is rho times the floor's direct light,
  // nearly even below it (the floor beyond 2 units of it sends 1.5 % of what it sees).
  std::vector<Patch> patches;
  AppendSplit(patches,
    Parallelogram(
      glm::dvec3(-20.0, -20.0, 0.0), glm::dvec3(40.0, 0.0, 0.0), glm::dvec3(0.0, 40.0, 0.0)),
    0,
    5,
    5);
  AppendSplit(patches,
    Parallelogram(
      glm::dvec3(-10.0, -10.0, 1.0), glm::dvec3(0.0, 20.0, 0.0), glm::dvec3(20.0, 0.0, 0.0)),
    1,
    4,
    4);
  AppendSplit(patches,
    Parallelogram(
      glm::dvec3(1.975, 1.975, 0.25), glm::dvec3(0.0, 0.05, 0.0), glm::dvec3(0.05, 0.0, 0.0)),
    2,
    1,
    1);
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  std::vector<glm::dvec3> emission(patches.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> diffuse(patches.size(), glm::dvec3(0.0));
  for (std::size_t p = 0; p < patches.size(); ++p)
  {
    emission[p] = patches[p].SurfaceIndex == 1 ? LampEmission : glm::dvec3(0.0);
    diffuse[p] = patches[p].SurfaceIndex == 0 ? glm::dvec3(0.5) : glm::dvec3(0.0);
  }
  const std::vector<bool> lamps = BrightEmitters(patches, emission);
  ASSERT_TRUE(lamps.size() > 1 && lamps[1] && !lamps[0]);
  DirectIrradianceOptions options;
  DirectIrradianceNodes nodes;
  ASSERT_TRUE(ComputeDirectIrradiance(patches, caster, lamps, emission, diffuse, options, nodes));
  const std::size_t plate = patches.size() - 1;
  // The floor's nodes at (4, 4) (patch 18's corner (0, 0)) and at (0, 0) (patch 12's centre).
  const glm::dvec3 floorA = nodes.At(18, 0.0, 0.0);
  const glm::dvec3 floorB = nodes.At(12, 0.5, 0.5);
  ASSERT_GT(floorA.x, 0.0);
  for (int band = 0; band < 3; ++band)
  {
    const double expected = 0.5 * 0.5 * (floorA[band] + floorB[band]);
    EXPECT_NEAR(nodes.At(plate, 0.5, 0.5)[band] / expected, 1.0, 0.01) << "band " << band;
    EXPECT_NEAR(nodes.At(plate, 0.0, 1.0)[band] / expected, 1.0, 0.01) << "band " << band;
  }
  // Without the bounce the plate has nothing.
  options.BounceRaysPerSide = 0;
  ASSERT_TRUE(ComputeDirectIrradiance(patches, caster, lamps, emission, {}, options, nodes));
  EXPECT_EQ(nodes.At(plate, 0.5, 0.5), glm::dvec3(0.0));
}

TEST(DirectIrradiance, NoBrightEmitterNoNodesAndBadSizesRefused)
{
  std::vector<Patch> patches = LampOverFloor(false);
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  const std::vector<glm::dvec3> diffuse(patches.size(), glm::dvec3(0.5));
  // Everything emitting alike (a furnace): no lamp, no direct part.
  const std::vector<glm::dvec3> even(patches.size(), glm::dvec3(1.0));
  DirectIrradianceNodes nodes;
  EXPECT_TRUE(ComputeDirectIrradiance(patches,
    caster,
    BrightEmitters(patches, even),
    even,
    diffuse,
    DirectIrradianceOptions(),
    nodes));
  EXPECT_TRUE(nodes.Empty());
  const std::vector<glm::dvec3> emission = EmissionOf(patches);
  const std::vector<bool> lamps = BrightEmitters(patches, emission);
  DirectIrradianceOptions even4;
  even4.NodesPerSide = 4;
  EXPECT_THROW(ComputeDirectIrradiance(patches, caster, lamps, emission, diffuse, even4, nodes),
    std::invalid_argument);
  for (const double tolerance : { -0.01, std::nan("") })
  {
    DirectIrradianceOptions badTolerance;
    badTolerance.NodesPerSide = 9;
    badTolerance.RefinementTolerance = tolerance;
    EXPECT_THROW(
      ComputeDirectIrradiance(patches, caster, lamps, emission, diffuse, badTolerance, nodes),
      std::invalid_argument);
  }
  DirectIrradianceOptions tooMany;
  tooMany.BounceRaysPerSide = 257;
  EXPECT_THROW(ComputeDirectIrradiance(patches, caster, lamps, emission, diffuse, tooMany, nodes),
    std::invalid_argument);
  const std::vector<glm::dvec3> shortEmission(3, glm::dvec3(1.0));
  EXPECT_THROW(ComputeDirectIrradiance(
                 patches, caster, lamps, shortEmission, diffuse, DirectIrradianceOptions(), nodes),
    std::invalid_argument);
  // The bounce needs every patch's reflectance.
  EXPECT_THROW(
    ComputeDirectIrradiance(patches, caster, lamps, emission, {}, DirectIrradianceOptions(), nodes),
    std::invalid_argument);
  // Abort between batches: false, nothing returned.
  EXPECT_FALSE(ComputeDirectIrradiance(patches,
    caster,
    lamps,
    emission,
    diffuse,
    DirectIrradianceOptions(),
    nodes,
    SequentialFor,
    [](double) { return false; }));
  EXPECT_TRUE(nodes.Empty());
}

namespace
{
/// The floor of LampOverFloor (its first 9 patches) and the nodes of its direct light.
std::vector<Patch> LitFloor()
{
  const std::vector<Patch> all = LampOverFloor(false);
  return std::vector<Patch>(all.begin(), all.begin() + 9);
}

DirectIrradianceNodes LitFloorNodes()
{
  const DirectIrradianceNodes lit = Compute(LampOverFloor(false));
  DirectIrradianceNodes nodes;
  nodes.NodesPerSide = lit.NodesPerSide;
  nodes.Values.assign(lit.Values.begin(), lit.Values.begin() + 9 * 9 * 3);
  return nodes;
}
}

TEST(DirectIrradiance, RendererKeepsThePointsAndAddsTheNodesBetween)
{
  const std::vector<Patch> floor = LitFloor();
  const DirectIrradianceNodes nodes = LitFloorNodes();
  // Every floor point's I: its reflected direct light plus an even rest of 0.1.
  const glm::dvec3 rho(0.5, 0.6, 0.7);
  std::vector<glm::dvec3> exitant;
  for (std::size_t p = 0; p < floor.size(); ++p)
  {
    exitant.push_back(rho / Pi * nodes.At(p, 0.5, 0.5) + glm::dvec3(0.1));
  }
  RadianceRenderer renderer(floor, CharacteristicPointInterpolator::OfPatches(floor), exitant);
  renderer.SetDirectLight(
    DirectLight(nodes, std::vector<glm::dvec3>(floor.size(), rho), floor.size()));
  ASSERT_TRUE(renderer.HasDirectLight());
  for (std::size_t p = 0; p < floor.size(); ++p)
  {
    const glm::dvec3 atPoint =
      renderer.SurfaceRadiance(0, floor[p].Domain.CenterU(), floor[p].Domain.CenterV());
    for (int band = 0; band < 3; ++band)
    {
      EXPECT_NEAR(atPoint[band], exitant[p][band], 1e-9) << "point " << p;
    }
  }
  // Between the points: the rest (0.1) plus the nodes' own direct light at (u, v), here at the
  // floor's corner (0, 0), a node, and at (0.4, 0.1) inside patch 1.
  const glm::dvec3 corner = renderer.SurfaceRadiance(0, 0.0, 0.0);
  const glm::dvec3 inside = renderer.SurfaceRadiance(0, 0.4, 0.1);
  for (int band = 0; band < 3; ++band)
  {
    EXPECT_NEAR(corner[band], 0.1 + rho[band] / Pi * nodes.At(0, 0.0, 0.0)[band], 1e-9);
    EXPECT_NEAR(
      inside[band], 0.1 + rho[band] / Pi * nodes.At(1, 0.4 * 3.0 - 1.0, 0.1 * 3.0)[band], 1e-9);
  }
  EXPECT_THROW(
    DirectLight(nodes, std::vector<glm::dvec3>(2, rho), floor.size()), std::invalid_argument);
}

TEST(DirectIrradiance, RendererReplacesTheCoversVersionOfTheNodesLightAtThePoints)
{
  // The points' I holds the cover's version of the nodes' light (here 90 % of the nodes' own
  // value at the centre, as a coarse cover might see it) plus an even rest of 0.1: given that
  // version (CoverLampIrradiance), the render is the rest plus the nodes' light everywhere, at
  // the points too.
  const std::vector<Patch> floor = LitFloor();
  const DirectIrradianceNodes nodes = LitFloorNodes();
  const glm::dvec3 rho(0.5, 0.6, 0.7);
  std::vector<glm::dvec3> exitant;
  std::vector<glm::dvec3> coverIrradiance;
  for (std::size_t p = 0; p < floor.size(); ++p)
  {
    coverIrradiance.push_back(0.9 * nodes.At(p, 0.5, 0.5));
    exitant.push_back(rho / Pi * coverIrradiance.back() + glm::dvec3(0.1));
  }
  RadianceRenderer renderer(floor, CharacteristicPointInterpolator::OfPatches(floor), exitant);
  renderer.SetDirectLight(
    DirectLight(nodes, std::vector<glm::dvec3>(floor.size(), rho), floor.size(), coverIrradiance));
  for (std::size_t p = 0; p < floor.size(); ++p)
  {
    const glm::dvec3 atPoint =
      renderer.SurfaceRadiance(0, floor[p].Domain.CenterU(), floor[p].Domain.CenterV());
    for (int band = 0; band < 3; ++band)
    {
      EXPECT_NEAR(atPoint[band], 0.1 + rho[band] / Pi * nodes.At(p, 0.5, 0.5)[band], 1e-9)
        << "point " << p;
    }
  }
  const glm::dvec3 inside = renderer.SurfaceRadiance(0, 0.4, 0.1);
  for (int band = 0; band < 3; ++band)
  {
    EXPECT_NEAR(
      inside[band], 0.1 + rho[band] / Pi * nodes.At(1, 0.4 * 3.0 - 1.0, 0.1 * 3.0)[band], 1e-9);
  }
  EXPECT_THROW(DirectLight(nodes,
                 std::vector<glm::dvec3>(floor.size(), rho),
                 floor.size(),
                 std::vector<glm::dvec3>(2, rho)),
    std::invalid_argument);
}

// The finer nodes go where the direct light is not bilinear across a patch (DirectIrradiance.h,
// RefinementTolerance): on the floor of LampOverFloor split 9 x 9 under an occluder near it,
// the refined patches are those the shadow's edge crosses, a minority; there the nodes are those of
// computing every patch's nodes, bit for bit, elsewhere the coarse nodes' bilinear
// interpolation; and the refinement removes most of what interpolating every patch's coarse
// nodes misses of the fully computed light.
TEST(DirectIrradiance, FinerNodesWhereTheShadowsEdgeCrosses)
{
  std::vector<Patch> patches;
  AppendSplit(patches,
    Parallelogram(glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0)),
    0,
    9,
    9);
  for (const Patch& patch : LampOverFloor(false))
  {
    if (patch.SurfaceIndex != 0)
    {
      patches.push_back(patch);
    }
  }
  // An occluder near the floor casts a shadow with a narrow penumbra (under a patch wide).
  AppendSplit(patches,
    Parallelogram(glm::dvec3(0.3, 0.3, 0.05), glm::dvec3(0.0, 0.4, 0.0), glm::dvec3(0.4, 0.0, 0.0)),
    3,
    1,
    1);
  const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
  const std::vector<glm::dvec3> emission = EmissionOf(patches);
  auto compute = [&](double tolerance)
  {
    DirectIrradianceOptions options;
    options.NodesPerSide = 9;
    options.BounceRaysPerSide = 0;
    options.RefinementTolerance = tolerance;
    DirectIrradianceNodes nodes;
    EXPECT_TRUE(ComputeDirectIrradiance(
      patches, caster, BrightEmitters(patches, emission), emission, {}, options, nodes));
    return nodes;
  };
  const DirectIrradianceNodes every = compute(0.0);
  const DirectIrradianceNodes adaptive = compute(0.05);
  const DirectIrradianceNodes coarse = compute(1e9); // no patch refined
  ASSERT_EQ(every.Values.size(), adaptive.Values.size());
  const std::size_t perPatch = 81 * 3;
  int refined = 0;
  double missedByCoarse = 0.0;
  double missedByAdaptive = 0.0;
  for (std::size_t p = 0; p < 81; ++p) // the floor's patches
  {
    const auto first = adaptive.Values.begin() + static_cast<std::ptrdiff_t>(p * perPatch);
    const bool same = std::equal(first,
      first + static_cast<std::ptrdiff_t>(perPatch),
      every.Values.begin() + static_cast<std::ptrdiff_t>(p * perPatch));
    // Not refined: the coarse nodes' interpolation inside, and on its sides the nodes a
    // refined neighbour computed where it has one (so the two agree along their edge).
    bool interpolated = true;
    for (std::size_t j = 1; j + 1 < 9; ++j)
    {
      for (std::size_t i = 1; i + 1 < 9; ++i)
      {
        const std::size_t k = p * perPatch + (j * 9 + i) * 3;
        interpolated = interpolated && adaptive.Values[k + 2] == coarse.Values[k + 2];
      }
    }
    EXPECT_TRUE(same || interpolated) << "patch " << p;
    // A patch whose coarse nodes are all lit alike or all dark needs no refinement.
    refined += interpolated ? 0 : 1;
    for (std::size_t k = p * perPatch; k < (p + 1) * perPatch; k += 3)
    {
      missedByCoarse += std::pow(coarse.Values[k + 2] - every.Values[k + 2], 2.0);
      missedByAdaptive += std::pow(adaptive.Values[k + 2] - every.Values[k + 2], 2.0);
    }
  }
  EXPECT_GT(refined, 0);
  EXPECT_LT(refined, 81 / 2);
  ASSERT_GT(missedByCoarse, 0.0);
  EXPECT_LT(std::sqrt(missedByAdaptive), 0.25 * std::sqrt(missedByCoarse))
    << refined << " of 81 patches refined";
}
