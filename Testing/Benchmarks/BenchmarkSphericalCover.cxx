// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkSphericalCover.cxx
 * @brief Speed and memory of the spherical cover (paper §3.3, §4.3 Steps 2-4) on the Cornell
 * box split uniformly at several resolutions, with both R-buffer fills
 * (Documentation/Verification.md#quality-bars: speed and memory are measured by a benchmark
 * program, never by timed tests).
 *
 *   BenchmarkSphericalCover [--threads N] [--splits 1,2,3,4,6] [--scene path.scene]
 *   BenchmarkSphericalCover --pipeline [--scene path.scene]... [--variants
 * projection,rays,adaptive]
 *
 * Prints, per resolution and fill: patches N, rows, entries (non-null h_ij), strips, bytes
 * (and the estimate made before building), seconds, cells per second, the candidate culling
 * counts, and how the time grows with N (exponent of N between consecutive resolutions).
 *
 * --pipeline (the figures of the closing note of issue 4): per scene (default the Cornell box
 * and the teapot room) the patches of the real pipeline at the scene's settings (interval
 * subdivision, then the receiver-side refinement that vtkSphericalCoverFilter applies by
 * default, 3 levels deeper); Embree's raw ray throughput on this machine with 1 and 2 threads
 * (rtcIntersect1 along every sample direction of every hemisphere, no filter predicate, no
 * classification); then for each variant (projection fill; ray fill casting every sample; ray
 * fill with AdaptiveSampling, rays one by one and as packets) and 1 and 2 threads: N, strips, bytes
 * (and bytes per strip), seconds, and for the ray fills the rays actually cast per hemisphere
 * (mean), the seconds raw Embree takes for that many rays at its measured rate, and the cover's
 * seconds over those, so the cover's cost reads as a ratio to that limit in the same run.
 */
#include "cover/CoverRefinement.h"
#include "cover/HemisphereGrid.h"
#include "cover/RayCastFill.h"
#include "cover/SphericalCover.h"
#include "geometry/BezierPatch.h"
#include "math/ParallelFor.h"
#include "scene/SceneLoader.h"
#include "subdivision/IntervalSubdivision.h"
#include "subdivision/Patch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace sphcover;

namespace
{
std::vector<Patch> SplitScene(const Scene& scene, int split)
{
  std::vector<Patch> patches;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    for (int b = 0; b < split; ++b)
    {
      for (int a = 0; a < split; ++a)
      {
        const UVRect rect{ static_cast<double>(a) / split,
          a + 1 == split ? 1.0 : static_cast<double>(a + 1) / split,
          static_cast<double>(b) / split,
          b + 1 == split ? 1.0 : static_cast<double>(b + 1) / split };
        patches.emplace_back(static_cast<int>(s), rect, 0, scene.Surfaces[s].Patch.SubPatch(rect));
      }
    }
  }
  return patches;
}

ParallelFor ThreadPoolFor(int threads)
{
  if (threads <= 1)
  {
    return SequentialFor;
  }
  return [threads](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    std::atomic<std::size_t> next{ 0 };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
    {
      pool.emplace_back(
        [&]()
        {
          for (;;)
          {
            const std::size_t begin = next.fetch_add(1);
            if (begin >= count)
            {
              return;
            }
            body(begin, begin + 1);
          }
        });
    }
    for (std::thread& thread : pool)
    {
      thread.join();
    }
  };
}
}

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The patches of sphcover solve at the scene's settings (subdivision, default refinement).
std::vector<Patch> PipelinePatches(const Scene& scene)
{
  SubdivisionSettings subdivision;
  subdivision.MaxLevel = scene.Settings.MaxLevel;
  subdivision.ThetaBins = scene.Settings.ThetaBins;
  subdivision.PhiBins = scene.Settings.PhiBins;
  for (double& tolerance : subdivision.Tolerance)
  {
    tolerance = scene.Settings.Tolerance;
  }
  IntervalSubdivision subdivide(scene, subdivision);
  subdivide.Run(nullptr, ThreadPoolFor(2));
  RefinementSettings refinement;
  refinement.Cover.ThetaBins = scene.Settings.ThetaBins;
  refinement.Cover.PhiBins = scene.Settings.PhiBins;
  refinement.MaxLevel = scene.Settings.MaxLevel + 3;
  refinement.AnalyseHemispheres = false;
  CoverRefinement refine(scene, subdivide.Patches(), refinement);
  refine.Run(nullptr, ThreadPoolFor(2));
  return refine.Patches();
}

/// The rays a ray fill casts over all of `patches`' hemispheres (thread-independent) and the
/// seconds of the fill alone (no strips extracted), on `threads` threads.
std::uint64_t CountFillRays(const std::vector<Patch>& patches,
  const HemisphereGrid& grid,
  const RBufferFillOptions& fillOptions,
  int threads,
  double& seconds)
{
  const RayCastFiller filler(patches, grid, fillOptions);
  const auto start = std::chrono::steady_clock::now();
  ThreadPoolFor(threads)(patches.size(),
    [&](std::size_t begin, std::size_t end)
    {
      RBuffer buffer(grid);
      for (std::size_t i = begin; i < end; ++i)
      {
        filler.Fill(i, buffer, nullptr);
      }
    });
  seconds = SecondsSince(start);
  return filler.RaysCast();
}

/// One variant of the cover for RunPipeline.
struct PipelineVariant
{
  RBufferFill Fill;
  bool Adaptive;
  bool Packets = true;
};

void RunPipeline(const std::string& scenePath, const std::vector<PipelineVariant>& variants)
{
  const Scene scene = LoadSceneFile(scenePath);
  const std::vector<Patch> patches = PipelinePatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = scene.Settings.ThetaBins;
  options.PhiBins = scene.Settings.PhiBins;
  const HemisphereGrid grid(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  std::printf("scene %s: N = %zu characteristic points, grid %d x %d, %d x %d samples per "
              "cell, %zu sample directions per hemisphere\n",
    scenePath.c_str(),
    patches.size(),
    options.ThetaBins,
    options.PhiBins,
    options.SamplesTheta,
    options.SamplesPhi,
    grid.SampleCount());

  // Embree's limit: every sample direction of every hemisphere, first hit only, rtcIntersect1;
  // its rate converts the rays a fill casts into the seconds raw Embree takes for as many.
  const RayCaster rays(RayCastPatches(patches), RayCastOptions(options.FillOptions));
  double rawRate[3] = { 0.0, 0.0, 0.0 };
  for (const int threads : { 1, 2 })
  {
    std::atomic<unsigned long long> hits{ 0 };
    const auto start = std::chrono::steady_clock::now();
    ThreadPoolFor(threads)(patches.size(),
      [&](std::size_t begin, std::size_t end)
      {
        unsigned long long found = 0;
        for (std::size_t i = begin; i < end; ++i)
        {
          const HemisphereFrame frame = HemisphereFrame::OfPatch(patches[i]);
          const double near = 1e-3 * patches[i].Geometry.Size();
          for (int row = 0; row < grid.SampleRows(); ++row)
          {
            for (int column = 0; column < grid.SampleColumns(); ++column)
            {
              std::size_t patch;
              double distance;
              bool front;
              found += rays.FirstHit(frame.Origin,
                frame.ToWorld(grid.SampleDirection(row, column)),
                near,
                patch,
                distance,
                front);
            }
          }
        }
        hits += found;
      });
    const double seconds = SecondsSince(start);
    const double count = static_cast<double>(patches.size()) * grid.SampleCount();
    rawRate[threads] = count / seconds;
    std::printf("  raw Embree, %d thread(s): %.3e rays in %.2f s: %.3e rays/s (%llu hits)\n",
      threads,
      count,
      seconds,
      count / seconds,
      static_cast<unsigned long long>(hits));
    std::fflush(stdout);
  }

  std::printf("  %-10s %8s %7s %6s %10s %12s %8s %9s %11s %9s %9s\n",
    "fill",
    "adaptive",
    "threads",
    "N",
    "strips",
    "bytes",
    "B/strip",
    "seconds",
    "rays/hemi",
    "raw s",
    "s/raw s");
  for (const PipelineVariant& variant : variants)
  {
    options.Fill = variant.Fill;
    options.FillOptions.AdaptiveSampling = variant.Adaptive;
    options.FillOptions.RayPackets = variant.Packets;
    const bool rayFill = variant.Fill == RBufferFill::RayCasting;
    // The rays this fill casts (the same for any number of threads).
    double fillSeconds = 0.0;
    const double raysCast = rayFill
      ? static_cast<double>(CountFillRays(patches, grid, options.FillOptions, 2, fillSeconds))
      : 0.0;
    for (const int threads : { 1, 2 })
    {
      SphericalCover cover;
      const auto start = std::chrono::steady_clock::now();
      cover.Build(patches, options, ThreadPoolFor(threads));
      const double seconds = SecondsSince(start);
      std::printf("  %-10s %8s %7d %6zu %10zu %12zu %8zu %9.2f",
        RBufferFillName(variant.Fill),
        rayFill ? (variant.Adaptive ? (variant.Packets ? "packets" : "single") : "off") : "-",
        threads,
        patches.size(),
        cover.StripCount(),
        cover.MemoryBytes(),
        SphericalCover::BytesPerStrip,
        seconds);
      if (rayFill)
      {
        // Raw Embree's seconds for as many rays as the fill cast, at this thread count.
        const double raw = raysCast / rawRate[threads];
        std::printf(" %11.0f %9.2f %9.2f", raysCast / patches.size(), raw, seconds / raw);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
  }
}

namespace
{
int Run(int argc, char** argv)
{
  bool pipeline = false;
  std::vector<std::string> pipelineScenes;
  std::vector<PipelineVariant> variants{ { RBufferFill::Projection, false },
    { RBufferFill::RayCasting, false },
    { RBufferFill::RayCasting, true, false },
    { RBufferFill::RayCasting, true } };
  int threads = 1;
  std::vector<int> splits{ 1, 2, 3, 4, 6 };
  std::string scenePath = std::string(SPHCOVER_DATA_DIR) + "/scenes/cornell_box.scene";
  for (int k = 1; k < argc; ++k)
  {
    const std::string arg = argv[k];
    if (arg == "--threads" && k + 1 < argc)
    {
      threads = std::max(1, std::atoi(argv[++k]));
    }
    else if (arg == "--splits" && k + 1 < argc)
    {
      splits.clear();
      std::stringstream list(argv[++k]);
      std::string item;
      while (std::getline(list, item, ','))
      {
        splits.push_back(std::max(1, std::atoi(item.c_str())));
      }
    }
    else if (arg == "--scene" && k + 1 < argc)
    {
      // A bare name is one of Data/scenes, as BenchmarkLightPropagation takes it.
      scenePath = argv[++k];
      if (!std::filesystem::exists(scenePath))
      {
        scenePath = std::string(SPHCOVER_DATA_DIR) + "/scenes/" + scenePath;
      }
      pipelineScenes.push_back(scenePath);
    }
    else if (arg == "--pipeline")
    {
      pipeline = true;
    }
    else if (arg == "--variants" && k + 1 < argc)
    {
      // projection, rays (every sample cast), adaptive (RBufferFillOptions::AdaptiveSampling),
      // adaptive-single (the same without RayPackets: rtcIntersect1 per ray)
      variants.clear();
      std::stringstream list(argv[++k]);
      std::string item;
      while (std::getline(list, item, ','))
      {
        if (item == "projection")
        {
          variants.push_back({ RBufferFill::Projection, false });
        }
        else if (item == "rays" || item == "adaptive")
        {
          variants.push_back({ RBufferFill::RayCasting, item == "adaptive" });
        }
        else if (item == "adaptive-single")
        {
          variants.push_back({ RBufferFill::RayCasting, true, false });
        }
        else
        {
          std::fprintf(stderr, "unknown variant %s\n", item.c_str());
          return 2;
        }
      }
    }
    else
    {
      std::fprintf(stderr,
        "usage: %s [--threads N] [--splits 1,2,3] [--scene file.scene]\n"
        "       %s --pipeline [--scene file.scene]... [--variants "
        "projection,rays,adaptive-single,adaptive]\n",
        argv[0],
        argv[0]);
      return 2;
    }
  }
  if (pipeline)
  {
    if (pipelineScenes.empty())
    {
      pipelineScenes = { std::string(SPHCOVER_DATA_DIR) + "/scenes/cornell_box.scene",
        std::string(SPHCOVER_DATA_DIR) + "/scenes/teapot_room.scene" };
    }
    for (const std::string& path : pipelineScenes)
    {
      RunPipeline(path, variants);
    }
    return 0;
  }
  const Scene scene = LoadSceneFile(scenePath);
  const SphericalCoverOptions defaults;
  std::printf("scene %s, grid %d x %d, %d x %d samples per cell, %d thread(s)\n",
    scenePath.c_str(),
    defaults.ThetaBins,
    defaults.PhiBins,
    defaults.SamplesTheta,
    defaults.SamplesPhi,
    threads);
  std::printf("%-10s %6s %6s %8s %9s %11s %11s %8s %11s %6s  %s\n",
    "fill",
    "split",
    "N",
    "entries",
    "strips",
    "bytes",
    "estimate",
    "seconds",
    "cells/s",
    "N-exp",
    "culling: candidates below back kept pieces occluder-pieces");
  for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
  {
    double previousSeconds = 0.0;
    size_t previousCount = 0;
    for (const int split : splits)
    {
      const std::vector<Patch> patches = SplitScene(scene, split);
      SphericalCoverOptions options;
      options.Fill = fill;
      const size_t estimate = SphericalCover::EstimateBytes(patches, options, 8);
      SphericalCover cover;
      const auto start = std::chrono::steady_clock::now();
      cover.Build(patches, options, ThreadPoolFor(threads));
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double cells = static_cast<double>(patches.size()) * cover.Grid().CellCount();
      char exponent[16] = "-";
      if (previousCount > 0)
      {
        std::snprintf(exponent,
          sizeof exponent,
          "%.2f",
          std::log(seconds / previousSeconds) /
            std::log(static_cast<double>(patches.size()) / previousCount));
      }
      const CullingStatistics& c = cover.Culling();
      std::printf("%-10s %6d %6zu %8zu %9zu %11zu %11zu %8.3f %11.3e %6s  %llu %llu %llu %llu "
                  "%llu %llu\n",
        RBufferFillName(fill),
        split,
        patches.size(),
        cover.EntryCount(),
        cover.StripCount(),
        cover.MemoryBytes(),
        estimate,
        seconds,
        cells / seconds,
        exponent,
        static_cast<unsigned long long>(c.Candidates),
        static_cast<unsigned long long>(c.BelowTangentPlane),
        static_cast<unsigned long long>(c.BackFacing),
        static_cast<unsigned long long>(c.Kept),
        static_cast<unsigned long long>(c.Pieces),
        static_cast<unsigned long long>(c.Occluders));
      std::fflush(stdout);
      previousSeconds = seconds;
      previousCount = patches.size();
    }
  }
  return 0;
}
}

int main(int argc, char** argv)
{
  try
  {
    return Run(argc, argv);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "BenchmarkSphericalCover: %s\n", e.what());
    return 1;
  }
}
