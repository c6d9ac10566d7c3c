// SPDX-License-Identifier: BSD-3-Clause
// Textures (paper §5.4): PNG decoding (8- and 16-bit, grey and RGB, sRGB and linear), the
// orientation of (u, v) over the image, the bilinear reconstruction of the render and the exact
// rectangle means of the propagation; and the scene keys transmittance and texture.
#include "scene/InputError.h"
#include "scene/SceneLoader.h"
#include "scene/Texture.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace sphcover;

namespace
{
const std::string Support = SPHCOVER_TEST_DATA_DIR "/bad/support/";

double Srgb(double c)
{
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
}

// grey_ramp.png: 4 x 2 grey, both rows 0, 85, 170, 255 (8-bit).
TEST(Texture, DecodesEightBitGreyAsSrgbOrLinear)
{
  const Texture srgb = Texture::Load(Support + "grey_ramp.png", TextureEncoding::Srgb);
  const Texture linear = Texture::Load(Support + "grey_ramp.png", TextureEncoding::Linear);
  ASSERT_EQ(srgb.Width(), 4);
  ASSERT_EQ(srgb.Height(), 2);
  const int codes[4] = { 0, 85, 170, 255 };
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 2; ++j)
    {
      EXPECT_NEAR(linear.Texel(i, j).x, codes[i] / 255.0, 1e-7);
      EXPECT_NEAR(srgb.Texel(i, j).y, Srgb(codes[i] / 255.0), 1e-7);
      EXPECT_EQ(srgb.Texel(i, j).x, srgb.Texel(i, j).z); // grey: the same in every band
    }
  }
}

// rgb16.png: 2 x 2, 16-bit RGB; the file's top row red, green; its bottom row blue, 32768 grey.
// v runs up the rows from the bottom, u across the columns from the left.
TEST(Texture, SixteenBitRgbWithVUpTheRows)
{
  const Texture t = Texture::Load(Support + "rgb16.png", TextureEncoding::Linear);
  ASSERT_EQ(t.Width(), 2);
  EXPECT_EQ(t.Texel(0, 1), glm::dvec3(1, 0, 0)); // top left
  EXPECT_EQ(t.Texel(1, 1), glm::dvec3(0, 1, 0)); // top right
  EXPECT_EQ(t.Texel(0, 0), glm::dvec3(0, 0, 1)); // bottom left
  EXPECT_NEAR(t.Texel(1, 0).x, 32768.0 / 65535.0, 1e-7);
  // At the texel centres the reconstruction is the texel; between them it is bilinear.
  EXPECT_EQ(t.At(0.25, 0.75), glm::dvec3(1, 0, 0));
  EXPECT_EQ(t.At(0.0, 1.0), glm::dvec3(1, 0, 0)); // clamped to the edge texel
  const glm::dvec3 centre = t.At(0.5, 0.5);
  const glm::dvec3 mean = 0.25 * (t.Texel(0, 0) + t.Texel(1, 0) + t.Texel(0, 1) + t.Texel(1, 1));
  EXPECT_NEAR(centre.x, mean.x, 1e-7);
  EXPECT_NEAR(centre.z, mean.z, 1e-7);
}

// The rectangle mean against a brute-force integral of the texels as constant squares, for
// rectangles at random (fractions of texels included), and the limits of a thin rectangle.
TEST(Texture, RectangleMeanIsTheExactIntegral)
{
  const int w = 7;
  const int h = 5;
  std::mt19937 random(20261203);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<glm::vec3> texels(w * h);
  for (glm::vec3& t : texels)
  {
    t = glm::vec3(value(random), value(random), value(random));
  }
  const Texture texture(w, h, texels);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    double u0 = coordinate(random);
    double u1 = coordinate(random);
    double v0 = coordinate(random);
    double v1 = coordinate(random);
    if (u1 < u0)
    {
      std::swap(u0, u1);
    }
    if (v1 < v0)
    {
      std::swap(v0, v1);
    }
    glm::dvec3 integral(0.0);
    for (int j = 0; j < h; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const double du = std::max(0.0, std::min(u1, (i + 1.0) / w) - std::max(u0, double(i) / w));
        const double dv = std::max(0.0, std::min(v1, (j + 1.0) / h) - std::max(v0, double(j) / h));
        integral += du * dv * glm::dvec3(texture.Texel(i, j));
      }
    }
    const glm::dvec3 expected = integral / ((u1 - u0) * (v1 - v0));
    const glm::dvec3 mean = texture.Mean(UVRect{ u0, u1, v0, v1 });
    for (int b = 0; b < 3; ++b)
    {
      EXPECT_NEAR(mean[b], expected[b], 1e-9) << "trial " << trial;
    }
  }
  // Inside one texel the mean is that texel; a rectangle of zero width is the limit (here
  // inside texel (3, 2) too).
  EXPECT_NEAR(
    texture.Mean(UVRect{ 3.2 / w, 3.7 / w, 2.1 / h, 2.9 / h }).y, texture.Texel(3, 2).y, 1e-6);
  EXPECT_NEAR(
    texture.Mean(UVRect{ 3.5 / w, 3.5 / w, 2.5 / h, 2.5 / h }).z, texture.Texel(3, 2).z, 1e-6);
  glm::dvec3 all(0.0);
  for (const glm::vec3& t : texels)
  {
    all += glm::dvec3(t);
  }
  EXPECT_NEAR(texture.Mean().x, all.x / (w * h), 1e-9);
}

TEST(Texture, RefusesBadSizesAndValues)
{
  EXPECT_THROW(Texture(0, 1, {}), std::invalid_argument);
  EXPECT_THROW(Texture(2, 1, { glm::vec3(0.5f) }), std::invalid_argument);
  EXPECT_THROW(Texture(1, 1, { glm::vec3(1.5f) }), std::invalid_argument);
  EXPECT_THROW(Texture(1, 1, { glm::vec3(NAN) }), std::invalid_argument);
  // A header of 100000 x 100000 is refused before any pixel memory is taken.
  try
  {
    Texture::Load(Support + "huge.png", TextureEncoding::Srgb);
    FAIL() << "huge.png was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("image too large"), std::string::npos) << e.what();
  }
}

// The scene keys: transmittance, texture (resolved relative to the scene's folder, read with the
// scene), texture_encoding; a pane is two one-sided surfaces.
TEST(Texture, SceneReadsTransmittanceAndTexture)
{
  const std::string text = R"({
  "version": 1,
  "materials": {
    "glass": {"type": "diffuse", "reflectance": [0.1, 0.1, 0.1], "transmittance": [0.8, 0.7, 0.9]},
    "tiles": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5], "texture": "rgb16.png",
              "texture_encoding": "linear"},
    "varnish": {"type": "phong", "diffuse": [0.5, 0.5, 0.5], "specular": [0.2, 0.2, 0.2],
                "exponent": 10, "texture": "grey_ramp.png"}
  },
  "surfaces": [
    {"name": "pane", "type": "bilinear", "material": "glass",
     "points": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]},
    {"name": "floor", "type": "bilinear", "material": "tiles",
     "points": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]]},
    {"name": "cap", "type": "bilinear", "material": "varnish",
     "points": [[0,1,0],[0,1,1],[1,1,1],[1,1,0]]}
  ]
})";
  const Scene scene = ParseScene(text, Support + "textured.scene");
  const Material& glass = scene.Materials[static_cast<size_t>(scene.FindMaterial("glass"))];
  EXPECT_EQ(glass.Transmittance, glm::dvec3(0.8, 0.7, 0.9));
  EXPECT_TRUE(glass.IsTransmitter());
  // The pane is two one-sided surfaces, the patch and its reversed copy, then the floor.
  ASSERT_EQ(scene.Surfaces.size(), 4u);
  EXPECT_NEAR(
    glm::dot(scene.Surfaces[0].Patch.Normal(0.5, 0.5), scene.Surfaces[1].Patch.Normal(0.5, 0.5)),
    -1.0,
    1e-12);
  EXPECT_FALSE(scene.Surfaces[0].TwoSided);
  EXPECT_FALSE(scene.Surfaces[2].TwoSided);
  const Material& tiles = scene.Materials[static_cast<size_t>(scene.FindMaterial("tiles"))];
  ASSERT_TRUE(tiles.DiffuseTexture);
  EXPECT_EQ(tiles.TextureFileEncoding, TextureEncoding::Linear);
  EXPECT_EQ(tiles.TextureFile, Support + "rgb16.png");
  EXPECT_EQ(tiles.DiffuseTexture->Texel(0, 1), glm::dvec3(1, 0, 0));
  const Material& varnish = scene.Materials[static_cast<size_t>(scene.FindMaterial("varnish"))];
  ASSERT_TRUE(varnish.DiffuseTexture);
  EXPECT_EQ(varnish.TextureFileEncoding, TextureEncoding::Srgb);
  EXPECT_NEAR(varnish.DiffuseTexture->Texel(1, 0).x, Srgb(85 / 255.0), 1e-7);
}

// The propagation's material of a patch: the diffuse reflectance times the texture's mean over
// the patch's rectangle (paper §5.4); untextured materials unchanged.
TEST(Texture, MaterialOverPatchTakesTheRectangleMean)
{
  Material material;
  material.Diffuse = glm::dvec3(0.8, 0.6, 0.4);
  EXPECT_EQ(MaterialOverPatch(material, UVRect{ 0.0, 0.5, 0.0, 1.0 }).Diffuse, material.Diffuse);
  material.DiffuseTexture = std::make_shared<const Texture>(
    Texture::Load(Support + "grey_ramp.png", TextureEncoding::Linear));
  // Left half of the ramp: columns 0 and 1, codes 0 and 85.
  const UVRect left{ 0.0, 0.5, 0.0, 1.0 };
  const glm::dvec3 expected = material.Diffuse * (0.5 * 85.0 / 255.0);
  const glm::dvec3 diffuse = MaterialOverPatch(material, left).Diffuse;
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_NEAR(diffuse[b], expected[b], 1e-7);
  }
}
