// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SceneSummary.h
 * @brief The human-readable scene summary of `sphcover info`.
 */
#ifndef SPHCOVER_SCENESUMMARY_H
#define SPHCOVER_SCENESUMMARY_H

#include <ostream>

namespace sphcover
{
struct Scene;

/// Surfaces (per named entry: patch count and degrees), materials, cameras, bounds, settings.
void PrintSceneSummary(const Scene& scene, std::ostream& os);
}

#endif
