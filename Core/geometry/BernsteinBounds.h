// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BernsteinBounds.h
 * @brief Range bounds over a parametric rectangle of a Bezier patch for the subdivision
 * criteria of paper §4.2, by natural interval evaluation (paper §4.1) or by the Bernstein
 * (convex-hull) form.
 *
 * Every function bounds one quantity of the patch Q over (u,v) in a UVRect, in the patch's
 * own parameters (derivatives are d/du and d/dv of the original patch, not of a
 * reparametrised sub-patch):
 *  - position Q(u,v) (paper §4.1: the bounding box of a patch);
 *  - normal N(u,v) = Qu x Qv, unnormalised (paper §4.2.1);
 *  - facing function f(u,v) = N(u,v) . (Q(u,v) - P) for a point P, of degree (3m-1, 3n-1)
 *    (paper §4.2.1, self-shadowing criterion);
 *  - squared distance g(u,v) = |Q(u,v) - P|^2, degree (2m, 2n) (paper §4.2.3, distance form);
 *  - height above a plane h(u,v) = M . (Q(u,v) - P) for a fixed vector M through a point P,
 *    degree (m, n) (paper §4.2.2 containment with M = N_i, and §4.2.4 characterisability).
 *
 * RangeMethod::NaturalInterval evaluates the defining Bernstein sums with interval arguments
 * U = [u0,u1], V = [v0,v1] in outward-rounded Interval arithmetic (rigorous; its excess width
 * shrinks linearly with the rectangle). RangeMethod::Bernstein, the default, restricts the
 * nets exactly to the rectangle (de Casteljau), forms the polynomial's Bernstein coefficients
 * by the product formula and takes their min/max (convex hull property), widened by an
 * a-priori bound on their rounding error (the restriction's own rounding, a few ulps, is not
 * enclosed except on UVRect::Unit()); its excess width shrinks quadratically and it is never
 * wider than the natural bound (up to rounding). Q - P is always evaluated with control
 * points P_ij - P, so no bound depends on where the origin lies. Details, rigour and
 * measurements: Documentation/notes/range-bounds.md.
 *
 * Sign convention of f: f < 0 over the whole rectangle means P lies on the front side
 * (the side of N) of every tangent plane there, i.e. the front of the whole sub-patch faces P;
 * f > 0 means the sub-patch turns its back to P. (Paper §4.2.1 calls f > 0 "facing"; that
 * holds with the opposite orientation of N, so callers test the sign they need.)
 *
 * All functions throw std::invalid_argument unless rect.IsValid() (0 <= U0 <= U1 <= 1,
 * 0 <= V0 <= V1 <= 1; zero-width rectangles are allowed). They do not allocate (fixed-capacity
 * stack buffers), so they are safe to call concurrently from many threads.
 *
 * Complexity: Bernstein O(m^2 n^2) per call, natural O(m n); measured costs:
 * Documentation/notes/range-bounds.md.
 */
#ifndef SPHCOVER_BERNSTEINBOUNDS_H
#define SPHCOVER_BERNSTEINBOUNDS_H

#include "geometry/BezierPatch.h"
#include "math/Interval.h"
#include "math/IntervalVector.h"
#include "math/UVRect.h"

#include <glm/vec3.hpp>

namespace sphcover
{

/// How a range over a parametric rectangle is bounded (both selectable,
/// Documentation/Pipeline.md#interval-subdivision).
enum class RangeMethod
{
  Bernstein,      ///< min/max of the Bernstein coefficients over the exact sub-patch
  NaturalInterval ///< the defining formula evaluated in interval arithmetic (paper §4.1)
};

/// Box enclosing Q(u,v) over the rectangle (paper §4.1).
IntervalVec3 RangeOfPosition(const BezierPatch& patch,
  const UVRect& rect,
  RangeMethod method = RangeMethod::Bernstein);

/// Box enclosing N(u,v) = Qu x Qv (unnormalised, original parameters) over the rectangle
/// (paper §4.2.1).
IntervalVec3 RangeOfNormal(const BezierPatch& patch,
  const UVRect& rect,
  RangeMethod method = RangeMethod::Bernstein);

/// Interval enclosing f(u,v) = N(u,v) . (Q(u,v) - point) over the rectangle: the
/// self-shadowing criterion of paper §4.2.1. See the file comment for the sign convention.
Interval RangeOfFacing(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  RangeMethod method = RangeMethod::Bernstein);

/// Interval enclosing g(u,v) = |Q(u,v) - point|^2 over the rectangle: the distance form of
/// the spherical shape criterion, paper §4.2.3. The lower end is never negative.
Interval RangeOfSquaredDistance(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& point,
  RangeMethod method = RangeMethod::Bernstein);

/// Interval enclosing h(u,v) = planeNormal . (Q(u,v) - planePoint) over the rectangle: the
/// height of the patch above the plane through planePoint (in units of |planeNormal|). With
/// planeNormal = N_i and planePoint = P_i this is the hemispherical containment criterion of
/// paper §4.2.2 (h > 0: the sub-patch lies in the hemisphere over N_i).
Interval RangeOfHeightAbovePlane(const BezierPatch& patch,
  const UVRect& rect,
  const glm::dvec3& planePoint,
  const glm::dvec3& planeNormal,
  RangeMethod method = RangeMethod::Bernstein);

} // namespace sphcover

#endif
