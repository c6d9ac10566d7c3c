// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SceneLoader.h
 * @brief Reads the `.scene` JSON format (Data/scenes/FORMAT.md) into a Scene.
 *
 * Validation is strict: unknown keys, wrong types, non-finite numbers, out-of-range
 * reflectances, wrong point counts, unknown materials and degenerate patches are errors.
 * The first problem found is thrown as one InputError naming the file, the JSON pointer of the
 * offending value and the problem; nothing partial is returned. The JSON reading itself is
 * JsonInput.h's, the "settings" block SettingsOverride.h's (shared with the command line's --set).
 */
#ifndef SPHCOVER_SCENELOADER_H
#define SPHCOVER_SCENELOADER_H

#include "scene/Scene.h"

#include <functional>
#include <string>
#include <vector>

namespace sphcover
{

/// One polygon of a mesh file, its vertices in the file's order.
using MeshFace = std::vector<glm::dvec3>;

/// Reads the faces of a mesh file (OBJ/PLY/VTP). Core has no mesh readers of its own (it does
/// not depend on VTK); the VTK reader module supplies this. Throws InputError.
using MeshFaceReader = std::function<std::vector<MeshFace>(const std::string& path)>;

/// Reads a scene file. Mesh surfaces need `readMesh`; without it they are an error.
Scene LoadSceneFile(const std::string& path, const MeshFaceReader& readMesh = nullptr);

/// Parses scene text; `path` names it in messages and anchors relative file paths.
Scene ParseScene(const std::string& text,
  const std::string& path,
  const MeshFaceReader& readMesh = nullptr);

/// A .bpt file on its own as a scene: one surface per patch, all named after the file, with a
/// white diffuse material (reflectance 0.8) and default settings.
Scene LoadBptAsScene(const std::string& path);

/// True when the patch has (numerically) no area: every sampled Pu x Pv vanishes relative to
/// the patch size. A triangle stored as a degenerate bilinear patch is not degenerate.
bool IsDegeneratePatch(const BezierPatch& patch);

} // namespace sphcover

#endif
