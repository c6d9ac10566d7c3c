// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SolutionFigures.h
 * @brief What an equilibrium amounts to per named surface (README.md#command-line's report): each
 * surface's area, its area-weighted mean irradiance and exitant radiance, the form factors between
 * the named surfaces (paper §3.3, from the cover), the energy balance and the counts.
 *
 * Inputs: the spherical cover, per characteristic point its surface (an index of the named
 * surfaces), area, irradiance E and exitant radiance L (paper §5.1's result), and the emitted
 * and absorbed power. Outputs: one SurfaceFigures per named surface, the form-factor matrix
 * (row a: from surface a, area-weighted over it), the relative imbalance, the point and strip
 * counts. vtkLightPropagationFilter stores them in its output's field data; `sphcover` prints
 * them.
 *
 * Cost: O(points) for the means, plus SphericalCover::FormFactors (O(entries)).
 */
#ifndef SPHCOVER_SOLUTIONFIGURES_H
#define SPHCOVER_SOLUTIONFIGURES_H

#include "cover/SphericalCover.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace sphcover
{
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
  /// Surfaces.size() x Surfaces.size(), row-major: row a holds F from surface a.
  std::vector<double> FormFactors;
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
  std::vector<double> FormFactors;
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
