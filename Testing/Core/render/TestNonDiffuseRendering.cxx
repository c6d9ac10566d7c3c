// SPDX-License-Identifier: BSD-3-Clause
// The final rendering of non-diffuse surfaces (paper §5.3.1 with the interpolation of §3.4):
// white furnaces of mirror, phong and tabulated walls render uniform Le / (1 - a) in every
// pixel, and a flat mirror shows, pixel for pixel, what a camera at the mirrored position sees
// of the room.
#include "render/RadianceRenderer.h"

#include "CoverTestUtilities.h"
#include "cover/SphericalCover.h"
#include "distributed/RowShares.h"
#include "math/RankShare.h"
#include "propagation/LightPropagation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace sphcover;
using namespace sphcover_test;

namespace
{
/// The propagated solution of `patches` with one material per patch, ready to render: the
/// renderer casts against `visible` (all patches when empty) and has the directional part.
struct Solution
{
  std::vector<glm::dvec3> Exitant;
  DirectionalIllumination Directional;
};

Solution Propagate(const std::vector<Patch>& patches, const std::vector<Material>& materials)
{
  Solution solution;
  SphericalCover& cover = solution.Directional.Cover;
  EXPECT_TRUE(cover.Build(patches));
  {
    LightPropagation propagation(cover, materials);
    std::vector<HemisphereFrame> frames;
    for (const Patch& patch : patches)
    {
      frames.push_back(HemisphereFrame::OfPatch(patch));
    }
    propagation.SetFrames(frames);
    PropagationSettings settings;
    settings.ConvergenceTolerance = 1e-6;
    EXPECT_TRUE(propagation.Run(settings));
    for (size_t i = 0; i < patches.size(); ++i)
    {
      solution.Exitant.push_back(propagation.ExitantRadiance(i));
    }
    solution.Directional.IncidentRadiance = propagation.IncidentRadiances();
    solution.Directional.Frames = std::move(frames);
  }
  solution.Directional.Materials = materials;
  return solution;
}

Material WithEmission(Material m, const glm::dvec3& le)
{
  m.Emission = le;
  return m;
}
}

TEST(NonDiffuseRendering, WhiteFurnacesOfMirrorPhongAndTabulatedWallsRenderUniform)
{
  // Walls that all emit Le and reflect with one directional albedo a fill the enclosure with
  // radiance Le / (1 - a) in every direction, whatever the BRDF's shape; so every pixel of a
  // camera inside shows it. Without the directional part (§5.3.1) a mirror wall would show Le
  // only and a phong wall Le + k_d E.
  const glm::dvec3 le(1.0);
  Material mirror;
  mirror.Type = MaterialType::Mirror;
  mirror.Specular = glm::dvec3(0.3, 0.6, 0.8);
  Material phong;
  phong.Type = MaterialType::Phong;
  phong.Diffuse = glm::dvec3(0.2, 0.3, 0.0);
  phong.Specular = glm::dvec3(0.1, 0.3, 0.8);
  phong.PhongExponent = 20.0;
  struct Case
  {
    const char* Scene;
    Material Walls;
    glm::dvec3 Albedo;
  };
  std::vector<Case> cases = {
    { "furnace_box.scene", WithEmission(mirror, le), mirror.Specular },
    { "furnace_box.scene", WithEmission(phong, le), phong.Diffuse + phong.Specular },
    { "furnace_sphere.scene", WithEmission(phong, le), phong.Diffuse + phong.Specular },
    { "furnace_sphere.scene", WithEmission(mirror, le), mirror.Specular },
  };
  // The tabulated clay furnace as the scene file gives it (albedo of Data/brdf/clay.brdf.csv).
  const Scene clay = LoadSceneFile(ScenePath("furnace_clay.scene"));
  cases.push_back({ "furnace_clay.scene", clay.Materials.front(), glm::dvec3(0.75, 0.55, 0.35) });
  for (const Case& c : cases)
  {
    const Scene scene = LoadSceneFile(ScenePath(c.Scene));
    // Level 3 for the mirrors even under the sanitizers (level 2 elsewhere, for time): at level
    // 2 the mirror sphere renders 4.9 % off at grazing views, a known limit of following the
    // reflected ray on a coarse curved mirror (its grazing rays meet the back of the sphere's own
    // chords beyond PassOwnBackNear's reach and fall back to the stored value;
    // Documentation/notes/reflectance.md, 2026-12-07).
    const bool mirrorWalls = c.Walls.Type == MaterialType::Mirror;
    const std::vector<Patch> patches = SplitScene(scene, Sanitized && !mirrorWalls ? 2 : 3);
    Solution solution = Propagate(patches, std::vector<Material>(patches.size(), c.Walls));
    RadianceRenderer renderer(
      patches, CharacteristicPointInterpolator::OfPatches(patches), solution.Exitant);
    renderer.SetDirectionalIllumination(std::move(solution.Directional));
    ASSERT_FALSE(scene.Cameras.empty());
    Camera camera = scene.Cameras.front();
    camera.Width = 40;
    camera.Height = 30;
    RenderSettings settings;
    settings.SamplesPerPixel = 4;
    RenderedImage image;
    ASSERT_TRUE(renderer.Render(camera, settings, image));
    const glm::dvec3 expected = le / (glm::dvec3(1.0) - c.Albedo);
    double worst = 0.0;
    for (size_t p = 0; p < image.SurfaceId.size(); ++p)
    {
      ASSERT_GE(image.SurfaceId[p], 0) << c.Scene << ": pixel " << p << " sees nothing";
      for (int b = 0; b < 3; ++b)
      {
        worst = std::max(worst, std::fabs(image.Radiance[3 * p + b] / expected[b] - 1.0));
      }
    }
    std::printf("[ Furnace  ] %s, %s walls: largest |pixel / (Le / (1 - a)) - 1| = %.1e\n",
      c.Scene,
      MaterialTypeName(c.Walls.Type),
      worst);
    EXPECT_LT(worst, 0.01) << c.Scene << " " << MaterialTypeName(c.Walls.Type);
  }
}

TEST(NonDiffuseRendering, FlatMirrorShowsTheViewOfTheMirroredCamera)
{
  // The Cornell box closed by a white front wall (z = 0), its back wall (z = 559.2) an ideal
  // mirror of k_s = 0.9. A camera inside looking at the mirror sees k_s times what the camera
  // mirrored through the plane z = 559.2 sees of the room (rendered with the mirror's patches
  // left out, so that it looks through the plane; its image is the first one flipped left to
  // right). Paper §3.5.1: a mirror's I toward the eye is k_s e(theta_r, phi_r - pi), the
  // radiance arriving at the visible point from the mirror direction, which is the radiance
  // toward it of the point its reflected ray meets: with one sample per pixel (its centre) the
  // two cameras' rays are the same lines, so each pixel is k_s times its mirrored pixel up to
  // the rays' single precision, the shading's edges (the blocks' outlines, the light's
  // shadows) as sharp as in the direct view. Taking instead the mirror cell of the stencil's
  // characteristic points' E (each seeing the room from its own position, up to half a patch
  // away) blurs and doubles the image: 9.5 % RMS over 8 x 8-pixel blocks, 3 % off in the mean,
  // at this 12 x 12 split of the mirror.
  Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  int back = -1;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    if (scene.SurfaceNames[static_cast<size_t>(scene.Surfaces[s].NameIndex)] == "back_wall")
    {
      back = static_cast<int>(s);
    }
  }
  ASSERT_GE(back, 0);
  scene.SurfaceNames.push_back("front_wall");
  scene.Surfaces.emplace_back(
    Parallelogram(
      glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(556.0, 0.0, 0.0), glm::dvec3(0.0, 548.8, 0.0)),
    static_cast<int>(scene.SurfaceNames.size() - 1),
    scene.Surfaces[static_cast<size_t>(back)].MaterialIndex);
  std::vector<Patch> patches;
  for (size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const int split = static_cast<int>(s) == back ? 12 : 4;
    AppendSplit(patches, scene.Surfaces[s].Patch, static_cast<int>(s), split, split);
  }
  std::vector<Material> materials = LightPropagation::MaterialsOfPatches(scene, patches);
  const double ks = 0.9;
  std::vector<Patch> withoutMirror;
  for (size_t i = 0; i < patches.size(); ++i)
  {
    if (patches[i].SurfaceIndex == back)
    {
      materials[i] = Material();
      materials[i].Type = MaterialType::Mirror;
      materials[i].Specular = glm::dvec3(ks);
    }
    else
    {
      withoutMirror.push_back(patches[i]);
    }
  }
  Solution solution = Propagate(patches, materials);
  Solution copy;
  copy.Exitant = solution.Exitant;
  RadianceRenderer viewer(
    patches, CharacteristicPointInterpolator::OfPatches(patches), solution.Exitant);
  viewer.SetDirectionalIllumination(std::move(solution.Directional));
  const RadianceRenderer mirrored(
    withoutMirror, CharacteristicPointInterpolator::OfPatches(patches), copy.Exitant);

  Camera camera;
  camera.Position = glm::dvec3(150.0, 300.0, 100.0);
  camera.FocalPoint = glm::dvec3(150.0, 300.0, 559.2);
  camera.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
  camera.ViewAngle = 26.0; // the mirror fills the view, past the tall block
  camera.Width = 48;
  camera.Height = 48;
  // Mirrored through z = 559.2: the image is the first one flipped left to right.
  Camera image = camera;
  image.Position.z = 2.0 * 559.2 - camera.Position.z;
  image.FocalPoint.z = 2.0 * 559.2 - camera.FocalPoint.z;
  RenderSettings settings;
  settings.SamplesPerPixel = 1;
  RenderedImage seen;
  RenderedImage reference;
  ASSERT_TRUE(viewer.Render(camera, settings, seen));
  ASSERT_TRUE(mirrored.Render(image, settings, reference));

  // Per pixel; a pixel whose two rays part at an edge by rounding (one meets a block's side,
  // the other the floor) may differ wholly, so a few are allowed.
  int differing = 0;
  double worstOther = 0.0;
  double contrast = 0.0;
  double darkest = 1e300;
  for (int j = 0; j < camera.Height; ++j)
  {
    for (int i = 0; i < camera.Width; ++i)
    {
      const size_t p = static_cast<size_t>(j * camera.Width + i);
      const size_t q = static_cast<size_t>(j * camera.Width + (camera.Width - 1 - i));
      ASSERT_EQ(seen.SurfaceId[p], back) << "pixel " << i << ", " << j << " misses the mirror";
      double worst = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double expected = ks * reference.Radiance[3 * q + c];
        worst = std::max(worst, std::fabs(seen.Radiance[3 * p + c] - expected) / expected);
        contrast = std::max(contrast, expected);
        darkest = std::min(darkest, expected);
      }
      if (worst > 1e-4)
      {
        ++differing;
      }
      else
      {
        worstOther = std::max(worstOther, worst);
      }
    }
  }
  std::printf("[ Mirror   ] %d of %d pixels differ from k_s x the mirrored camera's by more "
              "than 1e-4 (largest of the others %.1e); the image spans %.3g to %.3g\n",
    differing,
    camera.Width * camera.Height,
    worstOther,
    darkest,
    contrast);
  // The image is not flat: sharp features are there to be blurred.
  EXPECT_GT(contrast, 3.0 * darkest);
  EXPECT_LE(differing, camera.Width * camera.Height / 100);
}

TEST(NonDiffuseRendering, DirectionalPartFromSharesOfTheCoverGivesTheWholeCoversImage)
{
  // A solution kept in pieces: each rank holds the rows of its points r, r + K, ... and their
  // regions' incident radiance. The view's (point, cell) pairs (DirectionalPairs), each
  // evaluated by the rank that holds its point's row (DirectionalValues of its share) and
  // rendered from the table, give the image of the whole cover bit for bit: the Cornell box
  // with a glossy back wall and mirror blocks.
  const Scene scene = LoadSceneFile(ScenePath("cornell_box.scene"));
  const std::vector<Patch> patches = SplitScene(scene, 2);
  std::vector<Material> materials = LightPropagation::MaterialsOfPatches(scene, patches);
  for (size_t i = 0; i < patches.size(); ++i)
  {
    const std::string& name = scene.SurfaceNames[static_cast<size_t>(
      scene.Surfaces[static_cast<size_t>(patches[i].SurfaceIndex)].NameIndex)];
    if (name == "back_wall")
    {
      materials[i].Type = MaterialType::Phong;
      materials[i].Diffuse *= 0.5;
      materials[i].Specular = glm::dvec3(0.3);
      materials[i].PhongExponent = 30.0;
    }
    else if (name.find("block") != std::string::npos)
    {
      materials[i] = Material();
      materials[i].Type = MaterialType::Mirror;
      materials[i].Specular = glm::dvec3(0.8);
    }
  }
  Solution solution = Propagate(patches, materials);
  // Each rank's share: its rows of the cover and their regions' incident radiance.
  const SphericalCover& cover = solution.Directional.Cover;
  const uint64_t cells = static_cast<uint64_t>(cover.Grid().CellCount());
  const auto shareOf = [&solution, &cover](int rank, int ranks)
  {
    const std::vector<size_t> receivers = RankShare::ItemsOf(rank, ranks, cover.PatchCount());
    DirectionalIllumination share;
    share.Cover = RowShares::RowsOf(cover, receivers);
    for (const size_t e : RowShares::KeptEntries(cover, receivers))
    {
      share.IncidentRadiance.push_back(solution.Directional.IncidentRadiance[e]);
    }
    share.Frames = solution.Directional.Frames;
    share.Materials = solution.Directional.Materials;
    return share;
  };
  std::vector<std::vector<DirectionalIllumination>> shares(4);
  for (const int ranks : { 2, 3 })
  {
    for (int r = 0; r < ranks; ++r)
    {
      shares[static_cast<size_t>(ranks)].push_back(shareOf(r, ranks));
    }
  }
  const CharacteristicPointInterpolator layout =
    CharacteristicPointInterpolator::OfPatches(patches);
  RadianceRenderer whole(patches, layout, solution.Exitant);
  whole.SetDirectionalIllumination(std::move(solution.Directional));
  ASSERT_FALSE(scene.Cameras.empty());
  Camera camera = scene.Cameras.front();
  camera.Width = 40;
  camera.Height = 30;
  RenderSettings settings;
  settings.SamplesPerPixel = 2;
  RenderedImage reference;
  ASSERT_TRUE(whole.Render(camera, settings, reference));
  const std::vector<uint64_t> pairs = whole.DirectionalPairs(camera, settings, ThreadedFor(2));
  ASSERT_GT(pairs.size(), 100u);
  ASSERT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));

  ASSERT_EQ(whole.DirectionalCellCount(), cells);
  for (const int ranks : { 2, 3 })
  {
    SCOPED_TRACE(testing::Message() << ranks << " ranks");
    RadianceRenderer::DirectionalValueTable table;
    table.Keys = pairs;
    table.Values.resize(pairs.size());
    std::vector<std::unique_ptr<RadianceRenderer>> renderers;
    for (int r = 0; r < ranks; ++r)
    {
      renderers.push_back(std::make_unique<RadianceRenderer>(patches, layout, solution.Exitant));
      renderers.back()->SetDirectionalIllumination(
        std::move(shares[static_cast<size_t>(ranks)][static_cast<size_t>(r)]));
      std::vector<uint64_t> own;
      std::vector<size_t> at;
      for (size_t k = 0; k < pairs.size(); ++k)
      {
        if ((pairs[k] / cells) % static_cast<uint64_t>(ranks) == static_cast<uint64_t>(r))
        {
          own.push_back(pairs[k]);
          at.push_back(k);
        }
      }
      const std::vector<glm::dvec3> values = renderers.back()->DirectionalValues(own);
      for (size_t k = 0; k < own.size(); ++k)
      {
        table.Values[at[k]] = values[k];
      }
    }
    RenderedImage image;
    ASSERT_TRUE(renderers.front()->Render(camera, settings, table, image, ThreadedFor(2)));
    EXPECT_EQ(image.Radiance, reference.Radiance);
    EXPECT_EQ(image.Depth, reference.Depth);
    EXPECT_EQ(image.SurfaceId, reference.SurfaceId);
    // Its own share alone (the other ranks' points read as zero) is not the image: the test
    // sees the directional part.
    RenderedImage alone;
    ASSERT_TRUE(renderers.front()->Render(camera, settings, alone));
    EXPECT_NE(alone.Radiance, reference.Radiance);
  }
  RadianceRenderer::DirectionalValueTable lacking;
  lacking.Keys.assign(pairs.begin() + 1, pairs.end());
  lacking.Values.assign(lacking.Keys.size(), glm::dvec3(0.0));
  RenderedImage image;
  EXPECT_THROW(whole.Render(camera, settings, lacking, image), std::runtime_error);
  size_t diffuse = 0;
  while (materials[diffuse].Type != MaterialType::Diffuse)
  {
    ++diffuse;
  }
  EXPECT_THROW(whole.DirectionalValues({ diffuse * cells }), std::invalid_argument);
}
