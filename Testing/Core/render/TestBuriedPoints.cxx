// SPDX-License-Identifier: BSD-3-Clause
// The buried characteristic points (Core/render/BuriedPoints.h): a block standing on a floor
// buries exactly the floor's points under it, whose hemispheres see only the block's back
// sides; in an open scene no point is buried; a surface that would lose all its points keeps
// them.
#include "render/BuriedPoints.h"

#include "CoverTestUtilities.h"

#include <gtest/gtest.h>

#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// The unit floor at z = 0 (front +z) split 9 x 9 (surface 0), and, when `side` > 0, a
/// block [a, a + side]^2 x [0, side / 2] of five outward-facing faces (surfaces 1-5, no bottom).
std::vector<Patch> FloorWithBlock(double a, double side)
{
  std::vector<Patch> patches;
  AppendSplit(patches,
    Parallelogram(glm::dvec3(0.0), glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0)),
    0,
    9,
    9);
  if (side <= 0.0)
  {
    return patches;
  }
  const double b = a + side;
  const double h = side / 2.0;
  const glm::dvec3 x(side, 0.0, 0.0);
  const glm::dvec3 y(0.0, side, 0.0);
  const glm::dvec3 z(0.0, 0.0, h);
  const std::vector<BezierPatch> faces{ Parallelogram(glm::dvec3(a, a, h), x, y),
    Parallelogram(glm::dvec3(a, a, 0.0), z, y),
    Parallelogram(glm::dvec3(b, a, 0.0), y, z),
    Parallelogram(glm::dvec3(a, a, 0.0), x, z),
    Parallelogram(glm::dvec3(a, b, 0.0), z, x) };
  for (size_t k = 0; k < faces.size(); ++k)
  {
    AppendSplit(patches, faces[k], static_cast<int>(k + 1), 1, 1);
  }
  return patches;
}

std::vector<bool> Buried(const std::vector<Patch>& patches)
{
  return BuriedPoints(CharacteristicPointInterpolator::OfPatches(patches), patches);
}
}

TEST(BuriedPoints, ABlockBuriesTheFloorUnderIt)
{
  const std::vector<Patch> patches = FloorWithBlock(1.0 / 3.0, 1.0 / 3.0);
  const std::vector<bool> buried = Buried(patches);
  ASSERT_EQ(buried.size(), patches.size());
  int count = 0;
  for (size_t p = 0; p < patches.size(); ++p)
  {
    const UVRect& r = patches[p].Domain;
    const bool under = patches[p].SurfaceIndex == 0 && r.CenterU() > 1.0 / 3.0 &&
      r.CenterU() < 2.0 / 3.0 && r.CenterV() > 1.0 / 3.0 && r.CenterV() < 2.0 / 3.0;
    EXPECT_EQ(buried[p], under) << "point " << p;
    count += buried[p] ? 1 : 0;
  }
  EXPECT_EQ(count, 9);
}

TEST(BuriedPoints, NoneInAnOpenScene)
{
  for (const bool value : Buried(FloorWithBlock(0.0, 0.0)))
  {
    EXPECT_FALSE(value);
  }
}

TEST(BuriedPoints, ASurfaceAllBuriedKeepsItsPoints)
{
  // A block wider than the floor: every floor point sees back sides only.
  for (const bool value : Buried(FloorWithBlock(-0.1, 1.2)))
  {
    EXPECT_FALSE(value);
  }
}
