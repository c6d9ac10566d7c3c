// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Scene.h
 * @brief The environment of paper §4.3: surfaces S_1..S_n, their materials, cameras and the
 * solver settings of the scene file.
 */
#ifndef SPHCOVER_SCENE_H
#define SPHCOVER_SCENE_H

#include "geometry/BezierPatch.h"
#include "scene/Camera.h"
#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace sphcover
{

/**
 * The deepest level the parameter domain can represent: a patch at level L spans 3^-L of its
 * surface's [0, 1] in one direction, and the doubles just below 1 are 2^-53 apart. At level 32
 * a patch is 3^-32 = 5.4e-16 wide (about 5 of those steps); one more split would make pieces
 * of 1.6 steps, whose cut values round to neighbouring doubles or coincide.
 */
constexpr int MaxSubdivisionLevel = 32;
/**
 * The smallest tolerance of a criterion. The criteria compare ranges bounded in double
 * precision (relative rounding ~1e-15, growing with the patch degrees) with tolerance x scale;
 * below 1e-9 the verdict would be decided by that rounding rather than by the geometry, and
 * every pair would split to the limits.
 */
constexpr double MinimumTolerance = 1e-9;

/// The solver settings of a scene file (its "settings" block), with its defaults (see
/// Data/scenes/FORMAT.md).
struct SceneSettings
{
  int ThetaBins = 32;
  int PhiBins = 128;
  int MaxLevel = 5;
  double Tolerance = 0.02;
  /// No patch is split once its bounding box's diagonal is at most this fraction of the
  /// scene's (the "min_patch_size" setting; 0: no such limit). Data/scenes/FORMAT.md.
  double MinPatchSize = 0.0;
};

/// The scene's length unit (the file's "unit", Data/scenes/FORMAT.md): lengths and areas are in
/// it, radiance and irradiance do not depend on it, and powers (W) do through the area, so the
/// reports convert them with Metres (a Cornell box in mm emits 1e-6 of what the same numbers in
/// metres would).
struct LengthUnit
{
  std::string Name = "m";
  /// The unit's length in metres.
  double Metres = 1.0;
};

/// The unit called `name` (mm, cm, dm, m, km, in, ft, yd); false when there is none.
bool FindLengthUnit(const std::string& name, LengthUnit& unit);

/// The names FindLengthUnit knows, for messages: "mm, cm, dm, m, km, in, ft, yd".
std::string LengthUnitNames();

/// One parametric surface S_i (paper §4.3): a single Bezier patch over [0,1]^2. A scene entry
/// that loads a .bpt file or a mesh yields several surfaces sharing the entry's name.
struct Surface
{
  Surface(BezierPatch patch, int nameIndex, int materialIndex)
    : Patch(std::move(patch))
    , NameIndex(nameIndex)
    , MaterialIndex(materialIndex)
  {
  }

  BezierPatch Patch;
  /// Index into Scene::SurfaceNames.
  int NameIndex = 0;
  /// Index into Scene::Materials.
  int MaterialIndex = 0;
  /**
   * One side of a two-sided surface (the scene's "two_sided"): the loader makes such a surface
   * two one-sided surfaces of the same name, the patch and its reversed copy, next to each other
   * (as it does a pane). Each sends, receives and reflects light on its front only; its back
   * side is never met: the rays of the cover, of the direct light and of the render pass it and
   * meet the other copy's front at the same place (RBufferFillOptions::TwoSidedSurfaces,
   * RadianceRenderer). Such surfaces come in these pairs; false for a pane's sides.
   */
  bool TwoSided = false;
  /// The patch came from a mesh triangle and is stored as the degenerate bilinear patch
  /// (P00, P10, P11, P01 = P11).
  bool IsTriangle = false;
};

struct Scene
{
  /// The file the scene was read from (for messages).
  std::string SourceFile;
  std::vector<Material> Materials;
  /// Names of the scene file's surface entries, in file order.
  std::vector<std::string> SurfaceNames;
  std::vector<Surface> Surfaces;
  std::vector<Camera> Cameras;
  SceneSettings Settings;
  LengthUnit Unit;

  /// Axis-aligned box of all control points (it encloses the surfaces: convex hull property).
  void Bounds(glm::dvec3& lower, glm::dvec3& upper) const;
  /// The index of the material called `name`, or -1; a search of the list (the loader looks the
  /// surfaces' materials up in a hash table of its own).
  int FindMaterial(const std::string& name) const;
};

/**
 * A fingerprint of what a solution depends on: the surfaces (degrees, control points, names,
 * materials, sidedness), the materials and the settings block, as 16 hex digits (FNV-1a over
 * the exact bits). The cameras and the source file's name are left out, so that a solution
 * renders through any camera and from a copy of the scene.
 */
std::string Fingerprint(const Scene& scene);

} // namespace sphcover

#endif
