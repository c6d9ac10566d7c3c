// SPDX-License-Identifier: BSD-3-Clause
// SolutionFigures (the report's figures, README.md#command-line): on Howell's parallel rectangles
// (lamp A facing white B) each surface's area is the sum of its patches', B's mean irradiance is pi
// Le F_BA (it is lit directly only), the form factors are the cover's per surface, the imbalance is
// LightPropagation's; inconsistent input is refused.
#include "CoverTestUtilities.h"

#include "propagation/SolutionFigures.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// The sparse form factors are the dense matrix's values bit for bit, a pair listed for every
/// non-zero element, each row ascending.
void ExpectTheDenseMatrix(const SurfaceFormFactors& sparse, const std::vector<double>& dense)
{
  const int n = sparse.SurfaceCount;
  ASSERT_EQ(dense.size(), static_cast<size_t>(n) * static_cast<size_t>(n));
  ASSERT_EQ(sparse.RowOffsets.size(), static_cast<size_t>(n) + 1);
  size_t nonZero = 0;
  for (int a = 0; a < n; ++a)
  {
    for (uint64_t k = sparse.RowOffsets[a]; k + 1 < sparse.RowOffsets[a + 1]; ++k)
    {
      EXPECT_LT(sparse.Seen[k], sparse.Seen[k + 1]);
    }
    for (int b = 0; b < n; ++b)
    {
      const double value = dense[static_cast<size_t>(a) * static_cast<size_t>(n) + b];
      EXPECT_EQ(sparse.At(a, b), value) << a << " -> " << b;
      nonZero += value != 0.0 ? 1 : 0;
    }
  }
  EXPECT_GE(sparse.PairCount(), nonZero);
  EXPECT_EQ(sparse.MemoryBytes(),
    (n + 1) * SurfaceFormFactors::BytesPerSurface +
      sparse.PairCount() * SurfaceFormFactors::BytesPerPair);
}

/// The illumination of the Howell scene at equilibrium, per point its surface (name index).
PointIllumination Solve(const CoveredScene& setup, LightPropagation& propagation)
{
  PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-12;
  EXPECT_TRUE(propagation.Run(settings));
  PointIllumination illumination;
  illumination.SurfaceCount = static_cast<int>(setup.Environment.SurfaceNames.size());
  for (size_t i = 0; i < setup.Patches.size(); ++i)
  {
    illumination.SurfaceOfPoint.push_back(
      setup.Environment.Surfaces[static_cast<size_t>(setup.Patches[i].SurfaceIndex)].NameIndex);
    illumination.Area.push_back(setup.Cover.PatchArea(i));
    illumination.Irradiance.push_back(propagation.Irradiance(i));
    illumination.ExitantRadiance.push_back(propagation.ExitantRadiance(i));
  }
  const EnergyBalance energy = propagation.Energy();
  illumination.Emitted = energy.Emitted;
  illumination.Absorbed = energy.Absorbed;
  return illumination;
}
}

TEST(SolutionFigures, HowellParallelRectangles)
{
  CoveredScene setup("howell_parallel.scene", 4);
  LightPropagation propagation(setup.Cover, setup.Materials);
  const PointIllumination illumination = Solve(setup, propagation);
  ASSERT_EQ(illumination.SurfaceCount, 2);
  const SolutionFigures figures = ComputeSolutionFigures(setup.Cover, illumination);

  ASSERT_EQ(figures.Surfaces.size(), 2u);
  EXPECT_EQ(figures.CharacteristicPoints, setup.Patches.size());
  EXPECT_EQ(figures.Strips, setup.Cover.StripCount());
  ExpectTheDenseMatrix(figures.FormFactors,
    setup.Cover.FormFactors(illumination.SurfaceOfPoint, illumination.SurfaceCount));
  EXPECT_EQ(figures.RelativeImbalance, propagation.Energy().RelativeImbalance);
  EXPECT_EQ(figures.Emitted, propagation.Energy().Emitted);

  // Which named surface is the lamp: the one that emits.
  const int lamp = setup.Environment.FindMaterial("lamp");
  int a = -1;
  for (const Surface& surface : setup.Environment.Surfaces)
  {
    if (surface.MaterialIndex == lamp)
    {
      a = surface.NameIndex;
    }
  }
  ASSERT_GE(a, 0);
  const int b = 1 - a;
  // The scene's rectangles are 1 x 2.
  EXPECT_NEAR(figures.Surfaces[static_cast<size_t>(a)].Area, 2.0, 1e-12);
  EXPECT_NEAR(figures.Surfaces[static_cast<size_t>(b)].Area, 2.0, 1e-12);
  const glm::dvec3 le = setup.Environment.Materials[static_cast<size_t>(lamp)].Emission;
  const double fBA = figures.FormFactors.At(b, a);
  for (int band = 0; band < 3; ++band)
  {
    const double mean = figures.Surfaces[static_cast<size_t>(b)].MeanIrradiance[band];
    EXPECT_NEAR(mean, Pi * le[band] * fBA, 1e-12 * mean);
    // The lamp reflects nothing: its mean exitant radiance is its emission.
    EXPECT_NEAR(figures.Surfaces[static_cast<size_t>(a)].MeanExitantRadiance[band],
      le[band],
      1e-12 * le[band]);
  }
}

TEST(SolutionFigures, RelativeImbalanceCountsOnlyEmittingBands)
{
  EXPECT_DOUBLE_EQ(RelativeImbalance({ 1.0, 0.0, 2.0 }, { 0.9, 5.0, 2.0 }), 0.1 / 1.0);
  EXPECT_EQ(RelativeImbalance(glm::dvec3(0.0), glm::dvec3(1.0)), 0.0);
}

TEST(SolutionFigures, RefusesInconsistentInput)
{
  CoveredScene setup("howell_parallel.scene", 2);
  LightPropagation propagation(setup.Cover, setup.Materials);
  PointIllumination illumination = Solve(setup, propagation);
  PointIllumination shorter = illumination;
  shorter.Area.pop_back();
  EXPECT_THROW(ComputeSolutionFigures(setup.Cover, shorter), std::invalid_argument);
  PointIllumination outOfRange = illumination;
  outOfRange.SurfaceOfPoint[0] = outOfRange.SurfaceCount;
  EXPECT_THROW(ComputeSolutionFigures(setup.Cover, outOfRange), std::invalid_argument);
  outOfRange.SurfaceOfPoint[0] = -1;
  EXPECT_THROW(ComputeSolutionFigures(setup.Cover, outOfRange), std::invalid_argument);
}
