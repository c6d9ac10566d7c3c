// SPDX-License-Identifier: BSD-3-Clause
#include "scene/SettingsOverride.h"

#include "scene/InputError.h"
#include "scene/JsonInput.h"

namespace sphcover
{

SceneSettings ParseSettings(const JsonInput& input,
  const Json& j,
  const std::string& pointer,
  SceneSettings settings)
{
  input.ExpectObject(j, pointer);
  input.CheckKeys(
    j, pointer, { "theta_bins", "phi_bins", "max_level", "tolerance", "min_patch_size" });
  if (j.contains("theta_bins"))
  {
    settings.ThetaBins = input.PositiveInteger(j["theta_bins"], Child(pointer, "theta_bins"), 4096);
  }
  if (j.contains("phi_bins"))
  {
    settings.PhiBins = input.PositiveInteger(j["phi_bins"], Child(pointer, "phi_bins"), 16384);
  }
  if (j.contains("max_level"))
  {
    const long long level = input.Integer(j["max_level"], Child(pointer, "max_level"));
    if (level < 0 || level > MaxSubdivisionLevel)
    {
      input.Fail(Child(pointer, "max_level"),
        "must be >= 0 and at most " + std::to_string(MaxSubdivisionLevel) +
          " (deeper patches are narrower than the double precision of the parameter domain)");
    }
    settings.MaxLevel = static_cast<int>(level);
  }
  if (j.contains("tolerance"))
  {
    settings.Tolerance = input.Number(j["tolerance"], Child(pointer, "tolerance"));
    // Smaller tolerances test only the rounding of the range bounds (MinimumTolerance).
    if (!(settings.Tolerance >= MinimumTolerance))
    {
      input.Fail(Child(pointer, "tolerance"), "must be >= 1e-9");
    }
  }
  if (j.contains("min_patch_size"))
  {
    settings.MinPatchSize = input.Number(j["min_patch_size"], Child(pointer, "min_patch_size"));
    if (!(settings.MinPatchSize >= 0.0 && settings.MinPatchSize < 1.0))
    {
      input.Fail(Child(pointer, "min_patch_size"),
        "must be >= 0 and < 1 (a fraction of the scene's bounding-box diagonal)");
    }
  }
  return settings;
}

SceneSettings OverrideSetting(const SceneSettings& base, const std::string& assignment)
{
  const size_t equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0)
  {
    throw InputError("--set", assignment, "expected key=value, e.g. theta_bins=64");
  }
  const std::string key = assignment.substr(0, equals);
  const std::string value = assignment.substr(equals + 1);
  // The value is read as JSON and checked exactly as in a scene file's settings block.
  Json parsed;
  if (!ParseJsonValue(value, parsed))
  {
    throw InputError("--set", key, "not a JSON value: " + Quote(value));
  }
  Json object = Json::object();
  object[key] = parsed;
  return ParseSettings(JsonInput("--set"), object, "", base);
}

} // namespace sphcover
