// SPDX-License-Identifier: BSD-3-Clause
#include "Budgets.h"

#include "Options.h"

#include "cover/SphericalCover.h"
#include "propagation/LightPropagation.h"
#include "propagation/SolutionFigures.h"
#include "scene/Material.h"

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

std::size_t LeastSolveBytes(std::size_t patches, std::size_t surfaces)
{
  constexpr std::size_t perPatch = sphcover::SphericalCover::BytesPerPatch +
    sizeof(sphcover::Material) + sphcover::LightPropagation::LeastBytesPerPatch;
  // The figures with no region at all: their per-point and per-surface parts.
  return patches * perPatch + sphcover::FiguresBoundBytes(patches, 0, surfaces);
}

void CheckSceneSize(std::size_t patches, std::size_t surfaces, const Options& options)
{
  const std::size_t least = LeastSolveBytes(patches, surfaces);
  if (least > options.MemoryLimitBytes())
  {
    const auto mib = [](std::size_t bytes)
    { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
    throw std::runtime_error(options.Scene + ": " + std::to_string(patches) + " patches of " +
      std::to_string(surfaces) + " named surfaces need at least " + mib(least) +
      " to solve before any is split (" + std::to_string(LeastSolveBytes(1, 0)) +
      " bytes per patch: its row of the cover, material, propagation state and figures), " +
      "more than --memory-limit (" + mib(options.MemoryLimitBytes()) + ")");
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
