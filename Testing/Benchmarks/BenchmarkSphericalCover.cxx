// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkSphericalCover.cxx
 * @brief Speed and memory of the spherical cover (paper §3.3, §4.3 Steps 2-4) on the Cornell
 * box split uniformly at several resolutions, with both R-buffer fills
 * (Documentation/Verification.md#quality-bars: speed and memory are measured by a benchmark
 * program, never by timed tests).
 *
 *   BenchmarkSphericalCover [--threads N] [--splits 1,2,3,4,6] [--scene path.scene]
 *   BenchmarkSphericalCover --pipeline [--scene path.scene]...
 *
 * Prints, per resolution and fill: patches N, rows, entries (non-null h_ij), strips, bytes
 * (and the estimate made before building), seconds, cells per second, the candidate culling
 * counts, and how the time grows with N (exponent of N between consecutive resolutions).
 *
 * --pipeline (the figures of the closing note of issue 4): per scene (default the Cornell box
 * and the teapot room) the patches of the real pipeline at the scene's settings (interval
 * subdivision, then the receiver-side refinement that vtkSphericalCoverFilter applies by
 * default, 3 levels deeper), then for 1 and 2 threads and each fill: N, strips, bytes (and
 * bytes per strip), seconds; and Embree's raw ray throughput on this machine for the same
 * number of rays (N x samples per hemisphere, from the characteristic points along the sample
 * directions, no classification), so the cover's cost reads as a ratio to that limit.
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

void RunPipeline(const std::string& scenePath)
{
  const Scene scene = LoadSceneFile(scenePath);
  const std::vector<Patch> patches = PipelinePatches(scene);
  SphericalCoverOptions options;
  options.ThetaBins = scene.Settings.ThetaBins;
  options.PhiBins = scene.Settings.PhiBins;
  const HemisphereGrid grid(
    options.ThetaBins, options.PhiBins, options.SamplesTheta, options.SamplesPhi);
  std::printf("scene %s: N = %zu characteristic points, grid %d x %d, %d x %d samples per "
              "cell, %zu rays per hemisphere\n",
    scenePath.c_str(),
    patches.size(),
    options.ThetaBins,
    options.PhiBins,
    options.SamplesTheta,
    options.SamplesPhi,
    grid.SampleCount());
  std::printf("  %-10s %7s %6s %10s %12s %8s %9s\n",
    "fill",
    "threads",
    "N",
    "strips",
    "bytes",
    "B/strip",
    "seconds");
  for (const RBufferFill fill : { RBufferFill::Projection, RBufferFill::RayCasting })
  {
    for (const int threads : { 1, 2 })
    {
      options.Fill = fill;
      SphericalCover cover;
      const auto start = std::chrono::steady_clock::now();
      cover.Build(patches, options, ThreadPoolFor(threads));
      const double seconds = SecondsSince(start);
      std::printf("  %-10s %7d %6zu %10zu %12zu %8zu %9.2f\n",
        RBufferFillName(fill),
        threads,
        patches.size(),
        cover.StripCount(),
        cover.MemoryBytes(),
        SphericalCover::BytesPerStrip,
        seconds);
      std::fflush(stdout);
    }
  }
  // Embree's limit: the same rays (every sample direction of every hemisphere), first hit only.
  const RayCaster rays(RayCastPatches(patches), RayCastOptions(options.FillOptions));
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
    std::printf("  raw Embree %7d %6zu rays %.3e in %.2f s: %.3e rays/s (%llu hits)\n",
      threads,
      patches.size(),
      count,
      seconds,
      count / seconds,
      static_cast<unsigned long long>(hits));
    std::fflush(stdout);
  }
}

namespace
{
int Run(int argc, char** argv)
{
  bool pipeline = false;
  std::vector<std::string> pipelineScenes;
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
    else
    {
      std::fprintf(stderr,
        "usage: %s [--threads N] [--splits 1,2,3] [--scene file.scene]\n"
        "       %s --pipeline [--scene file.scene]...\n",
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
      RunPipeline(path);
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
