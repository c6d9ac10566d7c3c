// SPDX-License-Identifier: BSD-3-Clause
// The .bpt reader and the .scene loader of Core: formats (CRLF, tabs, exponent notation),
// the geometry conventions of Data/scenes/FORMAT.md (point order, front side, transforms, flip),
// defaults, and located error messages.
#include "scene/BptReader.h"
#include "scene/InputError.h"
#include "scene/MeshFileCheck.h"
#include "scene/SceneLoader.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

using namespace sphcover;

namespace
{
std::vector<BezierPatch> ParseText(const std::string& text)
{
  std::istringstream in(text);
  return ParseBpt(in, "test.bpt");
}

/// The InputError message the callable throws, or "" if it does not throw.
template<typename F>
std::string ErrorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return std::string();
}

Scene Parse(const std::string& text, const MeshFaceReader& meshes = nullptr)
{
  return ParseScene(text, "/virtual/test.scene", meshes);
}

const char* QuadScene = R"({
  "version": 1,
  "materials": {"white": {"type": "diffuse", "reflectance": [0.5, 0.6, 0.7]}},
  "surfaces": [{"name": "quad", "type": "bilinear", "material": "white",
                "points": [[0,0,0],[2,0,0],[2,1,0],[0,1,0]] %EXTRA% }]
})";

Scene QuadWith(const std::string& extra)
{
  std::string text = QuadScene;
  text.replace(text.find("%EXTRA%"), 7, extra);
  return Parse(text);
}
}

TEST(BptReader, AcceptsCrLfTabsAndExponentNotation)
{
  const std::string text = "1\r\n1\t1\r\n0 0 0\r\n\t1.0E0 0 0\r\n0 1e0 0\r\n  1 1 -1.07143E-4\r\n";
  const auto patches = ParseText(text);
  ASSERT_EQ(patches.size(), 1u);
  EXPECT_EQ(patches[0].DegreeU(), 1);
  EXPECT_DOUBLE_EQ(patches[0].ControlPoint(1, 0).x, 1.0);
  EXPECT_DOUBLE_EQ(patches[0].ControlPoint(1, 1).z, -1.07143e-4);
}

TEST(BptReader, ControlPointsAreUFastest)
{
  // Degree (2,1): 3 points along u per row.
  const auto patches = ParseText("1\n2 1\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 1\n");
  ASSERT_EQ(patches.size(), 1u);
  EXPECT_EQ(patches[0].DegreeU(), 2);
  EXPECT_EQ(patches[0].DegreeV(), 1);
  EXPECT_EQ(patches[0].ControlPoint(2, 1), glm::dvec3(2, 1, 1));
  EXPECT_EQ(patches[0].ControlPoint(1, 0), glm::dvec3(1, 0, 0));
}

TEST(BptReader, ErrorsNameTheLineAndProblem)
{
  EXPECT_EQ(ErrorOf([] { ParseText("1\n1 1\n0 0 0\n1 0 0\n0 1 0\n"); }),
    "test.bpt: line 5: unexpected end of file (expected control point coordinate)");
  EXPECT_EQ(ErrorOf([] { ParseText("1\n1 1\n0 0 0\n1 x 0\n0 1 0\n1 1 0\n"); }),
    "test.bpt: line 4: expected a number (control point coordinate), got 'x'");
  EXPECT_EQ(ErrorOf([] { ParseText("1\n1 1\n0 0 0\n1 nan 0\n0 1 0\n1 1 0\n"); }),
    "test.bpt: line 4: not a finite number (control point coordinate): 'nan'");
  EXPECT_NE(
    ErrorOf([] { ParseText("1\n16 1\n"); }).find("degree must be in [1, 15]"), std::string::npos);
  EXPECT_NE(ErrorOf([] { ParseText("1\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n7\n"); })
              .find("line 7: unexpected data after the last patch"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf([] { ParseText("0\n"); }).find("must be a positive integer"), std::string::npos);
  // A huge declared count is not trusted: it fails at the end of the data, without allocating.
  EXPECT_NE(ErrorOf([] { ParseText("999999999\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"); })
              .find("unexpected end of file"),
    std::string::npos);
  EXPECT_EQ(
    ErrorOf([] { ReadBptFile("/no/such/file.bpt"); }), "/no/such/file.bpt: cannot open file");
}

TEST(SceneLoader, BilinearPointOrderAndFrontSide)
{
  const Scene scene = QuadWith("");
  ASSERT_EQ(scene.Surfaces.size(), 1u);
  const BezierPatch& quad = scene.Surfaces[0].Patch;
  // Data/scenes/FORMAT.md: points are P(0,0), P(1,0), P(1,1), P(0,1).
  EXPECT_EQ(quad.ControlPoint(0, 0), glm::dvec3(0, 0, 0));
  EXPECT_EQ(quad.ControlPoint(1, 0), glm::dvec3(2, 0, 0));
  EXPECT_EQ(quad.ControlPoint(1, 1), glm::dvec3(2, 1, 0));
  EXPECT_EQ(quad.ControlPoint(0, 1), glm::dvec3(0, 1, 0));
  // Counter-clockwise seen from +z: the front is +z.
  EXPECT_NEAR(quad.Normal(0.5, 0.5).z, 1.0, 1e-15);
  EXPECT_EQ(scene.Materials[0].Diffuse, glm::dvec3(0.5, 0.6, 0.7));
  EXPECT_EQ(scene.SurfaceNames[0], "quad");
  EXPECT_FALSE(scene.Surfaces[0].TwoSided);
  // Defaults of the settings block, as Data/scenes/FORMAT.md's table states them.
  EXPECT_EQ(scene.Settings.ThetaBins, 32);
  EXPECT_EQ(scene.Settings.PhiBins, 128);
  EXPECT_EQ(scene.Settings.MaxLevel, 5);
  EXPECT_DOUBLE_EQ(scene.Settings.Tolerance, 0.02);
  EXPECT_DOUBLE_EQ(scene.Settings.MinPatchSize, 0.0);
}

TEST(SceneLoader, FlipReversesTheFront)
{
  const Scene scene = QuadWith(R"(, "flip": true, "two_sided": true)");
  EXPECT_NEAR(scene.Surfaces[0].Patch.Normal(0.5, 0.5).z, -1.0, 1e-15);
  EXPECT_TRUE(scene.Surfaces[0].TwoSided);
  // The surface itself is unchanged: same corners.
  EXPECT_EQ(scene.Surfaces[0].Patch.Evaluate(0.5, 0.5), glm::dvec3(1, 0.5, 0));
}

TEST(SceneLoader, TransformScalesThenRotatesXYZThenTranslates)
{
  const Scene scene =
    QuadWith(R"(, "transform": {"scale": 2, "rotate": [0, 0, 90], "translate": [10, 0, 0]})");
  const BezierPatch& quad = scene.Surfaces[0].Patch;
  // (2,0,0) -> scale (4,0,0) -> rotate 90 about z (0,4,0) -> translate (10,4,0).
  EXPECT_NEAR(glm::length(quad.ControlPoint(1, 0) - glm::dvec3(10, 4, 0)), 0.0, 1e-12);
  EXPECT_NEAR(quad.Normal(0.5, 0.5).z, 1.0, 1e-12);

  const Scene turned = QuadWith(R"(, "transform": {"rotate": [90, 0, 0]})");
  // Rotating +z by 90 degrees about x gives -y.
  EXPECT_NEAR(turned.Surfaces[0].Patch.Normal(0.5, 0.5).y, -1.0, 1e-12);
}

TEST(SceneLoader, MirroringTransformKeepsTheFront)
{
  // A mirror image in x keeps the quad in the z = 0 plane; its front must stay +z.
  const Scene scene = QuadWith(R"(, "transform": {"scale": [-1, 1, 1]})");
  EXPECT_NEAR(scene.Surfaces[0].Patch.Normal(0.5, 0.5).z, 1.0, 1e-15);
  EXPECT_NEAR(scene.Surfaces[0].Patch.Evaluate(0.5, 0.5).x, -1.0, 1e-15);
}

TEST(SceneLoader, MeshFacesBecomeBilinearPatches)
{
  // The loader checks that the file exists before it hands it to the mesh reader, which is
  // faked here: any existing file will do.
  const std::string text =
    R"({"version": 1, "materials": {"m": {"type": "diffuse", "reflectance": [1,1,1]}},
    "surfaces": [{"name": "part", "type": "mesh", "file": ")" SPHCOVER_DATA_DIR
    R"(/models/cornell_box/cbox_floor.obj", "material": "m"}]})";
  const MeshFaceReader fake = [](const std::string&)
  {
    return std::vector<MeshFace>{ { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
      { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } } };
  };
  const Scene scene = Parse(text, fake);
  ASSERT_EQ(scene.Surfaces.size(), 2u);
  const Surface& triangle = scene.Surfaces[0];
  EXPECT_TRUE(triangle.IsTriangle);
  EXPECT_EQ(triangle.Patch.ControlPoint(1, 1), glm::dvec3(0, 1, 0));
  EXPECT_EQ(triangle.Patch.ControlPoint(0, 1), glm::dvec3(0, 1, 0));
  // Right-hand rule of (0,0,0), (1,0,0), (0,1,0): +z, also at the collapsed edge.
  EXPECT_NEAR(triangle.Patch.Normal(0.5, 1.0).z, 1.0, 1e-12);
  EXPECT_FALSE(scene.Surfaces[1].IsTriangle);
  EXPECT_EQ(scene.Surfaces[1].Patch.ControlPoint(1, 1), glm::dvec3(1, 1, 1));
  EXPECT_EQ(scene.SurfaceNames.size(), 1u);
  EXPECT_EQ(scene.Surfaces[1].NameIndex, 0);

  const MeshFaceReader pentagon = [](const std::string&)
  {
    return std::vector<MeshFace>{
      { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0.5, 2, 0 }, { 0, 1, 0 } }
    };
  };
  EXPECT_NE(
    ErrorOf([&] { Parse(text, pentagon); }).find("face 1: only triangles and quads are supported"),
    std::string::npos);
  EXPECT_NE(ErrorOf([&] { Parse(text); }).find("mesh surfaces need the VTK scene reader"),
    std::string::npos);
}

TEST(SceneLoader, ErrorsNameTheJsonPointer)
{
  EXPECT_EQ(ErrorOf([] { QuadWith(R"(, "flip": 1)"); }),
    "/virtual/test.scene: /surfaces/0/flip: expected a boolean");
  EXPECT_EQ(ErrorOf([] { QuadWith(R"(, "colour": 1)"); }),
    "/virtual/test.scene: /surfaces/0/colour: unknown key 'colour'");
  EXPECT_EQ(ErrorOf([] { QuadWith(R"(, "transform": {"rotate": [0, "x", 0]})"); }),
    "/virtual/test.scene: /surfaces/0/transform/rotate/1: expected a number");
  EXPECT_EQ(ErrorOf([] { Parse("{\n  \"materials\": {},\n  \"surfaces\": [,]\n}"); }).substr(0, 59),
    "/virtual/test.scene: line 3, column 16: JSON syntax error: ");
  EXPECT_EQ(ErrorOf([] { Parse(R"({"version": 1, "materials": {}, "surfaces": []})"); }),
    "/virtual/test.scene: /surfaces: scene has no surfaces");
  EXPECT_EQ(
    ErrorOf(
      []
      {
        Parse(
          R"({"version": 1, "materials": {"a/b": {"type": "diffuse", "reflectance": [0.5, 1.5, 0]}},
              "surfaces": []})");
      }),
    "/virtual/test.scene: /materials/a~1b/reflectance/1: must be in [0, 1], got 1.5");
  EXPECT_EQ(ErrorOf(
              []
              {
                Parse(R"({"version": 1, "materials": {}, "surfaces": [{"name": "x",
      "type": "bezier", "degree": [2, 1], "material": "m", "points": []}]})");
              }),
    "/virtual/test.scene: /surfaces/0/material: unknown material 'm'");
  // JSON has no NaN or infinity; a number beyond the double range is located by line, column.
  const std::string overflow = ErrorOf(
    [] {
      Parse("{\"materials\": {\"m\": {\"type\": \"diffuse\",\n \"reflectance\": [0, 1e999, 0]}}}");
    });
  EXPECT_EQ(
    overflow.find("/virtual/test.scene: /materials/m/reflectance/1: not a finite number"), 0u)
    << overflow;
  EXPECT_NE(overflow.find("line 2, column 25"), std::string::npos) << overflow;
}

TEST(SceneLoader, ReadsSettingsAndCameras)
{
  const Scene scene =
    Parse(R"({"version": 1, "materials": {"m": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]}},
    "surfaces": [{"name": "q", "type": "bilinear", "material": "m",
                  "points": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}],
    "cameras": [{"name": "c", "position": [0,0,5], "focal_point": [0,0,0], "view_up": [0,1,0],
                 "view_angle": 30, "width": 64, "height": 48}],
    "settings": {"theta_bins": 16, "phi_bins": 64, "max_level": 0, "tolerance": 0.1}})");
  EXPECT_EQ(scene.Settings.ThetaBins, 16);
  EXPECT_EQ(scene.Settings.PhiBins, 64);
  EXPECT_EQ(scene.Settings.MaxLevel, 0);
  EXPECT_DOUBLE_EQ(scene.Settings.Tolerance, 0.1);
  ASSERT_EQ(scene.Cameras.size(), 1u);
  EXPECT_EQ(scene.Cameras[0].Width, 64);
  EXPECT_EQ(scene.Cameras[0].Height, 48);
  EXPECT_EQ(scene.Materials[0].Type, MaterialType::Mirror);
  EXPECT_EQ(scene.Materials[0].Specular, glm::dvec3(0.9));
}

TEST(SceneLoader, ReadsTheLengthUnit)
{
  const std::string scene = R"({"version": 1, UNIT "materials": {"m": {"type": "diffuse",
    "reflectance": [0.5, 0.5, 0.5]}}, "surfaces": [{"name": "q", "type": "bilinear",
    "material": "m", "points": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})";
  auto with = [&scene](const std::string& unit)
  { return Parse(std::string(scene).replace(scene.find("UNIT"), 4, unit)); };
  EXPECT_EQ(with("").Unit.Name, "m"); // metres without a unit
  EXPECT_EQ(with("").Unit.Metres, 1.0);
  EXPECT_EQ(with(R"("unit": "mm",)").Unit.Metres, 0.001);
  EXPECT_EQ(with(R"("unit": "in",)").Unit.Metres, 0.0254);
  EXPECT_EQ(with(R"("unit": "ft",)").Unit.Name, "ft");
  EXPECT_EQ(with(R"("unit": "ft",)").Unit.Metres, 0.3048);
  // The Cornell box is measured in millimetres (its walls are 556 x 548.8 x 559.2).
  EXPECT_EQ(LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene").Unit.Name, "mm");
}

TEST(SceneLoader, ShippedScenesResolveRelativePaths)
{
  // teapot_room.scene refers to ../models/teapot.bpt relative to its own folder.
  const Scene scene = LoadSceneFile(SPHCOVER_DATA_DIR "/scenes/teapot_room.scene");
  size_t bicubic = 0;
  for (const Surface& surface : scene.Surfaces)
  {
    bicubic += (surface.Patch.DegreeU() == 3 && surface.Patch.DegreeV() == 3) ? 1 : 0;
  }
  EXPECT_EQ(bicubic, 32u);
}

TEST(SceneLoader, DegeneratePatchIsDetected)
{
  EXPECT_TRUE(IsDegeneratePatch(
    BezierPatch(1, 1, { glm::dvec3(1), glm::dvec3(1), glm::dvec3(1), glm::dvec3(1) })));
  // Collinear control points: a line, no area.
  EXPECT_TRUE(
    IsDegeneratePatch(BezierPatch(1, 1, { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 3, 0, 0 } })));
  // A triangle stored as a degenerate bilinear patch has area.
  EXPECT_FALSE(
    IsDegeneratePatch(BezierPatch(1, 1, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 1, 0 } })));
}

TEST(SceneLoader, BptModelsAsScenes)
{
  const Scene teapot = LoadBptAsScene(SPHCOVER_DATA_DIR "/models/teapot.bpt");
  EXPECT_EQ(teapot.Surfaces.size(), 32u);
  glm::dvec3 lower;
  glm::dvec3 upper;
  teapot.Bounds(lower, upper);
  EXPECT_EQ(lower, glm::dvec3(-3, -2, 0));
  EXPECT_EQ(upper, glm::dvec3(3.525, 2, 3.15));
  const Scene spoon = LoadBptAsScene(SPHCOVER_DATA_DIR "/models/geonum2017/teaspoon.bpt");
  EXPECT_EQ(spoon.Surfaces.size(), 16u);
}

// The malformed-input corpus through Core alone, so the sanitizer build (which has no VTK)
// checks that no bad input crashes or misbehaves in the parsers: each gives one InputError
// whose message holds the expected file, location and problem.
TEST(SceneLoader, BadInputCorpus)
{
  const std::string folder = SPHCOVER_TEST_DATA_DIR "/bad/";
  std::ifstream in(folder + "expected.json");
  ASSERT_TRUE(in) << "cannot open expected.json";
  const nlohmann::json expected = nlohmann::json::parse(in);
  int cases = 0;
  for (auto it = expected.begin(); it != expected.end(); ++it)
  {
    const std::string name = it.key();
    const bool isBpt = name.size() > 4 && name.compare(name.size() - 4, 4, ".bpt") == 0;
    const std::string message = ErrorOf(
      [&]
      {
        if (isBpt)
        {
          LoadBptAsScene(folder + name);
        }
        else
        {
          // Core's own mesh checks; reading the faces needs VTK ("mesh has no faces" here).
          LoadSceneFile(folder + name,
            [](const std::string& path)
            {
              CheckMeshFile(path);
              return std::vector<MeshFace>();
            });
        }
      });
    if (message.find("mesh has no faces") != std::string::npos)
    {
      continue; // a problem only VTK's readers find: covered by Cxx.TestReaderBadInput
    }
    EXPECT_FALSE(message.empty()) << name << " was accepted";
    for (const std::string& fragment : it.value().get<std::vector<std::string>>())
    {
      EXPECT_NE(message.find(fragment), std::string::npos)
        << name << ": '" << message << "' lacks '" << fragment << "'";
    }
    ++cases;
  }
  EXPECT_GE(cases, 20);
  EXPECT_NO_THROW(LoadSceneFile(folder + "support/base.scene"));
  EXPECT_NO_THROW(LoadBptAsScene(folder + "support/base.bpt"));
}
