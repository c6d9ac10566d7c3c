// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkCoverRefinement.cxx
 * @brief The R-buffer refinement of paper §4.3 Steps 3 and 5 (CoverRefinement.h) on the Cornell
 * box and the teapot room at the scenes' settings: interval subdivision, cover, refinement,
 * cover over the refined patches (Documentation/Verification.md#quality-bars: speed is measured by
 * a benchmark, never by timed tests).
 *
 *   BenchmarkCoverRefinement [--threads N] [--extra-levels K] [--enclosures 0|1]
 *                            [--horizons 0|1] [--hemispheres 0|1] [--scene name.scene]...
 *
 * --enclosures, --horizons and --hemispheres switch the receiver-side enclosure probes, the
 * receiver-side horizon splits and the Step 3 hemisphere analysis (RefinementSettings) on or
 * off; all are on by default. --margin sets
 * RefinementSettings::EnclosureMargin and --horizon-reach RefinementSettings::HorizonReach;
 * --skip-before skips the cover before refinement.
 *
 * The refinement may go K levels (default 2) deeper than the scene's MaxLevel: at the scenes'
 * settings the interval subdivision already takes every patch to MaxLevel, so with the same
 * limit Step 3 could split nothing.
 *
 * Prints per scene: patches before/after refinement, rounds, hemispheres analysed by the
 * refinement, splits, seconds of each stage, and the worst surface-pair reciprocity error
 * |A_a F_ab - A_b F_ba| / max(A_a F_ab, A_b F_ba) before and after (over pairs whose exchange
 * min(A_a F_ab, A_b F_ba) exceeds 0.1% of the smaller area), with the pair, and the worst
 * |row sum - 1| of the surfaces' form factors.
 */
#include "cover/CoverRefinement.h"
#include "math/ParallelFor.h"
#include "scene/SceneLoader.h"
#include "subdivision/IntervalSubdivision.h"

#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace sphcover;

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Run(const std::string& name,
  int extraLevels,
  bool enclosures,
  bool horizons,
  double reach,
  bool hemispheres,
  double margin,
  bool skipBefore,
  bool patchesOnly,
  const ParallelFor& parallelFor)
{
  const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/") + name);
  SubdivisionSettings subdivisionSettings;
  subdivisionSettings.MaxLevel = scene.Settings.MaxLevel;
  subdivisionSettings.ThetaBins = scene.Settings.ThetaBins;
  subdivisionSettings.PhiBins = scene.Settings.PhiBins;
  for (double& tolerance : subdivisionSettings.Tolerance)
  {
    tolerance = scene.Settings.Tolerance;
  }
  SphericalCoverOptions coverOptions;
  coverOptions.ThetaBins = scene.Settings.ThetaBins;
  coverOptions.PhiBins = scene.Settings.PhiBins;

  auto start = std::chrono::steady_clock::now();
  IntervalSubdivision subdivision(scene, subdivisionSettings);
  subdivision.Run(nullptr, parallelFor);
  const std::vector<Patch> before = subdivision.Patches();
  const double subdivisionSeconds = Seconds(start);

  start = std::chrono::steady_clock::now();
  SphericalCover coverBefore;
  if (!skipBefore)
  {
    coverBefore.Build(before, coverOptions, parallelFor);
  }
  const double coverBeforeSeconds = Seconds(start);
  const sphcover_test::Exchange reciprocityBefore = skipBefore
    ? sphcover_test::Exchange()
    : sphcover_test::MeasureExchange(scene, before, coverBefore);

  RefinementSettings refinementSettings;
  refinementSettings.Cover = coverOptions;
  refinementSettings.MaxLevel = scene.Settings.MaxLevel + extraLevels;
  refinementSettings.SplitEnclosureBoundaries = enclosures;
  refinementSettings.SplitHorizons = horizons;
  refinementSettings.HorizonReach = reach;
  refinementSettings.AnalyseHemispheres = hemispheres;
  refinementSettings.EnclosureMargin = margin;
  start = std::chrono::steady_clock::now();
  CoverRefinement refinement(scene, before, refinementSettings);
  refinement.Run(nullptr, parallelFor);
  const std::vector<Patch> after = refinement.Patches();
  const double refinementSeconds = Seconds(start);

  const RefinementStatistics& s = refinement.Statistics();
  std::printf("%s (grid %dx%d, MaxLevel %d, refinement MaxLevel %d, enclosure probes %s, "
              "horizons %s, hemisphere analysis %s)\n",
    name.c_str(),
    coverOptions.ThetaBins,
    coverOptions.PhiBins,
    scene.Settings.MaxLevel,
    refinementSettings.MaxLevel,
    enclosures ? "on" : "off",
    horizons ? "on" : "off",
    hemispheres ? "on" : "off");
  std::printf("  subdivision          %8zu patches  %8.2f s\n", before.size(), subdivisionSeconds);
  std::printf("  cover before         %8zu rows     %8.2f s  worst reciprocity %.2e (%s), "
              "worst |row - 1| %.2e\n",
    before.size(),
    coverBeforeSeconds,
    reciprocityBefore.WorstReciprocity,
    reciprocityBefore.WorstPair.c_str(),
    reciprocityBefore.WorstRowError);
  std::printf(
    "  refinement           %8zu patches  %8.2f s  rounds %d, hemispheres analysed %zu, "
    "splits %zu (%zu across enclosure boundaries by %zu probe rays, %zu across horizons, %zu "
    "for disconnection only), refused by limits %zu\n",
    after.size(),
    refinementSeconds,
    s.Rounds,
    s.RowsAnalysed,
    s.Splits,
    s.EnclosureSplits,
    s.Probes,
    s.HorizonSplits,
    s.DisconnectedSplits,
    s.LimitedRequests);
  if (patchesOnly)
  {
    return;
  }

  start = std::chrono::steady_clock::now();
  SphericalCover coverAfter;
  coverAfter.Build(after, coverOptions, parallelFor);
  const double coverAfterSeconds = Seconds(start);
  const sphcover_test::Exchange reciprocityAfter =
    sphcover_test::MeasureExchange(scene, after, coverAfter);
  std::printf("  cover after          %8zu rows     %8.2f s  worst reciprocity %.2e (%s), "
              "worst |row - 1| %.2e\n",
    after.size(),
    coverAfterSeconds,
    reciprocityAfter.WorstReciprocity,
    reciprocityAfter.WorstPair.c_str(),
    reciprocityAfter.WorstRowError);
  // Every pair with min(F_ab, F_ba) >= 0.01 and every other pair above 1%, with its exchange
  // relative to the smaller area.
  {
    const size_t count = scene.Surfaces.size();
    std::vector<int> groups;
    std::vector<double> area(count, 0.0);
    for (const Patch& patch : after)
    {
      groups.push_back(patch.SurfaceIndex);
      area[static_cast<size_t>(patch.SurfaceIndex)] += patch.Area;
    }
    const std::vector<double> f = coverAfter.FormFactors(groups, static_cast<int>(count));
    for (size_t a = 0; a < count; ++a)
    {
      for (size_t b = a + 1; b < count; ++b)
      {
        const double ab = area[a] * f[a * count + b];
        const double ba = area[b] * f[b * count + a];
        const bool significant = std::min(f[a * count + b], f[b * count + a]) >= 0.01;
        if (std::max(ab, ba) > 0.0 && (significant || std::fabs(ab - ba) > 0.01 * std::max(ab, ba)))
        {
          std::printf("    %s: %s / %s  F %.4g / %.4g  error %.2e  exchange / min "
                      "area %.2e\n",
            significant ? "pair F >= 0.01" : "pair above 1% ",
            scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[a].NameIndex)].c_str(),
            scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[b].NameIndex)].c_str(),
            f[a * count + b],
            f[b * count + a],
            std::fabs(ab - ba) / std::max(ab, ba),
            std::min(ab, ba) / std::min(area[a], area[b]));
        }
      }
    }
  }
  std::printf("  hemispheres computed after subdivision: %zu (refinement) + %zu (final cover)\n",
    s.RowsAnalysed,
    after.size());
}
}

int main(int argc, char* argv[])
{
  int threads = 2;
  int extraLevels = 2;
  bool enclosures = true;
  bool horizons = true;
  double reach = RefinementSettings().HorizonReach;
  double margin = RefinementSettings().EnclosureMargin;
  bool skipBefore = false;
  bool patchesOnly = false;
  bool hemispheres = true;
  std::vector<std::string> scenes;
  for (int k = 1; k < argc; ++k)
  {
    if (std::strcmp(argv[k], "--threads") == 0 && k + 1 < argc)
    {
      threads = std::max(1, std::atoi(argv[++k]));
    }
    else if (std::strcmp(argv[k], "--extra-levels") == 0 && k + 1 < argc)
    {
      extraLevels = std::max(0, std::atoi(argv[++k]));
    }
    else if (std::strcmp(argv[k], "--enclosures") == 0 && k + 1 < argc)
    {
      enclosures = std::atoi(argv[++k]) != 0;
    }
    else if (std::strcmp(argv[k], "--horizons") == 0 && k + 1 < argc)
    {
      horizons = std::atoi(argv[++k]) != 0;
    }
    else if (std::strcmp(argv[k], "--horizon-reach") == 0 && k + 1 < argc)
    {
      reach = std::atof(argv[++k]);
    }
    else if (std::strcmp(argv[k], "--margin") == 0 && k + 1 < argc)
    {
      margin = std::atof(argv[++k]);
    }
    else if (std::strcmp(argv[k], "--skip-before") == 0)
    {
      skipBefore = true;
    }
    else if (std::strcmp(argv[k], "--patches-only") == 0)
    {
      patchesOnly = true;
    }
    else if (std::strcmp(argv[k], "--hemispheres") == 0 && k + 1 < argc)
    {
      hemispheres = std::atoi(argv[++k]) != 0;
    }
    else if (std::strcmp(argv[k], "--scene") == 0 && k + 1 < argc)
    {
      scenes.emplace_back(argv[++k]);
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--threads N] [--extra-levels K] [--enclosures 0|1] [--horizons 0|1] "
        "[--horizon-reach R] [--hemispheres 0|1] [--margin W] [--skip-before] [--patches-only] "
        "[--scene "
        "name.scene]...\n",
        argv[0]);
      return 2;
    }
  }
  if (scenes.empty())
  {
    scenes = { "cornell_box.scene", "teapot_room.scene" };
  }
  // Unbuffered: a long run shows each stage as it ends.
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  const ParallelFor parallelFor = threads == 1 ? ParallelFor(SequentialFor) : ThreadedFor(threads);
  std::printf("threads %d\n", threads);
  for (const std::string& scene : scenes)
  {
    Run(scene,
      extraLevels,
      enclosures,
      horizons,
      reach,
      hemispheres,
      margin,
      skipBefore,
      patchesOnly,
      parallelFor);
  }
  return 0;
}
