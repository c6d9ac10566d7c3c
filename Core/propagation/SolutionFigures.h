// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SolutionFigures.h
 * @brief What an equilibrium amounts to per named surface (README.md#command-line's report): each
 * surface's area, its area-weighted mean irradiance and exitant radiance, the form factors between
 * the named surfaces (paper §3.3, from the cover), the energy balance and the counts.
 *
 * Inputs: the spherical cover, per characteristic point its surface (an index of the named
 * surfaces), area, irradiance E and exitant radiance L (paper §5.1's result), and the emitted
 * and absorbed power. Outputs: one SurfaceFigures per named surface, the form factors (row a:
 * from surface a, area-weighted over it) of the pairs of surfaces that see each other
 * (SurfaceFormFactors), the relative imbalance, the point and strip counts.
 * vtkLightPropagationFilter stores them in its output's field data; `sphcover` prints them.
 *
 * Why sparse: a scene of n named surfaces (a CAD or mesh scene has thousands of parts) has n^2
 * pairs, but a surface sees at most as many others as its points' hemispheres have regions, so
 * the pairs that see each other are at most the cover's entries (and at most n times the
 * hemisphere's cells when every surface is one patch). The dense n x n matrix of 20,000 tiles
 * was 3.3 GB, twice over (the figures and their field array), for 1.3 million non-zero pairs.
 *
 * Cost: O(points + surfaces) for the means, plus the cover's form-factor sums (O(entries)) and
 * O(pairs log pairs) to order them; memory O(surfaces + pairs).
 */
#ifndef SPHCOVER_SOLUTIONFIGURES_H
#define SPHCOVER_SOLUTIONFIGURES_H

#include "cover/SphericalCover.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphcover
{
/**
 * The form factors between named surfaces (paper §3.3, summed per surface) of the pairs that see
 * each other, in compressed rows: row a (from surface a) holds, for every surface b seen from a
 * (the layer-0 regions of a's points' hemispheres: panes opaque, as SphericalCover::FormFactors),
 * F_ab = (1 / A_a) sum_{i in a} A_i sum_{j in b} Omega(h_ij) / pi. A pair not listed is 0.
 * The values are SphericalCover::FormFactors' bit for bit (summed in the same order).
 */
struct SurfaceFormFactors
{
  int SurfaceCount = 0;
  /// Row a's pairs are [RowOffsets[a], RowOffsets[a + 1]): SurfaceCount + 1 offsets.
  std::vector<std::uint64_t> RowOffsets{ 0 };
  /// Per pair the surface seen, ascending within a row.
  std::vector<std::int32_t> Seen;
  /// Per pair F from the row's surface to the one seen.
  std::vector<double> Values;

  std::size_t PairCount() const { return this->Values.size(); }
  /// F from surface `from` to surface `to`: 0 when `from` does not see `to` (a binary search of
  /// the row). Throws std::out_of_range for a surface that is not one of SurfaceCount.
  double At(int from, int to) const;
  /// Bytes of the arrays.
  std::size_t MemoryBytes() const;
  /// Bytes per pair (the surface seen and F) and per surface (its row offset).
  static constexpr std::size_t BytesPerPair = sizeof(std::int32_t) + sizeof(double);
  static constexpr std::size_t BytesPerSurface = sizeof(std::uint64_t);
};

/**
 * The form factors of SphericalCover::FormFactorsOf, sparse: from every receiver's sums
 * (`rowSums`, one per patch, as SphericalCover::FormFactorSums gives them), group and area.
 * Summed per group in receiver order, as FormFactorsOf does, so that every value is its
 * matrix's bit for bit; a pair is listed when some receiver of a has a sum for b. Throws
 * std::invalid_argument as FormFactorsOf (sizes that differ from groupOfPatch's, a group out of
 * range).
 */
SurfaceFormFactors SumSurfaceFormFactors(
  const std::vector<std::vector<SphericalCover::GroupSum>>& rowSums,
  const std::vector<int>& groupOfPatch,
  int groupCount,
  const std::vector<double>& areas);

/// The sparse form factors between the groups of the cover's patches (SphericalCover::
/// FormFactors' values, without the dense matrix). Throws std::invalid_argument as it.
SurfaceFormFactors SurfaceFormFactorsOf(const SphericalCover& cover,
  const std::vector<int>& groupOfPatch,
  int groupCount);

/**
 * An upper bound of the bytes the figures of a cover of `patches` points and `entries` regions
 * between `surfaces` named surfaces take while they are summed and stored: per point its row of
 * sums (SphericalCover::FormFactorSums: at most one GroupSum per region) and its illumination,
 * per pair that sees each other (at most the entries, at most surfaces^2) the sparse factors and
 * their field arrays, per surface its figures, its field arrays and the summing scratch; the
 * vectors grown by push_back at twice their size (their slack). From sizes alone: a
 * caller refuses before summing (vtkLightPropagationFilter's MemoryLimit, with the propagation's
 * LightPropagation::EstimateBytes).
 */
std::size_t FiguresBoundBytes(std::size_t patches, std::size_t entries, std::size_t surfaces);

/// One named surface of the solution.
struct SurfaceFigures
{
  double Area = 0.0;
  glm::dvec3 MeanIrradiance{ 0.0 };
  glm::dvec3 MeanExitantRadiance{ 0.0 };
};

/// The characteristic points' illumination and the power balance it is summed up from.
struct PointIllumination
{
  /// Per point: its named surface, in [0, SurfaceCount).
  std::vector<int> SurfaceOfPoint;
  int SurfaceCount = 0;
  std::vector<double> Area;
  std::vector<glm::dvec3> Irradiance;
  std::vector<glm::dvec3> ExitantRadiance;
  glm::dvec3 Emitted{ 0.0 };
  glm::dvec3 Absorbed{ 0.0 };
};

struct SolutionFigures
{
  std::vector<SurfaceFigures> Surfaces;
  /// Between the Surfaces.size() surfaces, the pairs that see each other.
  SurfaceFormFactors FormFactors;
  glm::dvec3 Emitted{ 0.0 };
  glm::dvec3 Absorbed{ 0.0 };
  /// max over the bands that emit of |Emitted - Absorbed| / Emitted.
  double RelativeImbalance = 0.0;
  std::size_t CharacteristicPoints = 0;
  std::size_t Strips = 0;
};

/// What the figures take from the cover (the form factors between the named surfaces and the
/// counts), computed apart so that a caller can let the cover go before it solves.
struct CoverFigures
{
  SurfaceFormFactors FormFactors;
  std::size_t CharacteristicPoints = 0;
  std::size_t Strips = 0;
};
/// The cover's part of the figures, for the points' surfaces (`illumination`'s SurfaceOfPoint
/// and SurfaceCount; the other vectors are not read). Throws std::invalid_argument when the
/// cover has not one point per surface index or a point's surface is out of range.
CoverFigures ComputeCoverFigures(const SphericalCover& cover,
  const PointIllumination& illumination);
/// The figures of an equilibrium from the cover's part. Throws std::invalid_argument as below.
SolutionFigures ComputeSolutionFigures(const CoverFigures& cover,
  const PointIllumination& illumination);
/// max over the bands that emit of |emitted - absorbed| / emitted (0 if none emits).
double RelativeImbalance(const glm::dvec3& emitted, const glm::dvec3& absorbed);

/// The figures of an equilibrium. Throws std::invalid_argument when the per-point vectors do
/// not all have one value per point of the cover or a point's surface is out of range.
SolutionFigures ComputeSolutionFigures(const SphericalCover& cover,
  const PointIllumination& illumination);
}

#endif
