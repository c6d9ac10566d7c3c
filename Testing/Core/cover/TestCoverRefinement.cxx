// SPDX-License-Identifier: BSD-3-Clause
// The R-buffer refinement of paper §4.3 Steps 3 and 5 (CoverRefinement.h): reciprocity of the
// Cornell box after subdivision + refinement + cover, tiling of every surface's domain, closed
// scenes (with and without an occluder inside) stay closed, splits are marked RBuffer and are
// fewer than a uniform refinement, determinism whatever the thread count, progress and abort,
// settings checks.
#include "cover/CoverRefinement.h"

#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"
#include "distributed/InProcessRanks.h"
#include "math/Constants.h"
#include "subdivision/IntervalSubdivision.h"

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

/// A coarse configuration for the tests: the interval subdivision to `maxLevel` on a
/// thetaBins x 4 thetaBins grid, the refinement `extraLevels` deeper.
struct Pipeline
{
  SubdivisionSettings Subdivision;
  RefinementSettings Refinement;

  Pipeline(int thetaBins, int maxLevel, int extraLevels)
  {
    this->Subdivision.ThetaBins = thetaBins;
    this->Subdivision.PhiBins = 4 * thetaBins;
    this->Subdivision.MaxLevel = maxLevel;
    this->Refinement.Cover.ThetaBins = thetaBins;
    this->Refinement.Cover.PhiBins = 4 * thetaBins;
    this->Refinement.MaxLevel = maxLevel + extraLevels;
  }
};

std::vector<Patch> Subdivide(const Scene& scene, const SubdivisionSettings& settings)
{
  IntervalSubdivision subdivision(scene, settings);
  EXPECT_TRUE(subdivision.Run(nullptr, ThreadedFor(2)));
  return subdivision.Patches();
}

/// The patches of every surface tile its parameter domain [0,1]^2: their rectangles do not
/// overlap and their areas sum to 1.
void ExpectTiling(const Scene& scene, const std::vector<Patch>& patches)
{
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    std::vector<UVRect> rects;
    for (const Patch& patch : patches)
    {
      if (patch.SurfaceIndex == static_cast<int>(s))
      {
        rects.push_back(patch.Domain);
      }
    }
    double sum = 0.0;
    for (size_t a = 0; a < rects.size(); ++a)
    {
      ASSERT_TRUE(rects[a].IsValid());
      sum += (rects[a].U1 - rects[a].U0) * (rects[a].V1 - rects[a].V0);
      for (size_t b = a + 1; b < rects.size(); ++b)
      {
        const double du = std::min(rects[a].U1, rects[b].U1) - std::max(rects[a].U0, rects[b].U0);
        const double dv = std::min(rects[a].V1, rects[b].V1) - std::max(rects[a].V0, rects[b].V0);
        ASSERT_FALSE(du > 1e-12 && dv > 1e-12) << "surface " << s << ": patches overlap";
      }
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "surface " << s;
  }
}

}

TEST(CoverRefinement, CornellBoxReciprocity)
{
#ifdef SPHCOVER_SANITIZED
  // About 30 s in Release, many minutes under the sanitizers: the Release run covers it, and
  // the other refinement tests exercise the same code under the sanitizers.
  GTEST_SKIP() << "too slow under the sanitizers";
#endif
  // The full Cornell box: after the interval subdivision alone, patches straddling the blocks'
  // footprints and the contact edges are represented by their centres and reciprocity is off
  // by tens of per cent at these coarse settings; Step 3 splits the patches that are partly
  // hidden in others' hemispheres (a floor patch half under a block, seen from the ceiling and
  // the walls) and must at least halve the worst error. The 1% is NOT reached here:
  // the remaining error (light / block sides) is the one-point-per-receiver quadrature of
  // unoccluded pairs, which no visibility criterion addresses (see the report).
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const Pipeline pipeline(Sanitized ? 12 : 16, 3, 2);
  const std::vector<Patch> before = Subdivide(scene, pipeline.Subdivision);
  SphericalCover coverBefore;
  ASSERT_TRUE(coverBefore.Build(before, pipeline.Refinement.Cover, ThreadedFor(2)));
  const Exchange exchangeBefore = MeasureExchange(scene, before, coverBefore);

  CoverRefinement refinement(scene, before, pipeline.Refinement);
  ASSERT_TRUE(refinement.Run(nullptr, ThreadedFor(2)));
  const std::vector<Patch> after = refinement.Patches();
  SphericalCover coverAfter;
  ASSERT_TRUE(coverAfter.Build(after, pipeline.Refinement.Cover, ThreadedFor(2)));
  const Exchange exchangeAfter = MeasureExchange(scene, after, coverAfter);
  const RefinementStatistics& stats = refinement.Statistics();
  std::printf("[ Refine   ] Cornell box: %zu -> %zu patches in %d rounds (%zu hemispheres "
              "analysed, %zu splits); worst reciprocity %.2e (%s) -> %.2e (%s) over %zu pairs\n",
    before.size(),
    after.size(),
    stats.Rounds,
    stats.RowsAnalysed,
    stats.Splits,
    exchangeBefore.WorstReciprocity,
    exchangeBefore.WorstPair.c_str(),
    exchangeAfter.WorstReciprocity,
    exchangeAfter.WorstPair.c_str(),
    exchangeAfter.Pairs);

  EXPECT_GT(exchangeBefore.WorstReciprocity, 0.02) << "the refinement has something to fix";
  EXPECT_LT(exchangeAfter.WorstReciprocity, 0.5 * exchangeBefore.WorstReciprocity)
    << exchangeAfter.WorstPair;
  EXPECT_GE(exchangeAfter.Pairs, 40u);
  ExpectTiling(scene, after);

  // Splits are Step 3's, and fewer than refining every patch uniformly to the deepest level
  // the refinement reached.
  EXPECT_EQ(stats.InputPatches, before.size());
  EXPECT_EQ(stats.OutputPatches, after.size());
  EXPECT_EQ(after.size(), before.size() + 2 * stats.Splits);
  int deepest = 0;
  size_t marked = 0;
  for (const Patch& patch : after)
  {
    deepest = std::max(deepest, patch.Level);
    marked += patch.Reason == SplitReason::RBuffer ? 1 : 0;
    EXPECT_LE(patch.Level, pipeline.Refinement.MaxLevel);
  }
  EXPECT_GT(stats.Splits, 0u);
  // Each split adds three RBuffer pieces and removes one leaf (perhaps an RBuffer piece).
  EXPECT_GE(marked, 2 * stats.Splits + 1);
  size_t uniform = 0;
  for (const Patch& patch : before)
  {
    uniform += static_cast<size_t>(std::pow(3.0, deepest - patch.Level));
  }
  EXPECT_LT(after.size(), uniform / 2);
}

TEST(CoverRefinement, CornellBoxReciprocityAtTheFormFactorSettings)
{
#ifdef SPHCOVER_SANITIZED
  GTEST_SKIP() << "too slow under the sanitizers (the Release run covers it)";
#endif
  // The full Cornell box (blocks, light) through the pipeline at the settings the README gives
  // for form factors (32 x 128, max_level 5; the scene's own 16 x 64 at level 4 are for
  // pictures, whose direct light and first bounce come from the nodes) with the cover filter's
  // default refinement (enclosure boundaries and horizons with their margin, 3
  // levels deeper). Pairs of surfaces that exchange appreciably, min(F_ab, F_ba) >= 0.01:
  // A_a F_ab = A_b F_ba within 1% (the figure), and the largest error is printed.
  // Without the horizon splits two pairs stay above it, red_wall / tall_block_top (1.4%: the
  // red wall's row of patches across the plane of the block's top has its centres 5 mm above
  // it) and floor / back_wall (1.0%); without any refinement the worst pair is floor /
  // short_block_front at 9.5% (BenchmarkCoverRefinement prints every pair, --horizons 0|1).
  // A pair below 0.01 sees the other through a few dozen cells of 32 x 128 or fewer (a cell is
  // 2.4e-4 of a hemisphere's projected solid angle), where the rounding of the boundary cells
  // is an absolute error, not a relative one: for those pairs the error of the exchange
  // relative to the area of the side with the smaller F (the side that sees the other through
  // few cells), |A_a F_ab - A_b F_ba| / A_s, an error in that side's F averaged over its
  // surface, stays below 1e-3 (about four cells' worth), unless the relative error is within 1%
  // anyway. The walls and the small light are such a pair: F 0.0073 one way, 0.166 the other,
  // 1.05% apart; a direct quadrature of the kernel (light 24 x 24, red wall 160 x 160 points,
  // the blocks as occluders) gives F_light,red_wall = 0.16635 (the cover: 0.16637) and
  // F_red_wall,light = 0.00740, so the 1% is the wall's side, which sees the light through
  // about 30 cells.
  Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  scene.Settings.ThetaBins = 32;
  scene.Settings.PhiBins = 128;
  const SceneSettingsPipeline run(scene, 5, 3, false);
  const size_t count = scene.Surfaces.size();
  std::vector<int> groups;
  std::vector<double> area(count, 0.0);
  for (const Patch& patch : run.After)
  {
    groups.push_back(patch.SurfaceIndex);
    area[static_cast<size_t>(patch.SurfaceIndex)] += patch.Area;
  }
  const std::vector<double> f = run.Cover.FormFactors(groups, static_cast<int>(count));
  double worstRelative = 0.0;
  double worstAbsolute = 0.0;
  size_t significant = 0;
  size_t abovePercent = 0;
  for (size_t a = 0; a < count; ++a)
  {
    for (size_t b = a + 1; b < count; ++b)
    {
      const double ab = area[a] * f[a * count + b];
      const double ba = area[b] * f[b * count + a];
      const std::string pair =
        scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[a].NameIndex)] + " / " +
        scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[b].NameIndex)];
      if (std::min(f[a * count + b], f[b * count + a]) >= 0.01)
      {
        ++significant;
        const double relative = std::fabs(ab - ba) / std::max(ab, ba);
        worstRelative = std::max(worstRelative, relative);
        EXPECT_LT(relative, 0.01) << pair << ": F " << f[a * count + b] << " / "
                                  << f[b * count + a];
        abovePercent += relative > 0.01 ? 1 : 0;
      }
      else if (std::max(ab, ba) > 0.0)
      {
        const double relative = std::fabs(ab - ba) / std::max(ab, ba);
        const double smallSide = f[a * count + b] < f[b * count + a] ? area[a] : area[b];
        const double absolute = std::fabs(ab - ba) / smallSide;
        worstAbsolute = std::max(worstAbsolute, absolute);
        EXPECT_TRUE(relative < 0.01 || absolute < 1e-3)
          << pair << ": F " << f[a * count + b] << " / " << f[b * count + a] << ", error "
          << relative << " relative, " << absolute << " absolute";
      }
    }
  }
  std::printf("[ Refine   ] Cornell box at its settings: %zu -> %zu patches (%zu enclosure "
              "splits, %zu probe rays, %zu horizon splits); %zu pairs with F >= 0.01: worst "
              "reciprocity %.2e, %zu above "
              "1%%; others: worst |A_a F_ab - A_b F_ba| / A(smaller F) %.2e\n",
    run.Before.size(),
    run.After.size(),
    run.Statistics.EnclosureSplits,
    run.Statistics.Probes,
    run.Statistics.HorizonSplits,
    significant,
    worstRelative,
    abovePercent,
    worstAbsolute);
  EXPECT_GE(significant, 30u);
  EXPECT_GT(run.Statistics.EnclosureSplits, 0u);
  EXPECT_GT(run.Statistics.HorizonSplits, 0u);
  EXPECT_EQ(run.Statistics.Rounds, 0);
  ExpectTiling(scene, run.After);
}

TEST(CoverRefinement, ClosedScenesThroughThePipelineSumToOne)
{
  // The closed furnace box and sphere through the pipeline (their grids, the subdivision to
  // MaxLevel 2 to keep the test short, the default refinement): every row of surface form
  // factors sums to 1 within 0.5%; the refinement finds no enclosure boundary to split.
  for (const char* name : { "furnace_box.scene", "furnace_sphere.scene" })
  {
    const Scene scene = LoadSceneFile(ScenePath(name));
    const SceneSettingsPipeline run(scene, 2, 3, false);
    const Exchange exchange = MeasureExchange(scene, run.After, run.Cover);
    std::printf("[ Refine   ] %s through the pipeline: %zu patches, worst |row - 1| %.1e\n",
      name,
      run.After.size(),
      exchange.WorstRowError);
    EXPECT_LT(exchange.WorstRowError, 5e-3) << name;
    EXPECT_EQ(run.Statistics.EnclosureSplits, 0u) << name;
  }
}

TEST(CoverRefinement, ClosedScenesStayClosed)
{
  // Splitting changes no geometry: in a closed scene every hemisphere of the refined cover is
  // still covered completely (projected solid angle pi) and every row sums to 1. The empty
  // furnace box has nothing hidden, so nothing is split; with a cube inside, the walls behind
  // the cube are partly hidden and get split.
  const Pipeline pipeline(Sanitized ? 8 : 12, 1, 2);
  for (const bool occluder : { false, true })
  {
    const Scene scene =
      occluder ? FurnaceBoxWithOccluder() : LoadSceneFile(ScenePath("furnace_box.scene"));
    const std::vector<Patch> before = Subdivide(scene, pipeline.Subdivision);
    CoverRefinement refinement(scene, before, pipeline.Refinement);
    ASSERT_TRUE(refinement.Run(nullptr, ThreadedFor(2)));
    const std::vector<Patch> after = refinement.Patches();
    SphericalCover cover;
    ASSERT_TRUE(cover.Build(after, pipeline.Refinement.Cover, ThreadedFor(2)));
    double worstCovered = 0.0;
    for (size_t i = 0; i < after.size(); ++i)
    {
      worstCovered = std::max(worstCovered, std::fabs(cover.CoveredProjectedSolidAngle(i) - Pi));
    }
    const Exchange exchange = MeasureExchange(scene, after, cover);
    std::printf("[ Refine   ] furnace box%s: %zu -> %zu patches, largest |covered - pi| %.1e, "
                "|row - 1| %.1e, worst reciprocity %.2e\n",
      occluder ? " with a cube inside" : "",
      before.size(),
      after.size(),
      worstCovered,
      exchange.WorstRowError,
      exchange.WorstReciprocity);
    EXPECT_LT(worstCovered, 1e-12);
    EXPECT_LT(exchange.WorstRowError, 5e-3);
    ExpectTiling(scene, after);
    if (occluder)
    {
      EXPECT_GT(refinement.Statistics().Splits, 0u);
    }
    else
    {
      EXPECT_EQ(refinement.Statistics().Splits, 0u) << "nothing is hidden in an empty box";
    }
  }
}

namespace
{
/// The same patch list, rectangle for rectangle (exactly).
void ExpectSamePatches(const std::vector<Patch>& a, const std::vector<Patch>& b)
{
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
  {
    ASSERT_EQ(a[k].SurfaceIndex, b[k].SurfaceIndex) << "patch " << k;
    ASSERT_EQ(a[k].Domain.U0, b[k].Domain.U0) << "patch " << k;
    ASSERT_EQ(a[k].Domain.U1, b[k].Domain.U1) << "patch " << k;
    ASSERT_EQ(a[k].Domain.V0, b[k].Domain.V0) << "patch " << k;
    ASSERT_EQ(a[k].Domain.V1, b[k].Domain.V1) << "patch " << k;
    ASSERT_EQ(a[k].Level, b[k].Level) << "patch " << k;
  }
}
}

TEST(CoverRefinement, DeterministicWhateverTheThreads)
{
  const Scene scene = FurnaceBoxWithOccluder();
  const Pipeline pipeline(8, 1, 2);
  const std::vector<Patch> before = Subdivide(scene, pipeline.Subdivision);
  CoverRefinement sequential(scene, before, pipeline.Refinement);
  CoverRefinement threaded(scene, before, pipeline.Refinement);
  ASSERT_TRUE(sequential.Run(nullptr, SequentialFor));
  ASSERT_TRUE(threaded.Run(nullptr, ThreadedFor(3)));
  ASSERT_GT(sequential.Patches().size(), before.size());
  ExpectSamePatches(threaded.Patches(), sequential.Patches());
  EXPECT_EQ(sequential.Statistics().RowsAnalysed, threaded.Statistics().RowsAnalysed);
  EXPECT_EQ(sequential.Statistics().LimitedRequests, threaded.Statistics().LimitedRequests);
}

/// The refinement of `before` on 2 and 3 ranks (threads, InProcessRanks) gives every rank
/// `serial`'s patches and statistics.
void ExpectSharedRefinementEqualsSerial(const Scene& scene,
  const std::vector<Patch>& before,
  const RefinementSettings& settings,
  const CoverRefinement& serial)
{
  const std::vector<Patch> expected = serial.Patches();
  const RefinementStatistics& want = serial.Statistics();
  for (const int ranks : { 2, 3 })
  {
    InProcessRanks world(ranks);
    std::vector<std::vector<Patch>> results(static_cast<std::size_t>(ranks));
    std::vector<RefinementStatistics> statistics(static_cast<std::size_t>(ranks));
    world.Run(
      [&](const RankShare& share, int rank)
      {
        CoverRefinement refinement(scene, before, settings);
        refinement.SetRankShare(share);
        if (refinement.Run(nullptr, SequentialFor))
        {
          results[static_cast<std::size_t>(rank)] = refinement.Patches();
          statistics[static_cast<std::size_t>(rank)] = refinement.Statistics();
        }
      });
    for (int rank = 0; rank < ranks; ++rank)
    {
      SCOPED_TRACE(testing::Message() << "rank " << rank << " of " << ranks);
      ExpectSamePatches(results[static_cast<std::size_t>(rank)], expected);
      const RefinementStatistics& s = statistics[static_cast<std::size_t>(rank)];
      EXPECT_EQ(s.Rounds, want.Rounds);
      EXPECT_EQ(s.RowsAnalysed, want.RowsAnalysed);
      EXPECT_EQ(s.Splits, want.Splits);
      EXPECT_EQ(s.EnclosureSplits, want.EnclosureSplits);
      EXPECT_EQ(s.Probes, want.Probes);
      EXPECT_EQ(s.HorizonSplits, want.HorizonSplits);
      EXPECT_EQ(s.LimitedRequests, want.LimitedRequests);
    }
  }
}

// Step 1 alone (enclosure boundaries: the Cornell box's blocks stand on the floor) shared
// among ranks: each round's leaves probed in turn give the serial patches, splits and probe
// rays, and the pieces still tile their surfaces.
TEST(CoverRefinement, EnclosureSplitsSharedAmongRanksEqualSerial)
{
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  Pipeline pipeline(8, 2, 2);
  pipeline.Refinement.SplitHorizons = false;
  pipeline.Refinement.AnalyseHemispheres = false;
  const std::vector<Patch> before = Subdivide(scene, pipeline.Subdivision);
  CoverRefinement serial(scene, before, pipeline.Refinement);
  ASSERT_TRUE(serial.Run(nullptr, ThreadedFor(2)));
  ASSERT_GT(serial.Statistics().EnclosureSplits, 0u);
  ExpectTiling(scene, serial.Patches());
  ExpectSharedRefinementEqualsSerial(scene, before, pipeline.Refinement, serial);
}

// Under MPI the ranks test each round's leaves (Step 2) and analyse each round's hemispheres
// (Step 3) in turn and join their verdicts (RankShare.h): every rank refines to the serial
// patches, with the serial statistics.
TEST(CoverRefinement, SharedAmongRanksEqualsSerial)
{
  const Scene scene = FurnaceBoxWithOccluder();
  const Pipeline pipeline(8, 1, 2);
  ASSERT_TRUE(pipeline.Refinement.AnalyseHemispheres);
  const std::vector<Patch> before = Subdivide(scene, pipeline.Subdivision);
  CoverRefinement serial(scene, before, pipeline.Refinement);
  ASSERT_TRUE(serial.Run(nullptr, ThreadedFor(2)));
  ASSERT_GT(serial.Statistics().Rounds, 1);
  // Step 2's leaves are shared too: the scene has horizons to split across.
  ASSERT_GT(serial.Statistics().HorizonSplits, 0u);
  ExpectSharedRefinementEqualsSerial(scene, before, pipeline.Refinement, serial);
}

TEST(CoverRefinement, ProgressAndAbort)
{
  const Scene scene = FurnaceBoxWithOccluder();
  const Pipeline pipeline(8, 1, 2);
  const std::vector<Patch> before = Subdivide(scene, pipeline.Subdivision);

  std::vector<double> reported;
  CoverRefinement complete(scene, before, pipeline.Refinement);
  ASSERT_TRUE(complete.Run(
    [&](double fraction)
    {
      reported.push_back(fraction);
      return true;
    }));
  ASSERT_FALSE(reported.empty());
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
  EXPECT_EQ(reported.back(), 1.0);
  EXPECT_GE(reported.front(), 0.0);

  // Abort after the enclosure probes (one progress call per 64 patches) in the first round of
  // the hemisphere analysis: the patches are those after the probes, still a tiling.
  CoverRefinement aborted(scene, before, pipeline.Refinement);
  int calls = 0;
  EXPECT_FALSE(
    aborted.Run([&](double) { return ++calls < 2 + static_cast<int>(before.size() / 64); }));
  ExpectTiling(scene, aborted.Patches());
  EXPECT_LE(aborted.Patches().size(), complete.Patches().size());
}

TEST(CoverRefinement, HorizonSplitsFollowAPlaneAcrossAWall)
{
  // A unit wall (x = 0, facing +x) standing on a unit floor (y = 0), each 9 x 9 patches, and a
  // shelf (y = 0.5, x in [0.1, 0.4], z in [0.3, 0.7], facing up) in front of the wall: the
  // wall sees the shelf's top only above y = 0.5, so the shelf's plane is a horizon across the
  // wall. The receiver-side horizon test alone (no enclosure probes, no hemispheres) splits
  // wall patches, and only those within the margin of that plane; the floor meets the wall
  // along an edge, which is no horizon: without the shelf nothing is split. A curved shelf (a
  // vault over the same footprint) splits nothing either: the tangent plane at a curved
  // surface's patch is not where its horizon lies (it moves over the surface), and that rule
  // made the teapot's close curved surfaces split each other (33111 points in the teapot room
  // instead of 13461).
  const Scene furnace = LoadSceneFile(ScenePath("furnace_box.scene"));
  enum Shelf
  {
    None,
    Flat,
    Curved
  };
  for (const Shelf shelf : { None, Flat, Curved })
  {
    Scene scene = furnace;
    scene.Surfaces.clear();
    scene.Surfaces.emplace_back(Parallelogram({ 0, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }), 0, 0);
    scene.Surfaces.emplace_back(Parallelogram({ 0, 0, 0 }, { 0, 0, 1 }, { 1, 0, 0 }), 0, 0);
    if (shelf == Flat)
    {
      scene.Surfaces.emplace_back(
        Parallelogram({ 0.1, 0.5, 0.3 }, { 0, 0, 0.4 }, { 0.3, 0, 0 }), 0, 0);
    }
    if (shelf == Curved)
    {
      // Degree 1 along z (u), 2 along x (v), rising to y = 0.575 in the middle; front +y.
      scene.Surfaces.emplace_back(BezierPatch(1,
                                    2,
                                    { { 0.1, 0.5, 0.3 },
                                      { 0.1, 0.5, 0.7 },
                                      { 0.25, 0.65, 0.3 },
                                      { 0.25, 0.65, 0.7 },
                                      { 0.4, 0.5, 0.3 },
                                      { 0.4, 0.5, 0.7 } }),
        0,
        0);
    }
    const std::vector<Patch> before = SplitScene(scene, 9);
    RefinementSettings settings;
    settings.MaxLevel = 2;
    settings.SplitEnclosureBoundaries = false;
    settings.AnalyseHemispheres = false;
    CoverRefinement refinement(scene, before, settings);
    ASSERT_TRUE(refinement.Run(nullptr, ThreadedFor(2)));
    const std::vector<Patch> after = refinement.Patches();
    ExpectTiling(scene, after);
    const RefinementStatistics& stats = refinement.Statistics();
    EXPECT_EQ(stats.HorizonSplits, stats.Splits);
    if (shelf == None)
    {
      EXPECT_EQ(stats.HorizonSplits, 0u) << "a contact line is no horizon";
      continue;
    }
    if (shelf == Curved)
    {
      EXPECT_EQ(stats.HorizonSplits, 0u) << "a curved surface is no horizon source";
      continue;
    }
    EXPECT_GT(stats.HorizonSplits, 0u);
    bool straddlingSplit = false;
    for (const Patch& patch : after)
    {
      if (patch.Level == 0)
      {
        continue;
      }
      // Only the wall is cut by another surface's plane, within a patch width (1/9) of a
      // level-0 patch around it.
      EXPECT_EQ(patch.SurfaceIndex, 0);
      EXPECT_LT(std::fabs(patch.Point.y - 0.5), 2.0 / 9.0) << patch.Point.y;
      straddlingSplit = straddlingSplit ||
        (std::fabs(patch.Point.y - 0.5) < 1.0 / 9.0 && std::fabs(patch.Point.z - 0.5) < 0.1);
    }
    EXPECT_TRUE(straddlingSplit) << "the wall across the shelf's plane, behind the shelf";
  }
}

TEST(CoverRefinement, RejectsUnusableSettings)
{
  const Scene scene = LoadSceneFile(ScenePath("furnace_box.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 1);
  RefinementSettings settings;
  EXPECT_TRUE(settings.Problem().empty());
  settings.HiddenFraction = 1.0;
  EXPECT_THROW(CoverRefinement(scene, patches, settings), std::invalid_argument);
  settings = RefinementSettings();
  settings.MaxLevel = -1;
  EXPECT_THROW(CoverRefinement(scene, patches, settings), std::invalid_argument);
  settings = RefinementSettings();
  settings.ProbesPerSide = 1;
  EXPECT_THROW(CoverRefinement(scene, patches, settings), std::invalid_argument);
  settings = RefinementSettings();
  settings.HorizonReach = 0.0;
  EXPECT_THROW(CoverRefinement(scene, patches, settings), std::invalid_argument);
  settings = RefinementSettings();
  settings.Cover.ThetaBins = 0;
  EXPECT_THROW(CoverRefinement(scene, patches, settings), std::invalid_argument);
  CoverRefinement refinement(scene, patches, RefinementSettings());
  EXPECT_THROW(refinement.SetProbeExtents({ UVRect::Unit() }, {}), std::invalid_argument);
  std::vector<Patch> foreign = patches;
  foreign[0].SurfaceIndex = static_cast<int>(scene.Surfaces.size());
  EXPECT_THROW(CoverRefinement(scene, foreign, RefinementSettings()), std::invalid_argument);
}
