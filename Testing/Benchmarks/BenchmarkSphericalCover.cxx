// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkSphericalCover.cxx
 * @brief Speed and memory of the spherical cover (paper §3.3, §4.3 Steps 2-4) on the Cornell
 * box split uniformly at several resolutions, with both R-buffer fills (SPEC §7: speed and
 * memory are measured by a benchmark program, never by timed tests).
 *
 *   BenchmarkSphericalCover [--threads N] [--splits 1,2,3,4,6] [--scene path.scene]
 *
 * Prints, per resolution and fill: patches N, rows, entries (non-null h_ij), strips, bytes
 * (and the estimate made before building), seconds, cells per second, the candidate culling
 * counts, and how the time grows with N (exponent of N between consecutive resolutions).
 */
#include "BezierPatch.h"
#include "ParallelFor.h"
#include "Patch.h"
#include "SceneLoader.h"
#include "SphericalCover.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

int main(int argc, char** argv)
{
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
      scenePath = argv[++k];
    }
    else
    {
      std::fprintf(
        stderr, "usage: %s [--threads N] [--splits 1,2,3] [--scene file.scene]\n", argv[0]);
      return 2;
    }
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
