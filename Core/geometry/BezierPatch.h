// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class BezierPatch
 * @brief A tensor-product Bezier patch of degree (m, n), 1 <= m, n <= 15: the surfaces of
 * the environment (paper §3.2, §4.3) and their exact sub-patches.
 *
 * Q(u,v) = sum_ij B_i^m(u) B_j^n(v) P_ij for (u,v) in [0,1]^2. Control points are row-major
 * with u fastest: ControlPoints()[j*(m+1)+i] is P_ij (i along u, j along v). The front side
 * is the side of dQ/du x dQ/dv (paper §4.2.1 writes N = dQ/du x dQ/dv). A flat or bilinear
 * quad is a degree (1,1) patch; a triangle is a degree (1,1) patch with one collapsed edge.
 *
 * Evaluation and subdivision use de Casteljau's algorithm (numerically stable, see
 * DeCasteljau.h); the derivative nets (hodographs) are computed once at construction, so
 * partial derivatives are evaluated as Bezier patches of lower degree. Sub-patches
 * (SplitU/SplitV/SubPatch) are exact: they are the same polynomial surface reparametrised,
 * not a tessellation (Documentation/Pipeline.md#interval-subdivision).
 *
 * Normal() handles degenerate points, where dQ/du x dQ/dv vanishes: see its documentation.
 */
#ifndef SPHCOVER_BEZIERPATCH_H
#define SPHCOVER_BEZIERPATCH_H

#include "geometry/DeCasteljau.h"
#include "math/IntervalVector.h"
#include "math/UVRect.h"

#include <glm/vec3.hpp>

#include <utility>
#include <vector>

namespace sphcover
{

/// The largest coordinate magnitude among `points`, or NaN if any coordinate is NaN (so that a
/// bound written as `!(LargestCoordinate(p) <= limit)` refuses it).
double LargestCoordinate(const std::vector<glm::dvec3>& points);

class BezierPatch
{
public:
  /// The largest degree in either direction; fixed-capacity buffers are sized for it.
  static constexpr int MaxDegree = MaxNetDegree;
  /// The largest coordinate magnitude the readers accept (Data/scenes/FORMAT.md): areas,
  /// powers and squared distances of such patches stay far inside the double range, and
  /// Embree, which works in float, aborts on surfaces around 1e19 away.
  static constexpr double MaxCoordinate = 1e15;

  /**
   * Throws std::invalid_argument when a degree is outside [1, MaxDegree], when
   * controlPoints.size() != (degreeU+1)(degreeV+1), or when a coordinate is not finite.
   */
  BezierPatch(int degreeU, int degreeV, std::vector<glm::dvec3> controlPoints);

  int DegreeU() const { return this->DegreeUValue; }
  int DegreeV() const { return this->DegreeVValue; }

  /// P_ij, 0 <= i <= DegreeU(), 0 <= j <= DegreeV().
  const glm::dvec3& ControlPoint(int i, int j) const;
  /// All control points, row-major with u fastest.
  const std::vector<glm::dvec3>& ControlPoints() const { return this->Points; }

  /// Control net of dQ/du, a patch of degree (m-1, n): point j*m+i is m (P_{i+1,j} - P_ij).
  const std::vector<glm::dvec3>& DerivativeNetU() const { return this->NetU; }
  /// Control net of dQ/dv, a patch of degree (m, n-1): point j*(m+1)+i is n (P_{i,j+1} - P_ij).
  const std::vector<glm::dvec3>& DerivativeNetV() const { return this->NetV; }

  /// Q(u, v) by de Casteljau. Parameters outside [0,1] extrapolate the polynomial.
  glm::dvec3 Evaluate(double u, double v) const;
  /// dQ/du at (u, v).
  glm::dvec3 PartialU(double u, double v) const;
  /// dQ/dv at (u, v).
  glm::dvec3 PartialV(double u, double v) const;
  /// Q, dQ/du and dQ/dv at (u, v) in one call.
  void EvaluateWithPartials(double u,
    double v,
    glm::dvec3& position,
    glm::dvec3& partialU,
    glm::dvec3& partialV) const;

  /// N(u, v) = dQ/du x dQ/dv (paper §4.2.1); its length is the area element. Zero at
  /// degenerate points such as collapsed edges.
  glm::dvec3 UnnormalizedNormal(double u, double v) const;

  /**
   * The unit normal on the front side; never NaN.
   *
   * Where |N| is clearly non-zero (> 1e-12 Size()^2) this is N/|N|. At a degenerate point
   * (a collapsed edge such as the poles of the teapot's lid and bottom, or the apex of a
   * triangle stored as a degree (1,1) patch) it is the limit of N/|N| as (u,v) approaches the
   * point from the parametric centre (0.5, 0.5) along the straight line d: N vanishes there, so
   * N(p + t d) = t dN/dd + O(t^2) and the limit direction is that of the directional
   * derivative dN/dd = d_u (Quu x Qv + Qu x Quv) + d_v (Quv x Qv + Qu x Qvv), computed exactly
   * from the second derivative nets. On a collapsed edge this is the tangent-plane normal of
   * the surface next to the edge (for a triangle: its face normal). If dN/dd vanishes too
   * (a higher-order degeneracy), N is taken at points nudged toward the centre by fractions
   * 1e-6, 1e-4, 1e-2, 0.1, 0.5 of the way, and as a last resort the normal of the control net
   * (ControlNetNormal()), or +z for a patch without area.
   */
  glm::dvec3 Normal(double u, double v) const;

  /// The two halves of the patch split at u = t, 0 < t < 1: first over [0,t], second over
  /// [t,1], each reparametrised to [0,1]. Throws std::invalid_argument for t outside (0,1).
  std::pair<BezierPatch, BezierPatch> SplitU(double t) const;
  /// As SplitU, along v.
  std::pair<BezierPatch, BezierPatch> SplitV(double t) const;

  /// The exact sub-patch over [u0,u1] x [v0,v1] reparametrised to [0,1]^2 (its control points
  /// are the blossom values of the patch). Requires 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1,
  /// otherwise throws std::invalid_argument.
  BezierPatch SubPatch(double u0, double u1, double v0, double v1) const;
  BezierPatch SubPatch(const UVRect& rect) const;

  /// The axis-aligned box of the control net; it encloses the patch (convex hull property).
  const IntervalVec3& Bounds() const { return this->ControlNetBounds; }
  /// The diagonal length of Bounds(): the scale against which degeneracy is judged.
  double Size() const { return this->BoundsDiagonal; }

  /// Unit vector area of the control net, sum over its quads of (P_{i+1,j+1} - P_ij) x
  /// (P_{i,j+1} - P_{i+1,j}), normalised; zero if the net has no area.
  const glm::dvec3& ControlNetNormal() const { return this->NetNormal; }

private:
  /// Evaluates the second partial derivatives (zero in a direction of degree 1).
  void SecondPartials(double u, double v, glm::dvec3& uu, glm::dvec3& uv, glm::dvec3& vv) const;
  /// The limit normal at a degenerate point, see Normal(); |N| <= threshold counts as zero.
  glm::dvec3 DegenerateNormal(double u, double v, double threshold) const;

  int DegreeUValue;
  int DegreeVValue;
  std::vector<glm::dvec3> Points;
  std::vector<glm::dvec3> NetU;
  std::vector<glm::dvec3> NetV;
  IntervalVec3 ControlNetBounds;
  double BoundsDiagonal = 0.0;
  glm::dvec3 NetNormal{ 0.0 };
};

/// The fraction of a net's size (its bounding box's diagonal) within which NearlyPlanar holds.
constexpr double NearlyPlanarFraction = 0.01;

/**
 * Whether the control points `points` lie within NearlyPlanarFraction x `size` of the plane
 * through their centroid normal to `normal` (false for a zero normal). `points` may be one
 * patch's net (`size` its Size(), `normal` its ControlNetNormal()) or the nets of a surface's
 * pieces together: the de Casteljau pieces of a plane keep their control points in it, those of
 * a curved surface do not, however fine (the Cornell red wall's 3.2 mm twist over 780 mm counts
 * as planar).
 */
bool NearlyPlanar(const std::vector<glm::dvec3>& points, const glm::dvec3& normal, double size);

} // namespace sphcover

#endif
