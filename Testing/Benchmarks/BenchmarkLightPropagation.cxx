// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkLightPropagation.cxx
 * @brief Progressive light propagation (paper §5.1, §5.2) with all reflectance kinds
 * (Documentation/Verification.md#quality-bars: speed is measured by a benchmark, never by timed
 * tests).
 *
 *   BenchmarkLightPropagation [--threads N] [--tolerance T] [--refine K] [--max-shots N]
 *                             [--no-costs] [--scene name.scene]...
 *
 * --refine K first refines the patches as the cover filter does by default (receiver side,
 * enclosure boundaries, CoverRefinement; K = 3 is the filter's RefinementLevels default) and
 * propagates over the cover of the refined patches: the patch set of `sphcover solve`.
 * --max-shots stops each propagation early (for profiles); --no-costs skips parts 2 and 3.
 * --cache DIR keeps each scene's cover, materials and frames in DIR/<scene>.refine<K>.cover
 * and reads them from there on later runs (repeated measurements skip subdivision and cover;
 * delete the file when the scene or the cover code changes).
 * --compare propagates each scene a second time with every directional shot summed by strip
 * pairs (DirectionalMethod::StripPairs, the method before the whole-hemisphere grid) and prints
 * the largest differences of the incident radiance and the brightness.
 *
 * 1. For each scene (default: the Cornell box and the teapot room, whose mirror wall and phong
 *    teapot shoot through weight tables) at the scene's settings: interval subdivision, cover,
 *    then propagation to ConvergenceTolerance T (default 1e-5, the filter's default). Prints
 *    patches, cover entries, the set-up of the weight tables (seconds), shots to convergence,
 *    propagation seconds, entry updates per second (the column walks of §5.2), and for the
 *    non-diffuse shots the strip pairs summed over the weight tables.
 * 2. Per-shot cost against the column size for diffuse shooters (§5.2: "eta ... becomes
 *    O(N)", here O(column)): every patch of the Cornell box shoots 50 times; the shots are
 *    binned by column size and a least-squares line through (column size, seconds) gives the
 *    cost per update.
 * 3. Per-shot cost against D, the cells of the hemisphere, for a general BRDF (§5.2:
 *    "The cost of propagation, eta is O(ND)"): the furnace box split 4 x 4 per face with phong
 *    walls, grids 8 x 32 to 64 x 256; per grid the mean column size, and over the first 300
 *    shots the strip pairs per shot and microseconds per shot summing by strip pairs, and the
 *    microseconds per shot by the whole-hemisphere grid (DirectionalMethod).
 */
#include "cover/CoverRefinement.h"
#include "cover/SphericalCover.h"
#include "math/ParallelFor.h"
#include "propagation/ExchangeBalance.h"
#include "propagation/LightPropagation.h"
#include "scene/SceneLoader.h"
#include "subdivision/IntervalSubdivision.h"

#include "CoverTestUtilities.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <string>
#include <vector>

using namespace sphcover;

namespace
{
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<Patch> Subdivide(const Scene& scene, const ParallelFor& parallelFor)
{
  SubdivisionSettings settings;
  settings.MaxLevel = scene.Settings.MaxLevel;
  settings.ThetaBins = scene.Settings.ThetaBins;
  settings.PhiBins = scene.Settings.PhiBins;
  for (double& tolerance : settings.Tolerance)
  {
    tolerance = scene.Settings.Tolerance;
  }
  IntervalSubdivision subdivision(scene, settings);
  subdivision.Run(nullptr, parallelFor);
  return subdivision.Patches();
}

/// The receiver-side refinement of the cover filter's default (REFINEMENT_ENCLOSURES):
/// enclosure boundaries split up to `levels` below the deepest patch.
std::vector<Patch> Refine(const Scene& scene,
  std::vector<Patch> patches,
  const SphericalCoverOptions& options,
  int levels,
  const ParallelFor& parallelFor)
{
  int deepest = 0;
  for (const Patch& patch : patches)
  {
    deepest = std::max(deepest, patch.Level);
  }
  RefinementSettings settings;
  settings.Cover = options;
  settings.MaxLevel = deepest + levels;
  settings.AnalyseHemispheres = false;
  CoverRefinement refinement(scene, std::move(patches), settings);
  refinement.Run(nullptr, parallelFor);
  return refinement.Patches();
}

/// The shots by kind: uniform (diffuse or emission only, O(column)), directional by strip pairs
/// and by the grid, with their wall-clock cost.
void PrintShotKinds(const std::vector<ShotRecord>& history)
{
  std::size_t pairs = 0;
  std::size_t fallbacks = 0;
  std::size_t meanFallbacks = 0;
  std::size_t shots[3] = {};
  double seconds[3] = {};
  std::size_t uniformUpdates = 0;
  std::size_t directionalUpdates = 0;
  double previous = 0.0;
  for (const ShotRecord& record : history)
  {
    const int kind = record.GridShot ? 2 : (record.WeightEvaluations > 0 ? 1 : 0);
    ++shots[kind];
    seconds[kind] += record.Seconds - previous;
    previous = record.Seconds;
    pairs += record.WeightEvaluations;
    fallbacks += record.Fallbacks;
    meanFallbacks += record.MeanFallbacks;
    (kind == 0 ? uniformUpdates : directionalUpdates) += record.ReceiverUpdates;
  }
  const auto per = [](double value, std::size_t count)
  { return count > 0 ? value / static_cast<double>(count) : 0.0; };
  std::printf("  %zu uniform shots (diffuse, or emission only): %.1f us/shot, mean column %.0f\n",
    shots[0],
    1e6 * per(seconds[0], shots[0]),
    per(static_cast<double>(uniformUpdates), shots[0]));
  std::printf("  %zu directional shots (mean column %.0f): %zu by strip pairs, %.1f us/shot, "
              "%.0f pairs/shot, %.1f ns/pair; %zu by the grid, %.1f us/shot; %zu updates "
              "without h_ji (%zu by the mean)\n",
    shots[1] + shots[2],
    per(static_cast<double>(directionalUpdates), shots[1] + shots[2]),
    shots[1],
    1e6 * per(seconds[1], shots[1]),
    per(static_cast<double>(pairs), shots[1]),
    1e9 * per(seconds[1], pairs),
    shots[2],
    1e6 * per(seconds[2], shots[2]),
    fallbacks,
    meanFallbacks);
}

/// What the propagation needs of the patches: the cover, each patch's material and frame.
struct Prepared
{
  SphericalCover Cover;
  std::vector<Material> Materials;
  std::vector<HemisphereFrame> Frames;
  double CoverSeconds = 0.0;
};

template<typename T>
void WriteVector(std::FILE* file, const std::vector<T>& values)
{
  const uint64_t size = values.size();
  std::fwrite(&size, sizeof(size), 1, file);
  std::fwrite(values.data(), sizeof(T), values.size(), file);
}

template<typename T>
bool ReadVector(std::FILE* file, std::vector<T>& values)
{
  uint64_t size = 0;
  if (std::fread(&size, sizeof(size), 1, file) != 1 || size > (uint64_t(1) << 34))
  {
    return false;
  }
  values.resize(size);
  return std::fread(values.data(), sizeof(T), values.size(), file) == values.size();
}

/// The cover, surfaces and frames of a previous run (--cache), or false. A cache is only a
/// time saver for repeated measurements: it is keyed by the scene's name and the refinement.
bool ReadCache(const std::string& path, const Scene& scene, Prepared& prepared)
{
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
  {
    return false;
  }
  SphericalCover::Arrays arrays;
  int header[5] = {};
  std::vector<int> surfaces;
  bool ok = std::fread(header, sizeof(header), 1, file) == 1 &&
    ReadVector(file, arrays.RowOffsets) && ReadVector(file, arrays.Entries) &&
    ReadVector(file, arrays.Unoccluded) && ReadVector(file, arrays.Strips) &&
    ReadVector(file, arrays.StripDepths) && ReadVector(file, arrays.Areas) &&
    ReadVector(file, surfaces) && ReadVector(file, prepared.Frames);
  std::fclose(file);
  arrays.ThetaBins = header[0];
  arrays.PhiBins = header[1];
  arrays.SamplesTheta = header[2];
  arrays.SamplesPhi = header[3];
  arrays.Fill = header[4];
  arrays.UnoccludedKnown = !arrays.Unoccluded.empty();
  ok = ok && prepared.Cover.ImportArrays(std::move(arrays)).empty() &&
    surfaces.size() == prepared.Cover.PatchCount();
  for (std::size_t i = 0; ok && i < surfaces.size(); ++i)
  {
    const Surface& surface = scene.Surfaces.at(static_cast<std::size_t>(surfaces[i]));
    prepared.Materials.push_back(
      scene.Materials.at(static_cast<std::size_t>(surface.MaterialIndex)));
  }
  return ok;
}

void WriteCache(const std::string& path,
  const Prepared& prepared,
  const std::vector<Patch>& patches)
{
  std::FILE* file = std::fopen((path + ".part").c_str(), "wb");
  if (!file)
  {
    return;
  }
  const SphericalCover::Arrays arrays = prepared.Cover.ExportArrays();
  const int header[5] = {
    arrays.ThetaBins, arrays.PhiBins, arrays.SamplesTheta, arrays.SamplesPhi, arrays.Fill
  };
  std::fwrite(header, sizeof(header), 1, file);
  WriteVector(file, arrays.RowOffsets);
  WriteVector(file, arrays.Entries);
  WriteVector(file, arrays.UnoccludedKnown ? arrays.Unoccluded : std::vector<float>());
  WriteVector(file, arrays.Strips);
  WriteVector(file, arrays.StripDepths);
  WriteVector(file, arrays.Areas);
  std::vector<int> surfaces;
  for (const Patch& patch : patches)
  {
    surfaces.push_back(patch.SurfaceIndex);
  }
  WriteVector(file, surfaces);
  WriteVector(file, prepared.Frames);
  const bool ok = std::fclose(file) == 0;
  if (ok)
  {
    std::rename((path + ".part").c_str(), path.c_str());
  }
}

void Prepare(const Scene& scene,
  int refineLevels,
  const std::string& cache,
  const ParallelFor& parallelFor,
  Prepared& prepared)
{
  if (!cache.empty() && ReadCache(cache, scene, prepared))
  {
    std::printf("  (cover, materials and frames read from %s)\n", cache.c_str());
    return;
  }
  prepared = Prepared();
  SphericalCoverOptions options;
  options.ThetaBins = scene.Settings.ThetaBins;
  options.PhiBins = scene.Settings.PhiBins;
  std::vector<Patch> patches = Subdivide(scene, parallelFor);
  if (refineLevels > 0)
  {
    patches = Refine(scene, std::move(patches), options, refineLevels, parallelFor);
  }
  const Clock::time_point start = Clock::now();
  prepared.Cover.Build(patches, options, parallelFor);
  prepared.CoverSeconds = Seconds(start);
  prepared.Materials = LightPropagation::MaterialsOfPatches(scene, patches);
  for (const Patch& patch : patches)
  {
    prepared.Frames.push_back(HemisphereFrame::OfPatch(patch));
  }
  if (!cache.empty())
  {
    WriteCache(cache, prepared, patches);
  }
}

void Converge(const std::string& name,
  double tolerance,
  int refineLevels,
  std::size_t maximumShots,
  const std::string& cacheDirectory,
  bool compare,
  bool balance,
  const ParallelFor& parallelFor)
{
  const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/") + name);
  Prepared prepared;
  Prepare(scene,
    refineLevels,
    cacheDirectory.empty()
      ? std::string()
      : cacheDirectory + "/" + name + ".refine" + std::to_string(refineLevels) + ".cover",
    parallelFor,
    prepared);
  const SphericalCover& cover = prepared.Cover;
  const double coverSeconds = prepared.CoverSeconds;

  Clock::time_point start = Clock::now();
  LightPropagation propagation(cover, prepared.Materials);
  propagation.SetFrames(prepared.Frames);
  const double setUpSeconds = Seconds(start);
  ExchangeBalance exchangeBalance;
  if (balance)
  {
    start = Clock::now();
    exchangeBalance = ExchangeBalance(cover);
    propagation.SetExchangeFactors(exchangeBalance.EntryFactors());
    std::printf("  exchange balance: %s after %zu iterations, %.3f s; column residual %.2e "
                "(cover as built %.2e)\n",
      exchangeBalance.Converged()   ? "converged"
        : exchangeBalance.Stalled() ? "stalled"
                                    : "NOT converged",
      exchangeBalance.Iterations(),
      Seconds(start),
      exchangeBalance.ColumnResidual(),
      exchangeBalance.InitialColumnResidual());
  }
  std::size_t nonDiffuse = 0;
  for (std::size_t i = 0; i < cover.PatchCount(); ++i)
  {
    nonDiffuse += propagation.IsLambertian(i) ? 0 : 1;
  }
  std::printf("%s: %zu patches (%zu non-diffuse, refinement %d levels), %zu entries, grid %d x "
              "%d; cover %.2f s; weight tables %.3f s\n",
    name.c_str(),
    cover.PatchCount(),
    nonDiffuse,
    refineLevels,
    cover.EntryCount(),
    cover.Grid().ThetaBins(),
    cover.Grid().PhiBins(),
    coverSeconds,
    setUpSeconds);
  PropagationSettings settings;
  settings.ConvergenceTolerance = tolerance;
  settings.MaximumShots = maximumShots;
  int reported = 0;
  // Processor time of all threads as well as wall-clock time: on a loaded machine the wall
  // clock also counts the time the process waited for a core.
  const std::clock_t cpuStart = std::clock();
  const bool converged = propagation.Run(settings,
    [&](double fraction)
    {
      // Progress on long runs: every tenth of the unshot energy gone.
      if (fraction * 10 >= reported + 1)
      {
        reported = static_cast<int>(fraction * 10);
        std::printf("  ... %d%% of the unshot energy shot, %zu shots, %.1f s\n",
          10 * reported,
          propagation.History().size(),
          propagation.History().back().Seconds);
      }
      return true;
    });
  const double cpuSeconds = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  const std::vector<ShotRecord>& history = propagation.History();
  const double seconds = history.empty() ? 0.0 : history.back().Seconds;
  std::size_t updates = 0;
  for (const ShotRecord& record : history)
  {
    updates += record.ReceiverUpdates;
  }
  const EnergyBalance energy = propagation.Energy();
  std::printf("  %s after %zu shots (tolerance %g): %.3f s wall, %.3f s processor; %.3g entry "
              "updates/s, %.1f us/shot; energy imbalance %.2e\n",
    converged ? "converged" : "NOT converged",
    history.size(),
    tolerance,
    seconds,
    cpuSeconds,
    seconds > 0 ? static_cast<double>(updates) / seconds : 0.0,
    history.empty() ? 0.0 : 1e6 * seconds / static_cast<double>(history.size()),
    energy.RelativeImbalance);
  PrintShotKinds(history);

  if (compare)
  {
    // The same propagation with every directional shot summed by strip pairs (the method
    // before the grid): the two must agree up to rounding, shot for shot.
    LightPropagation reference(cover, prepared.Materials);
    reference.SetFrames(prepared.Frames);
    reference.SetExchangeFactors(exchangeBalance.EntryFactors());
    reference.SetDirectionalMethod(DirectionalMethod::StripPairs);
    reference.Run(settings);
    double largestIncident = 0.0;
    double incidentDifference = 0.0;
    for (std::size_t e = 0; e < cover.EntryCount(); ++e)
    {
      for (int b = 0; b < 3; ++b)
      {
        largestIncident = std::max(largestIncident, reference.IncidentRadiance(e)[b]);
        incidentDifference = std::max(incidentDifference,
          std::fabs(reference.IncidentRadiance(e)[b] - propagation.IncidentRadiance(e)[b]));
      }
    }
    double brightnessDifference = 0.0;
    for (std::size_t i = 0; i < cover.PatchCount(); ++i)
    {
      const glm::dvec3 a = reference.Brightness(i);
      const glm::dvec3 b = propagation.Brightness(i);
      for (int k = 0; k < 3; ++k)
      {
        if (a[k] > 0.0)
        {
          brightnessDifference = std::max(brightnessDifference, std::fabs(b[k] / a[k] - 1.0));
        }
      }
    }
    std::printf("  strip pairs only: %zu shots, %.3f s wall; largest difference: incident "
                "radiance %.1e of the largest, brightness %.1e relative\n",
      reference.History().size(),
      reference.History().empty() ? 0.0 : reference.History().back().Seconds,
      largestIncident > 0.0 ? incidentDifference / largestIncident : 0.0,
      brightnessDifference);
    PrintShotKinds(reference.History());
  }
}

void CostAgainstColumn(const ParallelFor& parallelFor)
{
  const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene"));
  const std::vector<Patch> patches = Subdivide(scene, parallelFor);
  SphericalCoverOptions options;
  options.ThetaBins = scene.Settings.ThetaBins;
  options.PhiBins = scene.Settings.PhiBins;
  SphericalCover cover;
  cover.Build(patches, options, parallelFor);
  LightPropagation propagation(cover, LightPropagation::MaterialsOfPatches(scene, patches));
  const int repeats = 50;
  std::map<std::size_t, std::pair<double, int>> bins; // column size / 50 -> seconds, shots
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t j = 0; j < patches.size(); ++j)
  {
    const Clock::time_point start = Clock::now();
    std::size_t column = 0;
    for (int r = 0; r < repeats; ++r)
    {
      column = propagation.Shoot(j);
    }
    const double perShot = Seconds(start) / repeats;
    auto& bin = bins[column / 50];
    bin.first += perShot;
    bin.second += 1;
    sx += static_cast<double>(column);
    sy += perShot;
    sxx += static_cast<double>(column) * static_cast<double>(column);
    sxy += static_cast<double>(column) * perShot;
    ++n;
  }
  std::printf("diffuse shot cost vs column size (Cornell box, %zu patches, %d shots each):\n",
    patches.size(),
    repeats);
  std::printf("  %-16s %8s %14s\n", "column size", "patches", "us per shot");
  for (const auto& [bin, value] : bins)
  {
    std::printf("  [%5zu, %5zu)   %8d %14.3f\n",
      bin * 50,
      bin * 50 + 50,
      value.second,
      1e6 * value.first / value.second);
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  std::printf(
    "  least squares: %.2f ns per update + %.2f us per shot\n", 1e9 * slope, 1e6 * intercept);
}

void CostAgainstCells(const ParallelFor& parallelFor)
{
  const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/furnace_box.scene"));
  const std::vector<Patch> patches = sphcover_test::SplitScene(scene, 4);
  Material phong;
  phong.Type = MaterialType::Phong;
  phong.Diffuse = glm::dvec3(0.2, 0.3, 0.0);
  phong.Specular = glm::dvec3(0.1, 0.3, 0.8);
  phong.PhongExponent = 20.0;
  phong.Emission = glm::dvec3(1.0);
  const std::vector<Material> materials(patches.size(), phong);
  std::printf("general-BRDF shot cost vs D (furnace box, %zu phong patches, first 300 shots; "
              "strip pairs and grid, DirectionalMethod):\n",
    patches.size());
  std::printf("  %6s %8s %12s %10s %16s %14s %14s %14s\n",
    "grid",
    "D",
    "table s",
    "column",
    "pairs per shot",
    "us per shot",
    "ns per pair",
    "grid us/shot");
  for (int theta : { 8, 16, 32, 64 })
  {
    SphericalCoverOptions options;
    options.ThetaBins = theta;
    options.PhiBins = 4 * theta;
    SphericalCover cover;
    cover.Build(patches, options, parallelFor);
    double tableSeconds = 0.0;
    double perShot[2] = {};
    std::size_t pairs = 0;
    std::size_t updates = 0;
    double shots = 0.0;
    for (int method = 0; method < 2; ++method)
    {
      Clock::time_point start = Clock::now();
      LightPropagation propagation(cover, materials);
      tableSeconds = Seconds(start);
      propagation.SetDirectionalMethod(
        method == 0 ? DirectionalMethod::StripPairs : DirectionalMethod::Grid);
      PropagationSettings settings;
      settings.MaximumShots = 300;
      settings.ConvergenceTolerance = 0.0;
      propagation.Run(settings);
      const std::vector<ShotRecord>& history = propagation.History();
      shots = static_cast<double>(history.size());
      perShot[method] = history.back().Seconds / shots;
      if (method == 0)
      {
        for (const ShotRecord& record : history)
        {
          pairs += record.WeightEvaluations;
          updates += record.ReceiverUpdates;
        }
      }
    }
    std::printf("  %3dx%-4d %8d %12.3f %10.1f %16.0f %14.2f %14.2f %14.2f\n",
      theta,
      4 * theta,
      theta * 4 * theta,
      tableSeconds,
      static_cast<double>(updates) / shots,
      static_cast<double>(pairs) / shots,
      1e6 * perShot[0],
      pairs > 0 ? 1e9 * perShot[0] * shots / static_cast<double>(pairs) : 0.0,
      1e6 * perShot[1]);
  }
}
}

int main(int argc, char* argv[])
{
  // One line at a time, so a long run shows its progress when redirected.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  int threads = 0;
  double tolerance = 1e-5;
  int refineLevels = 0;
  std::size_t maximumShots = 0;
  bool costs = true;
  std::string cacheDirectory;
  bool compare = false;
  bool balance = true;
  std::vector<std::string> scenes;
  for (int k = 1; k < argc; ++k)
  {
    if (!std::strcmp(argv[k], "--threads") && k + 1 < argc)
    {
      threads = std::atoi(argv[++k]);
    }
    else if (!std::strcmp(argv[k], "--tolerance") && k + 1 < argc)
    {
      tolerance = std::atof(argv[++k]);
    }
    else if (!std::strcmp(argv[k], "--scene") && k + 1 < argc)
    {
      scenes.emplace_back(argv[++k]);
    }
    else if (!std::strcmp(argv[k], "--refine") && k + 1 < argc)
    {
      refineLevels = std::atoi(argv[++k]);
    }
    else if (!std::strcmp(argv[k], "--max-shots") && k + 1 < argc)
    {
      maximumShots = static_cast<std::size_t>(std::atoll(argv[++k]));
    }
    else if (!std::strcmp(argv[k], "--cache") && k + 1 < argc)
    {
      cacheDirectory = argv[++k];
    }
    else if (!std::strcmp(argv[k], "--compare"))
    {
      compare = true;
    }
    else if (!std::strcmp(argv[k], "--balance") && k + 1 < argc)
    {
      balance = std::atoi(argv[++k]) != 0;
    }
    else if (!std::strcmp(argv[k], "--no-costs"))
    {
      costs = false;
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--threads N] [--tolerance T] [--refine K] [--max-shots N] [--no-costs] "
        "[--cache DIR] [--compare] [--balance 0|1] [--scene name.scene]...\n",
        argv[0]);
      return 2;
    }
  }
  if (scenes.empty())
  {
    scenes = { "cornell_box.scene", "teapot_room.scene" };
  }
  const ParallelFor parallelFor = threads == 1 ? ParallelFor(SequentialFor) : ThreadedFor(threads);
  for (const std::string& scene : scenes)
  {
    Converge(
      scene, tolerance, refineLevels, maximumShots, cacheDirectory, compare, balance, parallelFor);
  }
  if (costs)
  {
    CostAgainstColumn(parallelFor);
    CostAgainstCells(parallelFor);
  }
  return 0;
}
