// SPDX-License-Identifier: BSD-3-Clause
// RayCaster: a flat quadrilateral is two triangles, a filter asked about first hits only
// (RayFilter::RejectsAllNearer) gives the hits of the filter applied during traversal, and
// PatchesNear finds every patch whose tessellation comes that near.
#include "CoverTestUtilities.h"

#include "geometry/RayCaster.h"
#include "scene/SceneLoader.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{

/// The cover's visibility semantics in small: back sides pass, the origin's own patch nearer
/// than Exclusion is the origin itself.
struct OwnPatchFilter
{
  std::size_t Own;
  float Exclusion;
};

bool PassBacksAndOwnPatch(const void* context, std::size_t patch, float distance, bool front)
{
  const OwnPatchFilter& filter = *static_cast<const OwnPatchFilter*>(context);
  return front && !(patch == filter.Own && distance < filter.Exclusion);
}

struct TeapotRoom
{
  Scene Environment = LoadSceneFile(ScenePath("teapot_room.scene"));
  std::vector<Patch> Patches = SplitScene(this->Environment, 2);

  std::vector<RayCastPatch> CastPatches() const
  {
    std::vector<RayCastPatch> cast;
    for (const Patch& patch : this->Patches)
    {
      cast.push_back({ &patch.Geometry, patch.SurfaceIndex });
    }
    return cast;
  }
};

glm::dvec3 RandomDirection(std::mt19937_64& rng)
{
  std::normal_distribution<double> normal;
  glm::dvec3 d;
  do
  {
    d = glm::dvec3(normal(rng), normal(rng), normal(rng));
  } while (!(glm::length(d) > 1e-6));
  return glm::normalize(d);
}

} // namespace

TEST(RayCaster, FirstHitFilterGivesTheTraversalFiltersHits)
{
  // Rays in every direction (half of them into the surface they start on, so that back sides
  // are met first and the rays are cast again) from the centres of the teapot room's curved
  // and flat patches: the first-hit filter must find the hits the traversal filter finds.
  const TeapotRoom room;
  const RayCaster caster(room.CastPatches(), RayCasterOptions());
  std::mt19937_64 rng(7);
  std::size_t compared = 0;
  std::size_t recast = 0;
  std::size_t promised = 0;
  std::size_t tried = 0;
  std::vector<std::size_t> near;
  for (std::size_t p = 0; p < room.Patches.size(); p += 3)
  {
    ++tried;
    const glm::dvec3 origin = room.Patches[p].Geometry.Evaluate(0.5, 0.5);
    const OwnPatchFilter own{ p, static_cast<float>(1e-3 * room.Patches[p].Geometry.Size()) };
    caster.PatchesNear(origin, 2.0 * own.Exclusion, near);
    if (!std::all_of(near.begin(), near.end(), [&](std::size_t q) { return q == p; }))
    {
      continue;
    }
    ++promised;
    const RayFilter throughout{ PassBacksAndOwnPatch, &own };
    const RayFilter firstHit{ PassBacksAndOwnPatch, &own, own.Exclusion };
    glm::dvec3 directions[RayCaster::PacketSize];
    for (glm::dvec3& direction : directions)
    {
      direction = RandomDirection(rng);
    }
    TriangleHit packetHits[RayCaster::PacketSize];
    bool packetFound[RayCaster::PacketSize];
    caster.IntersectPacket(
      origin, directions, RayCaster::PacketSize, 0.0f, firstHit, packetHits, packetFound);
    for (int k = 0; k < RayCaster::PacketSize; ++k)
    {
      TriangleHit expected;
      TriangleHit single;
      TriangleHit unfiltered;
      const bool expectedFound =
        caster.Intersect(origin, directions[k], 0.0f, throughout, false, expected);
      const bool singleFound =
        caster.Intersect(origin, directions[k], 0.0f, firstHit, false, single);
      if (caster.Intersect(origin, directions[k], own.Exclusion, RayFilter(), false, unfiltered) &&
        !PassBacksAndOwnPatch(&own, unfiltered.Patch, unfiltered.Distance, unfiltered.FrontSide))
      {
        ++recast;
      }
      ASSERT_EQ(expectedFound, singleFound) << "patch " << p << " ray " << k;
      ASSERT_EQ(expectedFound, packetFound[k]) << "patch " << p << " ray " << k;
      if (!expectedFound)
      {
        continue;
      }
      ++compared;
      // The same hit, or (where triangles meet) one equally near.
      for (const TriangleHit* hit : { &single, &packetHits[k] })
      {
        EXPECT_NEAR(hit->Distance, expected.Distance, 1e-5f * expected.Distance)
          << "patch " << p << " ray " << k;
        EXPECT_TRUE(hit->FrontSide);
        if (hit->Patch != expected.Patch)
        {
          EXPECT_EQ(
            room.Patches[hit->Patch].SurfaceIndex, room.Patches[expected.Patch].SurfaceIndex);
        }
      }
    }
  }
  // The promise holds at most centres, and the second cast was exercised.
  EXPECT_GT(promised, tried / 2);
  EXPECT_GT(compared, promised * 4);
  EXPECT_GT(recast, promised);
}

TEST(RayCaster, PatchesNearFindsEveryPatchWithinTheRadius)
{
  // Brute force: a patch one of whose tessellation's vertices lies within the radius of the
  // point must be found (the vertices are exact patch points at the grid's parameters).
  const TeapotRoom room;
  const RayCaster caster(room.CastPatches(), RayCasterOptions());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::size_t> near;
  std::size_t found = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    const std::size_t p = static_cast<std::size_t>(trial * 7) % room.Patches.size();
    const glm::dvec3 point =
      room.Patches[p].Geometry.Evaluate(unit(rng), unit(rng)) + 0.05 * RandomDirection(rng);
    const double radius = 0.2 * unit(rng);
    caster.PatchesNear(point, radius, near);
    ASSERT_TRUE(std::is_sorted(near.begin(), near.end()));
    for (std::size_t q = 0; q < room.Patches.size(); ++q)
    {
      int nu;
      int nv;
      caster.Resolution(q, nu, nv);
      bool within = false;
      for (int j = 0; j <= nv && !within; ++j)
      {
        for (int i = 0; i <= nu && !within; ++i)
        {
          within = glm::length(room.Patches[q].Geometry.Evaluate(double(i) / nu, double(j) / nv) -
                     point) < radius * (1.0 - 1e-6);
        }
      }
      if (within)
      {
        ++found;
        EXPECT_TRUE(std::binary_search(near.begin(), near.end(), q))
          << "patch " << q << " within " << radius << " of trial " << trial;
      }
    }
  }
  EXPECT_GT(found, 50u);
}

TEST(RayCaster, FlatQuadrilateralIsTwoTrianglesAndAnyOtherPatchIsEven)
{
  // A flat rectangle, a flat trapezoid (bilinear, corners in a plane) and a degree-elevated flat
  // square are two triangles; a twisted bilinear patch and a non-convex flat quadrilateral are
  // not, and their tessellation keeps the centre a vertex (even).
  std::vector<BezierPatch> patches;
  patches.emplace_back(
    1, 1, std::vector<glm::dvec3>{ { 0, 0, 0 }, { 2, 0, 0 }, { 0, 1, 0 }, { 2, 1, 0 } });
  patches.emplace_back(
    1, 1, std::vector<glm::dvec3>{ { 0, 0, 1 }, { 3, 0, 1 }, { 1, 1, 1 }, { 2, 1, 1 } });
  std::vector<glm::dvec3> elevated;
  for (int j = 0; j <= 2; ++j)
  {
    for (int i = 0; i <= 3; ++i)
    {
      elevated.emplace_back(i / 3.0, j / 2.0, 2.0);
    }
  }
  patches.emplace_back(3, 2, elevated);
  patches.emplace_back(
    1, 1, std::vector<glm::dvec3>{ { 0, 0, 3 }, { 1, 0, 3 }, { 0, 1, 3 }, { 1, 1, 3.5 } });
  patches.emplace_back(
    1, 1, std::vector<glm::dvec3>{ { 0, 0, 4 }, { 1, 0, 4 }, { 0, 1, 4 }, { 0.2, 0.2, 4 } });
  std::vector<RayCastPatch> cast;
  for (std::size_t p = 0; p < patches.size(); ++p)
  {
    cast.push_back({ &patches[p], static_cast<int32_t>(p) });
  }
  const RayCaster caster(cast, RayCasterOptions());
  for (std::size_t p = 0; p < patches.size(); ++p)
  {
    int nu;
    int nv;
    caster.Resolution(p, nu, nv);
    if (p < 3)
    {
      EXPECT_EQ(nu, 1) << "patch " << p;
      EXPECT_EQ(nv, 1) << "patch " << p;
    }
    else
    {
      EXPECT_EQ(nu % 2, 0) << "patch " << p;
      EXPECT_EQ(nv % 2, 0) << "patch " << p;
    }
  }
  // The trapezoid's two triangles are the trapezoid: a ray through a point near its slanted
  // edge, inside, hits it; one just outside misses it.
  // Below the patches at z = 2 and above, so the trapezoid (z = 1) or the rectangle (z = 0).
  const glm::dvec3 down(0.0, 0.0, -1.0);
  const double z = 1.5;
  RayCaster::RayHit hit;
  for (const glm::dvec3& inside : { glm::dvec3(0.52, 0.01, z),
         glm::dvec3(1.01, 0.99, z),
         glm::dvec3(2.48, 0.01, z),
         glm::dvec3(1.99, 0.99, z) })
  {
    ASSERT_TRUE(caster.CastRay(inside, down, hit));
    EXPECT_EQ(hit.Patch, 1u) << inside.x << ", " << inside.y;
    EXPECT_NEAR(hit.T, 0.5, 1e-6);
  }
  for (const glm::dvec3& outside :
    { glm::dvec3(0.48, 0.51, z), glm::dvec3(0.97, 0.99, z), glm::dvec3(0.2, 0.3, z) })
  {
    ASSERT_TRUE(caster.CastRay(outside, down, hit));
    EXPECT_EQ(hit.Patch, 0u) << outside.x << ", " << outside.y;
  }
  EXPECT_FALSE(caster.CastRay(glm::dvec3(2.6, 0.45, z), down, hit));
}
