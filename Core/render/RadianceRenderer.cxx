// SPDX-License-Identifier: BSD-3-Clause
#include "render/RadianceRenderer.h"

#include "render/BuriedPoints.h"

#include "math/Constants.h"
#include "math/PatternShift.h"
#include "math/RadicalInverse.h"

#include "cover/HemisphereGrid.h"
#include "cover/RayCastFill.h"
#include "geometry/RayCaster.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sphcover
{

namespace
{

bool Finite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The camera's frame: the unit view direction and the right and up vectors scaled to the half
/// extents of the image plane at distance 1.
struct ViewFrame
{
  glm::dvec3 Eye;
  glm::dvec3 Forward;
  glm::dvec3 Right;
  glm::dvec3 Up;
};

ViewFrame FrameOf(const Camera& camera)
{
  ViewFrame frame;
  frame.Eye = camera.Position;
  frame.Forward = glm::normalize(camera.FocalPoint - camera.Position);
  const glm::dvec3 right = glm::normalize(glm::cross(frame.Forward, camera.ViewUp));
  const glm::dvec3 up = glm::cross(right, frame.Forward);
  const double halfHeight = std::tan(0.5 * camera.ViewAngle * Pi / 180.0);
  const double halfWidth = halfHeight * camera.Width / camera.Height;
  frame.Right = halfWidth * right;
  frame.Up = halfHeight * up;
  return frame;
}

/// The stratified positions of the samples in a pixel (Hammersley's set, file comment).
void SampleOffsets(int samples, std::vector<double>& offsetX, std::vector<double>& offsetY)
{
  offsetX.resize(static_cast<size_t>(samples));
  offsetY.resize(static_cast<size_t>(samples));
  for (int k = 0; k < samples; ++k)
  {
    offsetX[static_cast<size_t>(k)] = (k + 0.5) / samples;
    // Shifted by half a stratum so that one sample sits at the pixel's centre.
    offsetY[static_cast<size_t>(k)] = RadicalInverse(static_cast<unsigned>(k)) + 0.5 / samples;
  }
}

/// The shift of a pixel's sample pattern (a Cranley-Patterson rotation, in [0,1)^2, from the
/// pixel's index alone). With one pattern for every pixel, an edge across a row of pixels cuts
/// every pixel's pattern at the same place, and the error of its coverage (up to one sample in
/// N) is the same in all of them: along the outline of a lamp 100 times brighter than the
/// ceiling around it, that is several per cent of a block's mean. Shifted per pixel, the
/// errors average out along the edge; each pixel keeps one sample per column and per row
/// stratum (the shift is modulo 1).
void PixelShift(std::size_t pixel, double& shiftX, double& shiftY)
{
  PatternShift(static_cast<uint64_t>(pixel), shiftX, shiftY);
}

/// x modulo 1 for x in [0, 2).
double Wrap(double x)
{
  return x >= 1.0 ? x - 1.0 : x;
}

/// A sample's hit: its surface and distance from the eye.
struct SampleHit
{
  int Surface;
  double Distance;
};

/// The surface most of a pixel's samples hit (ties: the lowest index) and their mean
/// distance: the few samples sorted by surface, the runs counted. `hits` is not empty.
void MostHitSurface(std::vector<SampleHit>& hits, int& surface, double& depth)
{
  // A stable insertion sort: the order std::stable_sort gives, without its buffer's allocation
  // per pixel (a pixel has a few samples).
  for (size_t k = 1; k < hits.size(); ++k)
  {
    const SampleHit hit = hits[k];
    size_t m = k;
    for (; m > 0 && hit.Surface < hits[m - 1].Surface; --m)
    {
      hits[m] = hits[m - 1];
    }
    hits[m] = hit;
  }
  int best = -1;
  size_t bestCount = 0;
  double bestDistance = 0.0;
  for (size_t first = 0; first < hits.size();)
  {
    size_t last = first;
    double distance = 0.0;
    for (; last < hits.size() && hits[last].Surface == hits[first].Surface; ++last)
    {
      distance += hits[last].Distance;
    }
    if (last - first > bestCount)
    {
      best = hits[first].Surface;
      bestCount = last - first;
      bestDistance = distance / static_cast<double>(bestCount);
    }
    first = last;
  }
  surface = best;
  depth = bestDistance;
}

/// The pixel's mean radiance over its samples and, where a sample hit a surface, the surface
/// most of them hit and their mean distance.
void StorePixel(size_t pixel,
  const glm::dvec3& sum,
  int samples,
  std::vector<SampleHit>& hits,
  RenderedImage& image)
{
  const glm::dvec3 mean = sum / static_cast<double>(samples);
  image.Radiance[3 * pixel + 0] = static_cast<float>(mean.x);
  image.Radiance[3 * pixel + 1] = static_cast<float>(mean.y);
  image.Radiance[3 * pixel + 2] = static_cast<float>(mean.z);
  if (hits.empty())
  {
    return;
  }
  int surface;
  double depth;
  MostHitSurface(hits, surface, depth);
  image.SurfaceId[pixel] = surface;
  image.Depth[pixel] = static_cast<float>(depth);
}
}

std::string CheckCamera(const Camera& camera, const RenderSettings& settings)
{
  std::ostringstream problem;
  const std::string name = camera.Name.empty() ? "the camera" : "camera '" + camera.Name + "'";
  if (!Finite(camera.Position) || !Finite(camera.FocalPoint) || !Finite(camera.ViewUp) ||
    !std::isfinite(camera.ViewAngle))
  {
    problem << name << ": position, focal point, view up and view angle must be finite numbers";
  }
  else if (!(LargestCoordinate({ camera.Position }) <= MaxRayCastCoordinate))
  {
    // The eye starts every ray: Embree aborts on an origin beyond its range.
    problem << name << ": the position is beyond the coordinates ray casting can trace (|x| <= "
            << MaxRayCastCoordinate << ")";
  }
  else if (!(camera.ViewAngle > 0.0 && camera.ViewAngle < 180.0))
  {
    problem << name << ": the view angle " << camera.ViewAngle << " is not in (0, 180) degrees";
  }
  else if (!(glm::length(camera.FocalPoint - camera.Position) > 0.0))
  {
    problem << name << ": the position is the focal point (no view direction)";
  }
  else if (!(glm::length(camera.ViewUp) > 0.0) ||
    !(glm::length(glm::cross(glm::normalize(camera.FocalPoint - camera.Position),
        glm::normalize(camera.ViewUp))) > 1e-6))
  {
    problem << name << ": the view up is zero or parallel to the view direction";
  }
  else if (camera.Width < 1 || camera.Height < 1)
  {
    problem << name << ": the image size " << camera.Width << "x" << camera.Height
            << " is not at least 1x1";
  }
  else if (settings.SamplesPerPixel < 1 || settings.SamplesPerPixel > 4096)
  {
    problem << "samples per pixel " << settings.SamplesPerPixel << " is not in [1, 4096]";
  }
  else
  {
    const double bytes = static_cast<double>(camera.Width) * camera.Height *
      static_cast<double>(RenderedImage::BytesPerPixel);
    const double samples =
      static_cast<double>(camera.Width) * camera.Height * settings.SamplesPerPixel;
    problem.precision(3);
    if (bytes > static_cast<double>(settings.MemoryLimitBytes))
    {
      problem << "an image of " << camera.Width << "x" << camera.Height << " pixels needs about "
              << bytes / (1024.0 * 1024.0) << " MiB, more than the limit of "
              << static_cast<double>(settings.MemoryLimitBytes) / (1024.0 * 1024.0) << " MiB";
    }
    else if (samples > static_cast<double>(settings.MaximumSamples))
    {
      problem << "an image of " << camera.Width << "x" << camera.Height << " pixels at "
              << settings.SamplesPerPixel << " samples per pixel casts " << samples
              << " rays, more than the budget of " << static_cast<double>(settings.MaximumSamples)
              << " (about "
              << RenderSecondsPerSample * static_cast<double>(settings.MaximumSamples) / 60.0
              << " minutes on one core)";
    }
  }
  return problem.str();
}

RadianceRenderer::RadianceRenderer(std::vector<Patch> patches,
  CharacteristicPointInterpolator interpolator,
  std::vector<glm::dvec3> exitantRadiance,
  std::vector<bool> twoSidedSurface)
  : Patches(std::move(patches))
  , Interpolator(std::move(interpolator))
  , Exitant(std::move(exitantRadiance))
  , TwoSided(std::move(twoSidedSurface))
{
  if (this->Exitant.size() != this->Interpolator.PointCount())
  {
    throw std::invalid_argument("RadianceRenderer: " + std::to_string(this->Exitant.size()) +
      " radiance values for " + std::to_string(this->Interpolator.PointCount()) +
      " characteristic points");
  }
  this->Caster = std::make_unique<RayCaster>(RayCastPatches(this->Patches), RayCasterOptions());
  this->MarkPassedBacks();
  // Buried points stand for no visible surface (BuriedPoints.h): no pixel takes after them.
  this->Interpolator.SetExcludedPoints(
    BuriedPoints(this->Interpolator, this->Patches, *this->Caster, this->PassedBack));
}

RadianceRenderer::~RadianceRenderer() = default;

std::size_t RadianceRenderer::TriangleCount() const
{
  return this->Caster->TriangleCount();
}

glm::dvec3 InterpolateRadiance(const CharacteristicPointInterpolator& interpolator,
  const std::vector<glm::dvec3>& exitantRadiance,
  int surface,
  double u,
  double v)
{
  InterpolationStencil stencil;
  if (!interpolator.Stencil(surface, u, v, stencil))
  {
    return glm::dvec3(0.0);
  }
  glm::dvec3 radiance(0.0);
  for (int k = 0; k < stencil.Count; ++k)
  {
    radiance += stencil.Weights[static_cast<size_t>(k)] *
      exitantRadiance[stencil.Points[static_cast<size_t>(k)]];
  }
  return glm::max(radiance, glm::dvec3(0.0));
}

glm::dvec3 RadianceRenderer::SurfaceRadiance(int surface, double u, double v) const
{
  return this->Textured(surface,
    u,
    v,
    InterpolateRadiance(this->Interpolator, this->Exitant, surface, u, v) +
      this->Direct.At(this->Interpolator, surface, u, v));
}

void RadianceRenderer::SetSurfaceTextures(std::vector<SurfaceTexture> textures)
{
  this->Textures = std::move(textures);
}

bool RadianceRenderer::IsTextured(int surface) const
{
  return surface >= 0 && static_cast<std::size_t>(surface) < this->Textures.size() &&
    this->Textures[static_cast<std::size_t>(surface)].Image != nullptr;
}

glm::dvec3 TexturedRadiance(const std::vector<SurfaceTexture>& textures,
  int surface,
  double u,
  double v,
  const glm::dvec3& untextured)
{
  if (surface < 0 || static_cast<std::size_t>(surface) >= textures.size() ||
    !textures[static_cast<std::size_t>(surface)].Image)
  {
    return untextured;
  }
  // The emission is uniform over the surface and not textured; the reflected rest is k_d / pi
  // times the interpolated irradiance, which the texture multiplies at (u, v) (paper §5.4).
  const SurfaceTexture& texture = textures[static_cast<std::size_t>(surface)];
  const glm::dvec3 reflected = glm::max(untextured - texture.Emission, glm::dvec3(0.0));
  return texture.Emission + texture.Image->At(u, v) * reflected;
}

glm::dvec3 RadianceRenderer::Textured(int surface,
  double u,
  double v,
  const glm::dvec3& untextured) const
{
  return TexturedRadiance(this->Textures, surface, u, v, untextured);
}

DirectLight::DirectLight(DirectIrradianceNodes nodes,
  const std::vector<glm::dvec3>& diffuse,
  std::size_t points,
  const std::vector<glm::dvec3>& coverIrradiance)
{
  if (!coverIrradiance.empty() && coverIrradiance.size() != points)
  {
    throw std::invalid_argument("the cover's lamp irradiance of " +
      std::to_string(coverIrradiance.size()) + " points for " + std::to_string(points) +
      " characteristic points");
  }
  const std::size_t perPoint =
    3 * static_cast<std::size_t>(nodes.NodesPerSide) * static_cast<std::size_t>(nodes.NodesPerSide);
  if (diffuse.size() != points || nodes.Values.size() != perPoint * points)
  {
    throw std::invalid_argument("direct irradiance of " +
      std::to_string(perPoint > 0 ? nodes.Values.size() / perPoint : 0) + " points and " +
      std::to_string(diffuse.size()) + " reflectances for " + std::to_string(points) +
      " characteristic points");
  }
  this->Factor.resize(points);
  for (std::size_t p = 0; p < points; ++p)
  {
    this->Factor[p] = diffuse[p] / Pi;
  }
  this->Nodes = std::move(nodes);
  if (!coverIrradiance.empty())
  {
    this->CoverPart.resize(points);
    for (std::size_t p = 0; p < points; ++p)
    {
      this->CoverPart[p] = this->Factor[p] * coverIrradiance[p];
    }
  }
}

glm::dvec3 DirectLight::PointPart(std::size_t point) const
{
  return this->CoverPart.empty() ? this->AtPoint(point) : this->CoverPart[point];
}

glm::dvec3 DirectLight::AtPoint(std::size_t point) const
{
  return this->Factor[point] * this->Nodes.At(point, 0.5, 0.5);
}

glm::dvec3 DirectLight::At(const CharacteristicPointInterpolator& interpolator,
  int surface,
  double u,
  double v) const
{
  if (this->Empty())
  {
    return glm::dvec3(0.0);
  }
  const std::ptrdiff_t point = interpolator.ContainingPoint(surface, u, v);
  if (point < 0)
  {
    return glm::dvec3(0.0);
  }
  const std::size_t p = static_cast<std::size_t>(point);
  const UVRect& domain = interpolator.Domain(p);
  const double s = (u - domain.U0) / (domain.U1 - domain.U0);
  const double t = (v - domain.V0) / (domain.V1 - domain.V0);
  return this->Factor[p] * this->Nodes.At(p, s, t);
}

std::vector<glm::dvec3> DirectLight::Rest(std::vector<glm::dvec3> exitantRadiance) const
{
  if (!this->Empty())
  {
    for (std::size_t p = 0; p < exitantRadiance.size(); ++p)
    {
      exitantRadiance[p] -= this->PointPart(p);
    }
  }
  return exitantRadiance;
}

void RadianceRenderer::SetDirectLight(DirectLight direct)
{
  if (!direct.Empty() && direct.Factor.size() != this->Interpolator.PointCount())
  {
    throw std::invalid_argument("RadianceRenderer: direct light of " +
      std::to_string(direct.Factor.size()) + " points for " +
      std::to_string(this->Interpolator.PointCount()) + " characteristic points");
  }
  // The rest is taken of the points' own I (an earlier direct light given back first).
  for (std::size_t p = 0; p < this->Exitant.size() && !this->Direct.Empty(); ++p)
  {
    this->Exitant[p] += this->Direct.PointPart(p);
  }
  this->Exitant = direct.Rest(std::move(this->Exitant));
  this->Direct = std::move(direct);
}

void RadianceRenderer::SetDirectionalIllumination(DirectionalIllumination illumination)
{
  const std::size_t points = this->Interpolator.PointCount();
  if (illumination.Cover.PatchCount() != points || illumination.Frames.size() != points ||
    illumination.Materials.size() != points)
  {
    throw std::invalid_argument("RadianceRenderer: the directional illumination has a cover of " +
      std::to_string(illumination.Cover.PatchCount()) + " points, " +
      std::to_string(illumination.Frames.size()) + " frames and " +
      std::to_string(illumination.Materials.size()) + " materials for " + std::to_string(points) +
      " characteristic points");
  }
  if (illumination.IncidentRadiance.size() != illumination.Cover.EntryCount())
  {
    throw std::invalid_argument(
      "RadianceRenderer: " + std::to_string(illumination.IncidentRadiance.size()) +
      " incident radiance values for a cover of " +
      std::to_string(illumination.Cover.EntryCount()) + " entries");
  }
  this->Reflectances = PointReflectances(illumination.Cover.Grid(), illumination.Materials);
  // The ideal mirrors, whose view the render follows along the reflected ray (file comment).
  this->MirrorSpecular.clear();
  for (std::size_t p = 0; p < points; ++p)
  {
    const Material& material = illumination.Materials[p];
    if (material.Type == MaterialType::Mirror)
    {
      const std::size_t surface = static_cast<std::size_t>(this->Interpolator.SurfaceOf(p));
      if (this->MirrorSpecular.size() <= surface)
      {
        this->MirrorSpecular.resize(surface + 1, glm::dvec3(-1.0));
      }
      this->MirrorSpecular[surface] = material.Specular;
    }
  }
  this->MirrorPatches.assign(this->MirrorSpecular.size(), {});
  for (std::size_t p = 0; p < this->Patches.size(); ++p)
  {
    if (this->MirrorOf(this->Patches[p].SurfaceIndex))
    {
      this->MirrorPatches[static_cast<std::size_t>(this->Patches[p].SurfaceIndex)].push_back(p);
    }
  }
  this->Directional = std::make_unique<DirectionalIllumination>(std::move(illumination));
  // The caches hold the former illumination's values.
  const std::lock_guard<std::mutex> lock(this->CachePoolMutex);
  this->CachePool.clear();
}

const glm::dvec3* RadianceRenderer::MirrorOf(int surface) const
{
  if (surface < 0 || static_cast<std::size_t>(surface) >= this->MirrorSpecular.size() ||
    this->MirrorSpecular[static_cast<std::size_t>(surface)].x < 0.0)
  {
    return nullptr;
  }
  return &this->MirrorSpecular[static_cast<std::size_t>(surface)];
}

glm::dvec3 RadianceRenderer::SurfaceRadianceToward(int surface,
  double u,
  double v,
  const glm::dvec3& towardEye) const
{
  return this->RadianceToward(surface, u, v, towardEye, nullptr);
}

RadianceRenderer::DirectionalCache::DirectionalCache(int bits)
  : Shift(64 - std::clamp(bits, 1, 30))
  , Keys(std::size_t(1) << std::clamp(bits, 1, 30), ~uint64_t(0))
  , Values(std::size_t(1) << std::clamp(bits, 1, 30))
{
}

RadianceRenderer::TowardTerms RadianceRenderer::Terms(int surface, double u, double v) const
{
  TowardTerms terms;
  terms.Surface = surface;
  terms.U = u;
  terms.V = v;
  terms.HasStencil = this->Interpolator.Stencil(surface, u, v, terms.Stencil);
  if (terms.HasStencil)
  {
    terms.Direct = this->Direct.At(this->Interpolator, surface, u, v);
  }
  if (terms.HasStencil && this->MirrorOf(surface))
  {
    // A mirror's view follows its reflected ray from the exact point (file comment): the patch
    // that holds (u, v) and its own parameters there.
    for (const std::size_t p : this->MirrorPatches[static_cast<std::size_t>(surface)])
    {
      const UVRect& d = this->Patches[p].Domain;
      if (u >= d.U0 && u <= d.U1 && v >= d.V0 && v <= d.V1)
      {
        terms.MirrorPatch = static_cast<std::ptrdiff_t>(p);
        terms.PatchU = (u - d.U0) / (d.U1 - d.U0);
        terms.PatchV = (v - d.V0) / (d.V1 - d.V0);
        break;
      }
    }
  }
  return terms;
}

glm::dvec3 RadianceRenderer::RadianceToward(const TowardTerms& terms,
  const glm::dvec3& towardEye,
  DirectionalCache& cache) const
{
  if (terms.MirrorPatch >= 0)
  {
    // The mirror's point seen from the eye, shaded as the render's ray that meets it.
    glm::dvec3 radiance(0.0);
    this->ShadeHit(static_cast<std::size_t>(terms.MirrorPatch),
      terms.PatchU,
      terms.PatchV,
      true,
      -towardEye,
      &cache,
      0,
      radiance);
    return radiance;
  }
  return this->TermsToward(terms, towardEye, &cache);
}

bool RadianceRenderer::IsViewDependent(const TowardTerms& terms) const
{
  for (int k = 0; this->Directional && terms.HasStencil && k < terms.Stencil.Count; ++k)
  {
    if (this->Reflectances.Table(terms.Stencil.Points[static_cast<size_t>(k)]))
    {
      return true;
    }
  }
  return false;
}

glm::dvec3 RadianceRenderer::DirectionalPart(std::size_t point,
  const ReflectanceWeights& table,
  const glm::dvec3& towardEye,
  DirectionalCache* cache) const
{
  const DirectionalIllumination& lit = *this->Directional;
  const glm::dvec3 local = lit.Frames[point].ToLocal(towardEye);
  if (!cache)
  {
    return DirectionalExitantRadiance(lit.Cover, table, point, lit.IncidentRadiance, local);
  }
  // DirectionalExitantRadiance depends on the direction through its cell only.
  const HemisphereGrid& grid = lit.Cover.Grid();
  const int cell = grid.CellOfLocalDirection(local);
  if (cell < 0 || !(local.z > 0.0))
  {
    return glm::dvec3(0.0);
  }
  const uint64_t key = static_cast<uint64_t>(point) * static_cast<uint64_t>(grid.CellCount()) +
    static_cast<uint64_t>(cell);
  const std::size_t slot = cache->Slot(key);
  if (cache->Keys[slot] != key)
  {
    cache->Keys[slot] = key;
    if (cache->Needed)
    {
      cache->Needed->push_back(key);
      cache->Values[slot] = glm::dvec3(0.0);
    }
    else if (cache->Given)
    {
      const std::vector<uint64_t>& keys = cache->Given->Keys;
      const auto found = std::lower_bound(keys.begin(), keys.end(), key);
      if (found == keys.end() || *found != key)
      {
        ++cache->Missing;
        cache->Values[slot] = glm::dvec3(0.0);
      }
      else
      {
        cache->Values[slot] = cache->Given->Values[static_cast<size_t>(found - keys.begin())];
      }
    }
    else
    {
      cache->Values[slot] =
        DirectionalExitantRadiance(lit.Cover, table, point, lit.IncidentRadiance, local);
    }
  }
  return cache->Values[slot];
}

glm::dvec3 RadianceRenderer::RadianceToward(int surface,
  double u,
  double v,
  const glm::dvec3& towardEye,
  DirectionalCache* cache) const
{
  // The stored value: Terms' mirror patch is not followed here (TermsToward).
  return this->TermsToward(this->Terms(surface, u, v), towardEye, cache);
}

glm::dvec3 RadianceRenderer::TermsToward(const TowardTerms& terms,
  const glm::dvec3& towardEye,
  DirectionalCache* cache) const
{
  if (!terms.HasStencil)
  {
    return glm::dvec3(0.0);
  }
  // Paper §5.3.1 with §3.4: each neighbour's exitant radiance toward the eye (the eye's
  // direction in its own hemisphere frame), blended with the interpolation weights; the same
  // as the BRDF applied to the interpolated E, the BRDF being linear in E.
  const InterpolationStencil& stencil = terms.Stencil;
  glm::dvec3 radiance(0.0);
  glm::dvec3 directional(0.0);
  const bool textured = this->IsTextured(terms.Surface);
  for (int k = 0; k < stencil.Count; ++k)
  {
    const std::size_t point = stencil.Points[static_cast<size_t>(k)];
    const double weight = stencil.Weights[static_cast<size_t>(k)];
    glm::dvec3 value = this->Exitant[point];
    const ReflectanceWeights* table = this->Directional ? this->Reflectances.Table(point) : nullptr;
    if (table)
    {
      const glm::dvec3 part = this->DirectionalPart(point, *table, towardEye, cache);
      if (textured)
      {
        directional += weight * part;
      }
      else
      {
        value += part;
      }
    }
    radiance += weight * value;
  }
  if (textured)
  {
    // The texture scales the Lambertian part only (SetSurfaceTextures).
    return this->Textured(
             terms.Surface, terms.U, terms.V, glm::max(radiance, glm::dvec3(0.0)) + terms.Direct) +
      glm::max(directional, glm::dvec3(0.0));
  }
  return glm::max(radiance, glm::dvec3(0.0)) + terms.Direct;
}

bool RadianceRenderer::ShadeHit(std::size_t patchIndex,
  double patchU,
  double patchV,
  bool frontSide,
  const glm::dvec3& direction,
  DirectionalCache* cache,
  int bounces,
  glm::dvec3& radiance) const
{
  const Patch& patch = this->Patches[patchIndex];
  const int surface = patch.SurfaceIndex;
  if (!frontSide)
  {
    // A back side sends no light; that of a two-sided surface is never met (TraceSample passes
    // it and meets the other side's front).
    return false;
  }
  const double u = patch.Domain.U0 + patchU * (patch.Domain.U1 - patch.Domain.U0);
  const double v = patch.Domain.V0 + patchV * (patch.Domain.V1 - patch.Domain.V0);
  const glm::dvec3* mirror = bounces < MaxMirrorBounces ? this->MirrorOf(surface) : nullptr;
  if (!mirror)
  {
    // The front side toward the eye (paper §5.3.1).
    radiance = this->RadianceToward(surface, u, v, -direction, cache);
    return true;
  }
  // An ideal mirror (paper §3.5.1): I toward the eye is k_s times the radiance arriving at this
  // very point from the mirror direction, what the reflected ray meets there, shaded as the
  // eye's rays are; not the mirror cell of the characteristic points' E blended over the
  // stencil (each holds what its own point sees: the file comment). Its Lambertian part (its
  // emission, a diffuse part) is interpolated as on any surface.
  radiance = this->SurfaceRadiance(surface, u, v);
  // The normal turned toward the ray (the limit normal at a degenerate point, a sphere's pole,
  // may face either way; the hit's side is the front).
  glm::dvec3 normal = patch.Geometry.Normal(patchU, patchV);
  if (glm::dot(direction, normal) > 0.0)
  {
    normal = -normal;
  }
  const glm::dvec3 reflected =
    glm::normalize(direction - 2.0 * glm::dot(direction, normal) * normal);
  // Off the front by a hair (as the direct light's rays, DirectIrradiance.h; the rays are single
  // precision), so that the ray does not meet the mirror it leaves.
  const glm::dvec3 origin =
    patch.Geometry.Evaluate(patchU, patchV) + normal * (1e-4 * patch.Geometry.Size());
  SampleResult seen;
  if (this->TraceSample(origin, reflected, cache, seen, bounces + 1, patchIndex) && seen.Lit)
  {
    radiance += *mirror * seen.Radiance;
  }
  else
  {
    // Nothing lit along the reflected ray: it escaped, or met a back side, which inside a closed
    // curved mirror is the tessellation's chord rather than the exact surface. The cover's own
    // value (its R-buffer counts the same sides, RBuffer.h) then stands for it: the stored E of
    // the mirror cell, blended over the stencil (0 where the cover sees nothing either).
    radiance = this->RadianceToward(surface, u, v, -direction, cache);
  }
  return true;
}

namespace
{
/// The eye rays' filter with panes or two-sided surfaces: the back side of a pane or of a side of
/// a two-sided surface is its reversed copy's front, met at the same place (PassedBack).
bool PassPaneBacks(const void* context, std::size_t patch, float, bool front)
{
  return front || !(*static_cast<const std::vector<char>*>(context))[patch];
}

/// A ray reflected by a mirror: it leaves the exact surface, which the tessellation only
/// approximates (RayCasterOptions::TessellationTolerance), so on a concave mirror it may meet
/// the back of its own surface's triangles at once.
struct LeavingMirror
{
  const std::vector<Patch>* Patches;
  /// PassPaneBacks' flags, or null.
  const std::vector<char>* PassedBack;
  int Surface;
  float Within;
};

bool PassOwnBackNear(const void* context, std::size_t patch, float distance, bool front)
{
  const LeavingMirror& leaving = *static_cast<const LeavingMirror*>(context);
  if (front)
  {
    return true;
  }
  if (distance < leaving.Within && (*leaving.Patches)[patch].SurfaceIndex == leaving.Surface)
  {
    return false;
  }
  return !leaving.PassedBack || !(*leaving.PassedBack)[patch];
}
}

bool RadianceRenderer::TraceSample(const glm::dvec3& eye,
  const glm::dvec3& direction,
  DirectionalCache* cache,
  SampleResult& sample,
  int bounces,
  std::ptrdiff_t leaving,
  const PrecastHit* precast) const
{
  RayCaster::RayHit hit;
  // The first cast's hit, given (a packet's, RenderRows) or cast here.
  auto first = [&](float nearest, const RayFilter& filter)
  {
    if (precast)
    {
      hit.Patch = precast->Patch;
      hit.U = precast->U;
      hit.V = precast->V;
      hit.T = precast->T;
      hit.FrontSide = precast->FrontSide;
      return precast->Found;
    }
    return this->Caster->CastRay(eye, direction, nearest, filter, hit);
  };
  LeavingMirror mirror{ &this->Patches,
    this->PassedBack.empty() ? nullptr : &this->PassedBack,
    leaving < 0 ? -1 : this->Patches[static_cast<std::size_t>(leaving)].SurfaceIndex,
    leaving < 0 ? 0.0f
                : static_cast<float>(
                    0.05 * this->Patches[static_cast<std::size_t>(leaving)].Geometry.Size()) };
  const RayFilter fromMirror{ PassOwnBackNear, &mirror };
  if (this->PassedBack.empty())
  {
    if (!(leaving < 0 ? first(0.0f, RayFilter())
                      : this->Caster->CastRay(eye, direction, 0.0f, fromMirror, hit)))
    {
      return false;
    }
    sample.Surface = this->Patches[hit.Patch].SurfaceIndex;
    sample.T = hit.T;
    sample.Lit = this->ShadeHit(
      hit.Patch, hit.U, hit.V, hit.FrontSide, direction, cache, bounces, sample.Radiance);
    return true;
  }
  // Through panes (paper §5.4): the pane's own radiance, then T times what lies behind it.
  const RayFilter filter = leaving < 0 ? RayFilter{ PassPaneBacks, &this->PassedBack } : fromMirror;
  glm::dvec3 throughput(1.0);
  float nearest = 0.0f;
  for (int pane = 0; pane <= MaxPanesPerSample; ++pane)
  {
    if (!(pane == 0 ? first(nearest, filter)
                    : this->Caster->CastRay(eye, direction, nearest, filter, hit)))
    {
      return pane > 0;
    }
    glm::dvec3 radiance(0.0);
    const bool lit =
      this->ShadeHit(hit.Patch, hit.U, hit.V, hit.FrontSide, direction, cache, bounces, radiance);
    if (pane == 0)
    {
      sample.Surface = this->Patches[hit.Patch].SurfaceIndex;
      sample.T = hit.T;
      sample.Lit = lit;
    }
    if (lit)
    {
      sample.Radiance += throughput * radiance;
      sample.Lit = true;
    }
    if (!hit.FrontSide || this->PanePatch.empty() || !this->PanePatch[hit.Patch])
    {
      break;
    }
    sample.PaneLimit = pane == MaxPanesPerSample;
    throughput *= this->Transmittance[static_cast<size_t>(this->Patches[hit.Patch].SurfaceIndex)];
    nearest = RayCaster::Beyond(static_cast<float>(hit.T));
  }
  return true;
}

void RadianceRenderer::SetSurfaceTransmittance(std::vector<glm::dvec3> transmittance)
{
  this->Transmittance = std::move(transmittance);
  this->PanePatch.assign(this->Patches.size(), 0);
  bool any = false;
  for (size_t p = 0; p < this->Patches.size(); ++p)
  {
    const size_t surface = static_cast<size_t>(this->Patches[p].SurfaceIndex);
    if (surface < this->Transmittance.size() && this->Transmittance[surface] != glm::dvec3(0.0))
    {
      this->PanePatch[p] = 1;
      any = true;
    }
  }
  if (!any)
  {
    this->PanePatch.clear();
  }
  this->MarkPassedBacks();
}

void RadianceRenderer::MarkPassedBacks()
{
  // Each side of a two-sided surface (paper §5.3 for each side) and of a pane: its back is the
  // other side's front.
  this->PassedBack.clear();
  for (size_t p = 0; p < this->Patches.size(); ++p)
  {
    const size_t surface = static_cast<size_t>(this->Patches[p].SurfaceIndex);
    const bool twoSided = surface < this->TwoSided.size() && this->TwoSided[surface];
    if (twoSided || (!this->PanePatch.empty() && this->PanePatch[p]))
    {
      this->PassedBack.resize(this->Patches.size(), 0);
      this->PassedBack[p] = 1;
    }
  }
}

RayFilter RadianceRenderer::EyeFilter() const
{
  return this->PassedBack.empty() ? RayFilter() : RayFilter{ PassPaneBacks, &this->PassedBack };
}

std::unique_ptr<RadianceRenderer::DirectionalCache> RadianceRenderer::AcquireCache() const
{
  {
    const std::lock_guard<std::mutex> lock(this->CachePoolMutex);
    if (!this->CachePool.empty())
    {
      std::unique_ptr<DirectionalCache> cache = std::move(this->CachePool.back());
      this->CachePool.pop_back();
      return cache;
    }
  }
  // 2^16 slots (2 MiB): the pairs a thread's tiles of a frame see, most of them again in the
  // next frame of a walk.
  return std::make_unique<DirectionalCache>(16);
}

void RadianceRenderer::ReleaseCache(std::unique_ptr<DirectionalCache> cache) const
{
  const std::lock_guard<std::mutex> lock(this->CachePoolMutex);
  this->CachePool.push_back(std::move(cache));
}

bool RadianceRenderer::Render(const Camera& camera,
  const RenderSettings& settings,
  RenderedImage& image,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress) const
{
  return this->RenderRows(camera, settings, image, parallelFor, progress, nullptr, nullptr);
}

bool RadianceRenderer::Render(const Camera& camera,
  const RenderSettings& settings,
  const DirectionalValueTable& given,
  RenderedImage& image,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress) const
{
  if (given.Keys.size() != given.Values.size())
  {
    throw std::invalid_argument("RadianceRenderer: " + std::to_string(given.Keys.size()) +
      " directional pairs with " + std::to_string(given.Values.size()) + " values");
  }
  return this->RenderRows(camera, settings, image, parallelFor, progress, &given, nullptr);
}

uint64_t RadianceRenderer::DirectionalCellCount() const
{
  return this->Directional ? static_cast<uint64_t>(this->Directional->Cover.Grid().CellCount()) : 0;
}

std::vector<uint64_t> RadianceRenderer::DirectionalPairs(const Camera& camera,
  const RenderSettings& settings,
  const ParallelFor& parallelFor) const
{
  if (!this->Directional)
  {
    const std::string problem = CheckCamera(camera, settings);
    if (!problem.empty())
    {
      throw std::invalid_argument(problem);
    }
    return {};
  }
  RenderedImage scratch;
  std::vector<std::vector<uint64_t>> needed;
  this->RenderRows(camera, settings, scratch, parallelFor, nullptr, nullptr, &needed);
  std::vector<uint64_t> pairs;
  for (std::vector<uint64_t>& row : needed)
  {
    pairs.insert(pairs.end(), row.begin(), row.end());
    row = std::vector<uint64_t>();
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

std::vector<glm::dvec3> RadianceRenderer::DirectionalValues(const std::vector<uint64_t>& pairs,
  const ParallelFor& parallelFor) const
{
  if (!this->Directional)
  {
    throw std::logic_error("RadianceRenderer::DirectionalValues: no directional illumination");
  }
  const DirectionalIllumination& lit = *this->Directional;
  const uint64_t cells = static_cast<uint64_t>(lit.Cover.Grid().CellCount());
  std::vector<const ReflectanceWeights*> tables(pairs.size(), nullptr);
  for (size_t k = 0; k < pairs.size(); ++k)
  {
    const uint64_t point = pairs[k] / cells;
    tables[k] = point < lit.Cover.PatchCount() ? this->Reflectances.Table(point) : nullptr;
    if (!tables[k])
    {
      throw std::invalid_argument("RadianceRenderer::DirectionalValues: pair " +
        std::to_string(pairs[k]) + " is not of a non-diffuse characteristic point");
    }
  }
  std::vector<glm::dvec3> values(pairs.size());
  parallelFor(pairs.size(),
    [&](size_t begin, size_t end)
    {
      for (size_t k = begin; k < end; ++k)
      {
        values[k] = DirectionalExitantRadianceOfCell(lit.Cover,
          *tables[k],
          static_cast<size_t>(pairs[k] / cells),
          lit.IncidentRadiance,
          static_cast<int>(pairs[k] % cells));
      }
    });
  return values;
}

bool RadianceRenderer::RenderRows(const Camera& camera,
  const RenderSettings& settings,
  RenderedImage& image,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  const DirectionalValueTable* given,
  std::vector<std::vector<uint64_t>>* needed) const
{
  const std::string problem = CheckCamera(camera, settings);
  if (!problem.empty())
  {
    throw std::invalid_argument(problem);
  }
  const int width = camera.Width;
  const int height = camera.Height;
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  image.Width = width;
  image.Height = height;
  image.Radiance.assign(3 * pixels, 0.0f);
  image.Depth.assign(pixels, -1.0f);
  image.SurfaceId.assign(pixels, -1);

  const ViewFrame frame = FrameOf(camera);
  const int samples = settings.SamplesPerPixel;
  std::vector<double> offsetX;
  std::vector<double> offsetY;
  SampleOffsets(samples, offsetX, offsetY);

  // Tiles of TileSide x TileSide pixels (paper §5.3: the visible surface of each pixel): a
  // tile's rays of one sample index leave the eye through neighbouring pixels, so they are cast
  // as one packet (RayCaster::CastPacket) and then shaded one by one, each pixel's samples in
  // their order (the pixel's sum is the same sum as one ray at a time).
  constexpr int side = TileSide;
  const int tilesX = (width + side - 1) / side;
  const int tilesY = (height + side - 1) / side;
  if (needed)
  {
    needed->assign(static_cast<size_t>(tilesX) * static_cast<size_t>(tilesY), {});
  }
  const RayFilter eyeFilter = this->EyeFilter();
  std::atomic<std::size_t> missing{ 0 };
  std::atomic<uint64_t> paneLimit{ 0 };
  auto renderTile = [&](int tileX, int tileY, DirectionalCache* cache)
  {
    uint64_t tilePaneLimit = 0;
    const int i0 = tileX * side;
    const int j0 = tileY * side;
    const int columns = std::min(side, width - i0);
    const int rows = std::min(side, height - j0);
    const int count = columns * rows;
    glm::dvec3 sums[side * side];
    // The samples' hits per pixel, kept per thread: no allocation per tile.
    thread_local std::vector<SampleHit> hits[side * side];
    double shiftX[side * side];
    double shiftY[side * side];
    for (int p = 0; p < count; ++p)
    {
      sums[p] = glm::dvec3(0.0);
      hits[p].clear();
      shiftX[p] = 0.0;
      shiftY[p] = 0.0;
      if (samples > 1)
      {
        // One sample stays at the pixel's centre (no shift).
        PixelShift(static_cast<size_t>(j0 + p / columns) * static_cast<size_t>(width) +
            static_cast<size_t>(i0 + p % columns),
          shiftX[p],
          shiftY[p]);
      }
    }
    glm::dvec3 directions[side * side];
    RayCaster::RayHit cast[side * side];
    bool found[side * side] = {};
    for (int k = 0; k < samples; ++k)
    {
      for (int p = 0; p < count; ++p)
      {
        const int i = i0 + p % columns;
        const int j = j0 + p / columns;
        const double x =
          2.0 * (i + Wrap(offsetX[static_cast<size_t>(k)] + shiftX[p])) / width - 1.0;
        const double y =
          2.0 * (j + Wrap(offsetY[static_cast<size_t>(k)] + shiftY[p])) / height - 1.0;
        directions[p] = glm::normalize(frame.Forward + x * frame.Right + y * frame.Up);
      }
      if (settings.FastPrimaryRays)
      {
        this->Caster->CastPacket(frame.Eye, directions, count, 0.0f, eyeFilter, cast, found, true);
      }
      for (int p = 0; p < count; ++p)
      {
        PrecastHit precast;
        precast.Found = found[p];
        if (found[p])
        {
          precast.Patch = cast[p].Patch;
          precast.U = cast[p].U;
          precast.V = cast[p].V;
          precast.T = cast[p].T;
          precast.FrontSide = cast[p].FrontSide;
        }
        SampleResult sample;
        if (!this->TraceSample(frame.Eye,
              directions[p],
              cache,
              sample,
              0,
              -1,
              settings.FastPrimaryRays ? &precast : nullptr))
        {
          continue;
        }
        hits[p].push_back({ sample.Surface, sample.T });
        tilePaneLimit += sample.PaneLimit ? 1 : 0;
        if (sample.Lit)
        {
          sums[p] += sample.Radiance;
        }
      }
    }
    for (int p = 0; p < count; ++p)
    {
      StorePixel(static_cast<size_t>(j0 + p / columns) * static_cast<size_t>(width) +
          static_cast<size_t>(i0 + p % columns),
        sums[p],
        samples,
        hits[p],
        image);
    }
    paneLimit += tilePaneLimit;
  };
  // Listing or reading the pairs (needed, given): caches of this call's own, as fresh as the
  // table (a pair a cache met in an earlier tile was listed there: the lists are merged).
  std::mutex callPoolMutex;
  std::vector<std::unique_ptr<DirectionalCache>> callPool;
  auto runTile = [&](size_t tile)
  {
    const int tileX = static_cast<int>(tile % static_cast<size_t>(tilesX));
    const int tileY = static_cast<int>(tile / static_cast<size_t>(tilesX));
    if (!this->Directional)
    {
      renderTile(tileX, tileY, nullptr);
      return;
    }
    if (!given && !needed)
    {
      std::unique_ptr<DirectionalCache> cache = this->AcquireCache();
      renderTile(tileX, tileY, cache.get());
      this->ReleaseCache(std::move(cache));
      return;
    }
    std::unique_ptr<DirectionalCache> cache;
    {
      const std::lock_guard<std::mutex> lock(callPoolMutex);
      if (!callPool.empty())
      {
        cache = std::move(callPool.back());
        callPool.pop_back();
      }
    }
    if (!cache)
    {
      cache = std::make_unique<DirectionalCache>();
      cache->Given = given;
    }
    cache->Needed = needed ? &(*needed)[tile] : nullptr;
    renderTile(tileX, tileY, cache.get());
    const std::lock_guard<std::mutex> lock(callPoolMutex);
    callPool.push_back(std::move(cache));
  };

  // Ten batches of tile rows, the tiles of each run in parallel; progress and abort between
  // batches.
  const int batch = std::max(1, (tilesY + 9) / 10);
  for (int first = 0; first < tilesY; first += batch)
  {
    const int last = std::min(tilesY, first + batch);
    const size_t firstTile = static_cast<size_t>(first) * static_cast<size_t>(tilesX);
    parallelFor(static_cast<size_t>(last - first) * static_cast<size_t>(tilesX),
      [&](size_t begin, size_t end)
      {
        for (size_t t = begin; t < end; ++t)
        {
          runTile(firstTile + t);
        }
      });
    if (progress && !progress(static_cast<double>(std::min(height, last * side)) / height))
    {
      return false;
    }
  }
  for (const std::unique_ptr<DirectionalCache>& cache : callPool)
  {
    missing += cache->Missing;
  }
  image.PaneLimitSamples = paneLimit.load();
  image.SampleCount = static_cast<uint64_t>(pixels) * static_cast<uint64_t>(samples);
  if (missing > 0)
  {
    throw std::runtime_error("RadianceRenderer: the directional values given lack " +
      std::to_string(missing.load()) + " of the pairs the view reads");
  }
  return true;
}

} // namespace sphcover
