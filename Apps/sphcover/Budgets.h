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
