// SPDX-License-Identifier: BSD-3-Clause
// SolutionFigures (the report's figures, README.md#command-line): on Howell's parallel rectangles
// (lamp A facing white B) each surface's area is the sum of its patches', B's mean irradiance is pi
// Le F_BA (it is lit directly only), the form factors are the cover's per surface, the imbalance is
// LightPropagation's; inconsistent input is refused. The sparse form factors are the dense
// matrix's, and those of 20,184 named surfaces of a closed room are a closed room's (rows of 1,
// reciprocity, Howell per wall) in memory linear in the surfaces.
#include "CoverTestUtilities.h"

#include "propagation/SolutionFigures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
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

/**
 * 20,184 named surfaces (issue 39: a CAD scene has thousands of named parts): the unit cube of
 * furnace_box.scene with its six walls cut into 58 x 58 tiles, every tile a named surface of its
 * own, covered on a coarse grid (4 x 16 cells) so that it takes seconds. The dense matrix would
 * be 20,184^2 doubles (3.3 GB); the sparse factors must hold only the pairs that see each other,
 * at most one per region of a tile's hemisphere, and still be the form factors of a closed room:
 *  - every tile's row sums to 1 (its hemisphere is covered: the cells partition pi);
 *  - summed area-weighted over the walls, the tiles' factors are the walls' own (the same cover
 *    grouped by wall), which are reciprocal, A_A F_AB = A_B F_BA, and Howell's for the unit
 *    cube's faces (C-11 opposite, C-14 adjacent) within the coarse grid's error.
 */
TEST(SolutionFigures, TwentyThousandNamedSurfacesOfAClosedRoom)
{
  const Scene scene = LoadSceneFile(ScenePath("furnace_box.scene"));
  ASSERT_EQ(scene.Surfaces.size(), 6u);
  const int split = Sanitized ? 20 : 58;
  const std::vector<Patch> patches = SplitScene(scene, split);
  SphericalCoverOptions options;
  options.ThetaBins = 4;
  options.PhiBins = 16;
  options.SamplesTheta = 1;
  options.SamplesPhi = 1;
  options.Fill = RBufferFill::RayCasting;
  SphericalCover cover;
  ASSERT_TRUE(cover.Build(patches, options, ThreadedFor(2)));
  const size_t tiles = patches.size();
  ASSERT_EQ(tiles, 6u * split * split);
  std::vector<int> tileOf(tiles);
  std::vector<int> wallOf(tiles);
  for (size_t i = 0; i < tiles; ++i)
  {
    tileOf[i] = static_cast<int>(i);
    wallOf[i] = patches[i].SurfaceIndex;
  }
  const SurfaceFormFactors f = SurfaceFormFactorsOf(cover, tileOf, static_cast<int>(tiles));
  ASSERT_EQ(f.SurfaceCount, static_cast<int>(tiles));
  ASSERT_EQ(f.RowOffsets.size(), tiles + 1);

  // Linear in the surfaces: a tile (one point) sees at most one surface per region, so the
  // pairs are at most the regions, at most the cells per tile.
  const size_t cells = static_cast<size_t>(options.ThetaBins * options.PhiBins);
  EXPECT_LE(f.PairCount(), cover.EntryCount());
  EXPECT_LE(f.PairCount(), tiles * cells);
  EXPECT_EQ(f.MemoryBytes(),
    (tiles + 1) * SurfaceFormFactors::BytesPerSurface +
      f.PairCount() * SurfaceFormFactors::BytesPerPair);
  EXPECT_LE(f.MemoryBytes(), FiguresBoundBytes(tiles, cover.EntryCount(), tiles));
  // Far below the dense matrix at the full size (the bound grows as the tiles, the matrix as their
  // square: at the sanitizers' 2,400 tiles the matrix is only 44 MiB and the bound a quarter).
  if (!Sanitized)
  {
    EXPECT_LT(static_cast<double>(FiguresBoundBytes(tiles, cover.EntryCount(), tiles)),
      0.05 * sizeof(double) * static_cast<double>(tiles) * static_cast<double>(tiles));
  }

  // A closed room: every row sums to 1 (to the rounding of the cell measures and the sums).
  double worstRow = 0.0;
  for (size_t a = 0; a < tiles; ++a)
  {
    double row = 0.0;
    for (uint64_t k = f.RowOffsets[a]; k < f.RowOffsets[a + 1]; ++k)
    {
      ASSERT_GE(f.Seen[k], 0);
      ASSERT_LT(f.Seen[k], static_cast<int32_t>(tiles));
      EXPECT_GT(f.Values[k], 0.0);
      row += f.Values[k];
    }
    worstRow = std::max(worstRow, std::fabs(row - 1.0));
  }
  EXPECT_LT(worstRow, 1e-12);

  // The tiles' factors summed over the walls, area-weighted: the walls' own factors.
  const SurfaceFormFactors walls = SurfaceFormFactorsOf(cover, wallOf, 6);
  std::vector<double> tileArea(tiles);
  std::vector<double> wallArea(6, 0.0);
  for (size_t i = 0; i < tiles; ++i)
  {
    tileArea[i] = cover.PatchArea(i);
    wallArea[static_cast<size_t>(wallOf[i])] += tileArea[i];
  }
  std::vector<double> summed(36, 0.0);
  for (size_t a = 0; a < tiles; ++a)
  {
    for (uint64_t k = f.RowOffsets[a]; k < f.RowOffsets[a + 1]; ++k)
    {
      summed[static_cast<size_t>(wallOf[a] * 6 + wallOf[static_cast<size_t>(f.Seen[k])])] +=
        tileArea[a] * f.Values[k];
    }
  }
  const double opposite = HowellParallel(1.0, 1.0, 1.0);
  const double adjacent = HowellPerpendicular(1.0, 1.0, 1.0);
  double worstHowell = 0.0;
  double worstReciprocity = 0.0;
  for (int a = 0; a < 6; ++a)
  {
    for (int b = 0; b < 6; ++b)
    {
      const double fab = walls.At(a, b);
      EXPECT_NEAR(
        summed[static_cast<size_t>(a * 6 + b)] / wallArea[static_cast<size_t>(a)], fab, 1e-12)
        << a << " -> " << b;
      if (a == b)
      {
        EXPECT_EQ(fab, 0.0) << "a flat wall does not see itself";
        continue;
      }
      // furnace_box lists the walls by axis, x_min, x_max, y_min, ...: 2k and 2k + 1 face.
      const double howell = a / 2 == b / 2 ? opposite : adjacent;
      worstHowell = std::max(worstHowell, std::fabs(fab - howell) / howell);
      const double exchange = wallArea[static_cast<size_t>(a)] * fab;
      const double back = wallArea[static_cast<size_t>(b)] * walls.At(b, a);
      worstReciprocity = std::max(worstReciprocity, std::fabs(exchange - back) / exchange);
      EXPECT_NEAR(exchange, back, 0.02 * exchange) << "reciprocity " << a << ", " << b;
    }
  }
  std::printf("[ Figures  ] %zu named surfaces, %zu regions: %zu pairs (%.1f MiB; the dense "
              "matrix %.0f MiB), worst |row - 1| %.1e, walls: reciprocal within %.2f%%, Howell's "
              "within %.2f%%\n",
    tiles,
    cover.EntryCount(),
    f.PairCount(),
    f.MemoryBytes() / 1048576.0,
    sizeof(double) * static_cast<double>(tiles) * tiles / 1048576.0,
    worstRow,
    100.0 * worstReciprocity,
    100.0 * worstHowell);
  // One sample per cell of a 4 x 16 grid at every tile's centre: 5.8 % at the sanitizers' 20 x 20
  // tiles per wall, 2.7 % at 58 x 58.
  EXPECT_LT(worstHowell, Sanitized ? 0.07 : 0.05);
}

/// The Cornell box's form factors between its named surfaces, sparse, are the dense matrix's bit
/// for bit (so the reports of the shipped scenes did not change), and bad sums are refused.
TEST(SolutionFigures, SparseFormFactorsAreTheDenseMatrixsOfTheCornellBox)
{
  CoveredScene setup("cornell_box.scene", 2);
  std::vector<int> groups;
  for (const Patch& patch : setup.Patches)
  {
    groups.push_back(setup.Environment.Surfaces[static_cast<size_t>(patch.SurfaceIndex)].NameIndex);
  }
  const int count = static_cast<int>(setup.Environment.SurfaceNames.size());
  ASSERT_GT(count, 2);
  ExpectTheDenseMatrix(
    SurfaceFormFactorsOf(setup.Cover, groups, count), setup.Cover.FormFactors(groups, count));

  std::vector<std::vector<SphericalCover::GroupSum>> sums =
    setup.Cover.FormFactorSums(groups, count);
  const std::vector<double> areas(groups.size(), 1.0);
  EXPECT_THROW(SumSurfaceFormFactors(sums, groups, count, {}), std::invalid_argument);
  EXPECT_THROW(SumSurfaceFormFactors(sums, groups, 1, areas), std::invalid_argument);
  sums[0].push_back(SphericalCover::GroupSum{ count, 1.0 });
  EXPECT_THROW(SumSurfaceFormFactors(sums, groups, count, areas), std::invalid_argument);
  const SurfaceFormFactors none = SumSurfaceFormFactors({}, {}, 3, {});
  EXPECT_EQ(none.PairCount(), 0u);
  EXPECT_EQ(none.At(2, 1), 0.0);
  EXPECT_THROW(none.At(3, 0), std::out_of_range);
}
