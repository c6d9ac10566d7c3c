// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DirectIrradiance.h
 * @brief The lamps' direct irradiance and its first bounce over every patch, on a grid of nodes
 * finer than the characteristic points: the part of the illumination that changes fastest,
 * sampled where it changes, so that the render interpolates only the smooth rest between the
 * points.
 *
 * Why: a characteristic point stands for its patch's illumination (paper §3.4), and §5.3.2
 * interpolates between the points. The light that arrives straight from a lamp has the sharp
 * features of a scene (a shadow's penumbra, the contact shadow at a block's foot, the fall to
 * zero along a wall under the lamp's plane) at scales below a patch, and so has its first
 * bounce near where surfaces meet (along a concave edge a wall sees mostly the strip of the
 * other surface next to it, whose direct light falls to zero there: the corner's dip, which
 * no extrapolation from patch centres follows). After that the light is smooth. Splitting
 * them is the lightmap's old trick, and it keeps the solution view-independent: the nodes are
 * part of the solution, a view only interpolates them.
 *
 * Lamps are the bright emitters (BrightEmitters.h); a scene with none (a white furnace) has no
 * nodes and keeps the plain interpolation. For every patch, the nodes are (i, j) at the
 * patch's own parameters (i / (n - 1), j / (n - 1)), n = NodesPerSide (odd, so that the centre,
 * the characteristic point, is a node). A node's value is, per band, E_direct + E_bounce:
 *  - E_direct: the sum over lamp pieces L of Emission(L) x the projected solid angle of L's
 *    visible front side from the node (VisibleProjectedSolidAngle: the midpoint rule over L's
 *    (u, v), one shadow ray per quadrature node); the pieces of the node's own surface count
 *    unless that surface is planar (NearlyPlanar: a plane cannot see itself, a concave lamp
 *    lights its own inside);
 *  - E_bounce (BounceRaysPerSide g > 0; fewer at finer nodes, see below): pi x the mean, over g x g
 * cosine-weighted rays (one in each stratum of sin^2 theta and phi, all at the place within their
 * strata that a shift hashed from the node's index gives, math/PatternShift.h), of the Lambertian
 * radiance rho(y) / pi E_direct(y) of the front side y each ray meets, E_direct(y) interpolated
 * from y's patch's nodes (rho: `diffuse`, the patches' diffuse reflectance; a mirror or the back of
 * a two-sided surface sends nothing here, the propagation counts it). The rest of the light (the
 * lamp's own light reflected again, later bounces, what mirrors send) is the propagation's. The
 * propagation's points hold their own, coarser version of the nodes' light
 * (LightPropagation::LampIrradiance); a renderer takes that off the points' values and adds the
 * nodes', so that only the smooth rest is interpolated. A node on the border of patches of one
 * surface is computed once (by its (surface, u, v)) and shared by them.
 *
 * Where the nodes go: the coarse 3 x 3 nodes of every patch are computed, and a patch's finer
 * nodes only where the coarse ones show a shadow's edge or a patch of light crossing it
 * (RefinementTolerance); elsewhere the finer nodes are the coarse ones' bilinear
 * interpolation. The characteristic points need not be as dense as the direct light's
 * features (paper §3.4: a point stands for its patch's smooth illumination), so the fine
 * nodes, not deeper patches, carry them. E_bounce is gathered at the coarse nodes, then at the
 * finer nodes of the patches where it is not bilinear by the same test (beside a patch of
 * light), with max(4, g / h) rays per side there (h = (n - 1) / 2), and interpolated at the
 * others. A refined patch's computed edge nodes
 * are also used by a coarse neighbour that shares them, so the two agree along their edge.
 *
 * Rays start a hair inside the patch and off its front (RayOrigin in the source), so that at
 * an edge where surfaces meet a ray into the other surface's front meets it and a ray leaving
 * its plane does not; a hit on the node's own surface nearer than SelfExclusionFraction x the
 * patch's Size() is the node itself; a back side occludes when BackFacesOcclude (the cover's
 * semantics, RBuffer.h). Cost: distinct coarse nodes x (the lamp's quadrature nodes + g^2) rays
 * and the refined patches' other nodes x the lamp's quadrature nodes. The
 * result does not depend on the thread count.
 */
#ifndef SPHCOVER_DIRECTIRRADIANCE_H
#define SPHCOVER_DIRECTIRRADIANCE_H

#include "math/ParallelFor.h"
#include "math/RankShare.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphcover
{

struct Patch;
class RayCaster;

struct DirectIrradianceOptions
{
  /// Nodes along each side of a patch, odd, 3 to 33: the finest grid. Its coarse 3 x 3 (the
  /// corners, the sides' midpoints and the centre) is computed at every patch, the rest only
  /// where RefinementTolerance asks.
  int NodesPerSide = 3;
  /**
   * A patch's finer nodes are computed when one of its coarse nodes' direct light departs from
   * the bilinear interpolation of its corners by more than this fraction of the larger of the
   * patch's brightest coarse node and the scene's mean (a shadow's edge or a patch of light
   * crosses it); elsewhere they are the coarse nodes' bilinear interpolation, the same
   * function the render would draw from the coarse nodes alone. 0: every patch's nodes are
   * computed. Without effect when NodesPerSide is 3.
   */
  double RefinementTolerance = 0.05;
  /// The quadrature of a whole lamp takes at least this many nodes per side (shared among its
  /// pieces, at least one each).
  int LampNodesPerSide = 8;
  /// The first bounce of the direct light is gathered at every node with g x g cosine-weighted
  /// rays, g this (0 to 256; 0: the direct light only).
  int BounceRaysPerSide = 32;
  double SelfExclusionFraction = 1e-3;
  bool BackFacesOcclude = true;
  /**
   * Per patch the transmittance of a thin pane (paper §5.4; empty: no panes). The shadow and
   * bounce rays go on behind a pane's front side scaled by it (a bounce ray adds the pane's own
   * Lambertian radiance first), and pass its back side, its reversed copy's front.
   */
  std::vector<glm::vec3> Transmittance;
  /// Per surface (Patch::SurfaceIndex; empty or shorter: none) whether it is one side of a
  /// two-sided surface (RBufferFillOptions::TwoSidedSurfaces): the rays pass its back side, the
  /// other side's front.
  std::vector<bool> TwoSidedSurfaces;
};

/// Per patch NodesPerSide^2 nodes, RGB irradiance (E_direct + E_bounce) each: patch p's node (i, j)
/// band b is at
/// ((p * n + j) * n + i) * 3 + b (i along u).
struct DirectIrradianceNodes
{
  int NodesPerSide = 0;
  std::vector<float> Values;
  /// The shadow and bounce rays (of the nodes this rank computed) that still met a pane after
  /// MaxPanesPerRay of them: the light behind it is left out (issue 39 item 6).
  uint64_t PaneLimitRays = 0;

  bool Empty() const { return this->Values.empty(); }
  /// The bilinear interpolation of patch p's nodes at its own (s, t) in [0,1]^2 (clamped).
  glm::dvec3 At(std::size_t patch, double s, double t) const;
};

/**
 * The direct irradiance of the lamps (`lamps`: per surface index, whether it is one;
 * `emission`: each patch's emitted radiance) and its first bounce (`diffuse`: each patch's
 * diffuse reflectance; may be empty when BounceRaysPerSide is 0) at the nodes of every patch
 * (see the file comment), computed with `caster`, a RayCaster over `patches` in the same
 * order. Empty
 * (NodesPerSide 0) when no patch belongs to a lamp. Returns false, the result incomplete,
 * when `progress` returned false. Throws std::invalid_argument for sizes that differ or
 * NodesPerSide or BounceRaysPerSide outside its range, or a RefinementTolerance that is
 * negative or not a number. Under MPI (`share`, RankShare.h) the ranks compute the nodes in
 * turn and every rank gets all of them, the serial values bit for bit; collective then, and
 * RankShare::PeerFailure when another rank failed.
 */
bool ComputeDirectIrradiance(const std::vector<Patch>& patches,
  const RayCaster& caster,
  const std::vector<bool>& lamps,
  const std::vector<glm::dvec3>& emission,
  const std::vector<glm::dvec3>& diffuse,
  const DirectIrradianceOptions& options,
  DirectIrradianceNodes& result,
  const ParallelFor& parallelFor = SequentialFor,
  const ProgressCallback& progress = nullptr,
  const RankShare& share = RankShare());

} // namespace sphcover

#endif
