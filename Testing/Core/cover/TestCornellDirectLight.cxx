// SPDX-License-Identifier: BSD-3-Clause
// Direct light in the Cornell box: the projected solid angle through which the spherical cover
// lets a point see the lamp agrees with Lambert's contour integral (the point-to-polygon form
// factor times pi) wherever rays show the lamp unoccluded. This located the ~2 % dark bias of
// the walls against the Cycles reference (issue 6): the sample rays were unbiased (+-0.15 %),
// the cells the plurality vote made of them were not (back wall -2.15 %, floor -1.3 %, green
// wall -1.2 %); RBuffer::Classify's error diffusion along the rows (RBufferFillOptions::
// DiffuseRounding) brings them within 0.6 %. Both are printed; the diffused one is asserted.
#include "CoverTestUtilities.h"
#include "cover/RayCastFill.h"
#include "cover/SphericalCover.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

TEST(CornellDirectLight, LampProjectedSolidAngle)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const int lamp = SurfaceNamed(scene, "light");
  ASSERT_GE(lamp, 0);
  const BezierPatch& lampPatch = scene.Surfaces[static_cast<size_t>(lamp)].Patch;
  const std::vector<glm::dvec3> polygon = CornerPolygon(lampPatch);

  for (const bool diffuse : { false, true })
  {
    // 15 x 15 patches per wall in every build: coarser ones (tried under the sanitizers: 9)
    // leave the diffused vote -1.4% on a wall, above the limit below.
    const int split = 15;
    {
      std::vector<Patch> patches;
      for (size_t s = 0; s < scene.Surfaces.size(); ++s)
      {
        const int n = static_cast<int>(s) == lamp ? 1 : (s <= 4 ? split : 3);
        AppendSplit(patches, scene.Surfaces[s].Patch, static_cast<int>(s), n, n);
      }
      // The cover's default 32 x 128 grid (the scene's own 16 x 64 leaves the lamp's light to
      // the nodes, DirectIrradiance.h, and is not what this measures).
      SphericalCoverOptions options;
      options.FillOptions.DiffuseRounding = diffuse;
      SphericalCover cover;
      ASSERT_TRUE(cover.Build(patches, options, ThreadedFor(2)));
      const HemisphereGrid& grid = cover.Grid();
      const std::unique_ptr<RBufferFiller> filler =
        RBufferFiller::Create(RBufferFill::RayCasting, patches, grid);
      RBuffer buffer(grid);
      const RayCaster rays(RayCastPatches(patches), RayCasterOptions());
      size_t lampPatches = 0;
      for (const Patch& p : patches)
      {
        lampPatches += p.SurfaceIndex == lamp ? 1 : 0;
      }
      std::vector<double> coverSum(scene.Surfaces.size(), 0.0);
      std::vector<double> exactSum(scene.Surfaces.size(), 0.0);
      std::vector<double> sampleSum(scene.Surfaces.size(), 0.0);
      std::vector<size_t> used(scene.Surfaces.size(), 0);
      for (size_t i = 0; i < patches.size(); ++i)
      {
        const Patch& p = patches[i];
        if (p.SurfaceIndex == lamp)
        {
          continue;
        }
        bool above = true;
        for (const glm::dvec3& corner : polygon)
        {
          above = above && glm::dot(corner - p.Point, p.Normal) > 1e-9;
        }
        if (!above)
        {
          continue;
        }
        if (!SeesWholeLamp(rays, patches, p.Point, lampPatch, lamp))
        {
          continue;
        }
        double omega = 0.0;
        for (size_t e = cover.EntryBegin(i); e < cover.EntryEnd(i); ++e)
        {
          if (patches[cover.EntryAt(e).Source].SurfaceIndex == lamp)
          {
            omega += cover.ProjectedSolidAngle(e);
          }
        }
        buffer.Reset(i);
        filler->Fill(i, buffer, nullptr);
        double sampleOmega = 0.0;
        for (int r = 0; r < grid.SampleRows(); ++r)
        {
          for (int c = 0; c < grid.SampleColumns(); ++c)
          {
            const int32_t src = buffer.SampleSource(grid.SampleIndex(r, c));
            if (src >= 0 && patches[static_cast<size_t>(src)].SurfaceIndex == lamp)
            {
              sampleOmega += grid.CellMeasure(r / grid.SamplesTheta()) / grid.SamplesPerCell();
            }
          }
        }
        const double exact = LambertProjectedSolidAngle(p.Point, p.Normal, polygon);
        const size_t s = static_cast<size_t>(p.SurfaceIndex);
        coverSum[s] += p.Area * omega;
        sampleSum[s] += p.Area * sampleOmega;
        exactSum[s] += p.Area * exact;
        ++used[s];
      }
      std::printf("split %d, %s: %zu patches, %zu lamp patches\n",
        split,
        diffuse ? "error diffusion" : "plain plurality vote",
        patches.size(),
        lampPatches);
      double allCover = 0.0;
      double allExact = 0.0;
      for (size_t s = 0; s < scene.Surfaces.size(); ++s)
      {
        if (used[s] == 0)
        {
          continue;
        }
        allCover += coverSum[s];
        allExact += exactSum[s];
        std::printf("  %-18s %5zu points: cover/exact - 1 = %+.4f, samples/exact - 1 = %+.4f\n",
          scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[s].NameIndex)].c_str(),
          used[s],
          coverSum[s] / exactSum[s] - 1.0,
          sampleSum[s] / exactSum[s] - 1.0);
      }
      std::printf("  all: %+.4f\n", allCover / allExact - 1.0);
      // Per surface with enough points (the walls and the floor): the samples are unbiased
      // estimates of the coverage and the cells keep what the samples say.
      for (size_t s = 0; s < scene.Surfaces.size(); ++s)
      {
        if (diffuse && used[s] >= 20)
        {
          EXPECT_LT(std::fabs(sampleSum[s] / exactSum[s] - 1.0), 0.003) << "samples, surface " << s;
          EXPECT_LT(std::fabs(coverSum[s] / exactSum[s] - 1.0), 0.008) << "cells, surface " << s;
        }
      }
      if (diffuse)
      {
        EXPECT_LT(std::fabs(allCover / allExact - 1.0), 0.005);
      }
      EXPECT_GE(used[2] + used[3] + used[4], 100u);
    }
  }
}

// Regions of the lamp measured on the lamp (SphericalCoverOptions::MeasuredSurfaces): wherever
// rays show the whole lamp, the lamp's regions of a point add up to Lambert's projected solid
// angle (the midpoint rule's error only), where the cells' vote is ~10 % off per point; every
// row keeps its covered measure.
TEST(CornellDirectLight, MeasuredLampRegions)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const int lamp = SurfaceNamed(scene, "light");
  ASSERT_GE(lamp, 0);
  const BezierPatch& lampPatch = scene.Surfaces[static_cast<size_t>(lamp)].Patch;
  const std::vector<glm::dvec3> polygon = CornerPolygon(lampPatch);
  std::vector<Patch> patches;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    // The lamp in 3 x 3 pieces: a point's lamp regions are several entries.
    const int n = static_cast<int>(s) == lamp ? 3 : (s <= 4 ? 9 : 3);
    AppendSplit(patches, scene.Surfaces[s].Patch, static_cast<int>(s), n, n);
  }
  // The cover's default 32 x 128 grid, as above.
  SphericalCoverOptions options;
  options.Fill = RBufferFill::RayCasting;
  SphericalCover cells;
  ASSERT_TRUE(cells.Build(patches, options, ThreadedFor(2)));
  options.MeasuredSurfaces.assign(scene.Surfaces.size(), false);
  options.MeasuredSurfaces[static_cast<size_t>(lamp)] = true;
  SphericalCover measured;
  ASSERT_TRUE(measured.Build(patches, options, ThreadedFor(2)));
  ASSERT_EQ(measured.EntryCount(), cells.EntryCount());

  const RayCaster rays(RayCastPatches(patches), RayCasterOptions());
  double cellError = 0.0;
  double measuredError = 0.0;
  double worst = 0.0;
  size_t used = 0;
  for (size_t i = 0; i < patches.size(); ++i)
  {
    const Patch& p = patches[i];
    double rowCells = 0.0;
    double rowMeasured = 0.0;
    for (size_t e = cells.EntryBegin(i); e < cells.EntryEnd(i); ++e)
    {
      rowCells += cells.ProjectedSolidAngle(e);
      rowMeasured += measured.ProjectedSolidAngle(e);
    }
    EXPECT_NEAR(rowMeasured, rowCells, 1e-5 * std::max(rowCells, 1.0)) << "row " << i;
    if (p.SurfaceIndex == lamp)
    {
      continue;
    }
    bool visible = true;
    for (const glm::dvec3& corner : polygon)
    {
      visible = visible && glm::dot(corner - p.Point, p.Normal) > 1e-9;
    }
    if (!visible || !SeesWholeLamp(rays, patches, p.Point, lampPatch, lamp))
    {
      continue;
    }
    double omegaCells = 0.0;
    double omegaMeasured = 0.0;
    for (size_t e = cells.EntryBegin(i); e < cells.EntryEnd(i); ++e)
    {
      if (patches[cells.EntryAt(e).Source].SurfaceIndex == lamp)
      {
        omegaCells += cells.ProjectedSolidAngle(e);
        omegaMeasured += measured.ProjectedSolidAngle(e);
      }
    }
    const double exact = LambertProjectedSolidAngle(p.Point, p.Normal, polygon);
    cellError += std::pow(omegaCells / exact - 1.0, 2);
    measuredError += std::pow(omegaMeasured / exact - 1.0, 2);
    worst = std::max(worst, std::fabs(omegaMeasured / exact - 1.0));
    ++used;
  }
  ASSERT_GE(used, 100u);
  cellError = std::sqrt(cellError / used);
  measuredError = std::sqrt(measuredError / used);
  std::printf("%zu points that see the whole lamp: rms of lamp measure / Lambert - 1: cells %.4f, "
              "measured %.5f (worst %.5f)\n",
    used,
    cellError,
    measuredError,
    worst);
  EXPECT_LT(measuredError, 2e-3);
  EXPECT_LT(worst, 5e-2); // near the lamp's plane, where cos(theta_i) varies most over it
  EXPECT_GT(cellError, 5.0 * measuredError);
}
