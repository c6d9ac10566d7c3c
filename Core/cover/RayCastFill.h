// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RayCastFill.h
 * @brief The second R-buffer fill (SPEC §4.3): the sample rays of every cell are cast from
 * P_i through a tessellation of the exact patches with Intel Embree 3, and the first front
 * side hit is mapped back to its patch.
 *
 * Tessellation: each patch is a grid of n_u x n_v quads (two triangles each), n even so that
 * the parametric centre, the characteristic point, is a vertex (rays from P_i then never
 * start inside one of its own triangles). n is chosen from the second-derivative bound of the
 * control net so that the piecewise linear surface deviates from the patch by at most
 * TessellationTolerance * Size(): the deviation of the linear interpolant over a triangle of
 * a cell h_u x h_v is at most (h_u^2 M_uu + 2 h_u h_v M_uv + h_v^2 M_vv) / 8, M the largest
 * second partials (convex hull of the second-difference nets). Patches of one surface with the
 * same degrees share the largest n of them, so that uniformly split surfaces are tessellated
 * without T-junctions (cracks) along their shared edges. n <= 256.
 *
 * One Embree scene holds the whole environment, one triangle geometry per patch (geometry id =
 * patch index), built in Embree's robust mode so that a ray never slips through the shared edge
 * of two triangles (a camera looking into a corner of a closed room would otherwise see through
 * it now and then). Rays are single precision: origin P_i, the sample directions of
 * HemisphereGrid in world coordinates. A context filter implements the visibility semantics of
 * RBuffer.h: hits on a triangle's back side are skipped (traversal goes on behind them), and
 * hits on the receiver's own patch nearer than the self-exclusion distance (or all of them when
 * CountSelfVisibility is off).
 *
 * Refinement (RefineHits, default on): the hit's triangle and barycentric coordinates give the
 * patch's (u, v); Newton's method on the exact Bezier patch (RayPatchIntersection) then gives
 * the exact R and normal, from which a grazing hit (|cos| < GrazingCosine) is flagged. Without
 * refinement R and the normal come from the triangle.
 *
 * The Embree device runs its BVH build in one thread (the environment is built once; results
 * must not depend on a thread count), and rtcIntersect1 is called concurrently from the
 * caller's threads, which Embree supports on a committed scene.
 */
#ifndef SPHCOVER_RAYCASTFILL_H
#define SPHCOVER_RAYCASTFILL_H

#include "cover/RBuffer.h"

#include <glm/vec3.hpp>

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

/// Why the patches cannot be handed to Embree (a control point beyond MaxRayCastCoordinate,
/// or not finite: the patches lie in their control nets' convex hulls), or "".
std::string RayCastCoordinateProblem(const std::vector<Patch>& patches);

class RayCastFiller : public RBufferFiller
{
public:
  /// Throws std::invalid_argument for patches beyond MaxRayCastCoordinate
  /// (RayCastCoordinateProblem), std::runtime_error if Embree fails.
  RayCastFiller(const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options);
  ~RayCastFiller() override;
  RayCastFiller(const RayCastFiller&) = delete;
  RayCastFiller& operator=(const RayCastFiller&) = delete;

  RBufferFill Kind() const override { return RBufferFill::RayCasting; }
  void Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics* culling) const override;
  std::size_t EnvironmentBytes() const override;

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
   * of any patch (surfaces are opaque), refined on the exact Bezier patch by Newton's method
   * when RefineHits is on (within the tessellation's accuracy otherwise). `direction` must be a
   * unit vector. False when the ray escapes. Safe to call from several threads at once.
   */
  bool CastRay(const glm::dvec3& origin, const glm::dvec3& direction, RayHit& hit) const;

  /// Number of triangles of the tessellation.
  std::size_t TriangleCount() const;
  /// Tessellation resolution of a patch.
  void Resolution(std::size_t patch, int& quadsU, int& quadsV) const;

  /**
   * The first patch met by the ray origin + t direction, t > tNear, from either side (no
   * receiver, no self-exclusion): its index, the distance t (of the tessellation) and whether
   * the side met is the front. False when the ray escapes. Thread-safe, like Fill().
   */
  bool FirstHit(const glm::dvec3& origin,
    const glm::dvec3& direction,
    double tNear,
    std::size_t& patch,
    double& distance,
    bool& front) const;

private:
  struct Implementation;
  std::unique_ptr<Implementation> Impl;
};

} // namespace sphcover

#endif
