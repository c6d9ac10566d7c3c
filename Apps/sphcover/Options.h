// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Options.h
 * @brief The command line's options (main.cxx parses them; see its help texts).
 */
#ifndef SPHCOVER_OPTIONS_H
#define SPHCOVER_OPTIONS_H

#include <cstddef>
#include <string>
#include <vector>

namespace sphcover_cli
{
struct Options
{
  std::string Scene;
  std::string Output;
  std::string RangeMethod = "bernstein";
  std::string Report;
  std::string Fill = "raycasting";
  /// The cover's measure of the lamps' regions: "measured" (on the lamp) or "cells".
  std::string Lamps = "measured";
  std::string Hemispheres = "computed";
  /// vtkSphericalCoverFilter::DirectIrradianceNodes (0: none).
  int DirectNodes = 9;
  /// vtkSphericalCoverFilter::DirectBounceRays (0: the direct light only).
  int BounceRays = 32;
  /// vtkSphericalCoverFilter::DirectNodesTolerance (0: every patch's nodes computed).
  double DirectTolerance = 0.05;
  std::vector<std::string> Settings;
  std::string Png;
  std::string Camera;
  std::string Size;
  std::string SolutionFile;
  /// sphcover walk: the camera path file (--path), or the number of cameras of an orbit
  /// (--orbit, 0: none), and whether EXR frames are added (--exr).
  std::string PathFile;
  int Orbit = 0;
  bool Exr = false;
  int SamplesPerPixel = 4;
  /// --exposure: a factor, as vtkRadianceImageFilter::ExposureFactor (not stops).
  double ExposureFactor = 1.0;
  int Threads = 0;
  bool Quiet = false;
  /// The budgets (see the options' help): what a stage may take before it refuses.
  double MemoryLimit = 8192.0;
  int MaxPatches = 1000000;
  double MaxPairTests = 1.0e9;
  double MaxSamples = 1073741824.0;
  /// This process's MPI rank and the number of ranks (0 and 1 outside mpiexec): only rank 0
  /// prints, writes files and renders.
  int Rank = 0;
  int Ranks = 1;

  /// --memory-limit (MiB) in bytes.
  std::size_t MemoryLimitBytes() const
  {
    return static_cast<std::size_t>(this->MemoryLimit * 1024.0 * 1024.0);
  }
};
}

#endif
