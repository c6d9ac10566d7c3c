// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RayPatchIntersection.h
 * @brief The exact intersection of a ray with a Bezier patch by Newton's method: the distance
 * R of paper §4.2.5 where the R-buffer fills need it exactly (the projection fill's depth test
 * between patches whose depth ranges overlap, the ray fill's refinement of a hit on the
 * tessellation).
 *
 * Input: a patch, a ray and an initial guess (u, v, t); output: the converged (u, v, t) or
 * failure. Complexity: O(m^2 n + n^2) per Newton step (EvaluatePointAndPartials), a few steps
 * from a nearby guess.
 */
#ifndef SPHCOVER_RAYPATCHINTERSECTION_H
#define SPHCOVER_RAYPATCHINTERSECTION_H

#include "geometry/BezierPatch.h"

#include <glm/vec3.hpp>

namespace sphcover
{

/**
 * Solves Q(u, v) = origin + t direction for (u, v, t) by Newton's method from the initial
 * guess in (u, v, t), on the patch's polynomial (parameters may leave [0,1] during the
 * iteration; each step is limited to keep it near the domain). Returns true when it converged
 * (residual below 1e-12 of the patch size, or steps below 1e-13) with t > 0; the caller checks
 * whether (u, v) lies in the rectangle it cares about. Fails (returns false) where the ray is
 * tangent to the surface (singular Jacobian, N . direction = 0).
 */
/**
 * Q, dQ/du and dQ/dv at (u, v) in one pass over the control net (rows reduced to their last
 * de Casteljau level, then the column): about a third of the cost of Evaluate, PartialU and
 * PartialV. The partials are differences of the last level, so they lose relative accuracy
 * where they vanish (collapsed edges); BezierPatch's hodographs do not.
 */
void EvaluatePointAndPartials(const BezierPatch& patch,
  double u,
  double v,
  glm::dvec3& position,
  glm::dvec3& partialU,
  glm::dvec3& partialV);

bool IntersectRayPatch(const BezierPatch& patch,
  const glm::dvec3& origin,
  const glm::dvec3& direction,
  double& u,
  double& v,
  double& t);

} // namespace sphcover

#endif
