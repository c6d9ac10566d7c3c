// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SettingsOverride.h
 * @brief The settings of a run (SceneSettings: the hemisphere grid, the subdivision's depth and
 * tolerance; Data/scenes/FORMAT.md "settings") read from JSON, in one place for both sources:
 * a scene file's "settings" block (ParseSettings, called by the scene loader) and the command
 * line's `--set key=value` (OverrideSetting). The keys, bounds and messages are therefore the
 * same whichever way a setting is given.
 */
#ifndef SPHCOVER_SETTINGSOVERRIDE_H
#define SPHCOVER_SETTINGSOVERRIDE_H

#include "scene/Scene.h"

// Only the declaration of nlohmann::json: Core links nlohmann/json privately, and callers of
// OverrideSetting need none of it.
#include <nlohmann/json_fwd.hpp>

#include <string>

namespace sphcover
{

class JsonInput;

/// `settings` with the keys of the settings object `block` (at `pointer`) applied, each checked
/// against its bounds; unknown keys, wrong types and out-of-range values fail through `input`.
SceneSettings ParseSettings(const JsonInput& input,
  const nlohmann::json& block,
  const std::string& pointer,
  SceneSettings settings = SceneSettings());

/// The settings with one "key=value" assignment applied (the command line's --set), the value
/// read as JSON and checked as in a scene file's "settings" block. Throws InputError naming
/// "--set", the key and the problem.
SceneSettings OverrideSetting(const SceneSettings& base, const std::string& assignment);

} // namespace sphcover

#endif
