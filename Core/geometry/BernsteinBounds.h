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
 * RangeMethod::NaturalInterval evaluates the defining formula with interval arguments
 * U = [u0,u1], V = [v0,v1]: Q = sum_i B_i^m(U) sum_j B_j^n(V) P_ij with
 * B_i^m(U) = C(m,i) U^i (1-U)^(m-i), likewise the hodographs for Qu and Qv, then the cross and
 * dot products of paper §4.2 in Interval arithmetic. Q - P is evaluated as the Bezier form with
 * control points P_ij - P, which keeps the bounds of f, g and h independent of where the origin
 * lies. It is cheap but overestimates: its excess width shrinks only linearly with the
 * rectangle, and over the whole patch (U = [0,1]) the basis alone is overestimated up to 2^m.
 *
 * RangeMethod::Bernstein restricts the control net and the derivative nets exactly to the
 * rectangle (de Casteljau), multiplies the Bernstein polynomials by the product formula
 * B_a^p B_b^q = C(p,a) C(q,b) / C(p+q,a+b) B_{a+b}^{p+q}, and bounds the polynomial by the
 * smallest and largest of its Bernstein coefficients (convex hull property). The excess width
 * shrinks quadratically with the rectangle, and each Bernstein coefficient is a convex
 * combination of values the natural evaluation encloses, so the Bernstein bounds are never
 * wider than the natural ones (up to rounding). This is the default (SPEC §4.2).
 *
 * Rigour: the natural bounds are rigorous (outward-rounded Interval arithmetic throughout). The
 * Bernstein coefficients are computed in double arithmetic and the final min/max is widened by
 * an a-priori bound on their rounding error (Higham's gamma_k analysis, see the .cxx), which
 * encloses the exact coefficients of the restricted nets as surely as Interval arithmetic
 * would, about 50 times faster; the tests check this against exact rational arithmetic. The
 * restriction of the nets to the rectangle is done in doubles and its rounding (a few ulps of
 * the coordinates, from convex combinations only) is not enclosed; on the whole patch
 * (UVRect::Unit()) there is none.
 *
 * Sign convention of f: f < 0 over the whole rectangle means P lies on the front side
 * (the side of N) of every tangent plane there, i.e. the front of the whole sub-patch faces P;
 * f > 0 means the sub-patch turns its back to P. (Paper §4.2.1 calls f > 0 "facing"; that
 * holds with the opposite orientation of N, so callers test the sign they need.)
 *
 * All functions throw std::invalid_argument unless rect.IsValid() (0 <= U0 <= U1 <= 1,
 * 0 <= V0 <= V1 <= 1; zero-width rectangles are allowed). They do not allocate: the
 * coefficient buffers are fixed-capacity arrays on the stack, sized for the smallest of the
 * maximum degrees 3, 7, 15 that holds the patch (about 3 KB for bicubic patches, at most
 * about 60 KB for degree 15), so they are safe to call concurrently from many threads.
 *
 * Cost per call (Release, one core, bicubic patch): Bernstein f about 1.4 us, natural f about
 * 6 us; Bernstein grows as O(m^2 n^2) and is slower than natural from degree 7 on.
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

/// How a range over a parametric rectangle is bounded (SPEC §4.2: both selectable).
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
