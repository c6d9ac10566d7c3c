// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TestBezierPatch.cxx
 * @brief Geometry of tensor-product Bezier patches: evaluation, derivatives, normals at
 * degenerate points, and the exact de Casteljau sub-patches of paper §4.3.
 *
 * Every check is a mathematical identity: de Casteljau agrees with the Bernstein sum; a split
 * or sub-patch is the same polynomial surface reparametrised; derivatives agree with central
 * differences; the unit normal is unit everywhere, and at collapsed edges (teapot poles, a
 * triangle stored as a bilinear patch) it is the limit of the normals next to the edge.
 */
#include "PatchTestUtilities.h"
#include "geometry/BezierPatch.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace
{

using sphcover::BezierPatch;
using sphcover_test::MaxDeviation;
using sphcover_test::RandomPatch;
using sphcover_test::Teapot;
using sphcover_test::TestDegrees;

/// Pieces must reproduce the parent to this fraction of its bounding-box diagonal.
constexpr double ReproductionTolerance = 1e-12;

/// The patches every geometric identity is checked on: random ones of all test degrees
/// (several each) and the 32 teapot patches.
std::vector<BezierPatch> SamplePatches(std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::vector<BezierPatch> patches;
  for (const auto& degrees : TestDegrees())
  {
    for (int k = 0; k < 4; ++k)
    {
      patches.push_back(RandomPatch(rng, degrees.first, degrees.second));
    }
  }
  patches.insert(patches.end(), Teapot().begin(), Teapot().end());
  return patches;
}

std::vector<glm::dvec3> Grid(int m, int n)
{
  std::vector<glm::dvec3> points;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      points.emplace_back(i, j, 0.1 * i * j);
    }
  }
  return points;
}

bool IsFiniteUnit(const glm::dvec3& n)
{
  return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) &&
    std::fabs(glm::length(n) - 1.0) < 1e-12;
}

TEST(BezierPatch, ConstructorValidatesDegreesCountsAndValues)
{
  EXPECT_THROW(BezierPatch(0, 1, Grid(0, 1)), std::invalid_argument);
  EXPECT_THROW(BezierPatch(1, 0, Grid(1, 0)), std::invalid_argument);
  EXPECT_THROW(BezierPatch(-1, 1, {}), std::invalid_argument);
  EXPECT_THROW(BezierPatch(16, 1, Grid(16, 1)), std::invalid_argument);
  EXPECT_THROW(BezierPatch(3, 3, Grid(3, 2)), std::invalid_argument);
  EXPECT_THROW(BezierPatch(3, 3, {}), std::invalid_argument);
  std::vector<glm::dvec3> withNaN = Grid(2, 2);
  withNaN[4].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(BezierPatch(2, 2, withNaN), std::invalid_argument);
  std::vector<glm::dvec3> withInf = Grid(2, 2);
  withInf[8].z = std::numeric_limits<double>::infinity();
  EXPECT_THROW(BezierPatch(2, 2, withInf), std::invalid_argument);
  try
  {
    BezierPatch(3, 3, Grid(3, 2));
    FAIL() << "expected std::invalid_argument";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("needs 16 control points, got 12"), std::string::npos)
      << e.what();
  }
  EXPECT_NO_THROW(BezierPatch(15, 15, Grid(15, 15)));
  EXPECT_NO_THROW(BezierPatch(1, 15, Grid(1, 15)));
}

TEST(BezierPatch, LayoutIsRowMajorWithUFastestAndCornersInterpolate)
{
  std::mt19937_64 rng(11);
  for (const auto& degrees : TestDegrees())
  {
    const int m = degrees.first;
    const int n = degrees.second;
    const BezierPatch patch = RandomPatch(rng, m, n);
    ASSERT_EQ(patch.DegreeU(), m);
    ASSERT_EQ(patch.DegreeV(), n);
    ASSERT_EQ(patch.ControlPoints().size(), size_t((m + 1) * (n + 1)));
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= m; ++i)
      {
        EXPECT_EQ(patch.ControlPoint(i, j), patch.ControlPoints()[size_t(j * (m + 1) + i)]);
      }
    }
    // A Bezier patch interpolates its corner control points; de Casteljau does so exactly.
    EXPECT_EQ(patch.Evaluate(0, 0), patch.ControlPoint(0, 0));
    EXPECT_EQ(patch.Evaluate(1, 0), patch.ControlPoint(m, 0));
    EXPECT_EQ(patch.Evaluate(0, 1), patch.ControlPoint(0, n));
    EXPECT_EQ(patch.Evaluate(1, 1), patch.ControlPoint(m, n));
    // The boundary curves are the Bezier curves of the boundary rows and columns; in
    // particular dQ/du at a corner is m (P_10 - P_00).
    EXPECT_LT(glm::length(patch.PartialU(0, 0) -
                double(m) * (patch.ControlPoint(1, 0) - patch.ControlPoint(0, 0))),
      1e-13 * m * patch.Size());
    EXPECT_LT(glm::length(patch.PartialV(1, 1) -
                double(n) * (patch.ControlPoint(m, n) - patch.ControlPoint(m, n - 1))),
      1e-13 * n * patch.Size());
  }
}

TEST(BezierPatch, DeCasteljauAgreesWithTheBernsteinSum)
{
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::pair<int, int>> degrees = TestDegrees();
  degrees.emplace_back(15, 15);
  degrees.emplace_back(1, 15);
  for (const auto& d : degrees)
  {
    const BezierPatch patch = RandomPatch(rng, d.first, d.second);
    for (int k = 0; k < 200; ++k)
    {
      const double u = unit(rng);
      const double v = unit(rng);
      EXPECT_LT(glm::length(patch.Evaluate(u, v) - sphcover_test::BernsteinSum(patch, u, v)),
        1e-12 * patch.Size())
        << "degree (" << d.first << ", " << d.second << ") at " << u << ", " << v;
    }
  }
}

TEST(BezierPatch, SplitHalvesReproduceTheParent)
{
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> split(0.02, 0.98);
  for (const BezierPatch& patch : SamplePatches(14))
  {
    for (double t : { split(rng), split(rng), 0.5, 1e-3, 1.0 - 1e-3 })
    {
      const double tolerance = ReproductionTolerance * patch.Size();
      // Where a point (s, w) of each half lies on the parent.
      const auto lowerU = [t](double s, double w) { return std::make_pair(s * t, w); };
      const auto upperU = [t](double s, double w) { return std::make_pair(t + s * (1 - t), w); };
      const auto lowerV = [t](double s, double w) { return std::make_pair(s, w * t); };
      const auto upperV = [t](double s, double w) { return std::make_pair(s, t + w * (1 - t)); };
      const auto halvesU = patch.SplitU(t);
      EXPECT_LT(MaxDeviation(halvesU.first, patch, lowerU), tolerance);
      EXPECT_LT(MaxDeviation(halvesU.second, patch, upperU), tolerance);
      const auto halvesV = patch.SplitV(t);
      EXPECT_LT(MaxDeviation(halvesV.first, patch, lowerV), tolerance);
      EXPECT_LT(MaxDeviation(halvesV.second, patch, upperV), tolerance);
      // The halves meet along the split curve exactly as de Casteljau computes it.
      EXPECT_EQ(halvesU.first.ControlPoint(patch.DegreeU(), 0), halvesU.second.ControlPoint(0, 0));
      EXPECT_EQ(halvesV.first.ControlPoint(0, patch.DegreeV()), halvesV.second.ControlPoint(0, 0));
    }
  }
}

TEST(BezierPatch, SubPatchesReproduceTheParentAndScaleItsDerivatives)
{
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const BezierPatch& patch : SamplePatches(16))
  {
    for (int k = 0; k < 6; ++k)
    {
      double u0 = unit(rng);
      double u1 = unit(rng);
      double v0 = unit(rng);
      double v1 = unit(rng);
      if (k == 0)
      {
        // A thin strip at the boundary, as deep ternary subdivision produces.
        u0 = 0.0;
        u1 = std::pow(3.0, -6);
        v0 = 1.0 - std::pow(3.0, -5);
        v1 = 1.0;
      }
      if (u0 > u1)
      {
        std::swap(u0, u1);
      }
      if (v0 > v1)
      {
        std::swap(v0, v1);
      }
      if (u1 - u0 < 1e-6 || v1 - v0 < 1e-6)
      {
        continue;
      }
      const BezierPatch sub = patch.SubPatch(u0, u1, v0, v1);
      const double du = u1 - u0;
      const double dv = v1 - v0;
      EXPECT_LT(
        MaxDeviation(
          sub, patch, [&](double s, double t) { return std::make_pair(u0 + s * du, v0 + t * dv); }),
        ReproductionTolerance * patch.Size());
      // Chain rule: the sub-patch's partials are the parent's scaled by the rectangle sides.
      for (double s : { 0.0, 0.3, 1.0 })
      {
        const double u = u0 + s * du;
        const double v = v0 + (1.0 - s) * dv;
        const double scale = patch.Size() * patch.DegreeU() * patch.DegreeV();
        EXPECT_LT(
          glm::length(sub.PartialU(s, 1.0 - s) - du * patch.PartialU(u, v)), 1e-11 * scale * du);
        EXPECT_LT(
          glm::length(sub.PartialV(s, 1.0 - s) - dv * patch.PartialV(u, v)), 1e-11 * scale * dv);
      }
    }
    // The whole rectangle gives the patch back exactly.
    EXPECT_EQ(patch.SubPatch(0.0, 1.0, 0.0, 1.0).ControlPoints(), patch.ControlPoints());
    EXPECT_EQ(patch.SubPatch(sphcover::UVRect::Unit()).ControlPoints(), patch.ControlPoints());
  }
}

TEST(BezierPatch, SplitAndSubPatchRejectBadParameters)
{
  const BezierPatch patch(2, 2, Grid(2, 2));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double t : { 0.0, 1.0, -0.5, 1.5, nan })
  {
    EXPECT_THROW(patch.SplitU(t), std::invalid_argument) << t;
    EXPECT_THROW(patch.SplitV(t), std::invalid_argument) << t;
  }
  EXPECT_THROW(patch.SubPatch(0.5, 0.5, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(patch.SubPatch(0.6, 0.5, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(patch.SubPatch(-0.1, 0.5, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(patch.SubPatch(0.0, 0.5, 0.0, 1.1), std::invalid_argument);
  EXPECT_THROW(patch.SubPatch(0.0, nan, 0.0, 1.0), std::invalid_argument);
}

TEST(BezierPatch, PartialsAgreeWithCentralDifferences)
{
  std::mt19937_64 rng(17);
  const double h = 1e-5;
  std::uniform_real_distribution<double> inside(h, 1.0 - h);
  for (const BezierPatch& patch : SamplePatches(18))
  {
    // Central differences err by h^2/6 |Q'''| (|Q'''| <= about 8 m^3 Size) plus rounding
    // of about 1e-16 |Q| / h.
    const int d = std::max(patch.DegreeU(), patch.DegreeV());
    const double tolerance = (1e-9 * d * d * d + 1e-9) * patch.Size();
    for (int k = 0; k < 40; ++k)
    {
      const double u = inside(rng);
      const double v = inside(rng);
      const glm::dvec3 differenceU =
        (patch.Evaluate(u + h, v) - patch.Evaluate(u - h, v)) / (2 * h);
      const glm::dvec3 differenceV =
        (patch.Evaluate(u, v + h) - patch.Evaluate(u, v - h)) / (2 * h);
      EXPECT_LT(glm::length(patch.PartialU(u, v) - differenceU), tolerance);
      EXPECT_LT(glm::length(patch.PartialV(u, v) - differenceV), tolerance);
      glm::dvec3 position;
      glm::dvec3 partialU;
      glm::dvec3 partialV;
      patch.EvaluateWithPartials(u, v, position, partialU, partialV);
      EXPECT_EQ(position, patch.Evaluate(u, v));
      EXPECT_EQ(partialU, patch.PartialU(u, v));
      EXPECT_EQ(partialV, patch.PartialV(u, v));
      EXPECT_EQ(patch.UnnormalizedNormal(u, v), glm::cross(partialU, partialV));
    }
  }
}

TEST(BezierPatch, NormalIsAFiniteUnitVectorOnTheFrontEverywhere)
{
  const int samples = 20;
  for (const BezierPatch& patch : SamplePatches(19))
  {
    for (int b = 0; b <= samples; ++b)
    {
      for (int a = 0; a <= samples; ++a)
      {
        const double u = double(a) / samples;
        const double v = double(b) / samples;
        const glm::dvec3 n = patch.Normal(u, v);
        ASSERT_TRUE(IsFiniteUnit(n)) << n.x << " " << n.y << " " << n.z << " at " << u << ", " << v;
        const glm::dvec3 area = patch.UnnormalizedNormal(u, v);
        if (glm::length(area) > 1e-6 * patch.Size() * patch.Size())
        {
          EXPECT_NEAR(glm::dot(n, area / glm::length(area)), 1.0, 1e-12);
        }
      }
    }
  }
}

TEST(BezierPatch, FrontSideIsThatOfPuCrossPv)
{
  // The unit square in the xy plane, u along x and v along y: the front is +z.
  const BezierPatch square(1, 1, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } });
  for (double u : { 0.0, 0.5, 1.0 })
  {
    for (double v : { 0.0, 0.25, 1.0 })
    {
      EXPECT_EQ(square.Normal(u, v), glm::dvec3(0, 0, 1));
    }
  }
  EXPECT_EQ(square.ControlNetNormal(), glm::dvec3(0, 0, 1));
  // A flat quad in a tilted plane: its normal is the plane's everywhere, including the corners
  // and on every sub-patch and split half.
  const glm::dvec3 e1 = glm::normalize(glm::dvec3(1, 2, 0.5));
  const glm::dvec3 e2 = glm::normalize(glm::cross(glm::dvec3(0.3, -1, 2), e1));
  const glm::dvec3 plane = glm::normalize(glm::cross(e1, e2));
  const glm::dvec3 o(5, -2, 7);
  const BezierPatch quad(
    1, 1, { o, o + 2.0 * e1 + 0.3 * e2, o - 0.2 * e1 + 1.5 * e2, o + 2.5 * e1 + 2.0 * e2 });
  for (const BezierPatch& piece :
    { quad, quad.SubPatch(0.2, 0.7, 0.1, 0.4), quad.SplitU(0.3).second, quad.SplitV(0.8).first })
  {
    for (double u : { 0.0, 0.37, 1.0 })
    {
      for (double v : { 0.0, 0.61, 1.0 })
      {
        EXPECT_LT(glm::length(piece.Normal(u, v) - plane), 1e-14);
      }
    }
  }
}

/// A triangle stored as a bilinear patch whose corner `collapsed` moved onto its successor
/// (counter-clockwise: (0,0) -> (1,0) -> (1,1) -> (0,1)), so one edge is a single point.
BezierPatch TriangleAsBilinear(int collapsedEdge, const glm::dvec3 (&corner)[4])
{
  // Corners in the order P00, P10, P11, P01 around the square.
  glm::dvec3 c[4] = { corner[0], corner[1], corner[2], corner[3] };
  c[(collapsedEdge + 1) % 4] = c[collapsedEdge];
  return BezierPatch(1, 1, { c[0], c[1], c[3], c[2] });
}

TEST(BezierPatch, TriangleAsDegenerateBilinearHasItsFaceNormalEverywhere)
{
  const glm::dvec3 corner[4] = {
    { 0.5, -1, 2 }, { 3, 0.2, 1.5 }, { 2.5, 2.5, 3 }, { -0.4, 1.5, 2.2 }
  };
  for (int edge = 0; edge < 4; ++edge)
  {
    // Edge k runs from corner k to corner k+1; collapsing it leaves a triangle of the other
    // three distinct corners, listed counter-clockwise.
    const BezierPatch triangle = TriangleAsBilinear(edge, corner);
    const glm::dvec3 a = corner[edge];
    const glm::dvec3 b = corner[(edge + 2) % 4];
    const glm::dvec3 c = corner[(edge + 3) % 4];
    const glm::dvec3 face = glm::normalize(glm::cross(b - a, c - a));
    for (int j = 0; j <= 10; ++j)
    {
      for (int i = 0; i <= 10; ++i)
      {
        const glm::dvec3 n = triangle.Normal(i / 10.0, j / 10.0);
        ASSERT_TRUE(IsFiniteUnit(n));
        EXPECT_LT(glm::length(n - face), 1e-13) << "edge " << edge << " at " << i << ", " << j;
      }
    }
    // On the collapsed edge itself Pu x Pv is exactly zero: the limit rule is what answers.
    const double u = (edge == 1) ? 1.0 : (edge == 3 ? 0.0 : 0.5);
    const double v = (edge == 0) ? 0.0 : (edge == 2 ? 1.0 : 0.5);
    EXPECT_EQ(triangle.UnnormalizedNormal(u, v), glm::dvec3(0.0));
    EXPECT_LT(glm::length(triangle.Normal(u, v) - face), 1e-13);
  }
}

TEST(BezierPatch, TeapotPolesHaveTheLimitNormalOfTheirNeighbourhood)
{
  // The lid's knob and the bottom collapse one boundary row of each of their 8 patches into a
  // point on the z axis. By rotational symmetry the tangent plane there is horizontal, so the
  // limit normal is +z or -z, and it must continue the normals next to the pole.
  int collapsedEdges = 0;
  for (const BezierPatch& patch : Teapot())
  {
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    for (int side = 0; side < 2; ++side) // side 0: edge v = 0, side 1: edge v = 1
    {
      const int j = side * n;
      bool collapsed = true;
      for (int i = 1; i <= m; ++i)
      {
        collapsed = collapsed && patch.ControlPoint(i, j) == patch.ControlPoint(0, j);
      }
      if (!collapsed)
      {
        continue;
      }
      ++collapsedEdges;
      const double v = side;
      for (int a = 0; a <= 12; ++a)
      {
        const double u = a / 12.0;
        ASSERT_EQ(patch.UnnormalizedNormal(u, v), glm::dvec3(0.0));
        const glm::dvec3 pole = patch.Normal(u, v);
        ASSERT_TRUE(IsFiniteUnit(pole));
        EXPECT_GT(std::fabs(pole.z), 1.0 - 1e-12) << u;
        // Next to the pole the ordinary normal converges to the limit (linearly in distance).
        const double inward = side == 0 ? 1e-6 : -1e-6;
        const glm::dvec3 nearby = glm::normalize(patch.UnnormalizedNormal(u, v + inward));
        EXPECT_GT(glm::dot(pole, nearby), 1.0 - 1e-9) << u;
      }
    }
  }
  EXPECT_EQ(collapsedEdges, 8);
}

TEST(BezierPatch, PatchesWithoutAreaStillGetAUnitNormal)
{
  std::vector<glm::dvec3> line;
  for (int k = 0; k < 9; ++k)
  {
    line.emplace_back(k % 3, 2.0 * (k % 3), -1.0 * (k % 3));
  }
  const BezierPatch segment(2, 2, line);
  const BezierPatch point(1, 1, std::vector<glm::dvec3>(4, glm::dvec3(1, 2, 3)));
  for (const BezierPatch& patch : { segment, point })
  {
    for (double u : { 0.0, 0.5, 1.0 })
    {
      for (double v : { 0.0, 0.5, 1.0 })
      {
        EXPECT_TRUE(IsFiniteUnit(patch.Normal(u, v)));
      }
    }
  }
}

TEST(BezierPatch, ControlNetBoundsEncloseThePatch)
{
  for (const BezierPatch& patch : SamplePatches(20))
  {
    const sphcover::IntervalVec3& box = patch.Bounds();
    for (const glm::dvec3& p : patch.ControlPoints())
    {
      EXPECT_TRUE(box.Contains(p));
    }
    EXPECT_DOUBLE_EQ(patch.Size(), glm::length(box.Upper() - box.Lower()));
    for (int b = 0; b <= 16; ++b)
    {
      for (int a = 0; a <= 16; ++a)
      {
        // Convex hull property (the evaluated point may round by an ulp past a face).
        const glm::dvec3 p = patch.Evaluate(a / 16.0, b / 16.0);
        const glm::dvec3 slack(1e-14 * patch.Size());
        EXPECT_TRUE(glm::all(glm::lessThanEqual(box.Lower() - slack, p)) &&
          glm::all(glm::lessThanEqual(p, box.Upper() + slack)));
      }
    }
  }
}

} // namespace
