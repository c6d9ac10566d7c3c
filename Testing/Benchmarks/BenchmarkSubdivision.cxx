// SPDX-License-Identifier: BSD-3-Clause
// Benchmark of the interval subdivision (paper §4): patches, characteristic points, pair tests
// and seconds for the Cornell box and the teapot room at the scenes' settings, with 1 and 2
// threads, and the patch counts of the two range methods.
//
//   BenchmarkSubdivision [--natural]     (--natural adds natural interval runs: minutes)
#include "scene/SceneLoader.h"
#include "subdivision/IntervalSubdivision.h"

#include <atomic>
#include <chrono>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <thread>
#include <vector>

using namespace sphcover;

namespace
{

void Run(const char* name, RangeMethod method, int threads)
{
  const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/") + name);
  SubdivisionSettings settings;
  settings.Method = method;
  settings.MaxLevel = scene.Settings.MaxLevel;
  settings.ThetaBins = scene.Settings.ThetaBins;
  settings.PhiBins = scene.Settings.PhiBins;
  for (double& tolerance : settings.Tolerance)
  {
    tolerance = scene.Settings.Tolerance;
  }
  const auto start = std::chrono::steady_clock::now();
  IntervalSubdivision subdivision(scene, settings);
  subdivision.Run(nullptr, threads == 1 ? ParallelFor(SequentialFor) : ThreadedFor(threads));
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const size_t patches = subdivision.Patches().size();
  const SubdivisionStatistics& s = subdivision.Statistics();
  std::cout << std::left << std::setw(20) << name << std::setw(10)
            << (method == RangeMethod::Bernstein ? "Bernstein" : "natural") << std::setw(9)
            << threads << std::setw(9) << patches << std::setw(9) << patches << std::setw(12)
            << s.PairTests << std::setw(8) << s.Sweeps << std::fixed << std::setprecision(2)
            << seconds << std::defaultfloat << "\n";
}
}

int main(int argc, char* argv[])
{
  const bool natural = argc > 1 && std::strcmp(argv[1], "--natural") == 0;
  std::cout
    << "scene               method    threads  patches  points   pair tests  sweeps  seconds\n";
  for (const char* scene : { "cornell_box.scene", "teapot_room.scene" })
  {
    for (int threads : { 1, 2 })
    {
      Run(scene, RangeMethod::Bernstein, threads);
    }
    if (natural)
    {
      Run(scene, RangeMethod::NaturalInterval, 2);
    }
  }
  return 0;
}
