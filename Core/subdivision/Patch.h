// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Patch.h
 * @brief One patch Q_i of the subdivided environment and its characteristic point P_i
 * (paper §3.2, §4.3 Step 0).
 *
 * A patch is a rectangle of one surface's parameter domain; its characteristic point is the
 * parametric centre. The geometry is the exact sub-patch (de Casteljau), not a tessellation.
 */
#ifndef SPHCOVER_PATCH_H
#define SPHCOVER_PATCH_H

#include "geometry/BezierPatch.h"
#include "math/UVRect.h"

#include <glm/vec3.hpp>

#include <vector>

#include <array>

namespace sphcover
{

/// Which criterion of paper §4.2 caused a patch's last split (None: never split).
enum class SplitReason
{
  None = 0,
  SelfShadowing = 1,            ///< §4.2.1
  HemisphericalContainment = 2, ///< §4.2.2
  SphericalShape = 3,           ///< §4.2.3
  Characterisability = 4,       ///< §4.2.4
  RBuffer = 5                   ///< §4.2.5: partially hidden in a hemisphere (cover stage)
};

const char* SplitReasonName(SplitReason reason);

struct Patch
{
  Patch(int surfaceIndex, const UVRect& domain, int level, BezierPatch geometry);

  /// Index of the surface (Scene::Surfaces) the patch is part of.
  int SurfaceIndex = 0;
  /// The parametric rectangle of the surface this patch covers.
  UVRect Domain;
  /// Number of ternary splits from the whole surface.
  int Level = 0;
  SplitReason Reason = SplitReason::None;
  /// The exact sub-patch over Domain, reparametrised to [0,1]^2.
  BezierPatch Geometry;
  /// The characteristic point P_i: the parametric centre (paper §4.3 Step 0).
  glm::dvec3 Point{ 0.0 };
  /// Unit normal (front side) at Point.
  glm::dvec3 Normal{ 0.0, 0.0, 1.0 };
  /// Surface area of the patch.
  double Area = 0.0;
};

/**
 * The ternary split of paper §4.3 note 3 shared by the interval subdivision and the R-buffer
 * refinement: `parent` is cut into three pieces of equal parametric width along u or v,
 * whichever is longer in 3-D (mean control polygon length), "so as to maintain relatively
 * square shaped subpatches in Euclidean space". The pieces are at Level + 1, carry `reason`,
 * tile the parent's domain exactly (the cut values are shared by neighbouring pieces) and are
 * taken from `surface`, the whole original surface, not from the parent, so that no rounding
 * accumulates over the levels. Returned in increasing u (or v).
 */
std::array<Patch, 3> SplitInThree(const Patch& parent,
  const BezierPatch& surface,
  SplitReason reason);

/// The patch list Q of the leaves `leaves` of `nodes`, in canonical order: by surface, then by
/// v, then by u of their domains (the order every stage's output uses).
std::vector<Patch> CollectPatches(const std::vector<Patch>& nodes, const std::vector<int>& leaves);

/// Area of a Bezier patch, the integral of |dQ/du x dQ/dv| over [0,1]^2, by Gauss-Legendre
/// quadrature of an order high enough for the patch's degrees.
double PatchArea(const BezierPatch& patch);

} // namespace sphcover

#endif
