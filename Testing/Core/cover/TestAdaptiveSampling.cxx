// SPDX-License-Identifier: BSD-3-Clause
// The ray fill's adaptive sampling (RBufferFillOptions::AdaptiveSampling, RayCastFill.h): a
// cell whose centre and 8 neighbouring centres show one surface takes its centre's sample for
// all its samples; every other cell is sampled in full. Checked against the full sampling of
// the same rays: the rule itself, the cells away from surface boundaries, the coverage of each
// surface and of the Cornell lamp (Lambert's contour integral), and the rays saved.
#include "CoverTestUtilities.h"
#include "cover/RayCastFill.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
RBufferFillOptions Adaptive(bool on)
{
  RBufferFillOptions options;
  options.AdaptiveSampling = on;
  return options;
}

/// The group (surface; -1 when empty) a sample shows.
int32_t GroupOf(const std::vector<Patch>& patches, const RBuffer& buffer, std::size_t sample)
{
  const int32_t source = buffer.SampleSource(sample);
  return source < 0 ? -1 : patches[static_cast<size_t>(source)].SurfaceIndex;
}

/// The samples of cell (row, column).
std::vector<std::size_t> CellSamples(const HemisphereGrid& grid, int row, int column)
{
  std::vector<std::size_t> samples;
  for (int a = 0; a < grid.SamplesTheta(); ++a)
  {
    for (int b = 0; b < grid.SamplesPhi(); ++b)
    {
      samples.push_back(
        grid.SampleIndex(row * grid.SamplesTheta() + a, column * grid.SamplesPhi() + b));
    }
  }
  return samples;
}

/// The 3 x 3 block of cells around (row, column), phi wrapping, rows clipped.
std::vector<int> Neighbourhood(const HemisphereGrid& grid, int row, int column)
{
  std::vector<int> cells;
  for (int r = std::max(0, row - 1); r <= std::min(grid.ThetaBins() - 1, row + 1); ++r)
  {
    for (int dc = -1; dc <= 1; ++dc)
    {
      cells.push_back(grid.CellIndex(r, (column + dc + grid.PhiBins()) % grid.PhiBins()));
    }
  }
  return cells;
}

double SurfaceProjectedSolidAngle(const std::vector<Patch>& patches,
  const RBuffer& buffer,
  int32_t surface)
{
  const HemisphereGrid& grid = buffer.Grid();
  double sum = 0.0;
  for (int cell = 0; cell < grid.CellCount(); ++cell)
  {
    const int32_t source = buffer.CellSource(cell);
    if (source >= 0 && patches[static_cast<size_t>(source)].SurfaceIndex == surface)
    {
      sum += grid.CellMeasureOfCell(cell);
    }
  }
  return sum;
}
}

TEST(AdaptiveSampling, AgreesWithFullSamplingAwayFromSurfaceBoundaries)
{
  // The Cornell box's flat surfaces, 2 x 2 patches each (patch boundaries inside surfaces).
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 2);
  const HemisphereGrid grid(32, 128, 3, 3);
  const RayCastFiller full(patches, grid, Adaptive(false));
  const RayCastFiller adaptive(patches, grid, Adaptive(true));
  RBuffer a(grid);
  RBuffer b(grid);
  const int centre = grid.SamplesFromCentre()[0];
  long cells = 0;
  long boundaryCells = 0;
  long differing = 0;
  double worstSurface = 0.0;
  for (size_t i = 0; i < patches.size(); i += Sanitized ? 9 : 3)
  {
    full.Fill(i, a, nullptr);
    adaptive.Fill(i, b, nullptr);
    for (int row = 0; row < grid.ThetaBins(); ++row)
    {
      for (int column = 0; column < grid.PhiBins(); ++column)
      {
        const int cell = grid.CellIndex(row, column);
        ++cells;
        // The rule, from the full fill's centre samples (the same rays the adaptive fill casts
        // first): uniform when the 3 x 3 block's centres show one group.
        const std::vector<std::size_t> own = CellSamples(grid, row, column);
        const int32_t ownGroup = GroupOf(patches, a, own[static_cast<size_t>(centre)]);
        bool uniform = true;
        // Near a surface boundary: the full samples of the block show more than one group.
        bool nearBoundary = false;
        for (const int n : Neighbourhood(grid, row, column))
        {
          const std::vector<std::size_t> samples =
            CellSamples(grid, grid.RowOfCell(n), grid.ColumnOfCell(n));
          uniform =
            uniform && GroupOf(patches, a, samples[static_cast<size_t>(centre)]) == ownGroup;
          for (const std::size_t s : samples)
          {
            nearBoundary = nearBoundary || GroupOf(patches, a, s) != ownGroup;
          }
        }
        for (const std::size_t s : own)
        {
          // A cell sampled in full has the full fill's samples; a uniform one its centre's.
          const std::size_t expected = uniform ? own[static_cast<size_t>(centre)] : s;
          ASSERT_EQ(b.SampleSource(s), a.SampleSource(expected)) << "receiver " << i;
          ASSERT_EQ(b.SampleGrazing(s), a.SampleGrazing(expected)) << "receiver " << i;
        }
        boundaryCells += nearBoundary;
        const bool same = a.CellSource(cell) == b.CellSource(cell);
        differing += !same;
        if (!nearBoundary)
        {
          // Away from surface boundaries the cell shows the same surface; where its samples
          // show one patch, the same patch at the same R (its centre's).
          EXPECT_EQ(b.CellSource(cell) < 0
              ? -1
              : patches[static_cast<size_t>(b.CellSource(cell))].SurfaceIndex,
            ownGroup)
            << "receiver " << i << " cell " << cell;
          bool onePatch = true;
          for (const std::size_t s : own)
          {
            onePatch = onePatch && a.SampleSource(s) == a.SampleSource(own[0]);
          }
          if (onePatch)
          {
            EXPECT_TRUE(same) << "receiver " << i << " cell " << cell;
            if (same && a.CellSource(cell) >= 0)
            {
              EXPECT_EQ(a.CellDepth(cell), b.CellDepth(cell)) << "receiver " << i;
            }
          }
        }
      }
    }
    for (size_t s = 0; s < scene.Surfaces.size(); ++s)
    {
      const double x = SurfaceProjectedSolidAngle(patches, a, static_cast<int32_t>(s));
      const double y = SurfaceProjectedSolidAngle(patches, b, static_cast<int32_t>(s));
      worstSurface = std::max(worstSurface, std::fabs(y - x));
    }
  }
  std::printf("[ Adaptive ] %ld cells, %ld near a surface boundary, %ld differ from the full "
              "fill's; worst |change| of a surface's projected solid angle %.2e sr\n",
    cells,
    boundaryCells,
    differing,
    worstSurface);
  // The cells that change are few: patch boundaries inside uniform cells, curved silhouettes.
  EXPECT_LT(differing, cells / 100);
  // A surface's coverage moves by less than a handful of cells' measure (a cell at the
  // horizon is ~5e-5 sr, at the pole ~2e-4 sr).
  EXPECT_LT(worstSurface, 2e-3);
}

TEST(AdaptiveSampling, CastsFewerRays)
{
  // The Cornell box split 3 x 3: every hemisphere casts its 4096 centre rays and the 8 others
  // of the cells at surface boundaries only. Measured: 8,800 rays per hemisphere (23.9 % of
  // the 36,864 samples); the limit leaves a margin. Without adaptive sampling every sample is
  // cast.
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 3);
  const HemisphereGrid grid(32, 128, 3, 3);
  const RayCastFiller full(patches, grid, Adaptive(false));
  const RayCastFiller adaptive(patches, grid, Adaptive(true));
  RBuffer buffer(grid);
  size_t receivers = 0;
  for (size_t i = 0; i < patches.size(); i += Sanitized ? 12 : 4)
  {
    full.Fill(i, buffer, nullptr);
    adaptive.Fill(i, buffer, nullptr);
    ++receivers;
  }
  EXPECT_EQ(full.RaysCast(), receivers * grid.SampleCount());
  const double perHemisphere = static_cast<double>(adaptive.RaysCast()) / receivers;
  std::printf("[ Adaptive ] %.0f rays per hemisphere (%.1f %% of %zu)\n",
    perHemisphere,
    100.0 * perHemisphere / grid.SampleCount(),
    grid.SampleCount());
  EXPECT_GE(perHemisphere, grid.CellCount());
  EXPECT_LT(perHemisphere, 0.27 * grid.SampleCount());
}

TEST(AdaptiveSampling, CornellLampFromTheFloorCorners)
{
  // The lamp seen from the floor's corners is its smallest image over the floor (0.022 sr,
  // about 28 cells): its cells with adaptive sampling against the full sampling, and where no
  // block hides part of it against Lambert's contour integral, from the floor patches at the
  // four corners (the tall block hides the lamp from one of them).
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const int lamp = SurfaceNamed(scene, "light");
  ASSERT_GE(lamp, 0);
  const BezierPatch& lampPatch = scene.Surfaces[static_cast<size_t>(lamp)].Patch;
  const std::vector<glm::dvec3> polygon = CornerPolygon(lampPatch);
  const int split = 15;
  std::vector<Patch> patches;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const int n = static_cast<int>(s) == lamp ? 1 : (s <= 4 ? split : 3);
    AppendSplit(patches, scene.Surfaces[s].Patch, static_cast<int>(s), n, n);
  }
  // The cover's default 32 x 128 grid (the scene's 16 x 64 leaves the lamp's light to the
  // nodes of DirectIrradiance.h).
  const HemisphereGrid grid(32, 128, 3, 3);
  const RayCastFiller full(patches, grid, Adaptive(false));
  const RayCastFiller adaptive(patches, grid, Adaptive(true));
  RBuffer a(grid);
  RBuffer b(grid);
  int compared = 0;
  // Surface 0 is the floor, split first: its corner patches are (0,0), (n-1,0), (0,n-1),
  // (n-1,n-1) in u-fastest order.
  for (const int k : { 0, split - 1, split * (split - 1), split * split - 1 })
  {
    const size_t i = static_cast<size_t>(k);
    ASSERT_EQ(patches[i].SurfaceIndex, 0);
    full.Fill(i, a, nullptr);
    adaptive.Fill(i, b, nullptr);
    const double exact = LambertProjectedSolidAngle(patches[i].Point, patches[i].Normal, polygon);
    const double cellsFull = SurfaceProjectedSolidAngle(patches, a, lamp);
    const double cellsAdaptive = SurfaceProjectedSolidAngle(patches, b, lamp);
    std::printf("[ Adaptive ] floor corner patch %3d: lamp %.4e sr exact, cells %+.4f full, "
                "%+.4f adaptive (relative)\n",
      k,
      exact,
      cellsFull / exact - 1.0,
      cellsAdaptive / exact - 1.0);
    // The lamp's boundary cells are sampled in full, so its cells are the full fill's.
    EXPECT_EQ(cellsAdaptive, cellsFull) << "corner " << k;
    // Unoccluded: rays to 9 x 9 points of the lamp all reach its front side.
    if (SeesWholeLamp(full.Caster(), patches, patches[i].Point, lampPatch, lamp))
    {
      // A cell of 28 is 3.6 %: the boundary cells' rounding, as in the full fill.
      EXPECT_NEAR(cellsAdaptive, exact, 0.05 * exact) << "corner " << k;
      ++compared;
    }
  }
  EXPECT_GE(compared, 3);
}
