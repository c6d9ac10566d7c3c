// SPDX-License-Identifier: BSD-3-Clause
#include "Budgets.h"

#include "Options.h"

#include "cover/SphericalCover.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sphcover_cli
{
void CheckCoverGrid(const sphcover::SceneSettings& settings, const Options& options)
{
  sphcover::SphericalCoverOptions cover;
  cover.ThetaBins = settings.ThetaBins;
  cover.PhiBins = settings.PhiBins;
  const std::size_t threads =
    static_cast<std::size_t>(std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads()));
  const std::string problem =
    sphcover::SphericalCover::MemoryProblem({}, cover, threads, options.MemoryLimitBytes());
  if (!problem.empty())
  {
    throw std::runtime_error(options.Scene + ": settings theta_bins " +
      std::to_string(settings.ThetaBins) + ", phi_bins " + std::to_string(settings.PhiBins) + ": " +
      problem + " (--memory-limit)");
  }
}

sphcover::RenderSettings RenderBudget(const Options& options)
{
  sphcover::RenderSettings settings;
  settings.SamplesPerPixel = options.SamplesPerPixel;
  settings.MemoryLimitBytes = options.MemoryLimitBytes();
  settings.MaximumSamples = static_cast<std::size_t>(options.MaxSamples);
  return settings;
}

void CheckRenderBudget(sphcover::Camera camera,
  int width,
  int height,
  const sphcover::RenderSettings& settings)
{
  camera.Width = width;
  camera.Height = height;
  const std::string problem = sphcover::CheckCamera(camera, settings);
  if (!problem.empty())
  {
    throw std::runtime_error(
      "--size/--spp: " + problem + " (--memory-limit and --max-samples raise the limits)");
  }
}
}
