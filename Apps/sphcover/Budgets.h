// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Budgets.h
 * @brief The checks made before the work they guard, from the settings and options alone: a
 * cover grid or an image beyond --memory-limit or --max-samples is refused before minutes of
 * subdividing or solving. Each throws one line naming the options that raise the limit.
 */
#ifndef SPHCOVER_BUDGETS_H
#define SPHCOVER_BUDGETS_H

#include "render/RadianceRenderer.h"
#include "scene/Scene.h"

namespace sphcover_cli
{
struct Options;

/// Refuses a cover grid whose R-buffers alone (one per thread) exceed --memory-limit.
void CheckCoverGrid(const sphcover::SceneSettings& settings, const Options& options);

/// What a solve of `patches` patches (the scene's, before any is split) of `surfaces` named
/// surfaces holds at least, whatever the subdivision and the visibility: per patch its row of
/// the cover, its material, its propagation state and its figures, per surface its figures.
std::size_t LeastSolveBytes(std::size_t patches, std::size_t surfaces);

/// Refuses a scene whose LeastSolveBytes exceed --memory-limit, before the subdivision: the
/// stages' own checks come once their sizes are known (the subdivision's patches, the cover's
/// sampled rows, the propagation's regions and figures), this one from the scene alone.
void CheckSceneSize(std::size_t patches, std::size_t surfaces, const Options& options);

/// The render's budgets from the options (--spp, --memory-limit, --max-samples).
sphcover::RenderSettings RenderBudget(const Options& options);

/// Refuses an image of `width` x `height` through `camera` that exceeds the memory limit or the
/// sample budget: the check the render filter makes, made before the solve.
void CheckRenderBudget(sphcover::Camera camera,
  int width,
  int height,
  const sphcover::RenderSettings& settings);
}

#endif
