// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RayCaster.h
 * @brief Rays against a tessellation of exact Bezier patches with Intel Embree 3, hits refined
 * on the exact patch: the visibility queries of the R-buffer's ray fill (paper §4.3 Step 2),
 * the cover refinement's enclosure probes and the final rendering (paper §5.3).
 *
 * Input: per patch its BezierPatch and a surface index (patches of one surface and degrees
 * share one resolution, so uniformly split surfaces have no cracks). Each patch becomes an
 * n_u x n_v grid of quads: one quad (two triangles, exact) for a convex planar quadrilateral
 * (a bilinear patch, degree-elevated or not, in one plane); otherwise n even (the parametric
 * centre is a vertex) and at most 256, chosen from the second-derivative bound of the control
 * net so that the triangles deviate from the patch by at most TessellationTolerance * Size(). One
 * Embree scene, geometry id = patch index, robust mode (no ray slips through a shared edge), BVH
 * built in one thread; queries call rtcIntersect1 (IntersectPacket: rtcIntersect16) and may run
 * from many threads at once. Rays are single precision.
 *
 * Intersect() reports the nearest hit a RayFilter accepts (a plain function pointer and
 * context, called per candidate hit during traversal: no allocation per ray); CastRay() and
 * FirstHit() accept every hit. Refine() is Newton's method on the exact patch
 * (RayPatchIntersection). Construction is O(triangles); a query O(log triangles).
 */
#ifndef SPHCOVER_RAYCASTER_H
#define SPHCOVER_RAYCASTER_H

#include "geometry/BezierPatch.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sphcover
{

/**
 * The largest coordinate magnitude ray casting accepts. Embree asserts (and aborts the
 * process) unless every ray's origin and direction lie within its FLT_LARGE, 1.844e18, per
 * component; the rays start at characteristic points and at the eye, so the patches and the
 * camera must stay inside, with a margin for the offsets along the rays.
 */
constexpr double MaxRayCastCoordinate = 1e18;

/// One patch for the caster: its exact geometry (not owned: it must outlive the caster) and
/// the surface it belongs to.
struct RayCastPatch
{
  const BezierPatch* Geometry = nullptr;
  int32_t Surface = 0;
};

/// Why the patches cannot be handed to Embree (a control point beyond MaxRayCastCoordinate,
/// or not finite: the patches lie in their control nets' convex hulls), or "".
std::string RayCastCoordinateProblem(const std::vector<RayCastPatch>& patches);

struct RayCasterOptions
{
  /// Largest deviation of the tessellation from the exact patch, as a fraction of its Size().
  double TessellationTolerance = 1e-3;
  /// CastRay refines its hits on the exact patch (Refine).
  bool RefineHits = true;
};

/// Whether a candidate hit counts (true) or the ray goes on behind it (false): the patch met,
/// the distance along the ray and whether the triangle's front side (wound like dQ/du x dQ/dv)
/// faces the ray. Called during traversal (or on the first hit, RayFilter::RejectsAllNearer),
/// from the querying thread.
using RayHitPredicate = bool (*)(const void* context,
  std::size_t patch,
  float distance,
  bool front);

struct RayFilter
{
  RayHitPredicate Accept = nullptr; ///< nullptr: every hit counts
  const void* Context = nullptr;
  /**
   * When > 0, the caller's promise that Accept rejects every hit nearer than this distance (a
   * ray's own start: nothing but the origin's own patches lies that near, PatchesNear). A query
   * then casts from there without asking Accept during traversal, asks it about the first hit
   * only, and casts again with it the rays whose first hit it rejects: the hits of the filter
   * applied during traversal (but for the choice between equally near triangles), at the cost
   * of one callback per ray instead of one per candidate hit. 0: the filter during traversal.
   */
  float RejectsAllNearer = 0.0f;
};

/// A hit on the tessellation.
struct TriangleHit
{
  std::size_t Patch = 0;
  /// The patch's (u, v) of the hit, from the triangle and its barycentric coordinates.
  double U = 0.0;
  double V = 0.0;
  /// Distance along the ray (single precision, as Embree computes it).
  float Distance = 0.0f;
  /// The triangle's side met: its normal . direction < 0 (in single precision).
  bool FrontSide = true;
  /// The triangle's (unnormalised) geometric normal.
  glm::dvec3 TriangleNormal{ 0.0 };
};

class RayCaster
{
public:
  /// Throws std::invalid_argument for patches beyond MaxRayCastCoordinate
  /// (RayCastCoordinateProblem) or without geometry, std::runtime_error if Embree fails.
  RayCaster(std::vector<RayCastPatch> patches, const RayCasterOptions& options);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /**
   * The nearest hit of origin + t direction, t > tNear, that `filter` accepts; `coherent`
   * tells Embree that consecutive rays are neighbours (the rays from one point). False when
   * the ray escapes.
   */
  bool Intersect(const glm::dvec3& origin,
    const glm::dvec3& direction,
    float tNear,
    const RayFilter& filter,
    bool coherent,
    TriangleHit& hit) const;

  /// The tNear that casts a ray on from a hit at `distance`, past it and past a coincident
  /// surface (a pane's reversed copy): the rays that go on behind panes (paper §5.4).
  static float Beyond(float distance) { return distance * (1.0f + 1e-5f) + 1e-7f; }

  /// Largest number of rays of one IntersectPacket call.
  static constexpr int PacketSize = 16;

  /**
   * Intersect() for `count` <= PacketSize rays from one origin at once (one Embree packet,
   * rtcIntersect16, the same filter): found[k] tells whether ray k hit, hits[k] its hit. The
   * hits are those of Intersect() up to the packet kernel's rounding (the same triangle but for
   * rays through an edge or a vertex); the same rays give the same hits.
   */
  void IntersectPacket(const glm::dvec3& origin,
    const glm::dvec3* directions,
    int count,
    float tNear,
    const RayFilter& filter,
    TriangleHit* hits,
    bool* found) const;

  /**
   * Newton's method on the exact patch from the guess (u, v, t); the result replaces it only
   * when it converged within 1e-3 of the patch's [0,1]^2 (true), else (u, v, t) stay.
   */
  bool Refine(std::size_t patch,
    const glm::dvec3& origin,
    const glm::dvec3& direction,
    double& u,
    double& v,
    double& t) const;

  /// The first surface a ray meets, mapped back to the exact patch.
  struct RayHit
  {
    /// Index of the patch hit.
    std::size_t Patch = 0;
    /// Parameters of the hit in the patch's own [0,1]^2.
    double U = 0.0;
    double V = 0.0;
    /// Distance along the (unit) direction.
    double T = 0.0;
    /// Whether the ray meets the front side (dQ/du x dQ/dv . direction < 0).
    bool FrontSide = true;
  };

  /**
   * The visible surface along one ray from a point outside every patch (a camera's eye, paper
   * §5.3: "Any standard visible surface algorithm may be used"): the nearest hit on either side
   * of any patch (surfaces are opaque), refined on the exact patch when RefineHits is on
   * (within the tessellation's accuracy otherwise), its side from the exact normal.
   * `direction` must be a unit vector. False when the ray escapes.
   */
  bool CastRay(const glm::dvec3& origin, const glm::dvec3& direction, RayHit& hit) const
  {
    return this->CastRay(origin, direction, 0.0f, RayFilter(), hit);
  }
  /// CastRay beyond `tNear` among the hits `filter` accepts (a renderer going on behind a pane).
  bool CastRay(const glm::dvec3& origin,
    const glm::dvec3& direction,
    float tNear,
    const RayFilter& filter,
    RayHit& hit) const;

  /**
   * CastRay for `count` <= PacketSize unit directions from one origin (a tile of a camera's
   * pixels, paper §5.3): one IntersectPacket, then each hit refined and sided as CastRay does.
   * found[k] tells whether ray k hit, hits[k] its hit. The same as CastRay ray by ray up to the
   * packet kernel's rounding (IntersectPacket): the refinement starts from the packet's
   * triangle point, so a hit could differ from CastRay's by the refinement's convergence
   * (1e-12 of the patch's size) and, for a ray through a shared edge or vertex, by the patch
   * met. `quadStart`: on a convex planar quadrilateral (one quad of two exact triangles) the
   * refinement starts from the closed-form (u, v, t) of the bilinear patch, which it confirms
   * in one evaluation, instead of the triangle's point: the same point up to that convergence.
   */
  void CastPacket(const glm::dvec3& origin,
    const glm::dvec3* directions,
    int count,
    float tNear,
    const RayFilter& filter,
    RayHit* hits,
    bool* found,
    bool quadStart = false) const;

  /**
   * The first patch met by the ray origin + t direction, t > tNear, from either side: its
   * index, the distance t (of the tessellation) and whether the side met is the front. False
   * when the ray escapes.
   */
  bool FirstHit(const glm::dvec3& origin,
    const glm::dvec3& direction,
    double tNear,
    std::size_t& patch,
    double& distance,
    bool& front) const;

  /// The patches whose tessellation comes within `radius` of `point` (their triangles'
  /// bounding boxes do), in increasing order; O(log patches) for a small radius.
  void PatchesNear(const glm::dvec3& point, double radius, std::vector<std::size_t>& patches) const;

  std::size_t PatchCount() const;
  /// Number of triangles of the tessellation.
  std::size_t TriangleCount() const;
  /// Number of vertices of the tessellation (each patch has its own).
  std::size_t VertexCount() const;
  /// Tessellation resolution of a patch.
  void Resolution(std::size_t patch, int& quadsU, int& quadsV) const;

private:
  /// CastRay's refinement and side of a triangle hit (`quadStart`: CastPacket's).
  void ResolveHit(const glm::dvec3& origin,
    const glm::dvec3& direction,
    const TriangleHit& triangle,
    RayHit& hit,
    bool quadStart) const;

  struct Implementation;
  std::unique_ptr<Implementation> Impl;
};

} // namespace sphcover

#endif
