// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RadianceRenderer.h
 * @brief The final rendering of paper §5.3: a view of the equilibrium illumination through a
 * pinhole camera, as an HDR radiance image.
 *
 * Visible surface ("Any standard visible surface algorithm may be used", §5.3): primary rays
 * from the eye through RayCaster::CastRay, the tessellation of the ray fill with the hit
 * refined on the exact Bezier patch, so the visible point's (surface, u, v) is exact up to the
 * refinement's tolerance. A back side of a one-sided surface has radiance 0
 * (Data/scenes/FORMAT.md).
 *
 * Brightness (§5.3.2, "bilinearly interpolating the I's"): the exitant radiance I of the
 * characteristic points around (u, v) (CharacteristicPointInterpolator, §3.4 Fig. 6),
 * extrapolated near the edges, clamped at zero per band; emitters show their emission. With
 * DirectionalIllumination a non-diffuse surface adds its directional part toward the eye
 * (§5.3.1 with §3.4 Fig. 7): L = sum_k w_k (I_k + I_dir,k(eye_k)) over the stencil's points
 * k, I_dir,k = DirectionalExitantRadiance of point k toward the eye in k's hemisphere frame
 * (the BRDF being linear in E, the same as the BRDF applied to the interpolated E), resolved
 * to the cells of the HemisphereGrid; a two-sided surface's back side shows its Lambertian
 * part only. I_dir,k depends on the eye through its cell only, so Render keeps it per (point,
 * eye cell) in caches that live across frames (a walk-through's): a frame evaluates the pairs
 * no frame before it met (RadianceRenderer::CachePool).
 *
 * Ideal mirrors (paper §3.5.1, "I(theta_r, phi_r) = k_specular e(theta_r, phi_r - pi)"): the
 * radiance a mirror sends toward the eye is k_s times the radiance that arrives at the visible
 * point itself from the mirror direction, that is the radiance of the surface the reflected ray
 * meets toward the mirror point. Render follows that ray (cast from the exact visible point
 * about the exact patch normal) and shades what it meets as it shades what the eye meets, up to
 * MaxMirrorBounces mirrors deep; the mirror adds its own Lambertian part, if any. It does not
 * take the mirror cell of the characteristic points' stored E blended over the stencil: each
 * point's E holds what that point sees, so the blend superimposes the reflected scene as seen
 * from the four points (shifted by their spacing) at the cells' resolution. Where the
 * reflected ray meets nothing lit (it escapes, or meets a back side: inside a closed curved
 * mirror the tessellation's chords), past MaxMirrorBounces, and in SurfaceRadianceToward (which
 * has no patch to reflect the ray from), a mirror gives the stencil's stored value as the other
 * non-diffuse surfaces do; RadianceToward(terms) (a walk-through's vertices) follows the ray as
 * Render does. On a textured surface (paper §5.4,
 * SetSurfaceTextures) the texture at the visible point's (u, v) multiplies the Lambertian part less
 * the emission.
 *
 * Camera (Camera.h, VTK's conventions): vertical view angle, square pixels, row 0 at the
 * bottom. SamplesPerPixel stratified, deterministic positions per pixel (Hammersley: one per
 * column of width 1/N, the rows by the base-2 radical inverse), the pattern shifted modulo 1 by
 * an offset hashed from the pixel's index when N > 1 (a Cranley-Patterson rotation: an edge
 * along a row of pixels then cuts each pattern elsewhere and the coverage errors average out
 * instead of adding up; one sample is the pixel's centre when N = 1); Radiance is their mean (an
 * escaping ray counts 0), SurfaceId the surface most samples hit (ties: the lowest index; -1:
 * none) and Depth their mean distance on it (-1: none). Cost: O(samples x (log triangles +
 * stencil)); tiles of 4 x 4 pixels whose rays of one sample index are cast as one Embree packet
 * (TileSide), the tiles in ten batches of tile rows through a ParallelFor, progress and abort
 * between batches; the image does not depend on the thread count. A packet's hits are those of
 * single rays up to Embree's packet kernel's rounding (RayCaster::CastPacket): the image equals
 * one cast ray by ray within Documentation/notes/walk-through.md's (2026-12-07) tolerance.
 * Details: Documentation/notes/ray-casting.md.
 */
#ifndef SPHCOVER_RADIANCERENDERER_H
#define SPHCOVER_RADIANCERENDERER_H

#include "cover/DirectIrradiance.h"
#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"
#include "math/ParallelFor.h"
#include "reflectance/DirectionalReflection.h"
#include "scene/Camera.h"
#include "scene/Material.h"
#include "subdivision/CharacteristicPointInterpolator.h"
#include "subdivision/Patch.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace sphcover
{

class RayCaster;
struct RayFilter;

/// What the directional part of non-diffuse surfaces needs (paper §5.3.1; see the file comment):
/// the propagation's result on the cover.
struct DirectionalIllumination
{
  /// The spherical cover of the characteristic points (the interpolator's points, same order).
  SphericalCover Cover;
  /// Incident radiance E_e of every entry of the cover (RGB, W m^-2 sr^-1).
  std::vector<glm::dvec3> IncidentRadiance;
  /// The hemisphere frame of every point (the cover's frames, HemisphereFrame::OfPatch).
  std::vector<HemisphereFrame> Frames;
  /// The material of every point.
  std::vector<Material> Materials;
};

/// A textured surface as the render sees it (paper §5.4): its texture and its material's
/// emission, which the texture does not scale.
struct SurfaceTexture
{
  /// Null: the surface is not textured.
  std::shared_ptr<const Texture> Image;
  glm::dvec3 Emission = glm::dvec3(0.0);
};

/// The Lambertian radiance `untextured` at (u, v) of `surface` with its texture (if any) applied:
/// Le + T(u, v) max(untextured - Le, 0) (RadianceRenderer::SetSurfaceTextures). Shared by the
/// render and the illumination field.
glm::dvec3 TexturedRadiance(const std::vector<SurfaceTexture>& textures,
  int surface,
  double u,
  double v,
  const glm::dvec3& untextured);

/// Seconds one sample (a ray refined on the exact patch and interpolated) takes on one core,
/// measured on the Cornell box (see MaximumSamples): the budget's time scale.
constexpr double RenderSecondsPerSample = 1e-6;

struct RenderSettings
{
  /// Samples per pixel (stratified, see the file comment), 1 to 4096.
  int SamplesPerPixel = 4;
  /// Largest memory the image may take (RenderedImage::BytesPerPixel per pixel).
  std::size_t MemoryLimitBytes = std::size_t(1024) * 1024 * 1024;
  /// Largest Width x Height x SamplesPerPixel: 2^30 samples, about 18 minutes on one core at
  /// RenderSecondsPerSample, more than an hour only in scenes far costlier than the Cornell box
  /// (a 4K image at 128 samples per pixel); the largest size and spp (32768^2 x 4096) would
  /// take weeks.
  std::size_t MaximumSamples = std::size_t(1) << 30;
  /// The eye rays of a tile cast as Embree packets (RadianceRenderer::TileSide), their hits on
  /// flat quadrilaterals refined from the closed-form point (RayCaster::CastPacket's
  /// quadStart); false: one rtcIntersect1 per ray refined from the triangle's point, the image
  /// of the renderer before issue 41 bit for bit (the reference of the tolerance,
  /// Documentation/notes/walk-through.md, 2026-12-07).
  bool FastPrimaryRays = true;
};

/// The rendered arrays, pixel (i, j) at index j * Width + i, row 0 at the bottom.
struct RenderedImage
{
  int Width = 0;
  int Height = 0;
  /// RGB radiance, W m^-2 sr^-1, 3 per pixel.
  std::vector<float> Radiance;
  /// Distance from the eye to the visible point (-1: nothing visible).
  std::vector<float> Depth;
  /// Index of the visible surface (-1: nothing visible).
  std::vector<int32_t> SurfaceId;
  /// Samples whose ray still met a pane's front after RadianceRenderer::MaxPanesPerSample
  /// panes: the light behind it is left out of their pixels (issue 39 item 6).
  uint64_t PaneLimitSamples = 0;
  /// The samples cast: Width x Height x RenderSettings::SamplesPerPixel.
  uint64_t SampleCount = 0;

  /// Bytes per pixel of the arrays above plus an 8-bit RGB copy for display.
  static constexpr std::size_t BytesPerPixel =
    3 * sizeof(float) + sizeof(float) + sizeof(int32_t) + 3;
};

/// The brightness of paper §5.3.2 at (u, v) of a surface: the interpolation of the
/// characteristic points' exitant radiance, clamped at zero per band (extrapolation near an
/// edge can undershoot); zero where the surface has no characteristic points.
glm::dvec3 InterpolateRadiance(const CharacteristicPointInterpolator& interpolator,
  const std::vector<glm::dvec3>& exitantRadiance,
  int surface,
  double u,
  double v);

/// The lamps' direct light over the surfaces (DirectIrradiance.h) as the renderer and the
/// illumination field use it: the direct irradiance on the nodes of every characteristic
/// point's patch and every point's diffuse reflectance rho.
struct DirectLight
{
  DirectIrradianceNodes Nodes;
  /// rho / pi of every point.
  std::vector<glm::dvec3> Factor;

  /// rho / pi times the same light as the cover carries it at every point
  /// (LightPropagation::LampIrradiance), or empty.
  std::vector<glm::dvec3> CoverPart;

  /// Throws std::invalid_argument when the sizes differ from `points` (`coverIrradiance`: 0 or
  /// `points`).
  DirectLight(DirectIrradianceNodes nodes,
    const std::vector<glm::dvec3>& diffuse,
    std::size_t points,
    const std::vector<glm::dvec3>& coverIrradiance = {});
  DirectLight() = default;
  bool Empty() const { return this->Nodes.Empty(); }
  /// rho / pi E_direct at the point's own centre, the characteristic point.
  glm::dvec3 AtPoint(std::size_t point) const;
  /// rho / pi E_direct at (u, v) of the surface, from the nodes of the point whose patch holds
  /// (u, v); zero where the surface has no points.
  glm::dvec3 At(const CharacteristicPointInterpolator& interpolator,
    int surface,
    double u,
    double v) const;
  /// What the points' I holds of the nodes' light: CoverPart when given, else AtPoint (at a
  /// point the render is then I itself).
  glm::dvec3 PointPart(std::size_t point) const;
  /// The rest that §5.3.2 interpolates between the points: I - PointPart, per point. With
  /// CoverPart, the cover's coarser version of the nodes' light is replaced by the nodes' at
  /// the points too.
  std::vector<glm::dvec3> Rest(std::vector<glm::dvec3> exitantRadiance) const;
};

/// The camera and settings' problem in one sentence, or "" when they can be rendered: a view
/// angle outside (0, 180) degrees, the eye at the focal point, a view up parallel to the view
/// direction (or zero), a width or height below 1, SamplesPerPixel outside [1, 4096], a
/// non-finite number, an eye beyond MaxRayCastCoordinate, or an image larger than the memory
/// limit or the sample budget.
std::string CheckCamera(const Camera& camera, const RenderSettings& settings);

class RadianceRenderer
{
public:
  /**
   * @param patches the patches whose tessellation is ray cast (any patches tiling the
   * surfaces: the subdivision's); Patch::SurfaceIndex and Domain map a hit to its surface's
   * (u, v).
   * @param interpolator the layout of the characteristic points over the surfaces.
   * @param exitantRadiance I of every characteristic point (RGB, W m^-2 sr^-1).
   * @param twoSidedSurface per surface index, whether it is one side of a two-sided surface
   * (Surface::TwoSided; missing entries: one-sided): the eye rays pass its back side and meet
   * the other side's front at the same place, which shows that side's own radiance.
   * Throws std::invalid_argument when the sizes differ, std::runtime_error if Embree fails.
   */
  RadianceRenderer(std::vector<Patch> patches,
    CharacteristicPointInterpolator interpolator,
    std::vector<glm::dvec3> exitantRadiance,
    std::vector<bool> twoSidedSurface = {});
  ~RadianceRenderer();
  RadianceRenderer(const RadianceRenderer&) = delete;
  RadianceRenderer& operator=(const RadianceRenderer&) = delete;

  /**
   * Renders the view. Throws std::invalid_argument with CheckCamera's message for a bad camera.
   * Returns false (the image incomplete) when `progress` returned false.
   */
  bool Render(const Camera& camera,
    const RenderSettings& settings,
    RenderedImage& image,
    const ParallelFor& parallelFor = SequentialFor,
    const ProgressCallback& progress = nullptr) const;

  /// The directional part of §5.3.1 per (point, out cell) pair, evaluated elsewhere: by the
  /// ranks whose share of the cover holds the points' rows (DirectionalValues).
  struct DirectionalValueTable
  {
    /// Pair keys, point x (the grid's cell count) + cell, ascending.
    std::vector<uint64_t> Keys;
    std::vector<glm::dvec3> Values;
  };

  /**
   * The view rendered with the directional part taken from `given` instead of evaluated: with
   * the values of DirectionalPairs(camera, settings) from DirectionalValues, the image Render
   * gives, bit for bit. So the directional illumination set here may be a share of the cover
   * (a rank's rows) or any cover of the same grid: only the points' materials and the grid are
   * read. Throws std::invalid_argument as Render, and std::runtime_error when `given` lacks a
   * pair the view reads.
   */
  bool Render(const Camera& camera,
    const RenderSettings& settings,
    const DirectionalValueTable& given,
    RenderedImage& image,
    const ParallelFor& parallelFor = SequentialFor,
    const ProgressCallback& progress = nullptr) const;

  /**
   * The (point, out cell) pairs whose directional part the view reads (keys as in
   * DirectionalValueTable, ascending, each once): the view traced as Render traces it, without
   * evaluating them. Empty without the directional illumination. Throws as Render.
   */
  std::vector<uint64_t> DirectionalPairs(const Camera& camera,
    const RenderSettings& settings,
    const ParallelFor& parallelFor = SequentialFor) const;

  /**
   * The directional part of each pair (DirectionalPairs' keys) from this renderer's
   * directional illumination: a share of the cover gives the whole cover's values for the
   * pairs of the points whose rows it holds (the caller asks for those). Throws
   * std::invalid_argument for a pair of a point out of range or of a diffuse point, and
   * std::logic_error without the directional illumination.
   */
  std::vector<glm::dvec3> DirectionalValues(const std::vector<uint64_t>& pairs,
    const ParallelFor& parallelFor = SequentialFor) const;

  /**
   * Adds the directional part of non-diffuse surfaces (see the file comment). Throws
   * std::invalid_argument when the cover's point count, the frames or the materials differ
   * from the characteristic points or IncidentRadiance from the cover's entries, and what
   * Reflectance throws for a bad material (InputError for an unreadable BRDF table).
   */
  void SetDirectionalIllumination(DirectionalIllumination illumination);
  bool HasDirectionalIllumination() const { return this->Directional != nullptr; }
  /// The cells of the directional illumination's grid (0 without it): a pair's key is
  /// point x this + cell (DirectionalValueTable).
  uint64_t DirectionalCellCount() const;

  /**
   * The lamps' direct light (DirectLight, the points' order): the Lambertian radiance becomes
   * the interpolated rest, I - rho / pi E_direct at the points, plus rho / pi E_direct at (u, v)
   * interpolated from the nodes of the point whose patch holds (u, v). At a characteristic
   * point this is I itself; between them the direct light follows its nodes (shadows, contact
   * shadows, the fall along a wall under the lamp) and only the smooth rest is interpolated by
   * §5.3.2. Throws std::invalid_argument when it has another number of points.
   */
  void SetDirectLight(DirectLight direct);
  bool HasDirectLight() const { return !this->Direct.Empty(); }

  /**
   * Textures per surface index (missing entries and null images: untextured). A textured
   * surface's Lambertian radiance at (u, v) is Le + T(u, v) (L(u, v) - Le), L the radiance
   * interpolated (with the direct light, if set) from the points' untextured values: pixel =
   * texture at the hit's (u, v) times the interpolated irradiance times k_d / pi, plus the
   * emission (paper §5.3.2 with §5.4). So the exitant radiance given for a textured surface's
   * points, and the DirectLight's reflectance, must be those of the material's own k_d
   * (Le + k_d / pi E), not of the texture's mean over the point's patch that the propagation
   * used (MaterialOverPatch). The directional part of a phong surface is not textured.
   */
  void SetSurfaceTextures(std::vector<SurfaceTexture> textures);

  /**
   * Per surface index the transmittance of a thin pane (paper §5.4; missing entries and zero:
   * opaque). A sample that meets a pane's front side shows the pane's own radiance plus T times
   * what its ray meets behind it (cast again beyond the pane, at most MaxPanesPerSample panes;
   * the samples that meet more are counted in RenderedImage::PaneLimitSamples);
   * a pane's back side is its reversed copy's front (the loader makes a pane two surfaces) and
   * is passed. The sample's surface and depth are the first pane's.
   */
  void SetSurfaceTransmittance(std::vector<glm::dvec3> transmittance);
  static constexpr int MaxPanesPerSample = 8;
  /// Mirrors a sample's ray is reflected by (see the file comment); the next one met shows its
  /// stored value.
  static constexpr int MaxMirrorBounces = 8;
  /// Render casts the eye rays of TileSide x TileSide pixels, one sample index at a time, as one
  /// packet (RayCaster::CastPacket: 16 rays, one Embree packet), and runs the tiles in
  /// parallel.
  static constexpr int TileSide = 4;

  /// The interpolated, clamped radiance of the front side at (u, v) of a surface (paper
  /// §5.3.2); zero where the surface has no characteristic points. The Lambertian part only.
  glm::dvec3 SurfaceRadiance(int surface, double u, double v) const;
  /// The radiance of the front side at (u, v) toward the unit world direction `towardEye`:
  /// SurfaceRadiance plus, with DirectionalIllumination, the interpolated directional part of
  /// a non-diffuse surface (paper §5.3.1), clamped at zero per band.
  glm::dvec3 SurfaceRadianceToward(int surface,
    double u,
    double v,
    const glm::dvec3& towardEye) const;

  /// Directional exitant radiance already evaluated, per (point, out cell): neighbouring
  /// samples share their characteristic points and mostly the eye's cell, so a row of pixels
  /// evaluates each pair once (a direct-mapped table; a value is the same whether it comes
  /// from the table or is evaluated, so the image does not depend on the cache).
  /// A cache kept across calls (a walk-through's vertices, frame after frame) is a lazily
  /// filled table of the directional part per (point, cell): after the first frames a camera
  /// move pays only the pairs it newly sees.
  struct DirectionalCache
  {
    /// 2^bits slots (bits 1 to 30; default 4096 slots, a row of pixels' working set).
    explicit DirectionalCache(int bits = 12);
    /// The slot of a (point, cell) key (Fibonacci hashing onto the table's bits).
    std::size_t Slot(uint64_t key) const { return (key * 0x9E3779B97F4A7C15ull) >> this->Shift; }
    int Shift;
    std::vector<uint64_t> Keys;
    std::vector<glm::dvec3> Values;
    /// Set: the pairs are listed here (once per slot fill) and read as zero (DirectionalPairs).
    std::vector<uint64_t>* Needed = nullptr;
    /// Set: the pairs are read from this table instead of evaluated; those it lacks counted.
    const DirectionalValueTable* Given = nullptr;
    std::size_t Missing = 0;
  };

  /// What the radiance at (u, v) of a surface toward an eye needs that does not depend on the
  /// eye: the interpolation stencil (§3.4 Fig. 6) and the lamps' direct light at (u, v).
  /// Tabulated once per vertex of a walk-through, so that a camera move pays the directional
  /// part of §5.3.1 only.
  struct TowardTerms
  {
    int Surface = -1;
    double U = 0.0;
    double V = 0.0;
    /// False where the surface has no characteristic points (radiance 0).
    bool HasStencil = false;
    InterpolationStencil Stencil;
    glm::dvec3 Direct = glm::dvec3(0.0);
    /// On an ideal mirror (with the directional illumination): the patch that holds (u, v) and
    /// (u, v) in its own [0,1]^2, from which RadianceToward follows the reflected ray; -1
    /// elsewhere.
    std::ptrdiff_t MirrorPatch = -1;
    double PatchU = 0.0;
    double PatchV = 0.0;
  };

  /// The terms of (u, v) of the surface (see TowardTerms).
  TowardTerms Terms(int surface, double u, double v) const;

  /**
   * SurfaceRadianceToward from tabulated terms and through `cache` (one per thread): the same
   * value (the cache holds exact values of the directional part per (point, eye cell)), each
   * pair the cache keeps evaluated once; on a mirror (TowardTerms::MirrorPatch) the value of
   * Render's ray from the eye that meets the point, its reflected ray followed (file comment).
   */
  glm::dvec3 RadianceToward(const TowardTerms& terms,
    const glm::dvec3& towardEye,
    DirectionalCache& cache) const;

  /// Whether the front's radiance with these terms depends on the eye: a point of the stencil
  /// has a directional part (a non-diffuse material, paper §5.3.1) and the directional
  /// illumination is set. Elsewhere SurfaceRadianceToward is SurfaceRadiance for every eye.
  bool IsViewDependent(const TowardTerms& terms) const;

  std::size_t TriangleCount() const;

private:
  /// What one sample ray of a pixel meets first: the surface, its distance, and whether and
  /// what radiance it sends back along the ray (a one-sided surface's back sends none).
  struct SampleResult
  {
    int Surface = -1;
    double T = 0.0;
    bool Lit = false;
    glm::dvec3 Radiance = glm::dvec3(0.0);
    /// The ray still met a pane after MaxPanesPerSample of them (what lies behind is left out).
    bool PaneLimit = false;
  };
  /// The radiance the hit shows toward the eye, and whether it sends any (a back side does not).
  /// `bounces`: mirrors the ray was reflected by before (MaxMirrorBounces).
  bool ShadeHit(std::size_t patch,
    double patchU,
    double patchV,
    bool frontSide,
    const glm::dvec3& direction,
    DirectionalCache* cache,
    int bounces,
    glm::dvec3& radiance) const;
  /// k_s of the ideal mirror that `surface` is, or nullptr (set with the directional
  /// illumination).
  const glm::dvec3* MirrorOf(int surface) const;
  /// Render's work: the directional part through caches that evaluate it, or list the pairs
  /// (`needed`: one list per row of pixels), or read them from `given`.
  bool RenderRows(const Camera& camera,
    const RenderSettings& settings,
    RenderedImage& image,
    const ParallelFor& parallelFor,
    const ProgressCallback& progress,
    const DirectionalValueTable* given,
    std::vector<std::vector<uint64_t>>* needed) const;
  /// The first hit of an eye ray cast beforehand (RayCaster::CastPacket, with TraceSample's
  /// own filter): RayCaster::RayHit's fields, and whether it hit.
  struct PrecastHit
  {
    bool Found = false;
    std::size_t Patch = 0;
    double U = 0.0;
    double V = 0.0;
    double T = 0.0;
    bool FrontSide = true;
  };
  /// Casts one sample ray from the eye (or, `bounces` > 0, reflected by that many mirrors, from
  /// a point of patch `leaving`, which then passes the back of its surface's triangles close
  /// by); false where it meets nothing. `precast`: an eye ray's first hit, already cast (the
  /// rays behind panes and off mirrors are cast here).
  bool TraceSample(const glm::dvec3& eye,
    const glm::dvec3& direction,
    DirectionalCache* cache,
    SampleResult& sample,
    int bounces = 0,
    std::ptrdiff_t leaving = -1,
    const PrecastHit* precast = nullptr) const;
  /// The filter of TraceSample's first cast from the eye (panes' and two-sided surfaces' backs
  /// passed), for the packets cast before it.
  RayFilter EyeFilter() const;
  /// A cache of the directional part for one task of a Render (see CachePool).
  std::unique_ptr<DirectionalCache> AcquireCache() const;
  void ReleaseCache(std::unique_ptr<DirectionalCache> cache) const;
  glm::dvec3 RadianceToward(int surface,
    double u,
    double v,
    const glm::dvec3& towardEye,
    DirectionalCache* cache) const;
  glm::dvec3 TermsToward(const TowardTerms& terms,
    const glm::dvec3& towardEye,
    DirectionalCache* cache) const;
  /// I_dir of point toward the world direction, through the cache when given.
  glm::dvec3 DirectionalPart(std::size_t point,
    const ReflectanceWeights& table,
    const glm::dvec3& towardEye,
    DirectionalCache* cache) const;

  /// The Lambertian radiance `untextured` at (u, v) of the surface with its texture applied
  /// (SetSurfaceTextures); `untextured` itself on an untextured surface.
  glm::dvec3 Textured(int surface, double u, double v, const glm::dvec3& untextured) const;
  bool IsTextured(int surface) const;
  /// Sets PassedBack from TwoSided and PanePatch.
  void MarkPassedBacks();

  std::vector<Patch> Patches;
  std::vector<SurfaceTexture> Textures;
  CharacteristicPointInterpolator Interpolator;
  std::vector<glm::dvec3> Exitant;
  std::vector<bool> TwoSided;
  std::vector<glm::dvec3> Transmittance;
  /// Per patch 1 when its surface is a pane (SetSurfaceTransmittance); empty without panes.
  std::vector<char> PanePatch;
  /// Per patch 1 when the eye rays pass its back side, its reversed copy's front: a pane or one
  /// side of a two-sided surface (TwoSided); empty when no patch is.
  std::vector<char> PassedBack;
  std::unique_ptr<RayCaster> Caster;
  std::unique_ptr<DirectionalIllumination> Directional;
  /// Per surface index k_s of an ideal mirror, (-1, -1, -1) for another surface; empty when no
  /// surface is one (SetDirectionalIllumination).
  std::vector<glm::dvec3> MirrorSpecular;
  /// Per surface index in MirrorSpecular, the patches of a mirror surface (Terms looks up the
  /// patch under (u, v) among them); empty lists for the other surfaces.
  std::vector<std::vector<std::size_t>> MirrorPatches;
  DirectLight Direct;
  PointReflectances Reflectances;
  /// The directional part's caches of Render's tasks, kept across Render calls (a walk-through's
  /// frames): each task takes one and gives it back, so a frame pays only the (point, eye cell)
  /// pairs its caches have not met yet, in this or an earlier frame (paper §5.3.1: I_dir of a
  /// point depends on the eye through its cell only). Their values are exact, so the image does
  /// not depend on which cache a task gets. Emptied by SetDirectionalIllumination.
  mutable std::mutex CachePoolMutex;
  mutable std::vector<std::unique_ptr<DirectionalCache>> CachePool;
};

} // namespace sphcover

#endif
