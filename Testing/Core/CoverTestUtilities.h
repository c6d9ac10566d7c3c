// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CoverTestUtilities.h
 * @brief Shared fixtures of the hemisphere, R-buffer and spherical cover tests: patch lists
 * made by splitting every surface of a scene uniformly (the interval subdivision engine is not
 * used, so the tests exercise the cover alone), rectangles for Howell's configurations, and
 * Howell's closed forms (Data/scenes/tools/howell.py).
 */
#ifndef SPHCOVER_COVERTESTUTILITIES_H
#define SPHCOVER_COVERTESTUTILITIES_H

#include "cover/CoverRefinement.h"
#include "cover/SphericalCover.h"
#include "geometry/BezierPatch.h"
#include "geometry/RayCaster.h"
#include "math/Constants.h"
#include "math/ParallelFor.h"
#include "propagation/LightPropagation.h"
#include "scene/Scene.h"
#include "scene/SceneLoader.h"
#include "subdivision/IntervalSubdivision.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphcover_test
{

/// A problem-size factor: sanitizer builds run smaller problems, same tolerances.
#ifdef SPHCOVER_SANITIZED
constexpr bool Sanitized = true;
#else
constexpr bool Sanitized = false;
#endif

inline std::string ScenePath(const std::string& name)
{
  return std::string(SPHCOVER_DATA_DIR) + "/scenes/" + name;
}

/// Appends the uniform splitCount x splitCount sub-patches of a surface.
inline void AppendSplit(std::vector<sphcover::Patch>& patches,
  const sphcover::BezierPatch& surface,
  int surfaceIndex,
  int splitU,
  int splitV)
{
  for (int b = 0; b < splitV; ++b)
  {
    for (int a = 0; a < splitU; ++a)
    {
      const sphcover::UVRect rect{ static_cast<double>(a) / splitU,
        a + 1 == splitU ? 1.0 : static_cast<double>(a + 1) / splitU,
        static_cast<double>(b) / splitV,
        b + 1 == splitV ? 1.0 : static_cast<double>(b + 1) / splitV };
      patches.emplace_back(surfaceIndex, rect, 0, surface.SubPatch(rect));
    }
  }
}

/// Every surface of the scene split into split x split patches.
inline std::vector<sphcover::Patch> SplitScene(const sphcover::Scene& scene, int split)
{
  std::vector<sphcover::Patch> patches;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    AppendSplit(patches, scene.Surfaces[s].Patch, static_cast<int>(s), split, split);
  }
  return patches;
}

/// A scene split uniformly (SplitScene), its cover at the default options and the scene's
/// material of every patch: the fixture of the propagation tests.
struct CoveredScene
{
  sphcover::Scene Environment;
  std::vector<sphcover::Patch> Patches;
  sphcover::SphericalCover Cover;
  std::vector<sphcover::Material> Materials;

  CoveredScene(const std::string& name, int split)
    : Environment(sphcover::LoadSceneFile(ScenePath(name)))
    , Patches(SplitScene(this->Environment, split))
  {
    if (!this->Cover.Build(this->Patches))
    {
      throw std::runtime_error("cover not built");
    }
    this->Materials =
      sphcover::LightPropagation::MaterialsOfPatches(this->Environment, this->Patches);
  }
};

/// The ray fill with every surface's pane transmittance (Material::Transmittance).
inline sphcover::SphericalCoverOptions PaneOptions(const sphcover::Scene& scene, int theta, int phi)
{
  sphcover::SphericalCoverOptions options;
  options.ThetaBins = theta;
  options.PhiBins = phi;
  options.Fill = sphcover::RBufferFill::RayCasting;
  for (const sphcover::Surface& surface : scene.Surfaces)
  {
    options.SurfaceTransmittance.push_back(
      glm::vec3(scene.Materials[static_cast<size_t>(surface.MaterialIndex)].Transmittance));
  }
  return options;
}

/// A scene with panes split uniformly (SplitScene) and its cover by the ray fill through them.
struct PaneScene
{
  sphcover::Scene Environment;
  std::vector<sphcover::Patch> Patches;
  sphcover::SphericalCover Cover;
  std::vector<sphcover::Material> Materials;

  PaneScene(const sphcover::Scene& scene, int split, int theta = 16, int phi = 64)
    : Environment(scene)
    , Patches(SplitScene(scene, split))
  {
    if (!this->Cover.Build(this->Patches, PaneOptions(scene, theta, phi), sphcover::ThreadedFor(2)))
    {
      throw std::runtime_error("cover not built");
    }
    this->Materials =
      sphcover::LightPropagation::MaterialsOfPatches(this->Environment, this->Patches);
  }
};

/// Adds to mixed_box.scene's JSON a pane across the box at x = 1/3 (on the walls' patch
/// boundaries at split 3), diffuse 0.1, transmittance (0.7, 0.6, 0.8).
inline void AddPaneAcrossMixedBox(nlohmann::json& scene)
{
  scene["materials"]["glass"] = { { "type", "diffuse" },
    { "reflectance", { 0.1, 0.1, 0.1 } },
    { "transmittance", { 0.7, 0.6, 0.8 } } };
  scene["surfaces"].push_back({ { "name", "pane" },
    { "type", "bilinear" },
    { "material", "glass" },
    { "points",
      { { 1.0 / 3.0, 0, 0 }, { 1.0 / 3.0, 1, 0 }, { 1.0 / 3.0, 1, 1 }, { 1.0 / 3.0, 0, 1 } } } });
}

/// The real pipeline at a scene's own settings (as sphcover solve and the filters run it): the
/// interval subdivision to `maxLevel`, the cover refinement `extraLevels` deeper (receiver side
/// only unless `hemispheres`), the cover of the refined patches. Throws std::runtime_error when
/// a stage fails.
struct SceneSettingsPipeline
{
  std::vector<sphcover::Patch> Before;
  std::vector<sphcover::Patch> After;
  sphcover::RefinementStatistics Statistics;
  sphcover::SphericalCover Cover;

  SceneSettingsPipeline(const sphcover::Scene& scene,
    int maxLevel,
    int extraLevels,
    bool hemispheres)
  {
    sphcover::SubdivisionSettings subdivision;
    subdivision.MaxLevel = maxLevel;
    subdivision.ThetaBins = scene.Settings.ThetaBins;
    subdivision.PhiBins = scene.Settings.PhiBins;
    for (double& tolerance : subdivision.Tolerance)
    {
      tolerance = scene.Settings.Tolerance;
    }
    sphcover::IntervalSubdivision interval(scene, subdivision);
    if (!interval.Run(nullptr, sphcover::ThreadedFor(2)))
    {
      throw std::runtime_error("subdivision failed");
    }
    this->Before = interval.Patches();
    sphcover::RefinementSettings settings;
    settings.Cover.ThetaBins = scene.Settings.ThetaBins;
    settings.Cover.PhiBins = scene.Settings.PhiBins;
    settings.MaxLevel = maxLevel + extraLevels;
    settings.AnalyseHemispheres = hemispheres;
    sphcover::CoverRefinement refinement(scene, this->Before, settings);
    if (!refinement.Run(nullptr, sphcover::ThreadedFor(2)))
    {
      throw std::runtime_error("refinement failed");
    }
    this->After = refinement.Patches();
    this->Statistics = refinement.Statistics();
    if (!this->Cover.Build(this->After, settings.Cover, sphcover::ThreadedFor(2)))
    {
      throw std::runtime_error("cover not built");
    }
  }
};

/// Runs `brightest` brightest-first and `fixed` in a fixed order, both to a relative tolerance
/// of 1e-7 (the order-independence tests); whether both converged.
inline bool RunInBothOrders(sphcover::LightPropagation& brightest,
  sphcover::LightPropagation& fixed)
{
  sphcover::PropagationSettings settings;
  settings.ConvergenceTolerance = 1e-7;
  const bool first = brightest.Run(settings);
  settings.Order = sphcover::ShootingOrder::FixedOrder;
  return fixed.Run(settings) && first;
}

/// A bilinear patch with corners origin, origin + e1, origin + e1 + e2, origin + e2: its front
/// side is e1 x e2.
inline sphcover::BezierPatch Parallelogram(const glm::dvec3& origin,
  const glm::dvec3& e1,
  const glm::dvec3& e2)
{
  return sphcover::BezierPatch(1, 1, { origin, origin + e1, origin + e2, origin + e1 + e2 });
}

/// The furnace box with a closed, outward-facing cube [0.35, 0.65]^3 inside: every direction
/// from every point still meets a surface, and the cube hides parts of the walls.
inline sphcover::Scene FurnaceBoxWithOccluder()
{
  sphcover::Scene scene = sphcover::LoadSceneFile(ScenePath("furnace_box.scene"));
  const double lo = 0.35;
  const double hi = 0.65;
  const double w = hi - lo;
  const int name = static_cast<int>(scene.SurfaceNames.size());
  scene.SurfaceNames.push_back("inner_box");
  const glm::dvec3 x(w, 0, 0);
  const glm::dvec3 y(0, w, 0);
  const glm::dvec3 z(0, 0, w);
  // Each face's e1 x e2 points out of the cube.
  const sphcover::BezierPatch faces[6] = { Parallelogram({ lo, lo, lo }, z, y),
    Parallelogram({ hi, lo, lo }, y, z),
    Parallelogram({ lo, lo, lo }, x, z),
    Parallelogram({ lo, hi, lo }, z, x),
    Parallelogram({ lo, lo, lo }, y, x),
    Parallelogram({ lo, lo, hi }, x, y) };
  for (const sphcover::BezierPatch& face : faces)
  {
    scene.Surfaces.emplace_back(face, name, 0);
  }
  return scene;
}

/// Howell C-11: parallel, directly opposed, equal a x b rectangles at distance c.
inline double HowellParallel(double a, double b, double c)
{
  const double x = a / c;
  const double y = b / c;
  const double x1 = 1 + x * x;
  const double y1 = 1 + y * y;
  return 2.0 / (sphcover::Pi * x * y) *
    (std::log(std::sqrt(x1 * y1 / (x1 + y * y))) +
      x * std::sqrt(y1) * std::atan(x / std::sqrt(y1)) +
      y * std::sqrt(x1) * std::atan(y / std::sqrt(x1)) - x * std::atan(x) - y * std::atan(y));
}

/// Howell C-14: from plate A (l x w) to plate B (l x h), perpendicular, common edge l.
inline double HowellPerpendicular(double l, double w, double h)
{
  const double H = h / l;
  const double W = w / l;
  const double h2 = H * H;
  const double w2 = W * W;
  const double s = std::sqrt(h2 + w2);
  const double logTerm = std::log((1 + w2) * (1 + h2) / (1 + w2 + h2)) +
    w2 * std::log(w2 * (1 + w2 + h2) / ((1 + w2) * (w2 + h2))) +
    h2 * std::log(h2 * (1 + h2 + w2) / ((1 + h2) * (h2 + w2)));
  return 1.0 / (sphcover::Pi * W) *
    (W * std::atan(1 / W) + H * std::atan(1 / H) - s * std::atan(1 / s) + 0.25 * logTerm);
}

/// The index of the scene's surface called `name` (-1: none).
inline int SurfaceNamed(const sphcover::Scene& scene, const std::string& name)
{
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    if (scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[s].NameIndex)] == name)
    {
      return static_cast<int>(s);
    }
  }
  return -1;
}

/// The corners of a planar bilinear patch as a polygon, in the order of its boundary.
inline std::vector<glm::dvec3> CornerPolygon(const sphcover::BezierPatch& patch)
{
  return { patch.Evaluate(0, 0), patch.Evaluate(1, 0), patch.Evaluate(1, 1), patch.Evaluate(0, 1) };
}

/// Whether rays from `point` to 9 x 9 points of the lamp (surface `lampSurface`, geometry
/// `lamp`) all first meet its front side: the whole lamp is in view.
inline bool SeesWholeLamp(const sphcover::RayCaster& rays,
  const std::vector<sphcover::Patch>& patches,
  const glm::dvec3& point,
  const sphcover::BezierPatch& lamp,
  int lampSurface)
{
  for (int a = 0; a <= 8; ++a)
  {
    for (int b = 0; b <= 8; ++b)
    {
      const glm::dvec3 target = lamp.Evaluate(0.01 + 0.98 * a / 8.0, 0.01 + 0.98 * b / 8.0);
      std::size_t hit = 0;
      double distance = 0.0;
      bool front = false;
      if (!rays.FirstHit(point, glm::normalize(target - point), 1e-3, hit, distance, front) ||
        patches[hit].SurfaceIndex != lampSurface || !front)
      {
        return false;
      }
    }
  }
  return true;
}

/**
 * Lambert's formula: the projected solid angle of a planar polygon (vertices in order, wholly
 * on or above the tangent plane) seen from point p with unit normal n is
 * |sum_k gamma_k (n . u_k)| / 2, gamma_k the angle its edge k subtends at p and u_k the unit
 * normal of the plane through p and the edge.
 */
inline double LambertProjectedSolidAngle(const glm::dvec3& p,
  const glm::dvec3& n,
  const std::vector<glm::dvec3>& polygon)
{
  double sum = 0.0;
  for (size_t k = 0; k < polygon.size(); ++k)
  {
    const glm::dvec3 a = glm::normalize(polygon[k] - p);
    const glm::dvec3 b = glm::normalize(polygon[(k + 1) % polygon.size()] - p);
    const glm::dvec3 c = glm::cross(a, b);
    const double length = glm::length(c);
    if (length > 0.0)
    {
      sum += std::atan2(length, glm::dot(a, b)) * glm::dot(c / length, n);
    }
  }
  return std::fabs(sum) / 2.0;
}

struct Exchange
{
  double WorstReciprocity = 0.0;
  std::string WorstPair;
  double WorstRowError = 0.0;
  std::size_t Pairs = 0;
};

/// Surface-pair reciprocity |A_a F_ab - A_b F_ba| / max(...) over the pairs whose exchange
/// min(A_a F_ab, A_b F_ba) exceeds 0.1% of the smaller area, and the worst |row sum - 1|.
inline Exchange MeasureExchange(const sphcover::Scene& scene,
  const std::vector<sphcover::Patch>& patches,
  const sphcover::SphericalCover& cover)
{
  const size_t count = scene.Surfaces.size();
  std::vector<int> groups;
  std::vector<double> area(count, 0.0);
  for (const sphcover::Patch& patch : patches)
  {
    groups.push_back(patch.SurfaceIndex);
    area[static_cast<size_t>(patch.SurfaceIndex)] += patch.Area;
  }
  const std::vector<double> f = cover.FormFactors(groups, static_cast<int>(count));
  Exchange result;
  for (size_t a = 0; a < count; ++a)
  {
    double row = 0.0;
    for (size_t b = 0; b < count; ++b)
    {
      row += f[a * count + b];
      const double ab = area[a] * f[a * count + b];
      const double ba = area[b] * f[b * count + a];
      if (b <= a || std::min(ab, ba) <= 1e-3 * std::min(area[a], area[b]))
      {
        continue;
      }
      ++result.Pairs;
      const double error = std::fabs(ab - ba) / std::max(ab, ba);
      if (error > result.WorstReciprocity)
      {
        result.WorstReciprocity = error;
        result.WorstPair = scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[a].NameIndex)] +
          " / " + scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[b].NameIndex)];
      }
    }
    result.WorstRowError = std::max(result.WorstRowError, std::fabs(row - 1.0));
  }
  return result;
}

} // namespace sphcover_test

#endif
