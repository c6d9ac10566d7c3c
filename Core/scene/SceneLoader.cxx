// SPDX-License-Identifier: BSD-3-Clause
#include "scene/SceneLoader.h"

#include "scene/BptReader.h"
#include "scene/BrdfTable.h"
#include "scene/CameraInput.h"
#include "scene/InputError.h"
#include "scene/InputFile.h"
#include "scene/JsonInput.h"
#include "scene/SettingsOverride.h"
#include "scene/Texture.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <unordered_map>
#include <unordered_set>

namespace sphcover
{
namespace
{

/// The problem of a coordinate `value` beyond BezierPatch::MaxCoordinate (or not finite).
std::string CoordinateTooLarge(double value)
{
  if (!std::isfinite(value))
  {
    return "not a finite number (a coordinate)";
  }
  return TooLarge("coordinate", value, BezierPatch::MaxCoordinate);
}

std::string FolderOf(const std::string& path)
{
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

/// The faces a mesh reader returned, checked: at least one, each a triangle or a quad with
/// coordinates within BezierPatch::MaxCoordinate. Throws InputError(file, "face F", problem).
std::vector<MeshFace> CheckMeshFaces(std::vector<MeshFace> faces, const std::string& file)
{
  if (faces.empty())
  {
    throw InputError(file, "", "mesh has no faces");
  }
  for (size_t f = 0; f < faces.size(); ++f)
  {
    if (faces[f].size() != 3 && faces[f].size() != 4)
    {
      throw InputError(file,
        "face " + std::to_string(f + 1),
        "only triangles and quads are supported, got a face with " +
          std::to_string(faces[f].size()) + " vertices");
    }
    const double largest = LargestCoordinate(faces[f]);
    if (!(largest <= BezierPatch::MaxCoordinate)) // also NaN, which a PLY may hold
    {
      throw InputError(file, "face " + std::to_string(f + 1), CoordinateTooLarge(largest));
    }
  }
  return faces;
}

/// What every surface has besides its geometry (FORMAT.md "surfaces").
struct SurfaceAttributes
{
  std::string Name;
  int MaterialIndex = -1;
  bool TwoSided = false;
  bool Flip = false;
  glm::dmat4 Transform{ 1.0 };
};

/// The scene schema (Data/scenes/FORMAT.md) over the located JSON access of JsonInput.
/**
 * The names a scene file's entries are looked up by while it is parsed: the materials' (name ->
 * index of Scene::Materials) and the surfaces' read so far. Hashed, so that a scene of n named
 * surfaces (a CAD or mesh scene has thousands of parts, often each with a material of its own)
 * loads in O(n): a search of the lists per surface made loading quadratic (80,000 tiles, each
 * with its own material: 26 s, nearly all of it in the searches).
 */
struct SceneNames
{
  std::unordered_map<std::string, int> Materials;
  std::unordered_set<std::string> Surfaces;
};

class SceneParser : public JsonInput
{
public:
  SceneParser(const std::string& path, const MeshFaceReader& readMesh)
    : JsonInput(path)
    , Folder(FolderOf(path))
    , ReadMesh(readMesh)
  {
  }

  Scene Parse(const Json& root);

private:
  /// A point or translation, each coordinate within BezierPatch::MaxCoordinate.
  glm::dvec3 Position(const Json& j, const std::string& pointer) const
  {
    const glm::dvec3 v = this->Vec3(j, pointer);
    for (size_t k = 0; k < 3; ++k)
    {
      this->Bounded(j[k], Child(pointer, k), BezierPatch::MaxCoordinate, "coordinate");
    }
    return v;
  }

  glm::dvec3 Reflectance(const Json& j, const std::string& pointer) const
  {
    return this->Bands(j, pointer, 0.0, 1.0);
  }

  glm::dvec3 Emission(const Json& j, const std::string& pointer) const
  {
    const glm::dvec3 v = this->Vec3(j, pointer);
    for (size_t k = 0; k < 3; ++k)
    {
      if (v[static_cast<int>(k)] < 0.0)
      {
        this->Fail(Child(pointer, k), "must be >= 0");
      }
      this->Bounded(j[k], Child(pointer, k), Material::MaxEmission, "emission");
    }
    return v;
  }

  std::string ResolvePath(const std::string& file) const
  {
    return (!file.empty() && file[0] == '/') ? file : this->Folder + file;
  }

  /// The resolved path of a file the scene refers to, checked by the input file policy
  /// (InputFile.h) before any reader opens it, whatever reads it.
  std::string ExistingFile(const Json& j, const std::string& pointer) const
  {
    const std::string file = this->String(j, pointer);
    const std::string resolved = this->ResolvePath(file);
    std::error_code error;
    if (file.empty() || !std::filesystem::exists(resolved, error))
    {
      this->Fail(pointer, "cannot open file " + Quote(resolved, 4096));
    }
    this->Included(pointer, [&] { CheckInputFile(resolved); });
    return resolved;
  }

  Material ParseMaterial(const std::string& name, const Json& j, const std::string& pointer) const;
  glm::dmat4 ParseTransform(const Json& j, const std::string& pointer) const;
  void ParseSurface(const Json& j,
    const std::string& pointer,
    Scene& scene,
    SceneNames& names) const;
  /// The keys a surface of `type` may have (fails on an unknown type).
  std::vector<const char*> SurfaceKeys(const std::string& type, const std::string& pointer) const;
  /// The entry's name (added to `names`: it must be new), material and sides.
  SurfaceAttributes ParseSurfaceAttributes(const Json& j,
    const std::string& pointer,
    SceneNames& names) const;
  /// The patches of a surface of `type` as its points, degree or file give them, before the
  /// transform; `triangles` marks the ones that are triangles (mesh faces of 3 vertices).
  std::vector<BezierPatch> ParseGeometry(const std::string& type,
    const Json& j,
    const std::string& pointer,
    std::vector<bool>& triangles) const;
  std::vector<BezierPatch> ParseBezierSurface(const Json& j, const std::string& pointer) const;
  std::vector<BezierPatch> ReadMeshSurface(const Json& j,
    const std::string& pointer,
    std::vector<bool>& triangles) const;
  /// Adds the surface to the scene, its patches placed by the transform and checked.
  void AddPlacedSurface(const std::vector<BezierPatch>& patches,
    std::vector<bool> triangles,
    const SurfaceAttributes& attributes,
    bool inFile,
    const std::string& pointer,
    Scene& scene) const;
  std::vector<BezierPatch> ParsePoints(const Json& j,
    const std::string& pointer,
    int degreeU,
    int degreeV) const;

  const std::string Folder;
  const MeshFaceReader& ReadMesh;
};

Material SceneParser::ParseMaterial(const std::string& name,
  const Json& j,
  const std::string& pointer) const
{
  this->ExpectObject(j, pointer);
  Material material;
  material.Name = name;
  const std::string type = this->String(this->Require(j, pointer, "type"), Child(pointer, "type"));
  if (j.contains("emission"))
  {
    material.Emission = this->Emission(j["emission"], Child(pointer, "emission"));
  }
  // Transmittance (a thin pane) and texture (over the diffuse part) extend the types that can
  // carry them (paper §5.4; FORMAT.md "materials").
  const std::initializer_list<const char*> paneAndTexture = {
    "transmittance", "texture", "texture_encoding"
  };
  const auto keys =
    [&](std::initializer_list<const char*> own, std::initializer_list<const char*> extensions)
  {
    std::vector<const char*> allowed(own);
    allowed.insert(allowed.end(), extensions.begin(), extensions.end());
    this->CheckKeys(j, pointer, allowed);
  };
  if (type == "diffuse")
  {
    keys({ "type", "reflectance", "emission" }, paneAndTexture);
    material.Type = MaterialType::Diffuse;
    material.Diffuse =
      this->Reflectance(this->Require(j, pointer, "reflectance"), Child(pointer, "reflectance"));
  }
  else if (type == "mirror")
  {
    keys({ "type", "reflectance", "emission" }, { "transmittance" });
    material.Type = MaterialType::Mirror;
    material.Specular =
      this->Reflectance(this->Require(j, pointer, "reflectance"), Child(pointer, "reflectance"));
  }
  else if (type == "phong")
  {
    keys({ "type", "diffuse", "specular", "exponent", "emission" }, paneAndTexture);
    material.Type = MaterialType::Phong;
    material.Diffuse =
      this->Reflectance(this->Require(j, pointer, "diffuse"), Child(pointer, "diffuse"));
    material.Specular =
      this->Reflectance(this->Require(j, pointer, "specular"), Child(pointer, "specular"));
    material.PhongExponent =
      this->Number(this->Require(j, pointer, "exponent"), Child(pointer, "exponent"));
    if (material.PhongExponent < 0.0)
    {
      this->Fail(Child(pointer, "exponent"), "must be >= 0");
    }
    for (int k = 0; k < 3; ++k)
    {
      // Energy conservation of the diffuse + normalized lobe model.
      if (material.Diffuse[k] + material.Specular[k] > 1.0)
      {
        this->Fail(pointer, "diffuse + specular exceeds 1 in band " + std::to_string(k));
      }
    }
  }
  else if (type == "tabulated")
  {
    this->CheckKeys(j, pointer, { "type", "file", "emission" });
    material.Type = MaterialType::Tabulated;
    material.TableFile =
      this->ExistingFile(this->Require(j, pointer, "file"), Child(pointer, "file"));
    // Read now, so that a bad table is reported with the scene (file, line, problem).
    const std::string file = material.TableFile;
    material.Table = this->Included(Child(pointer, "file"),
      [&] { return std::make_shared<const BrdfTable>(BrdfTable::Load(file)); });
  }
  else
  {
    this->Fail(Child(pointer, "type"), "unknown material type " + Quote(type));
  }
  if (j.contains("transmittance"))
  {
    material.Transmittance =
      this->Bands(j["transmittance"], Child(pointer, "transmittance"), 0.0, 1.0);
    // Energy conservation: what a pane reflects and what it lets through come from the same
    // light (paper §5.4).
    const glm::dvec3 reflected = material.Diffuse + material.Specular;
    const char* what =
      type == "phong" ? "diffuse + specular + transmittance" : "reflectance + transmittance";
    for (int k = 0; k < 3; ++k)
    {
      if (reflected[k] + material.Transmittance[k] > 1.0)
      {
        this->Fail(pointer, std::string(what) + " exceeds 1 in band " + std::to_string(k));
      }
    }
  }
  if (j.contains("texture"))
  {
    const std::string at = Child(pointer, "texture");
    material.TextureFile = this->ExistingFile(j["texture"], at);
    if (j.contains("texture_encoding"))
    {
      const std::string encodingAt = Child(pointer, "texture_encoding");
      const std::string encoding = this->String(j["texture_encoding"], encodingAt);
      if (encoding == "linear")
      {
        material.TextureFileEncoding = TextureEncoding::Linear;
      }
      else if (encoding != "srgb")
      {
        this->Fail(
          encodingAt, "unknown texture encoding " + Quote(encoding) + " (expected srgb or linear)");
      }
    }
    // Read now, so that a bad image is reported with the scene (file and problem).
    const std::string file = material.TextureFile;
    const TextureEncoding encoding = material.TextureFileEncoding;
    material.DiffuseTexture = this->Included(
      at, [&] { return std::make_shared<const Texture>(Texture::Load(file, encoding)); });
  }
  else if (j.contains("texture_encoding"))
  {
    this->Fail(Child(pointer, "texture_encoding"), "texture_encoding without a texture");
  }
  return material;
}

glm::dmat4 SceneParser::ParseTransform(const Json& j, const std::string& pointer) const
{
  this->ExpectObject(j, pointer);
  this->CheckKeys(j, pointer, { "scale", "rotate", "translate" });
  glm::dvec3 scale(1.0);
  if (j.contains("scale"))
  {
    const std::string at = Child(pointer, "scale");
    scale = j["scale"].is_number() ? glm::dvec3(this->Number(j["scale"], at))
                                   : this->Vec3(j["scale"], at);
    if (scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0)
    {
      this->Fail(at, "scale must not be 0");
    }
  }
  const glm::dvec3 rotate =
    j.contains("rotate") ? this->Vec3(j["rotate"], Child(pointer, "rotate")) : glm::dvec3(0.0);
  const glm::dvec3 translate = j.contains("translate")
    ? this->Position(j["translate"], Child(pointer, "translate"))
    : glm::dvec3(0.0);
  // Applied to a point: scale, then rotate about x, y, z (in that order), then translate.
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotate.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

/// Bezier control nets transform with the affine map exactly (affine invariance). A mirroring
/// map (negative determinant) would turn the front side to the back, so the u direction is
/// reversed as well to keep the front the user meant; "flip" reverses it on request.
BezierPatch PlacePatch(const BezierPatch& patch, const glm::dmat4& transform, bool flip)
{
  const glm::dmat3 linear(transform);
  const bool mirrored = glm::determinant(linear) < 0.0;
  const bool reverseU = mirrored != flip;
  const int m = patch.DegreeU();
  const int n = patch.DegreeV();
  std::vector<glm::dvec3> points(static_cast<size_t>((m + 1) * (n + 1)));
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      const glm::dvec3& p = patch.ControlPoint(reverseU ? m - i : i, j);
      points[static_cast<size_t>(j * (m + 1) + i)] = glm::dvec3(transform * glm::dvec4(p, 1.0));
    }
  }
  return BezierPatch(m, n, std::move(points));
}

std::vector<BezierPatch> SceneParser::ParsePoints(const Json& j,
  const std::string& pointer,
  int degreeU,
  int degreeV) const
{
  const size_t expected = static_cast<size_t>((degreeU + 1) * (degreeV + 1));
  if (!j.is_array())
  {
    this->Fail(pointer, "expected an array of " + std::to_string(expected) + " points");
  }
  if (j.size() != expected)
  {
    this->Fail(
      pointer, "expected " + std::to_string(expected) + " points, got " + std::to_string(j.size()));
  }
  std::vector<glm::dvec3> points;
  points.reserve(expected);
  for (size_t k = 0; k < expected; ++k)
  {
    points.push_back(this->Position(j[k], Child(pointer, k)));
  }
  return { BezierPatch(degreeU, degreeV, std::move(points)) };
}

std::vector<const char*> SceneParser::SurfaceKeys(const std::string& type,
  const std::string& pointer) const
{
  const std::initializer_list<const char*> common = {
    "name", "type", "material", "two_sided", "flip", "transform"
  };
  std::vector<const char*> allowed(common);
  if (type == "bilinear")
  {
    allowed.push_back("points");
  }
  else if (type == "bezier")
  {
    allowed.push_back("points");
    allowed.push_back("degree");
  }
  else if (type == "bpt" || type == "mesh")
  {
    allowed.push_back("file");
  }
  else
  {
    this->Fail(Child(pointer, "type"), "unknown surface type " + Quote(type));
  }
  return allowed;
}

SurfaceAttributes SceneParser::ParseSurfaceAttributes(const Json& j,
  const std::string& pointer,
  SceneNames& names) const
{
  SurfaceAttributes attributes;
  attributes.Name = this->String(this->Require(j, pointer, "name"), Child(pointer, "name"));
  if (!names.Surfaces.insert(attributes.Name).second)
  {
    this->Fail(Child(pointer, "name"), "duplicate surface name " + Quote(attributes.Name));
  }
  const std::string materialName =
    this->String(this->Require(j, pointer, "material"), Child(pointer, "material"));
  const auto material = names.Materials.find(materialName);
  if (material == names.Materials.end())
  {
    this->Fail(Child(pointer, "material"), "unknown material " + Quote(materialName));
  }
  attributes.MaterialIndex = material->second;
  attributes.TwoSided =
    j.contains("two_sided") && this->Boolean(j["two_sided"], Child(pointer, "two_sided"));
  attributes.Flip = j.contains("flip") && this->Boolean(j["flip"], Child(pointer, "flip"));
  if (j.contains("transform"))
  {
    attributes.Transform = this->ParseTransform(j["transform"], Child(pointer, "transform"));
  }
  return attributes;
}

std::vector<BezierPatch> SceneParser::ParseGeometry(const std::string& type,
  const Json& j,
  const std::string& pointer,
  std::vector<bool>& triangles) const
{
  if (type == "bilinear")
  {
    // Data/scenes/FORMAT.md's order P(0,0), P(1,0), P(1,1), P(0,1) -> row-major u fastest: P00,
    // P10, P01, P11.
    auto quad =
      this->ParsePoints(this->Require(j, pointer, "points"), Child(pointer, "points"), 1, 1);
    std::vector<glm::dvec3> cp = quad[0].ControlPoints();
    std::swap(cp[2], cp[3]);
    std::vector<BezierPatch> patches;
    patches.emplace_back(1, 1, std::move(cp));
    return patches;
  }
  if (type == "bezier")
  {
    return this->ParseBezierSurface(j, pointer);
  }
  if (type == "bpt")
  {
    const std::string at = Child(pointer, "file");
    const std::string file = this->ExistingFile(this->Require(j, pointer, "file"), at);
    return this->Included(at, [&] { return ReadBptFile(file); });
  }
  return this->ReadMeshSurface(j, pointer, triangles);
}

std::vector<BezierPatch> SceneParser::ParseBezierSurface(const Json& j,
  const std::string& pointer) const
{
  const std::string at = Child(pointer, "degree");
  const Json& degree = this->Require(j, pointer, "degree");
  if (!degree.is_array() || degree.size() != 2)
  {
    this->Fail(at, "expected an array of 2 integers");
  }
  long long mn[2];
  for (size_t k = 0; k < 2; ++k)
  {
    mn[k] = this->Integer(degree[k], Child(at, k));
    if (mn[k] < 1 || mn[k] > BezierPatch::MaxDegree)
    {
      this->Fail(Child(at, k),
        "degree must be in [1, " + std::to_string(BezierPatch::MaxDegree) + "], got " +
          std::to_string(mn[k]));
    }
  }
  const long long m = mn[0];
  const long long n = mn[1];
  return this->ParsePoints(this->Require(j, pointer, "points"),
    Child(pointer, "points"),
    static_cast<int>(m),
    static_cast<int>(n));
}

std::vector<BezierPatch> SceneParser::ReadMeshSurface(const Json& j,
  const std::string& pointer,
  std::vector<bool>& triangles) const
{
  const std::string at = Child(pointer, "file");
  const std::string file = this->ExistingFile(this->Require(j, pointer, "file"), at);
  const std::string ext = LowerExtension(file);
  if (ext != "obj" && ext != "ply" && ext != "vtp")
  {
    this->Fail(at, "unsupported mesh format '." + ext + "' (use .obj, .ply or .vtp)");
  }
  if (!this->ReadMesh)
  {
    this->Fail(at, "mesh surfaces need the VTK scene reader (vtkPatchSceneReader)");
  }
  const std::vector<MeshFace> faces =
    this->Included(at, [&] { return CheckMeshFaces(this->ReadMesh(file), file); });
  std::vector<BezierPatch> patches;
  for (const MeshFace& face : faces)
  {
    // A triangle becomes the bilinear patch with P(1,1) = P(0,1); the right-hand rule of the
    // face's vertex order is the front (dP/du x dP/dv).
    const glm::dvec3& last = face.size() == 4 ? face[3] : face[2];
    patches.emplace_back(1, 1, std::vector<glm::dvec3>{ face[0], face[1], last, face[2] });
    triangles.resize(patches.size(), false);
    triangles.back() = face.size() == 3;
  }
  return patches;
}

void SceneParser::AddPlacedSurface(const std::vector<BezierPatch>& patches,
  std::vector<bool> triangles,
  const SurfaceAttributes& attributes,
  bool inFile,
  const std::string& pointer,
  Scene& scene) const
{
  const int nameIndex = static_cast<int>(scene.SurfaceNames.size());
  scene.SurfaceNames.push_back(attributes.Name);
  triangles.resize(patches.size(), false);
  for (size_t p = 0; p < patches.size(); ++p)
  {
    BezierPatch placed = PlacePatch(patches[p], attributes.Transform, attributes.Flip);
    // The geometry read is within the limit; only the transform can carry it beyond.
    const double largest = LargestCoordinate(placed.ControlPoints());
    if (largest > BezierPatch::MaxCoordinate)
    {
      this->Fail(Child(pointer, "transform"),
        "moves patch " + std::to_string(p + 1) + " too far: " + CoordinateTooLarge(largest));
    }
    if (IsDegeneratePatch(placed))
    {
      // Located at the geometry: the points, or the file the patch came from.
      this->Fail(Child(pointer, inFile ? "file" : "points"),
        inFile ? "degenerate patch " + std::to_string(p + 1) + " (no area)"
               : std::string("degenerate patch (no area)"));
    }
    // A pane sends, receives and lets light through on both sides (FORMAT.md, "transmittance"),
    // and its two sides see different half-spaces: it becomes two one-sided surfaces, the patch
    // and its reversed copy, each with its own characteristic points and hemispheres (paper
    // §5.4: "an hemispherical tessellation in a direction opposite to the normal as well").
    // An opaque two-sided surface becomes the same pair, both marked TwoSided (Scene.h): each
    // side gets its own hemispheres in the cover (paper §3.3), emits, receives and reflects on
    // its own (§3.5), and is seen from its own half-space in the render (§5.3).
    const bool pane =
      scene.Materials[static_cast<size_t>(attributes.MaterialIndex)].IsTransmitter();
    const bool twoSided = attributes.TwoSided && !pane;
    Surface surface(std::move(placed), nameIndex, attributes.MaterialIndex);
    surface.TwoSided = twoSided;
    surface.IsTriangle = triangles[p];
    scene.Surfaces.push_back(std::move(surface));
    if (pane || twoSided)
    {
      Surface back(PlacePatch(patches[p], attributes.Transform, !attributes.Flip),
        nameIndex,
        attributes.MaterialIndex);
      back.TwoSided = twoSided;
      back.IsTriangle = triangles[p];
      scene.Surfaces.push_back(std::move(back));
    }
  }
}

void SceneParser::ParseSurface(const Json& j,
  const std::string& pointer,
  Scene& scene,
  SceneNames& names) const
{
  this->ExpectObject(j, pointer);
  const std::string type = this->String(this->Require(j, pointer, "type"), Child(pointer, "type"));
  this->CheckKeys(j, pointer, this->SurfaceKeys(type, pointer));
  const SurfaceAttributes attributes = this->ParseSurfaceAttributes(j, pointer, names);
  std::vector<bool> triangles;
  const std::vector<BezierPatch> patches = this->ParseGeometry(type, j, pointer, triangles);
  const bool inFile = type == "bpt" || type == "mesh";
  this->AddPlacedSurface(patches, std::move(triangles), attributes, inFile, pointer, scene);
}

Scene SceneParser::Parse(const Json& root)
{
  this->ExpectObject(root, "");
  this->CheckKeys(root, "", { "version", "unit", "materials", "surfaces", "cameras", "settings" });
  Scene scene;
  scene.SourceFile = this->Source;
  const long long version = this->Integer(this->Require(root, "", "version"), "/version");
  if (version != 1)
  {
    this->Fail("/version", "unsupported version " + std::to_string(version) + " (expected 1)");
  }
  if (root.contains("unit"))
  {
    const std::string unit = this->String(root["unit"], "/unit");
    if (!FindLengthUnit(unit, scene.Unit))
    {
      this->Fail("/unit",
        "unknown length unit " + Quote(unit) + " (expected one of " + LengthUnitNames() + ")");
    }
  }
  const Json& materials = this->Require(root, "", "materials");
  this->ExpectObject(materials, "/materials");
  SceneNames names;
  for (auto it = materials.begin(); it != materials.end(); ++it)
  {
    // The JSON object's keys are unique (a repeated key is refused as the text is read).
    names.Materials.emplace(it.key(), static_cast<int>(scene.Materials.size()));
    scene.Materials.push_back(
      this->ParseMaterial(it.key(), it.value(), Child("/materials", it.key())));
  }
  const Json& surfaces = this->Require(root, "", "surfaces");
  if (!surfaces.is_array())
  {
    this->Fail("/surfaces", "expected an array");
  }
  if (surfaces.empty())
  {
    this->Fail("/surfaces", "scene has no surfaces");
  }
  for (size_t s = 0; s < surfaces.size(); ++s)
  {
    this->ParseSurface(surfaces[s], Child("/surfaces", s), scene, names);
  }
  if (root.contains("cameras"))
  {
    const Json& cameras = root["cameras"];
    if (!cameras.is_array())
    {
      this->Fail("/cameras", "expected an array");
    }
    for (size_t c = 0; c < cameras.size(); ++c)
    {
      scene.Cameras.push_back(ParseCamera(*this, cameras[c], Child("/cameras", c)));
    }
  }
  if (root.contains("settings"))
  {
    scene.Settings = ParseSettings(*this, root["settings"], "/settings");
  }
  return scene;
}

} // namespace

bool IsDegeneratePatch(const BezierPatch& patch)
{
  glm::dvec3 lower(std::numeric_limits<double>::infinity());
  glm::dvec3 upper(-std::numeric_limits<double>::infinity());
  for (const glm::dvec3& p : patch.ControlPoints())
  {
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  const double size = glm::length(upper - lower);
  if (!(size > 0.0))
  {
    return true;
  }
  // Sample Pu x Pv on a grid that avoids the corners (where a triangle's collapsed edge makes
  // it vanish legitimately); any clearly non-zero value means the patch has area.
  constexpr int samples = 7;
  for (int b = 1; b < samples; ++b)
  {
    for (int a = 1; a < samples; ++a)
    {
      const glm::dvec3 n = patch.UnnormalizedNormal(double(a) / samples, double(b) / samples);
      if (glm::length(n) > 1e-12 * size * size)
      {
        return false;
      }
    }
  }
  return true;
}

Scene ParseScene(const std::string& text, const std::string& path, const MeshFaceReader& readMesh)
{
  const Json root = ParseJsonDocument(text, path);
  SceneParser parser(path, readMesh);
  return parser.Parse(root);
}

Scene LoadSceneFile(const std::string& path, const MeshFaceReader& readMesh)
{
  return ParseScene(ReadInputFile(path), path, readMesh);
}

Scene LoadBptAsScene(const std::string& path)
{
  Scene scene;
  scene.SourceFile = path;
  Material white;
  white.Name = "default";
  white.Diffuse = glm::dvec3(0.8);
  scene.Materials.push_back(white);
  const size_t slash = path.find_last_of('/');
  scene.SurfaceNames.push_back(slash == std::string::npos ? path : path.substr(slash + 1));
  std::vector<BezierPatch> patches = ReadBptFile(path);
  for (size_t p = 0; p < patches.size(); ++p)
  {
    if (IsDegeneratePatch(patches[p]))
    {
      throw InputError(path, "patch " + std::to_string(p + 1), "degenerate patch (no area)");
    }
    scene.Surfaces.emplace_back(std::move(patches[p]), 0, 0);
  }
  return scene;
}

} // namespace sphcover
