// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DirectIrradiance.h
 * @brief The lamps' direct irradiance over every patch, on a grid of nodes finer than the
 * characteristic points: the part of the illumination that changes fastest, sampled where it
 * changes, so that the render interpolates only the smooth rest between the points.
 *
 * Why: a characteristic point stands for its patch's illumination (paper §3.4), and §5.3.2
 * interpolates between the points. The light that arrives straight from a lamp has the sharp
 * features of a scene (a shadow's penumbra, the contact shadow at a block's foot, the fall to
 * zero along a wall under the lamp's plane) at scales below a patch; what arrives after a
 * bounce is smooth. Splitting them is the lightmap's old trick, and it keeps the solution
 * view-independent: the nodes are part of the solution, a view only interpolates them.
 *
 * Lamps are the bright emitters (BrightEmitters.h); a scene with none (a white furnace) has no
 * direct part and keeps the plain interpolation. For every patch, the nodes are (i, j) at the
 * patch's own parameters (i / (n - 1), j / (n - 1)), n = NodesPerSide (odd, so that the centre,
 * the characteristic point, is a node). A node's irradiance is, per band,
 * sum over lamp pieces L of other surfaces of Emission(L) x the projected solid angle of L's
 * visible front side from the node (VisibleProjectedSolidAngle: the midpoint rule over L's
 * (u, v), one shadow ray per quadrature node). The lamp's own light reflected again, and all
 * other light, is not direct: the propagation counts it. A node on the border of patches of
 * one surface is computed once (by its (surface, u, v)) and shared by them.
 *
 * Shadow rays start at the exact surface point; a hit nearer than SelfExclusionFraction x the
 * patch's Size() is where the node lies (its own surface's tessellation around the exact point,
 * and for a node on an edge where two surfaces meet, the other surface's plane, which the ray
 * leaves at once), not an occluder; a back side occludes when BackFacesOcclude (the cover's
 * semantics, RBuffer.h). Cost: patches x NodesPerSide^2 x the lamp's quadrature
 * nodes rays at most (fewer where nodes are shared). The result does
 * not depend on the thread count.
 */
#ifndef SPHCOVER_DIRECTIRRADIANCE_H
#define SPHCOVER_DIRECTIRRADIANCE_H

#include "math/ParallelFor.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace sphcover
{

struct Patch;
class RayCaster;

struct DirectIrradianceOptions
{
  /// Nodes along each side of a patch, odd, 3 to 33.
  int NodesPerSide = 3;
  /// The quadrature of a whole lamp takes at least this many nodes per side (shared among its
  /// pieces, at least one each).
  int LampNodesPerSide = 8;
  double SelfExclusionFraction = 1e-3;
  bool BackFacesOcclude = true;
};

/// Per patch NodesPerSide^2 nodes, RGB each: patch p's node (i, j) band b is at
/// ((p * n + j) * n + i) * 3 + b (i along u).
struct DirectIrradianceNodes
{
  int NodesPerSide = 0;
  std::vector<float> Values;

  bool Empty() const { return this->Values.empty(); }
  /// The bilinear interpolation of patch p's nodes at its own (s, t) in [0,1]^2 (clamped).
  glm::dvec3 At(std::size_t patch, double s, double t) const;
};

/**
 * The direct irradiance of the lamps (`lamps`: per surface index, whether it is one;
 * `emission`: each patch's emitted radiance) at the nodes of every patch (see the file
 * comment), computed with `caster`, a RayCaster over `patches` in the same order. Empty
 * (NodesPerSide 0) when no patch belongs to a lamp. Returns false, the result incomplete,
 * when `progress` returned false. Throws std::invalid_argument for sizes that differ or
 * NodesPerSide outside its range.
 */
bool ComputeDirectIrradiance(const std::vector<Patch>& patches,
  const RayCaster& caster,
  const std::vector<bool>& lamps,
  const std::vector<glm::dvec3>& emission,
  const DirectIrradianceOptions& options,
  DirectIrradianceNodes& result,
  const ParallelFor& parallelFor = SequentialFor,
  const ProgressCallback& progress = nullptr);

} // namespace sphcover

#endif
