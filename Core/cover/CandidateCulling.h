// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CandidateCulling.h
 * @brief Which patches can appear in the hemisphere H_i of a characteristic point: the
 * rigorous range tests of paper §4.2.1 (self-shadowing: is the patch turned away from P_i?)
 * and §4.2.2 (hemispherical containment: is it below the tangent plane of P_i?), run before
 * any projection or ray work.
 *
 * Both tests bound a polynomial over a parametric rectangle of the patch with
 * BernsteinBounds (the default Bernstein method):
 *  - height h = N_i . (Q - P_i) <= 0 everywhere: the (sub-)patch lies on or below the
 *    tangent plane and no direction of H_i reaches it;
 *  - facing f = N_j . (Q - P_i) >= 0 everywhere: P_i is behind every tangent plane of the
 *    (sub-)patch, which turns its back (or its edge) to P_i (BernsteinBounds.h: f < 0 means
 *    P_i is on the front side).
 * A relative tolerance of 1e-9 of the quantities' scale absorbs the rounding allowance of the
 * bounds, so that a patch lying exactly in the tangent plane (a coplanar neighbour) or a
 * collapsed edge (where N_j = 0 and f = 0) is decided rather than left undecided forever. The
 * same tests drive the piece quadtree of the projection fill.
 *
 * Complexity: two range bounds per call, O(m^2 n^2) for a source of degree (m, n).
 */
#ifndef SPHCOVER_CANDIDATECULLING_H
#define SPHCOVER_CANDIDATECULLING_H

#include "geometry/BezierPatch.h"
#include "math/UVRect.h"

#include <glm/vec3.hpp>

#include <cstdint>

namespace sphcover
{

/// What the range tests say about a (sub-)patch seen from a point with a normal.
enum class CandidateClass
{
  BelowTangentPlane, ///< h <= 0 over the rectangle: culled
  BackFacing,        ///< f >= 0 over the rectangle: culled
  FrontFacing,       ///< f < 0 over the rectangle and something above the plane
  Undecided          ///< f changes sign (a silhouette may cross it) and something above
};

/// Counts of the candidate tests for one or more receivers.
struct CullingStatistics
{
  /// Ordered pairs (receiver, source) tested, the receiver's own patch included.
  uint64_t Candidates = 0;
  uint64_t BelowTangentPlane = 0;
  uint64_t BackFacing = 0;
  /// Candidates kept for projection.
  uint64_t Kept = 0;
  /// Accepted pieces after the quadtree split of the kept candidates (projection fill).
  uint64_t Pieces = 0;
  /// Pieces of back-facing candidates projected as occluders (RBufferFillOptions::
  /// BackFacesOcclude): no source, but they hide what lies behind them.
  uint64_t Occluders = 0;

  CullingStatistics& operator+=(const CullingStatistics& other);
};

/**
 * Classifies the rectangle `rect` of `source` as seen from `point` with unit `normal`: first
 * the tangent-plane test, then the facing test.
 */
CandidateClass ClassifyCandidate(const BezierPatch& source,
  const UVRect& rect,
  const glm::dvec3& point,
  const glm::dvec3& normal);

} // namespace sphcover

#endif
