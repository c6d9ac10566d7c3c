// SPDX-License-Identifier: BSD-3-Clause
#include "cover/CandidateCulling.h"

#include "geometry/BernsteinBounds.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>

namespace sphcover
{

CullingStatistics& CullingStatistics::operator+=(const CullingStatistics& other)
{
  this->Candidates += other.Candidates;
  this->BelowTangentPlane += other.BelowTangentPlane;
  this->BackFacing += other.BackFacing;
  this->Kept += other.Kept;
  this->Pieces += other.Pieces;
  this->Occluders += other.Occluders;
  return *this;
}

CandidateClass ClassifyCandidate(const BezierPatch& source,
  const UVRect& rect,
  const glm::dvec3& point,
  const glm::dvec3& normal)
{
  // Scales: the farthest control point bounds |Q - P| (convex hull); |N_j| <= |Qu| |Qv| <=
  // (m Size) (n Size). Only the rounding allowance of the bounds must fall under the tolerance.
  double farthest = 0.0;
  double highest = -std::numeric_limits<double>::infinity();
  for (const glm::dvec3& p : source.ControlPoints())
  {
    farthest = std::max(farthest, glm::length(p - point));
    highest = std::max(highest, glm::dot(normal, p - point));
  }
  constexpr double relative = 1e-9;
  // The whole control net on or below the plane: so is the patch (convex hull), and every
  // sub-rectangle of it. Cheap, and it settles the receiver's coplanar neighbours.
  if (highest <= relative * farthest)
  {
    return CandidateClass::BelowTangentPlane;
  }
  const Interval height = RangeOfHeightAbovePlane(source, rect, point, normal);
  if (height.Upper() <= relative * farthest)
  {
    return CandidateClass::BelowTangentPlane;
  }
  const double size = source.Size();
  const double facingScale = farthest * size * size * source.DegreeU() * source.DegreeV();
  const Interval facing = RangeOfFacing(source, rect, point);
  if (facing.Lower() >= -relative * facingScale)
  {
    return CandidateClass::BackFacing;
  }
  if (facing.Upper() <= relative * facingScale)
  {
    return CandidateClass::FrontFacing;
  }
  return CandidateClass::Undecided;
}

} // namespace sphcover
