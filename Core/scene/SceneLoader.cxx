// SPDX-License-Identifier: BSD-3-Clause
#include "scene/SceneLoader.h"

#include "scene/BptReader.h"
#include "scene/BrdfTable.h"
#include "scene/InputError.h"
#include "scene/InputFile.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <set>
#include <sstream>

namespace sphcover
{
namespace
{
using Json = nlohmann::json;

/// Largest image side a camera may ask for; larger is surely a typo and would exhaust memory.
constexpr int MaxImageSide = 1 << 15;

/// Deepest nesting of arrays and objects accepted; a scene needs 5. Without a limit a file of
/// a million '[' is a million-level document (and a 2 MB pointer in the message).
constexpr size_t MaxJsonDepth = 64;

std::string FormatNumber(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string TooLarge(const std::string& what, double value, double limit)
{
  return what + " too large: " + FormatNumber(value) + " (the limit is " + FormatNumber(limit) +
    " in magnitude)";
}

/// The problem of a coordinate `value` beyond BezierPatch::MaxCoordinate (or not finite).
std::string CoordinateTooLarge(double value)
{
  if (!std::isfinite(value))
  {
    return "not a finite number (a coordinate)";
  }
  return TooLarge("coordinate", value, BezierPatch::MaxCoordinate);
}

std::string EscapePointerToken(const std::string& key)
{
  // RFC 6901: '~' -> "~0", '/' -> "~1".
  std::string out;
  for (char c : key)
  {
    if (c == '~')
    {
      out += "~0";
    }
    else if (c == '/')
    {
      out += "~1";
    }
    else
    {
      out += c;
    }
  }
  return Excerpt(out); // a key may be megabytes long; the message names its start
}

std::string Child(const std::string& pointer, const std::string& key)
{
  return pointer + "/" + EscapePointerToken(key);
}

std::string Child(const std::string& pointer, size_t index)
{
  return pointer + "/" + std::to_string(index);
}

std::string FolderOf(const std::string& path)
{
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

/// Typed, located access to the JSON document: every failure names the JSON pointer.
class SceneParser
{
public:
  SceneParser(const std::string& path, const MeshFaceReader& readMesh)
    : Path(path)
    , Folder(FolderOf(path))
    , ReadMesh(readMesh)
  {
  }

  Scene Parse(const Json& root);
  SceneSettings Override(const SceneSettings& base, const Json& assignment) const
  {
    return this->ParseSettings(assignment, "", base);
  }

private:
  [[noreturn]] void Fail(const std::string& pointer, const std::string& problem) const
  {
    throw InputError(this->Path, pointer.empty() ? std::string("/") : pointer, problem);
  }

  void ExpectObject(const Json& j, const std::string& pointer) const
  {
    if (!j.is_object())
    {
      this->Fail(pointer, "expected an object");
    }
  }

  void CheckKeys(const Json& j,
    const std::string& pointer,
    const std::vector<const char*>& allowed) const
  {
    for (auto it = j.begin(); it != j.end(); ++it)
    {
      if (std::none_of(
            allowed.begin(), allowed.end(), [&](const char* key) { return it.key() == key; }))
      {
        this->Fail(Child(pointer, it.key()), "unknown key " + Quote(it.key()));
      }
    }
  }

  const Json& Require(const Json& j, const std::string& pointer, const char* key) const
  {
    auto it = j.find(key);
    if (it == j.end())
    {
      this->Fail(pointer, std::string("missing key '") + key + "'");
    }
    return *it;
  }

  double Number(const Json& j, const std::string& pointer) const
  {
    if (!j.is_number())
    {
      this->Fail(pointer, "expected a number");
    }
    const double value = j.get<double>();
    if (!std::isfinite(value))
    {
      this->Fail(pointer, "not a finite number");
    }
    return value;
  }

  /// Integers are written without fraction or exponent (FORMAT.md): 32, not 32.0.
  long long Integer(const Json& j, const std::string& pointer) const
  {
    if (j.is_number_unsigned() && j.get<unsigned long long>() > (1ull << 62))
    {
      this->Fail(pointer, "integer out of range");
    }
    if (!j.is_number_integer())
    {
      this->Fail(pointer, "expected an integer");
    }
    return j.get<long long>();
  }

  int PositiveInteger(const Json& j, const std::string& pointer, long long limit) const
  {
    const long long value = this->Integer(j, pointer);
    if (value < 1 || value > limit)
    {
      this->Fail(pointer,
        "must be a positive integer (at most " + std::to_string(limit) + "), got " +
          std::to_string(value));
    }
    return static_cast<int>(value);
  }

  bool Boolean(const Json& j, const std::string& pointer) const
  {
    if (!j.is_boolean())
    {
      this->Fail(pointer, "expected a boolean");
    }
    return j.get<bool>();
  }

  std::string String(const Json& j, const std::string& pointer) const
  {
    if (!j.is_string())
    {
      this->Fail(pointer, "expected a string");
    }
    return j.get<std::string>();
  }

  /// A finite number of magnitude at most `limit`; beyond it, "<what> too large".
  double Bounded(const Json& j, const std::string& pointer, double limit, const char* what) const
  {
    const double value = this->Number(j, pointer);
    if (std::fabs(value) > limit)
    {
      this->Fail(pointer, TooLarge(what, value, limit));
    }
    return value;
  }

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

  glm::dvec3 Vec3(const Json& j, const std::string& pointer) const
  {
    if (!j.is_array() || j.size() != 3)
    {
      this->Fail(pointer, "expected an array of 3 numbers");
    }
    glm::dvec3 v;
    for (size_t k = 0; k < 3; ++k)
    {
      v[static_cast<int>(k)] = this->Number(j[k], Child(pointer, k));
    }
    return v;
  }

  /// Per-band values in [lo, hi].
  glm::dvec3 Bands(const Json& j, const std::string& pointer, double lo, double hi) const
  {
    const glm::dvec3 v = this->Vec3(j, pointer);
    for (int k = 0; k < 3; ++k)
    {
      if (v[k] < lo || v[k] > hi)
      {
        std::ostringstream problem;
        problem << "must be in [" << lo << ", " << hi << "], got " << v[k];
        this->Fail(Child(pointer, static_cast<size_t>(k)), problem.str());
      }
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

  /// Problems inside a file the scene refers to are reported at the scene entry that names it,
  /// followed by the file's own location: "room.scene: /surfaces/3/file: pot.bpt: line 7: ...".
  template<typename Read>
  auto Included(const std::string& pointer, Read&& read) const -> decltype(read())
  {
    try
    {
      return read();
    }
    catch (const InputError& e)
    {
      this->Fail(pointer, e.what());
    }
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
  void ParseSurface(const Json& j, const std::string& pointer, Scene& scene) const;
  Camera ParseCamera(const Json& j, const std::string& pointer) const;
  SceneSettings ParseSettings(const Json& j,
    const std::string& pointer,
    SceneSettings settings = SceneSettings()) const;
  std::vector<BezierPatch> ParsePoints(const Json& j,
    const std::string& pointer,
    int degreeU,
    int degreeV) const;

  const std::string& Path;
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
  if (type == "diffuse")
  {
    this->CheckKeys(j, pointer, { "type", "reflectance", "emission" });
    material.Type = MaterialType::Diffuse;
    material.Diffuse =
      this->Reflectance(this->Require(j, pointer, "reflectance"), Child(pointer, "reflectance"));
  }
  else if (type == "mirror")
  {
    this->CheckKeys(j, pointer, { "type", "reflectance", "emission" });
    material.Type = MaterialType::Mirror;
    material.Specular =
      this->Reflectance(this->Require(j, pointer, "reflectance"), Child(pointer, "reflectance"));
  }
  else if (type == "phong")
  {
    this->CheckKeys(j, pointer, { "type", "diffuse", "specular", "exponent", "emission" });
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

void SceneParser::ParseSurface(const Json& j, const std::string& pointer, Scene& scene) const
{
  this->ExpectObject(j, pointer);
  const std::string type = this->String(this->Require(j, pointer, "type"), Child(pointer, "type"));
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
  this->CheckKeys(j, pointer, allowed);

  const std::string name = this->String(this->Require(j, pointer, "name"), Child(pointer, "name"));
  if (std::find(scene.SurfaceNames.begin(), scene.SurfaceNames.end(), name) !=
    scene.SurfaceNames.end())
  {
    this->Fail(Child(pointer, "name"), "duplicate surface name " + Quote(name));
  }
  const std::string materialName =
    this->String(this->Require(j, pointer, "material"), Child(pointer, "material"));
  const int materialIndex = scene.FindMaterial(materialName);
  if (materialIndex < 0)
  {
    this->Fail(Child(pointer, "material"), "unknown material " + Quote(materialName));
  }
  const bool twoSided =
    j.contains("two_sided") && this->Boolean(j["two_sided"], Child(pointer, "two_sided"));
  const bool flip = j.contains("flip") && this->Boolean(j["flip"], Child(pointer, "flip"));
  const glm::dmat4 transform = j.contains("transform")
    ? this->ParseTransform(j["transform"], Child(pointer, "transform"))
    : glm::dmat4(1.0);

  std::vector<BezierPatch> patches;
  std::vector<bool> triangles;
  if (type == "bilinear")
  {
    // SPEC order P(0,0), P(1,0), P(1,1), P(0,1) -> row-major u fastest: P00, P10, P01, P11.
    auto quad =
      this->ParsePoints(this->Require(j, pointer, "points"), Child(pointer, "points"), 1, 1);
    std::vector<glm::dvec3> cp = quad[0].ControlPoints();
    std::swap(cp[2], cp[3]);
    patches.emplace_back(1, 1, std::move(cp));
  }
  else if (type == "bezier")
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
    patches = this->ParsePoints(this->Require(j, pointer, "points"),
      Child(pointer, "points"),
      static_cast<int>(m),
      static_cast<int>(n));
  }
  else if (type == "bpt")
  {
    const std::string at = Child(pointer, "file");
    const std::string file = this->ExistingFile(this->Require(j, pointer, "file"), at);
    patches = this->Included(at, [&] { return ReadBptFile(file); });
  }
  else // mesh
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
    const std::vector<MeshFace> faces = this->Included(at,
      [&]
      {
        std::vector<MeshFace> read = this->ReadMesh(file);
        if (read.empty())
        {
          throw InputError(file, "", "mesh has no faces");
        }
        for (size_t f = 0; f < read.size(); ++f)
        {
          if (read[f].size() != 3 && read[f].size() != 4)
          {
            throw InputError(file,
              "face " + std::to_string(f + 1),
              "only triangles and quads are supported, got a face with " +
                std::to_string(read[f].size()) + " vertices");
          }
          const double largest = LargestCoordinate(read[f]);
          if (!(largest <= BezierPatch::MaxCoordinate)) // also NaN, which a PLY may hold
          {
            throw InputError(file, "face " + std::to_string(f + 1), CoordinateTooLarge(largest));
          }
        }
        return read;
      });
    for (const MeshFace& face : faces)
    {
      // A triangle becomes the bilinear patch with P(1,1) = P(0,1); the right-hand rule of the
      // face's vertex order is the front (dP/du x dP/dv).
      const glm::dvec3& last = face.size() == 4 ? face[3] : face[2];
      patches.emplace_back(1, 1, std::vector<glm::dvec3>{ face[0], face[1], last, face[2] });
      triangles.resize(patches.size(), false);
      triangles.back() = face.size() == 3;
    }
  }

  const int nameIndex = static_cast<int>(scene.SurfaceNames.size());
  scene.SurfaceNames.push_back(name);
  triangles.resize(patches.size(), false);
  for (size_t p = 0; p < patches.size(); ++p)
  {
    BezierPatch placed = PlacePatch(patches[p], transform, flip);
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
      const bool inFile = type == "bpt" || type == "mesh";
      this->Fail(Child(pointer, inFile ? "file" : "points"),
        inFile ? "degenerate patch " + std::to_string(p + 1) + " (no area)"
               : std::string("degenerate patch (no area)"));
    }
    Surface surface(std::move(placed), nameIndex, materialIndex);
    surface.TwoSided = twoSided;
    surface.IsTriangle = triangles[p];
    scene.Surfaces.push_back(std::move(surface));
  }
}

Camera SceneParser::ParseCamera(const Json& j, const std::string& pointer) const
{
  this->ExpectObject(j, pointer);
  this->CheckKeys(
    j, pointer, { "name", "position", "focal_point", "view_up", "view_angle", "width", "height" });
  Camera camera;
  camera.Name = this->String(this->Require(j, pointer, "name"), Child(pointer, "name"));
  camera.Position =
    this->Position(this->Require(j, pointer, "position"), Child(pointer, "position"));
  camera.FocalPoint =
    this->Position(this->Require(j, pointer, "focal_point"), Child(pointer, "focal_point"));
  camera.ViewUp = this->Position(this->Require(j, pointer, "view_up"), Child(pointer, "view_up"));
  camera.ViewAngle =
    this->Number(this->Require(j, pointer, "view_angle"), Child(pointer, "view_angle"));
  if (!(camera.ViewAngle > 0.0 && camera.ViewAngle < 180.0))
  {
    this->Fail(Child(pointer, "view_angle"), "must be in (0, 180)");
  }
  camera.Width = this->PositiveInteger(
    this->Require(j, pointer, "width"), Child(pointer, "width"), MaxImageSide);
  camera.Height = this->PositiveInteger(
    this->Require(j, pointer, "height"), Child(pointer, "height"), MaxImageSide);
  const glm::dvec3 direction = camera.FocalPoint - camera.Position;
  if (glm::length(direction) == 0.0)
  {
    this->Fail(Child(pointer, "focal_point"), "focal_point equals position");
  }
  if (glm::length(glm::cross(glm::normalize(direction), camera.ViewUp)) <
      1e-9 * glm::length(camera.ViewUp) ||
    glm::length(camera.ViewUp) == 0.0)
  {
    this->Fail(Child(pointer, "view_up"), "view_up is zero or parallel to the view direction");
  }
  return camera;
}

SceneSettings SceneParser::ParseSettings(const Json& j,
  const std::string& pointer,
  SceneSettings settings) const
{
  this->ExpectObject(j, pointer);
  this->CheckKeys(j, pointer, { "theta_bins", "phi_bins", "max_level", "tolerance" });
  if (j.contains("theta_bins"))
  {
    settings.ThetaBins = this->PositiveInteger(j["theta_bins"], Child(pointer, "theta_bins"), 4096);
  }
  if (j.contains("phi_bins"))
  {
    settings.PhiBins = this->PositiveInteger(j["phi_bins"], Child(pointer, "phi_bins"), 16384);
  }
  if (j.contains("max_level"))
  {
    const long long level = this->Integer(j["max_level"], Child(pointer, "max_level"));
    if (level < 0 || level > MaxSubdivisionLevel)
    {
      this->Fail(Child(pointer, "max_level"),
        "must be >= 0 and at most " + std::to_string(MaxSubdivisionLevel) +
          " (deeper patches are narrower than the double precision of the parameter domain)");
    }
    settings.MaxLevel = static_cast<int>(level);
  }
  if (j.contains("tolerance"))
  {
    settings.Tolerance = this->Number(j["tolerance"], Child(pointer, "tolerance"));
    // Smaller tolerances test only the rounding of the range bounds (MinimumTolerance).
    if (!(settings.Tolerance >= MinimumTolerance))
    {
      this->Fail(Child(pointer, "tolerance"), "must be >= 1e-9");
    }
  }
  return settings;
}

Scene SceneParser::Parse(const Json& root)
{
  this->ExpectObject(root, "");
  this->CheckKeys(root, "", { "version", "materials", "surfaces", "cameras", "settings" });
  Scene scene;
  scene.SourceFile = this->Path;
  const long long version = this->Integer(this->Require(root, "", "version"), "/version");
  if (version != 1)
  {
    this->Fail("/version", "unsupported version " + std::to_string(version) + " (expected 1)");
  }
  const Json& materials = this->Require(root, "", "materials");
  this->ExpectObject(materials, "/materials");
  for (auto it = materials.begin(); it != materials.end(); ++it)
  {
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
    this->ParseSurface(surfaces[s], Child("/surfaces", s), scene);
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
      scene.Cameras.push_back(this->ParseCamera(cameras[c], Child("/cameras", c)));
    }
  }
  if (root.contains("settings"))
  {
    scene.Settings = this->ParseSettings(root["settings"], "/settings");
  }
  return scene;
}

/// nlohmann/json's DOM builder, told not to throw, remembering where and why parsing failed:
/// the byte offset and the JSON pointer of the value being read (nlohmann's exceptions lose
/// both for a number overflow such as 1e999, which is a non-finite number to us). It also
/// stops at what JSON allows but a scene must not have (Problem, at ErrorPointer): a repeated
/// key (nlohmann would keep the last silently), a NUL character in a key or string (it would
/// cut a file name short when the path reaches the C library), nesting beyond MaxJsonDepth.
class LocatingDomParser : public nlohmann::detail::json_sax_dom_parser<Json>
{
  using Base = nlohmann::detail::json_sax_dom_parser<Json>;

public:
  explicit LocatingDomParser(Json& root)
    : Base(root, false)
  {
  }

  bool null() { return this->Value(Base::null()); }
  bool boolean(bool value) { return this->Value(Base::boolean(value)); }
  bool number_integer(Json::number_integer_t value)
  {
    return this->Value(Base::number_integer(value));
  }
  bool number_unsigned(Json::number_unsigned_t value)
  {
    return this->Value(Base::number_unsigned(value));
  }
  bool number_float(Json::number_float_t value, const Json::string_t& text)
  {
    return this->Value(Base::number_float(value, text));
  }
  bool string(Json::string_t& value)
  {
    if (value.find('\0') != std::string::npos)
    {
      return this->Stop("NUL character (\\u0000) in a string");
    }
    return this->Value(Base::string(value));
  }
  bool binary(Json::binary_t& value) { return this->Value(Base::binary(value)); }
  bool start_object(std::size_t size)
  {
    if (this->Path.size() >= MaxJsonDepth)
    {
      return this->Stop("nested deeper than " + std::to_string(MaxJsonDepth) + " levels");
    }
    this->Path.push_back({ false, 0, std::string(), {} });
    return Base::start_object(size);
  }
  bool key(Json::string_t& name)
  {
    Level& level = this->Path.back();
    level.Key = name;
    if (name.find('\0') != std::string::npos)
    {
      return this->Stop("NUL character (\\u0000) in a key");
    }
    if (!level.Keys.insert(name).second)
    {
      return this->Stop("duplicate key " + Quote(name));
    }
    return Base::key(name);
  }
  bool end_object()
  {
    this->Path.pop_back();
    return this->Value(Base::end_object());
  }
  bool start_array(std::size_t size)
  {
    if (this->Path.size() >= MaxJsonDepth)
    {
      return this->Stop("nested deeper than " + std::to_string(MaxJsonDepth) + " levels");
    }
    this->Path.push_back({ true, 0, std::string(), {} });
    return Base::start_array(size);
  }
  bool end_array()
  {
    this->Path.pop_back();
    return this->Value(Base::end_array());
  }

  template<class Exception>
  bool parse_error(std::size_t position, const std::string&, const Exception& error)
  {
    this->Failed = true;
    this->ErrorPosition = position;
    this->ErrorMessage = error.what();
    this->ErrorId = error.id;
    this->ErrorPointer = this->Pointer();
    return false;
  }

  bool Failed = false;
  size_t ErrorPosition = 0;
  std::string ErrorMessage;
  std::string ErrorPointer;
  int ErrorId = 0;
  std::string Problem; // set when the callbacks stopped a syntactically valid document

private:
  struct Level
  {
    bool IsArray;
    size_t Count;               // elements read so far (arrays)
    std::string Key;            // the current key (objects)
    std::set<std::string> Keys; // the keys read so far (objects)
  };

  /// The JSON pointer of the value being read.
  std::string Pointer() const
  {
    std::string pointer;
    for (const Level& level : this->Path)
    {
      pointer += level.IsArray ? Child("", level.Count) : Child("", level.Key);
    }
    return pointer;
  }

  /// Ends the parse (a callback returning false) with `problem` at the current value.
  bool Stop(const std::string& problem)
  {
    this->Failed = true;
    this->ErrorPointer = this->Pointer();
    this->Problem = problem;
    return false;
  }

  /// A complete value was read: the enclosing array moves on to its next element.
  bool Value(bool result)
  {
    if (!this->Path.empty() && this->Path.back().IsArray)
    {
      ++this->Path.back().Count;
    }
    return result;
  }

  std::vector<Level> Path;
};

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
  Json root;
  LocatingDomParser dom(root);
  if (!Json::sax_parse(text, &dom) || dom.Failed)
  {
    if (!dom.Problem.empty())
    {
      throw InputError(
        path, dom.ErrorPointer.empty() ? std::string("/") : dom.ErrorPointer, dom.Problem);
    }
    // nlohmann reports the byte offset; users want line and column.
    const size_t end =
      std::min(dom.ErrorPosition == 0 ? size_t{ 0 } : dom.ErrorPosition - 1, text.size());
    size_t line = 1;
    size_t column = 1;
    for (size_t k = 0; k < end; ++k)
    {
      if (text[k] == '\n')
      {
        ++line;
        column = 1;
      }
      else
      {
        ++column;
      }
    }
    // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ".
    std::string detail = dom.ErrorMessage;
    const size_t bracket = detail.find("] ");
    if (detail.compare(0, 16, "[json.exception.") == 0 && bracket != std::string::npos)
    {
      detail = detail.substr(bracket + 2);
    }
    const size_t colon = detail.find(": ");
    if (detail.compare(0, 14, "parse error at") == 0 && colon != std::string::npos)
    {
      detail = detail.substr(colon + 2);
    }
    // nlohmann quotes the whole token it stopped in ("...; last read: '<token>'", maybe
    // followed by "; expected ..."), which may be a megabyte-long string.
    const std::string lastRead = "last read: '";
    const size_t quoted = detail.find(lastRead);
    if (quoted != std::string::npos)
    {
      const size_t begin = quoted + lastRead.size();
      size_t end = detail.find("'; expected", begin);
      end = end != std::string::npos ? end : detail.rfind('\'');
      if (end != std::string::npos && end >= begin)
      {
        detail = detail.substr(0, quoted) +
          "last read: " + Quote(detail.substr(begin, end - begin)) + detail.substr(end + 1);
      }
    }
    const std::string position =
      "line " + std::to_string(line) + ", column " + std::to_string(column);
    if (dom.ErrorId == 406) // a number too large for a double, such as 1e999
    {
      throw InputError(
        path, dom.ErrorPointer, "not a finite number (" + detail + ", " + position + ")");
    }
    throw InputError(path,
      position,
      "JSON syntax error: " + detail +
        (dom.ErrorPointer.empty() ? "" : " (in " + dom.ErrorPointer + ")"));
  }
  SceneParser parser(path, readMesh);
  return parser.Parse(root);
}

Scene LoadSceneFile(const std::string& path, const MeshFaceReader& readMesh)
{
  return ParseScene(ReadInputFile(path), path, readMesh);
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
  LocatingDomParser dom(parsed);
  if (!Json::sax_parse(value, &dom) || dom.Failed)
  {
    throw InputError("--set", key, "not a JSON value: " + Quote(value));
  }
  Json object = Json::object();
  object[key] = parsed;
  const std::string source = "--set";
  const MeshFaceReader none;
  SceneParser parser(source, none);
  return parser.Override(base, object);
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
