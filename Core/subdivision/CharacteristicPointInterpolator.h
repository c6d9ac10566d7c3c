// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CharacteristicPointInterpolator.h
 * @brief Interpolation of per-characteristic-point values over each surface's (u, v) (paper
 * §3.4, §5.3.2): "Given any (u, v) we determine the four characteristic points on the surface
 * (u0, v0), (u0, v1), (u1, v0), (u1, v1) such that u0 <= u <= u1 and v0 <= v <= v1. We then
 * bilinearly interpolate ... Since characteristic points are typically centres of patches, we
 * bilinearly extrapolate for points nearer to the boundaries of the surface (See Fig.6)."
 *
 * The characteristic points of one surface are the parametric centres of the patches of an
 * adaptive ternary subdivision (paper §4.3): the patches tile the surface's unit square, but
 * the centres form a regular grid only where the subdivision is uniform. The four points are
 * found from the layout itself:
 *  1. the patch P containing (u, v) (a bucket grid over the unit square per surface);
 *  2. the quadrant of (u, v) relative to P's centre c gives the side (su, sv) to look at; the
 *     neighbours are the patches containing the points just across P's edges on that side:
 *     X across the u edge at c's v, Y across the v edge at c's u, D across the corner. Where
 *     that side is the surface's edge there is no neighbour, and the other side is used
 *     instead, so the value is extrapolated linearly (Fig. 6);
 *  3. with four distinct centres c, X, D, Y (a quadrilateral in (u, v)), the weights are those
 *     of the bilinear map of the quadrilateral inverted at (u, v): on a uniform partition the
 *     quadrilateral is the axis-aligned rectangle of the paper and this is exactly its bilinear
 *     interpolation (and extrapolation). Where an adaptive layout makes two of them the same
 *     patch (a larger neighbour spans two of the positions) or the quadrilateral degenerates,
 *     the weights are those of the least-squares plane through the distinct centres (3 or 4),
 *     or the line through 2, or the constant of 1. A patch that spans its surface in one
 *     direction has no neighbour across it there; the nearest centres of the surface complete
 *     the set to three non-collinear points (a plane) where the surface has them.
 *
 * Properties (tested): the weights sum to 1, so a constant field stays constant everywhere,
 * edges included; a bilinear field is reproduced exactly on a uniform partition and a linear
 * field on any layout (both inside and in the extrapolated margins); on a uniform partition the
 * result is continuous across patch borders (both sides use the same four centres). Across the
 * border between patches of different levels, the two sides may choose different neighbour
 * sets: the jump is bounded by the field's second differences over the larger patch (zero for
 * linear fields).
 *
 * Excluded points (SetExcludedPoints: the buried points of BuriedPoints.h, whose value is not
 * characteristic of the visible surface around them) take part in no stencil: a neighbour that
 * is excluded counts as no neighbour (so the value is extrapolated from the other side, or
 * fitted by the plane or line through the points left), and a (u, v) in an excluded point's
 * patch is interpolated around the nearest point that is kept instead.
 *
 * Extrapolated weights can be negative; the renderer clamps interpolated radiance at zero.
 * Complexity: building O(points) (per surface a bucket grid of about one patch per bucket); a
 * query visits the patches of a few buckets, O(1) on a uniform layout.
 */
#ifndef SPHCOVER_CHARACTERISTICPOINTINTERPOLATOR_H
#define SPHCOVER_CHARACTERISTICPOINTINTERPOLATOR_H

#include "math/UVRect.h"

#include <array>
#include <cstddef>
#include <vector>

namespace sphcover
{
struct Patch;

/// At most four characteristic points and their weights (which sum to 1).
struct InterpolationStencil
{
  std::array<std::size_t, 4> Points{ { 0, 0, 0, 0 } };
  std::array<double, 4> Weights{ { 0.0, 0.0, 0.0, 0.0 } };
  int Count = 0;
};

class CharacteristicPointInterpolator
{
public:
  CharacteristicPointInterpolator() = default;
  /**
   * @param surfaceOfPoint the surface of every characteristic point (>= 0).
   * @param domainOfPoint the parametric rectangle of every point's patch in its surface's
   * [0,1]^2 (the centre is the characteristic point).
   * Throws std::invalid_argument for different sizes, a negative surface or an invalid or empty
   * rectangle.
   */
  CharacteristicPointInterpolator(const std::vector<int>& surfaceOfPoint,
    const std::vector<UVRect>& domainOfPoint);
  /// The characteristic points of `patches` (one per patch: its SurfaceIndex and Domain).
  static CharacteristicPointInterpolator OfPatches(const std::vector<Patch>& patches);

  std::size_t PointCount() const { return this->Domains.size(); }
  /// Number of surfaces indexed (one more than the largest surface index).
  std::size_t SurfaceCount() const { return this->Surfaces.size(); }
  /// Whether the surface has characteristic points.
  bool HasPoints(int surface) const;
  /// The surface of a point and its patch's parametric rectangle (its centre is the point).
  int SurfaceOf(std::size_t point) const { return this->PointSurfaces[point]; }
  const UVRect& Domain(std::size_t point) const { return this->Domains[point]; }

  /// Points left out of every stencil (see the file comment), one flag per point; an empty
  /// vector excludes none. Throws std::invalid_argument for another size.
  void SetExcludedPoints(std::vector<bool> excluded);
  bool IsExcluded(std::size_t point) const
  {
    return !this->Excluded.empty() && this->Excluded[point];
  }

  /// The point whose patch contains (u, v) on `surface` (the nearest patch if rounding leaves a
  /// gap); -1 when the surface has no points. (u, v) is clamped to [0,1]^2.
  std::ptrdiff_t ContainingPoint(int surface, double u, double v) const;

  /// The points and weights of (u, v) on `surface` (see the file comment); false when the
  /// surface has no points.
  bool Stencil(int surface, double u, double v, InterpolationStencil& stencil) const;

private:
  /// The patches of one surface and a bucket grid over its unit square.
  struct SurfaceLayout
  {
    int BucketsU = 0;
    int BucketsV = 0;
    /// Bucket b's points are BucketPoints[BucketOffsets[b] .. BucketOffsets[b + 1]).
    std::vector<std::size_t> BucketOffsets;
    std::vector<std::size_t> BucketPoints;
    /// The surface's points, ascending.
    std::vector<std::size_t> Points;
  };

  /// The point containing (u, v), or -1 when (u, v) is outside [0,1]^2 (no clamping).
  std::ptrdiff_t Locate(const SurfaceLayout& layout, double u, double v) const;
  /// The points c, X, D, Y of the stencil of (u, v) in the patch of point `found` (step 2 of
  /// the file comment); -1 where there is no neighbour.
  std::array<std::ptrdiff_t, 4> QuadrantCorners(const SurfaceLayout& layout,
    std::ptrdiff_t found,
    double u,
    double v) const;

  /// The kept point of the layout whose rectangle is nearest (u, v); -1 when none is kept.
  std::ptrdiff_t NearestKept(const SurfaceLayout& layout, double u, double v) const;

  std::vector<UVRect> Domains;
  std::vector<int> PointSurfaces;
  std::vector<SurfaceLayout> Surfaces;
  std::vector<bool> Excluded;
};

} // namespace sphcover

#endif
