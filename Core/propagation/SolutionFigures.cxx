// SPDX-License-Identifier: BSD-3-Clause
#include "propagation/SolutionFigures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphcover
{
double RelativeImbalance(const glm::dvec3& emitted, const glm::dvec3& absorbed)
{
  double imbalance = 0.0;
  for (int band = 0; band < 3; ++band)
  {
    if (emitted[band] > 0.0)
    {
      imbalance = std::max(imbalance, std::fabs(emitted[band] - absorbed[band]) / emitted[band]);
    }
  }
  return imbalance;
}

namespace
{

/// std::invalid_argument unless every point has a surface in [0, SurfaceCount).
void CheckSurfaces(const PointIllumination& illumination)
{
  const int groups = illumination.SurfaceCount;
  for (std::size_t k = 0; k < illumination.SurfaceOfPoint.size(); ++k)
  {
    const int g = illumination.SurfaceOfPoint[k];
    if (g < 0 || g >= groups)
    {
      throw std::invalid_argument("solution figures: point " + std::to_string(k) + " has surface " +
        std::to_string(g) + ", not one of the " + std::to_string(groups));
    }
  }
}

} // namespace

double SurfaceFormFactors::At(int from, int to) const
{
  if (from < 0 || from >= this->SurfaceCount || to < 0 || to >= this->SurfaceCount)
  {
    throw std::out_of_range("SurfaceFormFactors::At: surfaces " + std::to_string(from) + ", " +
      std::to_string(to) + " of " + std::to_string(this->SurfaceCount));
  }
  const auto begin = this->Seen.begin() + static_cast<std::ptrdiff_t>(this->RowOffsets[from]);
  const auto end = this->Seen.begin() + static_cast<std::ptrdiff_t>(this->RowOffsets[from + 1]);
  const auto found = std::lower_bound(begin, end, to);
  return found != end && *found == to
    ? this->Values[static_cast<std::size_t>(found - this->Seen.begin())]
    : 0.0;
}

std::size_t SurfaceFormFactors::MemoryBytes() const
{
  return this->RowOffsets.size() * sizeof(std::uint64_t) +
    this->Seen.size() * sizeof(std::int32_t) + this->Values.size() * sizeof(double);
}

SurfaceFormFactors SumSurfaceFormFactors(
  const std::vector<std::vector<SphericalCover::GroupSum>>& rowSums,
  const std::vector<int>& groupOfPatch,
  int groupCount,
  const std::vector<double>& areas)
{
  if (rowSums.size() != groupOfPatch.size() || areas.size() != groupOfPatch.size() ||
    groupCount < 0)
  {
    throw std::invalid_argument("solution figures: need one group, area and row of form-factor "
                                "sums per patch (" +
      std::to_string(groupOfPatch.size()) + "), got " + std::to_string(areas.size()) +
      " areas and " + std::to_string(rowSums.size()) + " rows");
  }
  const std::size_t g = static_cast<std::size_t>(groupCount);
  // The receivers of each group, ascending (a counting sort), and the groups' areas summed in
  // receiver order: the order in which FormFactorsOf adds them.
  std::vector<std::size_t> receiversBegin(g + 1, 0);
  std::vector<double> groupArea(g, 0.0);
  for (std::size_t i = 0; i < groupOfPatch.size(); ++i)
  {
    const int a = groupOfPatch[i];
    if (a >= groupCount)
    {
      throw std::invalid_argument("solution figures: group out of range");
    }
    if (a >= 0)
    {
      ++receiversBegin[static_cast<std::size_t>(a) + 1];
      groupArea[static_cast<std::size_t>(a)] += areas[i];
    }
  }
  for (std::size_t a = 0; a < g; ++a)
  {
    receiversBegin[a + 1] += receiversBegin[a];
  }
  std::vector<std::size_t> receivers(receiversBegin[g]);
  {
    std::vector<std::size_t> next(receiversBegin.begin(), receiversBegin.end() - 1);
    for (std::size_t i = 0; i < groupOfPatch.size(); ++i)
    {
      if (groupOfPatch[i] >= 0)
      {
        receivers[next[static_cast<std::size_t>(groupOfPatch[i])]++] = i;
      }
    }
  }
  SurfaceFormFactors factors;
  factors.SurfaceCount = groupCount;
  factors.RowOffsets.assign(g + 1, 0);
  // One row at a time in a dense scratch row (O(groups), reused), the groups seen listed to
  // read it back: F_ab accumulates A_i sum_ib over the receivers i of a in ascending order,
  // from 0, as FormFactorsOf's matrix element does, so the quotient is the same double.
  std::vector<double> scratch(g, 0.0);
  std::vector<bool> seen(g, false);
  std::vector<std::int32_t> row;
  for (std::size_t a = 0; a < g; ++a)
  {
    row.clear();
    for (std::size_t k = receiversBegin[a]; k < receiversBegin[a + 1]; ++k)
    {
      const std::size_t i = receivers[k];
      for (const SphericalCover::GroupSum& sum : rowSums[i])
      {
        if (sum.Group < 0 || sum.Group >= groupCount)
        {
          throw std::invalid_argument("solution figures: group out of range");
        }
        const std::size_t b = static_cast<std::size_t>(sum.Group);
        if (!seen[b])
        {
          seen[b] = true;
          row.push_back(sum.Group);
        }
        scratch[b] += areas[i] * sum.Sum;
      }
    }
    std::sort(row.begin(), row.end());
    for (const std::int32_t b : row)
    {
      const std::size_t column = static_cast<std::size_t>(b);
      factors.Seen.push_back(b);
      factors.Values.push_back(groupArea[a] > 0.0 ? scratch[column] / groupArea[a] : 0.0);
      scratch[column] = 0.0;
      seen[column] = false;
    }
    factors.RowOffsets[a + 1] = factors.Seen.size();
  }
  return factors;
}

std::size_t FiguresBoundBytes(std::size_t patches, std::size_t entries, std::size_t surfaces)
{
  // Per point: its row's vector, the receivers' index, its area (twice: the cover's copy and
  // the illumination's), its surface, irradiance and exitant radiance (PointIllumination).
  constexpr std::size_t perPoint = sizeof(std::vector<SphericalCover::GroupSum>) +
    sizeof(std::size_t) + 2 * sizeof(double) + sizeof(int) + 2 * sizeof(glm::dvec3);
  // Per pair: the factors' surface and value (with their growth's slack, and the solution
  // figures' copy), and the field arrays' From, To and value.
  constexpr std::size_t perPair =
    3 * SurfaceFormFactors::BytesPerPair + 2 * sizeof(int) + sizeof(double);
  // Per surface: the row offset, the receivers' offsets, its area, the scratch row (a double,
  // a flag and an entry of the list seen), its figures and their field arrays (7 doubles).
  constexpr std::size_t perSurface = SurfaceFormFactors::BytesPerSurface + sizeof(std::size_t) +
    2 * sizeof(double) + 1 + sizeof(std::int32_t) + sizeof(SurfaceFigures) + 7 * sizeof(double);
  const double pairs =
    std::min(static_cast<double>(entries), static_cast<double>(surfaces) * surfaces);
  const double bytes = static_cast<double>(patches) * perPoint +
    2.0 * static_cast<double>(entries) * sizeof(SphericalCover::GroupSum) + pairs * perPair +
    static_cast<double>(surfaces) * perSurface;
  return bytes >= static_cast<double>(std::numeric_limits<std::size_t>::max())
    ? std::numeric_limits<std::size_t>::max()
    : static_cast<std::size_t>(bytes);
}

SurfaceFormFactors SurfaceFormFactorsOf(const SphericalCover& cover,
  const std::vector<int>& groupOfPatch,
  int groupCount)
{
  std::vector<double> areas(cover.PatchCount());
  for (std::size_t i = 0; i < areas.size(); ++i)
  {
    areas[i] = cover.PatchArea(i);
  }
  return SumSurfaceFormFactors(
    cover.FormFactorSums(groupOfPatch, groupCount), groupOfPatch, groupCount, areas);
}

CoverFigures ComputeCoverFigures(const SphericalCover& cover, const PointIllumination& illumination)
{
  if (cover.PatchCount() != illumination.SurfaceOfPoint.size())
  {
    throw std::invalid_argument("solution figures: " + std::to_string(cover.PatchCount()) +
      " points in the cover, but " + std::to_string(illumination.SurfaceOfPoint.size()) +
      " surfaces");
  }
  CheckSurfaces(illumination);
  CoverFigures figures;
  figures.FormFactors =
    SurfaceFormFactorsOf(cover, illumination.SurfaceOfPoint, illumination.SurfaceCount);
  figures.CharacteristicPoints = cover.PatchCount();
  figures.Strips = cover.StripCount();
  return figures;
}

SolutionFigures ComputeSolutionFigures(const SphericalCover& cover,
  const PointIllumination& illumination)
{
  return ComputeSolutionFigures(ComputeCoverFigures(cover, illumination), illumination);
}

SolutionFigures ComputeSolutionFigures(const CoverFigures& cover,
  const PointIllumination& illumination)
{
  const std::size_t points = illumination.SurfaceOfPoint.size();
  if (illumination.Area.size() != points || illumination.Irradiance.size() != points ||
    illumination.ExitantRadiance.size() != points || cover.CharacteristicPoints != points)
  {
    throw std::invalid_argument("solution figures: " + std::to_string(cover.CharacteristicPoints) +
      " points in the cover, but " + std::to_string(points) + " surfaces, " +
      std::to_string(illumination.Area.size()) + " areas, " +
      std::to_string(illumination.Irradiance.size()) + " irradiances and " +
      std::to_string(illumination.ExitantRadiance.size()) + " radiances");
  }
  CheckSurfaces(illumination);
  if (cover.FormFactors.SurfaceCount != illumination.SurfaceCount)
  {
    throw std::invalid_argument("solution figures: form factors between " +
      std::to_string(cover.FormFactors.SurfaceCount) + " surfaces, but " +
      std::to_string(illumination.SurfaceCount) + " surfaces");
  }
  const std::size_t count = static_cast<std::size_t>(std::max(0, illumination.SurfaceCount));
  SolutionFigures figures;
  figures.Surfaces.resize(count);
  for (std::size_t k = 0; k < points; ++k)
  {
    figures.Surfaces[static_cast<std::size_t>(illumination.SurfaceOfPoint[k])].Area +=
      illumination.Area[k];
  }
  // Means weighted by the points' share of their surface's area (the patches tile it).
  for (std::size_t k = 0; k < points; ++k)
  {
    SurfaceFigures& surface =
      figures.Surfaces[static_cast<std::size_t>(illumination.SurfaceOfPoint[k])];
    const double weight = illumination.Area[k] / surface.Area;
    for (int band = 0; band < 3; ++band)
    {
      surface.MeanIrradiance[band] += weight * illumination.Irradiance[k][band];
      surface.MeanExitantRadiance[band] += weight * illumination.ExitantRadiance[k][band];
    }
  }
  figures.FormFactors = cover.FormFactors;
  figures.Emitted = illumination.Emitted;
  figures.Absorbed = illumination.Absorbed;
  figures.RelativeImbalance = RelativeImbalance(illumination.Emitted, illumination.Absorbed);
  figures.CharacteristicPoints = points;
  figures.Strips = cover.Strips;
  return figures;
}
}
