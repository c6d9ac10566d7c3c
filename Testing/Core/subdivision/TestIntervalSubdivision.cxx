// SPDX-License-Identifier: BSD-3-Clause
// The environment-dependent subdivision of paper §4 (IntervalSubdivision, SubdivisionCriteria):
// - the final patches tile every surface's parameter domain exactly and their areas add up to
//   the surface area;
// - soundness: every criterion a pair is reported to satisfy holds at densely sampled points;
// - two parallel facing quads need no split; a doubly curved patch seen from a point near it
//   (the paper's Fig. 9) is split along its silhouette, with large fully visible and fully
//   back-facing pieces found at shallow levels;
// - Bernstein bounds need no more patches than natural interval arithmetic;
// - limits (MaxLevel, one cell), bad settings, and thread-count independence.
#include "scene/InputError.h"
#include "scene/SceneLoader.h"
#include "scene/SettingsOverride.h"
#include "subdivision/IntervalSubdivision.h"
#include "subdivision/SubdivisionCriteria.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <thread>

using namespace sphcover;

namespace
{
#ifdef SPHCOVER_SANITIZED
constexpr int SamplesPerSide = 9;
#else
constexpr int SamplesPerSide = 17;
#endif

Scene SceneOf(const std::vector<BezierPatch>& patches, MaterialType type = MaterialType::Diffuse)
{
  Scene scene;
  Material material;
  material.Name = "m";
  material.Type = type;
  material.Diffuse = glm::dvec3(0.5);
  material.Specular = glm::dvec3(0.5);
  scene.Materials.push_back(material);
  for (size_t k = 0; k < patches.size(); ++k)
  {
    scene.SurfaceNames.push_back("s" + std::to_string(k));
    scene.Surfaces.emplace_back(patches[k], static_cast<int>(k), 0);
  }
  return scene;
}

/// A flat quad with corners c, c+a, c+a+b, c+b (front: a x b).
BezierPatch Quad(const glm::dvec3& c, const glm::dvec3& a, const glm::dvec3& b)
{
  return BezierPatch(1, 1, { c, c + a, c + b, c + a + b });
}

/// A bicubic dome over [-1,1]^2 in the xy-plane, top at z = 1, front facing +z.
BezierPatch Dome()
{
  std::vector<glm::dvec3> points;
  const double heights[4][4] = {
    { 0.0, 0.0, 0.0, 0.0 }, { 0.0, 2.0, 2.0, 0.0 }, { 0.0, 2.0, 2.0, 0.0 }, { 0.0, 0.0, 0.0, 0.0 }
  };
  for (int j = 0; j <= 3; ++j)
  {
    for (int i = 0; i <= 3; ++i)
    {
      points.emplace_back(-1.0 + 2.0 * i / 3.0, -1.0 + 2.0 * j / 3.0, heights[i][j]);
    }
  }
  return BezierPatch(3, 3, points);
}

std::vector<Patch> Subdivide(const Scene& scene,
  const SubdivisionSettings& settings,
  SubdivisionStatistics* statistics = nullptr,
  const ParallelFor& parallelFor = SequentialFor)
{
  IntervalSubdivision subdivision(scene, settings);
  EXPECT_TRUE(subdivision.Run(nullptr, parallelFor));
  if (statistics)
  {
    *statistics = subdivision.Statistics();
  }
  return subdivision.Patches();
}

/// Checks that the patches of each surface tile [0,1]^2 exactly: every rectangle lies inside
/// the unit square, the areas (in parameter space) add up to 1, and no two overlap; with
/// exact shared cut values this is equivalent to a tiling.
void ExpectTiling(const Scene& scene, const std::vector<Patch>& patches)
{
  std::map<int, std::vector<UVRect>> bySurface;
  for (const Patch& patch : patches)
  {
    bySurface[patch.SurfaceIndex].push_back(patch.Domain);
  }
  ASSERT_EQ(bySurface.size(), scene.Surfaces.size());
  for (const auto& entry : bySurface)
  {
    const std::vector<UVRect>& rects = entry.second;
    double parameterArea = 0.0;
    for (size_t a = 0; a < rects.size(); ++a)
    {
      const UVRect& r = rects[a];
      ASSERT_TRUE(
        r.U0 >= 0.0 && r.U1 <= 1.0 && r.V0 >= 0.0 && r.V1 <= 1.0 && r.U0 < r.U1 && r.V0 < r.V1);
      parameterArea += (r.U1 - r.U0) * (r.V1 - r.V0);
      for (size_t b = a + 1; b < rects.size(); ++b)
      {
        const UVRect& s = rects[b];
        const bool overlap = r.U0 < s.U1 && s.U0 < r.U1 && r.V0 < s.V1 && s.V0 < r.V1;
        ASSERT_FALSE(overlap) << "surface " << entry.first << ": patches " << a << " and " << b
                              << " overlap";
      }
    }
    EXPECT_NEAR(parameterArea, 1.0, 1e-12) << "surface " << entry.first;
  }
}

/// The sampled values of the criteria's functions over a patch, to check a verdict.
struct Sampled
{
  double HeightMin = INFINITY, HeightMax = -INFINITY;       // N_i . (Q_j - P_i)
  double FacingMin = INFINITY, FacingMax = -INFINITY;       // N_j . (Q_j - P_i)
  double DistanceMin = INFINITY, DistanceMax = -INFINITY;   // |Q_j - P_i|
  double ReceivingMin = INFINITY, ReceivingMax = -INFINITY; // N_i(u,v) . (Q_i - P_j)
};

void Extend(double value, double& lo, double& hi)
{
  lo = std::min(lo, value);
  hi = std::max(hi, value);
}

Sampled Sample(const PatchView& receiver, const PatchView& source)
{
  Sampled s;
  for (int b = 0; b < SamplesPerSide; ++b)
  {
    for (int a = 0; a < SamplesPerSide; ++a)
    {
      const double u = double(a) / (SamplesPerSide - 1);
      const double v = double(b) / (SamplesPerSide - 1);
      const glm::dvec3 q = source.Geometry->Evaluate(u, v);
      Extend(glm::dot(receiver.Normal, q - receiver.Point), s.HeightMin, s.HeightMax);
      Extend(glm::dot(source.Geometry->UnnormalizedNormal(u, v), q - receiver.Point),
        s.FacingMin,
        s.FacingMax);
      Extend(glm::length(q - receiver.Point), s.DistanceMin, s.DistanceMax);
      const glm::dvec3 r = receiver.Geometry->Evaluate(u, v);
      Extend(glm::dot(receiver.Geometry->UnnormalizedNormal(u, v), r - source.Point),
        s.ReceivingMin,
        s.ReceivingMax);
    }
  }
  return s;
}

/// Every verdict of AssessPair on every pair of the final patches holds at sampled points.
size_t ExpectSoundVerdicts(const IntervalSubdivision& subdivision,
  const std::vector<Patch>& patches,
  const SubdivisionSettings& settings)
{
  size_t verdicts = 0;
  std::vector<PatchView> views;
  for (const Patch& patch : patches)
  {
    views.push_back(subdivision.ViewOfPatch(patch));
  }
  const double tolShadow = settings.ToleranceOf(Criterion::SelfShadowing);
  const double tolContain = settings.ToleranceOf(Criterion::HemisphericalContainment);
  const double tolShape = settings.ToleranceOf(Criterion::SphericalShape);
  const double tolCharacter = settings.ToleranceOf(Criterion::Characterisability);
  for (size_t i = 0; i < views.size(); ++i)
  {
    for (size_t j = 0; j < views.size(); ++j)
    {
      if (i == j)
      {
        continue;
      }
      const PatchView& r = views[i];
      const PatchView& s = views[j];
      const PairAssessment verdict = AssessPair(r, s, settings);
      const Sampled sampled = Sample(r, s);
      const double d = glm::length(s.Point - r.Point);
      const double slack = 1e-9 * (1.0 + d * d);
      if (verdict.Relation == PairRelation::BelowHorizon)
      {
        EXPECT_LE(sampled.HeightMax, tolContain * d + slack) << i << " " << j;
        ++verdicts;
        continue;
      }
      if (verdict.Relation == PairRelation::BackFacing)
      {
        EXPECT_GE(sampled.FacingMin, -tolShadow * s.CentreNormalLength * d - slack)
          << i << " " << j;
        ++verdicts;
        continue;
      }
      if (verdict.Contained)
      {
        EXPECT_GE(sampled.HeightMin, -tolContain * d - slack) << i << " " << j;
        ++verdicts;
      }
      if (verdict.FrontFacing)
      {
        EXPECT_LE(sampled.FacingMax, tolShadow * s.CentreNormalLength * d + slack) << i << " " << j;
        ++verdicts;
      }
      if (verdict.Spherical)
      {
        if (s.Diffuse)
        {
          EXPECT_GE(sampled.DistanceMin, (1.0 - tolShape) * d - slack) << i << " " << j;
          EXPECT_LE(sampled.DistanceMax, (1.0 + tolShape) * d + slack) << i << " " << j;
        }
        else
        {
          EXPECT_LE(
            sampled.FacingMax - sampled.FacingMin, tolShape * s.CentreNormalLength * d + slack);
        }
        ++verdicts;
      }
      if (verdict.Characterised)
      {
        EXPECT_LE(sampled.ReceivingMax - sampled.ReceivingMin,
          tolCharacter * r.CentreNormalLength * d + slack)
          << i << " " << j;
        ++verdicts;
      }
    }
  }
  return verdicts;
}
}

TEST(IntervalSubdivision, PatchesTileEachSurfaceAndAreasAddUp)
{
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/teapot_room.scene");
  SubdivisionSettings settings;
  settings.MaxLevel = 3;
  const std::vector<Patch> patches = Subdivide(scene, settings);
  ASSERT_GT(patches.size(), scene.Surfaces.size());
  ExpectTiling(scene, patches);

  // Areas: the patches' areas add up to the area of their surface.
  std::vector<double> sums(scene.Surfaces.size(), 0.0);
  for (const Patch& patch : patches)
  {
    sums[static_cast<size_t>(patch.SurfaceIndex)] += patch.Area;
    EXPECT_EQ(patch.Point, patch.Geometry.Evaluate(0.5, 0.5));
  }
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    // The whole surface's area by a finer composite rule: 9 x 9 sub-squares.
    double reference = 0.0;
    for (int b = 0; b < 9; ++b)
    {
      for (int a = 0; a < 9; ++a)
      {
        reference += PatchArea(
          scene.Surfaces[s].Patch.SubPatch(a / 9.0, (a + 1) / 9.0, b / 9.0, (b + 1) / 9.0));
      }
    }
    EXPECT_NEAR(sums[s] / reference, 1.0, 1e-9) << "surface " << s;
  }
}

TEST(IntervalSubdivision, VerdictsHoldAtSampledPoints)
{
  // Both range methods, on the curved teapot room (mirror, phong and diffuse materials) and the
  // Cornell box (flat, with blocks).
  for (const char* name : { "teapot_room.scene", "cornell_box.scene" })
  {
    const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/") + name);
    for (RangeMethod method : { RangeMethod::Bernstein, RangeMethod::NaturalInterval })
    {
      SubdivisionSettings settings;
      settings.Method = method;
      settings.MaxLevel = 1;
      IntervalSubdivision subdivision(scene, settings);
      ASSERT_TRUE(subdivision.Run());
      const std::vector<Patch> patches = subdivision.Patches();
      const size_t verdicts = ExpectSoundVerdicts(subdivision, patches, settings);
      EXPECT_GT(verdicts, patches.size()) << name;
    }
  }
}

TEST(IntervalSubdivision, ParallelFacingQuadsNeedNoSplit)
{
  // Two 0.2 x 0.2 quads facing each other at distance 1: every criterion holds at the default
  // tolerance of 2% (the distance from one centre to the other quad varies by under 1%).
  const Scene scene = SceneOf({ Quad({ 0, 0, 0 }, { 0.2, 0, 0 }, { 0, 0.2, 0 }),
    Quad({ 0, 0, 1 }, { 0, 0.2, 0 }, { 0.2, 0, 0 }) });
  SubdivisionStatistics statistics;
  const std::vector<Patch> patches = Subdivide(scene, SubdivisionSettings(), &statistics);
  EXPECT_EQ(patches.size(), 2u);
  EXPECT_EQ(statistics.PairTests, 2u);
  EXPECT_EQ(statistics.Sweeps, 1);

  // Brought ten times closer, the distance form of the spherical shape criterion splits them.
  const Scene close = SceneOf({ Quad({ 0, 0, 0 }, { 0.2, 0, 0 }, { 0, 0.2, 0 }),
    Quad({ 0, 0, 0.1 }, { 0, 0.2, 0 }, { 0.2, 0, 0 }) });
  SubdivisionStatistics closeStatistics;
  EXPECT_GT(Subdivide(close, SubdivisionSettings(), &closeStatistics).size(), 2u);
  EXPECT_GT(closeStatistics.Splits[static_cast<size_t>(SplitReason::SphericalShape)], 0u);
}

TEST(IntervalSubdivision, DomeSplitsAlongItsSilhouette)
{
  // Paper Fig. 9: a doubly curved patch seen from a point near it, with self-shadowing alone.
  // The receiver is a small quad beside the dome facing it, at about half its height: its
  // centre sees the near flank of the dome and the back of the far one.
  const Scene scene = SceneOf({ Dome(), Quad({ 1.6, 0.05, 0.6 }, { 0, -0.1, 0 }, { 0, 0, 0.1 }) });
  SubdivisionSettings settings;
  settings.MaxLevel = 5;
  for (Criterion c : { Criterion::HemisphericalContainment,
         Criterion::SphericalShape,
         Criterion::Characterisability })
  {
    settings.Enabled[static_cast<int>(c)] = false;
  }
  IntervalSubdivision subdivision(scene, settings);
  ASSERT_TRUE(subdivision.Run());
  const std::vector<Patch> patches = subdivision.Patches();
  const glm::dvec3 eye = scene.Surfaces[1].Patch.Evaluate(0.5, 0.5);

  int shallowVisible = 0;
  int shallowBack = 0;
  int domePieces = 0;
  double shallowParameterArea = 0.0;
  for (const Patch& patch : patches)
  {
    if (patch.SurfaceIndex != 0)
    {
      continue;
    }
    ++domePieces;
    EXPECT_TRUE(patch.Reason == SplitReason::SelfShadowing) << SplitReasonName(patch.Reason);
    // The sign of f over the piece, sampled: negative where the eye sees the front.
    double lo = INFINITY;
    double hi = -INFINITY;
    for (int b = 0; b <= 8; ++b)
    {
      for (int a = 0; a <= 8; ++a)
      {
        const double f = glm::dot(patch.Geometry.UnnormalizedNormal(a / 8.0, b / 8.0),
          patch.Geometry.Evaluate(a / 8.0, b / 8.0) - eye);
        lo = std::min(lo, f);
        hi = std::max(hi, f);
      }
    }
    if (patch.Level < settings.MaxLevel)
    {
      shallowVisible += hi < 0 ? 1 : 0;
      shallowBack += lo > 0 ? 1 : 0;
      shallowParameterArea +=
        (patch.Domain.U1 - patch.Domain.U0) * (patch.Domain.V1 - patch.Domain.V0);
    }
    // A piece the silhouette crosses was split as far as allowed, unless the criterion holds
    // within its tolerance (a sliver of back side seen nearly edge-on).
    if (lo < 0 && hi > 0 && patch.Level < settings.MaxLevel)
    {
      const PairAssessment verdict = AssessPair(
        subdivision.ViewOfPatch(patches.back()), subdivision.ViewOfPatch(patch), settings);
      EXPECT_TRUE(verdict.FrontFacing || verdict.Relation == PairRelation::BackFacing)
        << "a piece with a silhouette was not split: level " << patch.Level;
    }
  }
  std::cout << "dome: " << domePieces
            << " pieces; fully visible / back-facing below the deepest level: " << shallowVisible
            << " / " << shallowBack << ", parameter area " << shallowParameterArea << "\n";
  EXPECT_GT(shallowVisible, 0) << "no large fully visible piece";
  EXPECT_GT(shallowBack, 0) << "no large fully back-facing piece";
  EXPECT_GT(shallowParameterArea, 0.2)
    << "too little of the dome resolved before the deepest level";
  // Adaptive, not uniform: uniform refinement to MaxLevel gives 3^5 = 243 pieces.
  EXPECT_LT(domePieces, 243);
  EXPECT_GT(subdivision.Statistics().Splits[static_cast<size_t>(SplitReason::SelfShadowing)], 0u);
}

TEST(IntervalSubdivision, BernsteinNeedsNoMorePatchesThanNaturalIntervals)
{
  // The teapot room at MaxLevel 3 (the default level 5 takes minutes with natural intervals;
  // the benchmark program reports both counts at the default settings).
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/teapot_room.scene");
  SubdivisionSettings settings;
  settings.MaxLevel = 3;
  const size_t bernstein = Subdivide(scene, settings).size();
  settings.Method = RangeMethod::NaturalInterval;
  const size_t natural = Subdivide(scene, settings).size();
  std::cout << "teapot room, MaxLevel 3: Bernstein " << bernstein << " patches, natural interval "
            << natural << "\n";
  EXPECT_LE(bernstein, natural);
}

TEST(IntervalSubdivision, LimitsHold)
{
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene");
  SubdivisionSettings settings;
  settings.MaxLevel = 2;
  for (const Patch& patch : Subdivide(scene, settings))
  {
    EXPECT_LE(patch.Level, 2);
  }
  settings.MaxLevel = 0;
  EXPECT_EQ(Subdivide(scene, settings).size(), scene.Surfaces.size());

  // A grid of one cell per hemisphere allows no split of anything smaller than a hemisphere.
  settings.MaxLevel = 5;
  settings.ThetaBins = 1;
  settings.PhiBins = 1;
  const std::vector<Patch> coarse = Subdivide(scene, settings);
  settings.ThetaBins = 32;
  settings.PhiBins = 128;
  EXPECT_LT(coarse.size(), Subdivide(scene, settings).size());
}

// MinPatchSize: no patch is split once its box's diagonal is at most that fraction of the
// scene's. Every criterion asks for splits in the Cornell box down to MaxLevel, so the patches
// of each flat surface are what splitting its longer side in three until the pieces are that
// small gives (computed here from the surfaces' edges): 27 x 27 on a wall, 9 x 9 on a block's
// face, where MaxLevel 5 alone gives every surface 243.
TEST(IntervalSubdivision, MinPatchSizeSpendsPointsBySize)
{
  const auto CornerPolygon = [](const BezierPatch& patch)
  {
    return std::vector<glm::dvec3>{
      patch.Evaluate(0, 0), patch.Evaluate(1, 0), patch.Evaluate(1, 1), patch.Evaluate(0, 1)
    };
  };
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene");
  SubdivisionSettings settings;
  settings.MaxLevel = 8;
  settings.MinPatchSize = 0.05;
  glm::dvec3 lower;
  glm::dvec3 upper;
  scene.Bounds(lower, upper);
  const double limit = settings.MinPatchSize * glm::length(upper - lower);
  std::map<int, size_t> made;
  for (const Patch& patch : Subdivide(scene, settings))
  {
    ++made[patch.SurfaceIndex];
  }
  size_t walls = 0;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const std::vector<glm::dvec3> corners = CornerPolygon(scene.Surfaces[s].Patch);
    // Each surface is an axis-aligned rectangle: its box's diagonal is the rectangle's.
    double alongU = glm::length(corners[1] - corners[0]);
    double alongV = glm::length(corners[3] - corners[0]);
    size_t expected = 1;
    for (int level = 0; level < settings.MaxLevel && std::hypot(alongU, alongV) > limit; ++level)
    {
      (alongU >= alongV ? alongU : alongV) /= 3.0;
      expected *= 3;
    }
    EXPECT_EQ(made[static_cast<int>(s)], expected) << "surface " << s;
    walls += expected == 729 ? 1 : 0;
  }
  EXPECT_EQ(walls, 5u); // floor, ceiling and three walls
  settings.MinPatchSize = 0.0;
  settings.MaxLevel = 5;
  EXPECT_EQ(Subdivide(scene, settings).size(), 243 * scene.Surfaces.size());
}

TEST(IntervalSubdivision, ResultDoesNotDependOnThreads)
{
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/teapot_room.scene");
  SubdivisionSettings settings;
  settings.MaxLevel = 3;
  SubdivisionStatistics one;
  SubdivisionStatistics three;
  const std::vector<Patch> a = Subdivide(scene, settings, &one, SequentialFor);
  const std::vector<Patch> b = Subdivide(scene, settings, &three, ThreadedFor(3));
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(a[k].SurfaceIndex, b[k].SurfaceIndex);
    EXPECT_EQ(a[k].Domain.U0, b[k].Domain.U0);
    EXPECT_EQ(a[k].Domain.V1, b[k].Domain.V1);
    EXPECT_EQ(a[k].Reason, b[k].Reason);
  }
  EXPECT_EQ(one.PairTests, three.PairTests);
}

TEST(IntervalSubdivision, BadSettingsAreRejected)
{
  const Scene scene = SceneOf({ Quad({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }) });
  SubdivisionSettings settings;
  settings.MaxLevel = -1;
  EXPECT_THROW(IntervalSubdivision(scene, settings), std::invalid_argument);
  settings = SubdivisionSettings();
  settings.Tolerance[2] = -0.1;
  EXPECT_NE(settings.Problem().find("SphericalShapeTolerance"), std::string::npos);
  EXPECT_THROW(IntervalSubdivision(scene, settings), std::invalid_argument);
  settings = SubdivisionSettings();
  settings.ThetaBins = 0;
  EXPECT_THROW(IntervalSubdivision(scene, settings), std::invalid_argument);
  for (const double size : { -0.1, 1.0 })
  {
    settings = SubdivisionSettings();
    settings.MinPatchSize = size;
    EXPECT_NE(settings.Problem().find("MinPatchSize"), std::string::npos);
    EXPECT_THROW(IntervalSubdivision(scene, settings), std::invalid_argument);
  }
  // The scene setting is checked as it is read (a scene file's settings block or --set).
  EXPECT_THROW(OverrideSetting(SceneSettings(), "min_patch_size=1"), InputError);
  EXPECT_THROW(OverrideSetting(SceneSettings(), "min_patch_size=-0.01"), InputError);
  EXPECT_THROW(OverrideSetting(SceneSettings(), "min_patch_size=\"a\""), InputError);
  EXPECT_EQ(OverrideSetting(SceneSettings(), "min_patch_size=0.05").MinPatchSize, 0.05);
}

TEST(IntervalSubdivision, AbortKeepsTheLastCompleteSweep)
{
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene");
  IntervalSubdivision subdivision(scene, SubdivisionSettings());
  int calls = 0;
  EXPECT_FALSE(subdivision.Run(
    [&](double)
    {
      ++calls;
      return false;
    }));
  EXPECT_EQ(calls, 1);
  // Aborted in the first sweep: Q is still the surfaces.
  EXPECT_EQ(subdivision.Patches().size(), scene.Surfaces.size());
}
