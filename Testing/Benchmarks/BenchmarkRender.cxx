// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BenchmarkRender.cxx
 * @brief Speed of the final rendering (paper §5.3) from a solved state, against the limit of
 * casting the same primary rays with raw Embree (Documentation/Verification.md#quality-bars: speed
 * is measured by a benchmark program, never by timed tests).
 *
 *   BenchmarkRender [--threads N] [--size 512 | WxH] [--spp 1] [--max-level L]
 *                   [--walk-sizes 256x256,1024x768] [--frames 8] [--compare 0|1]
 *                   [--scenes cornell_box.scene[:L],teapot_room.scene[:L]]
 *
 * --max-level overrides the scenes' subdivision depth (the teapot room's non-diffuse
 * propagation at its own depth 5 takes many minutes).
 *
 * Per scene (the Cornell box and the teapot room, their first camera at size x size):
 *  - the solved state: subdivision, spherical cover and propagation at the scene's settings,
 *    timed (the whole pipeline's seconds are these plus the render);
 *  - RadianceRenderer::Render: milliseconds, and rays per second;
 *  - raw Embree: the same count of rays, same directions, against the same tessellation (the
 *    resolution RayCaster chooses per patch), rtcIntersect1 with no filter, no refinement
 *    and no interpolation: milliseconds, and the render's cost as a ratio to it.
 *  - the render with the directional part of non-diffuse surfaces (paper §5.3.1: the teapot
 *    room's mirror wall and phong teapot), milliseconds (`dir_ms`), next to the render with
 *    the Lambertian part only (`render_ms`): the cost of the BRDF evaluations, O(strips of
 *    the row) per sample and neighbour (DirectionalExitantRadiance).
 *  - the walk-through (`sphcover walk`, issue 18): at each of --walk-sizes, --frames cameras
 *    on an orbit around the first camera (OrbitPath, as `walk --orbit`) rendered by the one
 *    renderer with the directional part, the mean milliseconds per frame next to raw Embree's
 *    for the same rays of the same frames, single rays (rtcIntersect1, rows in parallel) and
 *    packets (rtcIntersect16 over 4 x 4 pixel tiles, one sample index per packet, tile rows in
 *    parallel), and the ratios: what a frame costs against the limit of its primary rays alone.
 *    With --compare 1 each frame is rendered again with RenderSettings::FastPrimaryRays off (one
 *    rtcIntersect1 per ray, the renderer's images before packets), timed, and the packet
 *    frames' largest and mean radiance differences from it printed (issue 41's tolerance).
 *    Cycles at 16 spp for the same views is not run here: Data/reference/render_cycles.py
 *    (Documentation/notes/walk-through.md gives its times for the scenes' first cameras).
 */
#include "cover/HemisphereGrid.h"
#include "cover/RayCastFill.h"
#include "cover/SphericalCover.h"
#include "math/Constants.h"
#include "math/ParallelFor.h"
#include "propagation/LightPropagation.h"
#include "render/RadianceRenderer.h"
#include "scene/CameraPath.h"
#include "scene/SceneLoader.h"
#include "subdivision/CharacteristicPointInterpolator.h"
#include "subdivision/IntervalSubdivision.h"

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace sphcover;

namespace
{
using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The patches' tessellation as RayCaster makes it, in a plain Embree scene.
struct RawScene
{
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;

  explicit RawScene(const std::vector<Patch>& patches)
  {
    const RayCaster caster(RayCastPatches(patches), RayCasterOptions());
    this->Device = rtcNewDevice("threads=1");
    this->Scene = rtcNewScene(this->Device);
    rtcSetSceneFlags(this->Scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(this->Scene, RTC_BUILD_QUALITY_HIGH);
    for (size_t p = 0; p < patches.size(); ++p)
    {
      int nu = 0;
      int nv = 0;
      caster.Resolution(p, nu, nv);
      RTCGeometry geometry = rtcNewGeometry(this->Device, RTC_GEOMETRY_TYPE_TRIANGLE);
      float* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry,
        RTC_BUFFER_TYPE_VERTEX,
        0,
        RTC_FORMAT_FLOAT3,
        3 * sizeof(float),
        static_cast<size_t>((nu + 1) * (nv + 1))));
      for (int j = 0; j <= nv; ++j)
      {
        for (int i = 0; i <= nu; ++i)
        {
          const glm::dvec3 q = patches[p].Geometry.Evaluate(
            i == nu ? 1.0 : double(i) / nu, j == nv ? 1.0 : double(j) / nv);
          float* out = vertices + 3 * static_cast<size_t>(j * (nu + 1) + i);
          out[0] = static_cast<float>(q.x);
          out[1] = static_cast<float>(q.y);
          out[2] = static_cast<float>(q.z);
        }
      }
      unsigned* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry,
        RTC_BUFFER_TYPE_INDEX,
        0,
        RTC_FORMAT_UINT3,
        3 * sizeof(unsigned),
        static_cast<size_t>(2 * nu * nv)));
      for (int j = 0; j < nv; ++j)
      {
        for (int i = 0; i < nu; ++i)
        {
          const unsigned v00 = static_cast<unsigned>(j * (nu + 1) + i);
          const unsigned v01 = v00 + static_cast<unsigned>(nu + 1);
          unsigned* t = indices + 6 * static_cast<size_t>(j * nu + i);
          t[0] = v00;
          t[1] = v00 + 1;
          t[2] = v01 + 1;
          t[3] = v00;
          t[4] = v01 + 1;
          t[5] = v01;
        }
      }
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(this->Scene, geometry);
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(this->Scene);
  }
  ~RawScene()
  {
    rtcReleaseScene(this->Scene);
    rtcReleaseDevice(this->Device);
  }

  /// Casts the renderer's primary rays (same camera frame and sample positions); returns the
  /// number of hits (so the work cannot be optimised away).
  size_t Cast(const Camera& camera, int samples, const ParallelFor& parallelFor) const
  {
    const glm::dvec3 forward = glm::normalize(camera.FocalPoint - camera.Position);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.ViewUp));
    const glm::dvec3 up = glm::cross(right, forward);
    const double halfHeight = std::tan(0.5 * camera.ViewAngle * Pi / 180.0);
    const double halfWidth = halfHeight * camera.Width / camera.Height;
    std::vector<size_t> hitsPerRow(static_cast<size_t>(camera.Height), 0);
    parallelFor(static_cast<size_t>(camera.Height),
      [&](size_t begin, size_t end)
      {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        for (size_t j = begin; j < end; ++j)
        {
          for (int i = 0; i < camera.Width; ++i)
          {
            for (int k = 0; k < samples; ++k)
            {
              double radical = 0.0;
              double digit = 0.5;
              for (unsigned b = static_cast<unsigned>(k); b != 0; b >>= 1, digit *= 0.5)
              {
                radical += (b & 1u) ? digit : 0.0;
              }
              const double x = (2.0 * (i + (k + 0.5) / samples) / camera.Width - 1.0) * halfWidth;
              const double y =
                (2.0 * (j + radical + 0.5 / samples) / camera.Height - 1.0) * halfHeight;
              const glm::dvec3 d = glm::normalize(forward + x * right + y * up);
              RTCRayHit rayHit;
              rayHit.ray.org_x = static_cast<float>(camera.Position.x);
              rayHit.ray.org_y = static_cast<float>(camera.Position.y);
              rayHit.ray.org_z = static_cast<float>(camera.Position.z);
              rayHit.ray.dir_x = static_cast<float>(d.x);
              rayHit.ray.dir_y = static_cast<float>(d.y);
              rayHit.ray.dir_z = static_cast<float>(d.z);
              rayHit.ray.tnear = 0.0f;
              rayHit.ray.tfar = std::numeric_limits<float>::infinity();
              rayHit.ray.time = 0.0f;
              rayHit.ray.mask = 0xFFFFFFFFu;
              rayHit.ray.id = 0;
              rayHit.ray.flags = 0;
              rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
              rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
              rtcIntersect1(this->Scene, &context, &rayHit);
              hitsPerRow[j] += rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
          }
        }
      });
    size_t hits = 0;
    for (size_t h : hitsPerRow)
    {
      hits += h;
    }
    return hits;
  }
};

/// The renderer's primary direction of sample k of pixel (i, j) (RadianceRenderer's camera
/// frame and Hammersley positions, unshifted: the shift only moves samples within a pixel).
struct PrimaryRays
{
  glm::dvec3 Forward;
  glm::dvec3 Right;
  glm::dvec3 Up;
  double HalfWidth;
  double HalfHeight;
  int Width;
  int Height;
  int Samples;

  explicit PrimaryRays(const Camera& camera, int samples)
    : Width(camera.Width)
    , Height(camera.Height)
    , Samples(samples)
  {
    this->Forward = glm::normalize(camera.FocalPoint - camera.Position);
    this->Right = glm::normalize(glm::cross(this->Forward, camera.ViewUp));
    this->Up = glm::cross(this->Right, this->Forward);
    this->HalfHeight = std::tan(0.5 * camera.ViewAngle * Pi / 180.0);
    this->HalfWidth = this->HalfHeight * camera.Width / camera.Height;
  }
  glm::dvec3 Direction(int i, int j, int k) const
  {
    double radical = 0.0;
    double digit = 0.5;
    for (unsigned b = static_cast<unsigned>(k); b != 0; b >>= 1, digit *= 0.5)
    {
      radical += (b & 1u) ? digit : 0.0;
    }
    const double x = (2.0 * (i + (k + 0.5) / this->Samples) / this->Width - 1.0) * this->HalfWidth;
    const double y =
      (2.0 * (j + radical + 0.5 / this->Samples) / this->Height - 1.0) * this->HalfHeight;
    return glm::normalize(this->Forward + x * this->Right + y * this->Up);
  }
};

/// Casts the same rays as RawScene::Cast as rtcIntersect16 packets of 4 x 4 pixels (one sample
/// index per packet, as RadianceRenderer's tiles), the tile rows in parallel; returns the hits.
size_t CastPackets(RTCScene scene,
  const Camera& camera,
  int samples,
  const ParallelFor& parallelFor)
{
  const PrimaryRays rays(camera, samples);
  constexpr int side = RadianceRenderer::TileSide;
  const int tilesX = (camera.Width + side - 1) / side;
  const int tilesY = (camera.Height + side - 1) / side;
  std::vector<size_t> hitsPerRow(static_cast<size_t>(tilesY), 0);
  parallelFor(static_cast<size_t>(tilesY),
    [&](size_t begin, size_t end)
    {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (size_t tileY = begin; tileY < end; ++tileY)
      {
        for (int tileX = 0; tileX < tilesX; ++tileX)
        {
          const int i0 = tileX * side;
          const int j0 = static_cast<int>(tileY) * side;
          const int columns = std::min(side, camera.Width - i0);
          const int count = columns * std::min(side, camera.Height - j0);
          for (int k = 0; k < samples; ++k)
          {
            alignas(64) int valid[16];
            alignas(64) RTCRayHit16 packet;
            for (int p = 0; p < 16; ++p)
            {
              const bool active = p < count;
              valid[p] = active ? -1 : 0;
              const glm::dvec3 d =
                rays.Direction(i0 + (active ? p % columns : 0), j0 + (active ? p / columns : 0), k);
              packet.ray.org_x[p] = static_cast<float>(camera.Position.x);
              packet.ray.org_y[p] = static_cast<float>(camera.Position.y);
              packet.ray.org_z[p] = static_cast<float>(camera.Position.z);
              packet.ray.dir_x[p] = static_cast<float>(d.x);
              packet.ray.dir_y[p] = static_cast<float>(d.y);
              packet.ray.dir_z[p] = static_cast<float>(d.z);
              packet.ray.tnear[p] = 0.0f;
              packet.ray.tfar[p] = std::numeric_limits<float>::infinity();
              packet.ray.time[p] = 0.0f;
              packet.ray.mask[p] = 0xFFFFFFFFu;
              packet.ray.id[p] = static_cast<unsigned>(p);
              packet.ray.flags[p] = 0;
              packet.hit.geomID[p] = RTC_INVALID_GEOMETRY_ID;
              packet.hit.instID[0][p] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect16(valid, scene, &context, &packet);
            for (int p = 0; p < count; ++p)
            {
              hitsPerRow[tileY] += packet.hit.geomID[p] != RTC_INVALID_GEOMETRY_ID;
            }
          }
        }
      }
    });
  size_t hits = 0;
  for (size_t h : hitsPerRow)
  {
    hits += h;
  }
  return hits;
}

/// The largest and the mean absolute difference of two images' radiance (over the pixels'
/// bands), relative to the reference's largest value, and the pixels that differ at all.
struct ImageDifference
{
  double Largest = 0.0;
  double Sum = 0.0;
  size_t Values = 0;
  size_t PixelsDiffering = 0;
  size_t Pixels = 0;
  double LargestRadiance = 0.0;
  size_t SurfaceDiffering = 0;

  void Add(const RenderedImage& reference, const RenderedImage& image)
  {
    for (size_t p = 0; p < reference.SurfaceId.size(); ++p)
    {
      bool differs = false;
      for (size_t c = 0; c < 3; ++c)
      {
        const double a = reference.Radiance[3 * p + c];
        const double b = image.Radiance[3 * p + c];
        this->LargestRadiance = std::max(this->LargestRadiance, std::fabs(a));
        this->Largest = std::max(this->Largest, std::fabs(a - b));
        this->Sum += std::fabs(a - b);
        differs = differs || a != b;
      }
      this->Values += 3;
      this->PixelsDiffering += differs ? 1 : 0;
      this->SurfaceDiffering += reference.SurfaceId[p] != image.SurfaceId[p] ? 1 : 0;
    }
    this->Pixels += reference.SurfaceId.size();
  }
};

/// "N" (N x N) or "WxH"; false when it is neither.
bool ParseSize(const std::string& text, int& width, int& height)
{
  char x = 0;
  char rest = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &rest) == 3 && x == 'x')
  {
    return width > 0 && height > 0;
  }
  height = width = std::atoi(text.c_str());
  return width > 0 && text.find_first_not_of("0123456789") == std::string::npos;
}

struct Size
{
  int Width;
  int Height;
};

/// The walk-through's frames at each size (see the file comment), one line per size.
void Walk(const char* name,
  const RadianceRenderer& renderer,
  const RawScene& raw,
  const Camera& first,
  const glm::dvec3& lower,
  const glm::dvec3& upper,
  const std::vector<Size>& sizes,
  int frames,
  int samples,
  bool compare,
  const ParallelFor& parallelFor)
{
  for (const Size& size : sizes)
  {
    Camera orbitStart = first;
    orbitStart.Width = size.Width;
    orbitStart.Height = size.Height;
    RenderSettings settings;
    settings.SamplesPerPixel = samples;
    RenderSettings single = settings;
    single.FastPrimaryRays = false;
    double walkSeconds = 0.0;
    double rawSeconds = 0.0;
    double packetSeconds = 0.0;
    double singleSeconds = 0.0;
    size_t hits = 0;
    size_t packetHits = 0;
    ImageDifference difference;
    for (const Camera& camera : OrbitPath(orbitStart, frames, OrbitPivot(orbitStart, lower, upper)))
    {
      RenderedImage image;
      auto start = Clock::now();
      renderer.Render(camera, settings, image, parallelFor);
      walkSeconds += SecondsSince(start);
      start = Clock::now();
      hits += raw.Cast(camera, samples, parallelFor);
      rawSeconds += SecondsSince(start);
      start = Clock::now();
      packetHits += CastPackets(raw.Scene, camera, samples, parallelFor);
      packetSeconds += SecondsSince(start);
      if (compare)
      {
        RenderedImage reference;
        start = Clock::now();
        renderer.Render(camera, single, reference, parallelFor);
        singleSeconds += SecondsSince(start);
        difference.Add(reference, image);
      }
    }
    std::printf("%-18s walk %4dx%-4d %3d frames %8.1f ms/frame  raw Embree 1 %7.2f  16 %7.2f "
                "ms/frame  walk / raw 1 %5.2f  / raw 16 %5.2f  (%zu, %zu rays hit)\n",
      name,
      size.Width,
      size.Height,
      frames,
      1e3 * walkSeconds / frames,
      1e3 * rawSeconds / frames,
      1e3 * packetSeconds / frames,
      walkSeconds / rawSeconds,
      walkSeconds / packetSeconds,
      hits,
      packetHits);
    if (compare)
    {
      std::printf("%-18s   single-ray walk %8.1f ms/frame; packets against it: largest |dL| %.3g "
                  "(%.3g of the largest L), mean |dL| %.3g, %zu of %zu pixels differ, %zu "
                  "surface ids\n",
        "",
        1e3 * singleSeconds / frames,
        difference.Largest,
        difference.Largest / std::max(difference.LargestRadiance, 1e-300),
        difference.Sum / static_cast<double>(std::max<size_t>(difference.Values, 1)),
        difference.PixelsDiffering,
        difference.Pixels,
        difference.SurfaceDiffering);
    }
  }
}

void Run(const char* name,
  int threads,
  Size size,
  int samples,
  int maxLevel,
  const std::vector<Size>& walkSizes,
  int frames,
  bool compare)
{
  const ParallelFor parallelFor = threads <= 1 ? ParallelFor(SequentialFor) : ThreadedFor(threads);
  const Scene scene = LoadSceneFile(std::string(SPHCOVER_DATA_DIR "/scenes/") + name);

  // The solved state at the scene's settings.
  auto start = Clock::now();
  SubdivisionSettings subdivisionSettings;
  subdivisionSettings.MaxLevel = maxLevel >= 0 ? maxLevel : scene.Settings.MaxLevel;
  subdivisionSettings.ThetaBins = scene.Settings.ThetaBins;
  subdivisionSettings.PhiBins = scene.Settings.PhiBins;
  for (double& tolerance : subdivisionSettings.Tolerance)
  {
    tolerance = scene.Settings.Tolerance;
  }
  IntervalSubdivision subdivision(scene, subdivisionSettings);
  subdivision.Run(nullptr, parallelFor);
  const std::vector<Patch> patches = subdivision.Patches();
  const double subdivideSeconds = SecondsSince(start);
  start = Clock::now();
  SphericalCoverOptions coverOptions;
  coverOptions.ThetaBins = scene.Settings.ThetaBins;
  coverOptions.PhiBins = scene.Settings.PhiBins;
  SphericalCover cover;
  cover.Build(patches, coverOptions, parallelFor);
  const double coverSeconds = SecondsSince(start);
  start = Clock::now();
  const std::vector<Material> materials = LightPropagation::MaterialsOfPatches(scene, patches);
  std::vector<glm::dvec3> exitant;
  DirectionalIllumination directional;
  for (const Patch& patch : patches)
  {
    directional.Frames.push_back(HemisphereFrame::OfPatch(patch));
  }
  {
    LightPropagation propagation(cover, materials);
    propagation.SetFrames(directional.Frames);
    propagation.Run();
    for (size_t i = 0; i < patches.size(); ++i)
    {
      exitant.push_back(propagation.ExitantRadiance(i));
    }
    directional.IncidentRadiance = propagation.IncidentRadiances();
  }
  const double propagateSeconds = SecondsSince(start);
  directional.Cover = std::move(cover);
  directional.Materials = materials;

  start = Clock::now();
  const RadianceRenderer renderer(
    patches, CharacteristicPointInterpolator::OfPatches(patches), exitant);
  const double setupSeconds = SecondsSince(start);
  RadianceRenderer nonDiffuse(
    patches, CharacteristicPointInterpolator::OfPatches(patches), exitant);
  start = Clock::now();
  nonDiffuse.SetDirectionalIllumination(std::move(directional));
  const double directionalSetupSeconds = SecondsSince(start);
  Camera camera = scene.Cameras.at(0);
  camera.Width = size.Width;
  camera.Height = size.Height;
  RenderSettings settings;
  settings.SamplesPerPixel = samples;
  RenderedImage image;
  start = Clock::now();
  renderer.Render(camera, settings, image, parallelFor);
  const double renderSeconds = SecondsSince(start);
  start = Clock::now();
  nonDiffuse.Render(camera, settings, image, parallelFor);
  const double directionalSeconds = SecondsSince(start);

  const RawScene raw(patches);
  start = Clock::now();
  const size_t hits = raw.Cast(camera, samples, parallelFor);
  const double rawSeconds = SecondsSince(start);
  const double rays = static_cast<double>(size.Width) * size.Height * samples;

  std::printf("%-18s %7zu %9zu %7.1f %7.1f %9.1f %8.1f %9.2f %8.1f %7.1f %6.2f %9.2f %8.1f\n",
    name,
    patches.size(),
    renderer.TriangleCount(),
    subdivideSeconds,
    coverSeconds,
    1e3 * propagateSeconds,
    1e3 * setupSeconds,
    1e3 * renderSeconds,
    rays / renderSeconds / 1e6,
    1e3 * rawSeconds,
    renderSeconds / rawSeconds,
    1e3 * directionalSeconds,
    1e3 * directionalSetupSeconds);
  std::printf("%-18s whole pipeline %.1f s (%zu of %.0f rays hit)\n",
    "",
    subdivideSeconds + coverSeconds + propagateSeconds + setupSeconds + directionalSetupSeconds +
      directionalSeconds,
    hits,
    rays);
  glm::dvec3 lower;
  glm::dvec3 upper;
  scene.Bounds(lower, upper);
  Walk(name,
    nonDiffuse,
    raw,
    scene.Cameras.at(0),
    lower,
    upper,
    walkSizes,
    frames,
    samples,
    compare,
    parallelFor);
}
}

int main(int argc, char* argv[])
{
  int threads = 1;
  Size size{ 512, 512 };
  int samples = 1;
  int maxLevel = -1;
  std::vector<Size> walkSizes{ { 256, 256 }, { 1024, 768 } };
  int frames = 8;
  bool compare = false;
  std::vector<std::pair<std::string, int>> scenes{ { "cornell_box.scene", -1 },
    { "teapot_room.scene", -1 } };
  for (int k = 1; k + 1 < argc; k += 2)
  {
    if (std::strcmp(argv[k], "--threads") == 0)
    {
      threads = std::atoi(argv[k + 1]);
    }
    else if (std::strcmp(argv[k], "--size") == 0)
    {
      if (!ParseSize(argv[k + 1], size.Width, size.Height))
      {
        std::fprintf(stderr, "--size %s: expected N or WxH\n", argv[k + 1]);
        return 1;
      }
    }
    else if (std::strcmp(argv[k], "--walk-sizes") == 0)
    {
      walkSizes.clear();
      std::string list = argv[k + 1];
      for (size_t begin = 0; begin <= list.size();)
      {
        const size_t end = std::min(list.find(',', begin), list.size());
        Size walk{ 0, 0 };
        if (!ParseSize(list.substr(begin, end - begin), walk.Width, walk.Height))
        {
          std::fprintf(stderr, "--walk-sizes %s: expected WxH,WxH,...\n", argv[k + 1]);
          return 1;
        }
        walkSizes.push_back(walk);
        begin = end + 1;
      }
    }
    else if (std::strcmp(argv[k], "--frames") == 0)
    {
      frames = std::atoi(argv[k + 1]);
      if (frames < 1)
      {
        std::fprintf(stderr, "--frames %s: expected a positive number\n", argv[k + 1]);
        return 1;
      }
    }
    else if (std::strcmp(argv[k], "--spp") == 0)
    {
      samples = std::atoi(argv[k + 1]);
    }
    else if (std::strcmp(argv[k], "--max-level") == 0)
    {
      maxLevel = std::atoi(argv[k + 1]);
    }
    else if (std::strcmp(argv[k], "--compare") == 0)
    {
      compare = std::atoi(argv[k + 1]) != 0;
    }
    else if (std::strcmp(argv[k], "--scenes") == 0)
    {
      // NAME[:LEVEL],...: the scenes of Data/scenes, each at its own --max-level if given.
      scenes.clear();
      const std::string list = argv[k + 1];
      for (size_t begin = 0; begin <= list.size();)
      {
        const size_t end = std::min(list.find(',', begin), list.size());
        const std::string item = list.substr(begin, end - begin);
        const size_t colon = item.find(':');
        scenes.emplace_back(item.substr(0, colon),
          colon == std::string::npos ? -1 : std::atoi(item.c_str() + colon + 1));
        begin = end + 1;
      }
    }
  }
  std::printf("%d thread(s), %dx%d pixels, %d sample(s) per pixel\n",
    threads,
    size.Width,
    size.Height,
    samples);
  std::printf("scene              patches triangles subdiv_s cover_s prop_ms setup_ms render_ms "
              "Mrays/s  raw_ms  ratio    dir_ms dirset_ms\n");
  for (const auto& scene : scenes)
  {
    Run(scene.first.c_str(),
      threads,
      size,
      samples,
      scene.second >= 0 ? scene.second : maxLevel,
      walkSizes,
      frames,
      compare);
  }
  return 0;
}
