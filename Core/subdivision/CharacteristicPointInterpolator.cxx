// SPDX-License-Identifier: BSD-3-Clause
#include "subdivision/CharacteristicPointInterpolator.h"

#include "subdivision/Patch.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphcover
{

namespace
{
/// How far beyond a patch's edge its neighbour is probed: far below the width of any patch
/// the subdivision makes (3^-20 ~ 3e-10 at a depth no stage reaches).
constexpr double ProbeOffset = 1e-11;

bool Inside(const UVRect& r, double u, double v)
{
  return r.U0 <= u && u <= r.U1 && r.V0 <= v && v <= r.V1;
}

double DistanceSquared(const UVRect& r, double u, double v)
{
  const double du = u < r.U0 ? r.U0 - u : (u > r.U1 ? u - r.U1 : 0.0);
  const double dv = v < r.V0 ? r.V0 - v : (v > r.V1 ? v - r.V1 : 0.0);
  return du * du + dv * dv;
}

double Cross(const glm::dvec2& a, const glm::dvec2& b)
{
  return a.x * b.y - a.y * b.x;
}

/// Weights of the bilinear map of the quadrilateral q0 q1 q2 q3 (q0 = (0,0), q1 = (1,0), q2 =
/// (1,1), q3 = (0,1) in (s, t)) inverted at x, by Newton's method; false where the
/// quadrilateral is not strictly convex (the map is then not invertible everywhere).
bool InverseBilinear(const std::array<glm::dvec2, 4>& q, const glm::dvec2& x, double weights[4])
{
  // Strict convexity: the four corner cross products share their sign and are not tiny
  // relative to the quadrilateral's size.
  const double scale = glm::length(q[2] - q[0]) * glm::length(q[3] - q[1]);
  if (!(scale > 0.0))
  {
    return false;
  }
  double sign = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    const double c = Cross(q[(k + 1) % 4] - q[k], q[(k + 3) % 4] - q[k]);
    if (std::fabs(c) < 1e-6 * scale || (sign != 0.0 && c * sign < 0.0))
    {
      return false;
    }
    sign = c;
  }
  double s = 0.5;
  double t = 0.5;
  for (int iteration = 0; iteration < 30; ++iteration)
  {
    const glm::dvec2 p =
      (1 - s) * (1 - t) * q[0] + s * (1 - t) * q[1] + s * t * q[2] + (1 - s) * t * q[3] - x;
    const glm::dvec2 ds = (1 - t) * (q[1] - q[0]) + t * (q[2] - q[3]);
    const glm::dvec2 dt = (1 - s) * (q[3] - q[0]) + s * (q[2] - q[1]);
    const double det = Cross(ds, dt);
    if (!(std::fabs(det) > 0.0))
    {
      return false;
    }
    const double stepS = Cross(p, dt) / det;
    const double stepT = Cross(ds, p) / det;
    s -= stepS;
    t -= stepT;
    if (std::fabs(stepS) + std::fabs(stepT) < 1e-15)
    {
      break;
    }
  }
  // Far outside a skewed quadrilateral (extrapolation) the map can fold over: accept only a
  // converged inverse.
  const glm::dvec2 residual =
    (1 - s) * (1 - t) * q[0] + s * (1 - t) * q[1] + s * t * q[2] + (1 - s) * t * q[3] - x;
  if (!std::isfinite(s) || !std::isfinite(t) ||
    !(glm::length(residual) <= 1e-12 * std::sqrt(scale)))
  {
    return false;
  }
  weights[0] = (1 - s) * (1 - t);
  weights[1] = s * (1 - t);
  weights[2] = s * t;
  weights[3] = (1 - s) * t;
  return true;
}

/// Weights of the least-squares plane f = a + b u + c v through the points (3 or 4) at x; false
/// where they are (nearly) collinear.
bool PlaneWeights(const glm::dvec2* q, int count, const glm::dvec2& x, double* weights)
{
  // Centred coordinates keep the normal equations well conditioned.
  glm::dvec2 mean(0.0);
  for (int k = 0; k < count; ++k)
  {
    mean += q[k];
  }
  mean /= count;
  glm::dmat3 normal(0.0);
  double extent = 0.0;
  for (int k = 0; k < count; ++k)
  {
    const glm::dvec3 row(1.0, q[k].x - mean.x, q[k].y - mean.y);
    normal += glm::outerProduct(row, row);
    extent = std::max(extent, glm::dot(q[k] - mean, q[k] - mean));
  }
  const double det = glm::determinant(normal);
  // det scales as count * extent^2 for well-spread points; collinear points give 0.
  if (!(std::fabs(det) > 1e-9 * count * extent * extent))
  {
    return false;
  }
  const glm::dvec3 coefficients =
    glm::inverse(normal) * glm::dvec3(1.0, x.x - mean.x, x.y - mean.y);
  for (int k = 0; k < count; ++k)
  {
    weights[k] = glm::dot(glm::dvec3(1.0, q[k].x - mean.x, q[k].y - mean.y), coefficients);
  }
  return true;
}

/// Step 2 of the file comment: the parameter just beyond the side of the quadrant of x
/// (x >= centre: the high side), or the other side at the surface's edge (extrapolation,
/// paper §3.4 Fig. 6); false when neither lies in [0, 1].
bool ProbeBeyondEdge(double low, double high, double centre, double x, double& at)
{
  const double side = x >= centre ? 1.0 : -1.0;
  for (const double s : { side, -side })
  {
    const double candidate = s > 0 ? high + ProbeOffset : low - ProbeOffset;
    if (candidate >= 0.0 && candidate <= 1.0)
    {
      at = candidate;
      return true;
    }
  }
  return false;
}

/// The distinct points among `corners` (-1: none), in quadrilateral order, into the stencil's
/// points and their domain centres into q; returns how many.
int DistinctPoints(const std::vector<UVRect>& domains,
  const std::array<std::ptrdiff_t, 4>& corners,
  InterpolationStencil& stencil,
  std::array<glm::dvec2, 4>& q)
{
  int count = 0;
  for (const std::ptrdiff_t corner : corners)
  {
    if (corner < 0)
    {
      continue;
    }
    bool seen = false;
    for (int k = 0; k < count; ++k)
    {
      seen = seen || stencil.Points[static_cast<size_t>(k)] == static_cast<size_t>(corner);
    }
    if (!seen)
    {
      const UVRect& d = domains[static_cast<size_t>(corner)];
      stencil.Points[static_cast<size_t>(count)] = static_cast<size_t>(corner);
      q[static_cast<size_t>(count)] = glm::dvec2(d.CenterU(), d.CenterV());
      ++count;
    }
  }
  return count;
}

/// A patch spanning the surface in one direction has no neighbour across it: the points
/// found are collinear and say nothing about the other direction. Keeps the first two of the
/// `count` points and completes them with the surface's centres nearest to P's (cu, cv) until
/// three are not collinear; returns the new count.
int CompleteWithNearestPoints(const std::vector<UVRect>& domains,
  const std::vector<bool>& excluded,
  const std::vector<std::size_t>& surfacePoints,
  double cu,
  double cv,
  int count,
  InterpolationStencil& stencil,
  std::array<glm::dvec2, 4>& q)
{
  std::vector<std::pair<double, size_t>> byDistance;
  for (size_t k : surfacePoints)
  {
    if (!excluded.empty() && excluded[k])
    {
      continue;
    }
    const UVRect& d = domains[k];
    const double du = d.CenterU() - cu;
    const double dv = d.CenterV() - cv;
    byDistance.emplace_back(du * du + dv * dv, k);
  }
  std::sort(byDistance.begin(), byDistance.end());
  count = std::min(count, 2);
  for (const auto& [distance, k] : byDistance)
  {
    if (count == 3)
    {
      break;
    }
    bool seen = false;
    for (int m = 0; m < count; ++m)
    {
      seen = seen || stencil.Points[static_cast<size_t>(m)] == k;
    }
    const UVRect& d = domains[k];
    const glm::dvec2 c(d.CenterU(), d.CenterV());
    const bool collinear = count == 2 &&
      std::fabs(Cross(q[1] - q[0], c - q[0])) <=
        1e-9 * glm::length(q[1] - q[0]) * glm::length(c - q[0]);
    if (!seen && !collinear)
    {
      stencil.Points[static_cast<size_t>(count)] = k;
      q[static_cast<size_t>(count)] = c;
      ++count;
    }
  }
  return count;
}

/// Collinear points (count >= 2): linear along the line from c to the farthest of the others.
void LinearWeights(const std::array<glm::dvec2, 4>& q,
  int count,
  const glm::dvec2& x,
  InterpolationStencil& stencil)
{
  int far = 1;
  for (int k = 2; k < count; ++k)
  {
    if (glm::dot(q[static_cast<size_t>(k)] - q[0], q[static_cast<size_t>(k)] - q[0]) >
      glm::dot(q[static_cast<size_t>(far)] - q[0], q[static_cast<size_t>(far)] - q[0]))
    {
      far = k;
    }
  }
  const glm::dvec2 axis = q[static_cast<size_t>(far)] - q[0];
  const double t = glm::dot(x - q[0], axis) / glm::dot(axis, axis);
  stencil.Points[1] = stencil.Points[static_cast<size_t>(far)];
  stencil.Weights = { { 1.0 - t, t, 0.0, 0.0 } };
  stencil.Count = 2;
}
}

CharacteristicPointInterpolator CharacteristicPointInterpolator::OfPatches(
  const std::vector<Patch>& patches)
{
  std::vector<int> surfaces;
  std::vector<UVRect> domains;
  surfaces.reserve(patches.size());
  domains.reserve(patches.size());
  for (const Patch& patch : patches)
  {
    surfaces.push_back(patch.SurfaceIndex);
    domains.push_back(patch.Domain);
  }
  return CharacteristicPointInterpolator(surfaces, domains);
}

CharacteristicPointInterpolator::CharacteristicPointInterpolator(
  const std::vector<int>& surfaceOfPoint,
  const std::vector<UVRect>& domainOfPoint)
  : Domains(domainOfPoint)
  , PointSurfaces(surfaceOfPoint)
{
  if (surfaceOfPoint.size() != domainOfPoint.size())
  {
    throw std::invalid_argument(
      "CharacteristicPointInterpolator: " + std::to_string(surfaceOfPoint.size()) +
      " surface indices for " + std::to_string(domainOfPoint.size()) + " rectangles");
  }
  int surfaces = 0;
  for (size_t p = 0; p < surfaceOfPoint.size(); ++p)
  {
    const UVRect& r = domainOfPoint[p];
    if (surfaceOfPoint[p] < 0 || !r.IsValid() || !(r.U1 > r.U0) || !(r.V1 > r.V0))
    {
      throw std::invalid_argument("CharacteristicPointInterpolator: point " + std::to_string(p) +
        " has a negative surface or an invalid or empty rectangle");
    }
    surfaces = std::max(surfaces, surfaceOfPoint[p] + 1);
  }
  std::vector<std::vector<size_t>> pointsOfSurface(static_cast<size_t>(surfaces));
  for (size_t p = 0; p < surfaceOfPoint.size(); ++p)
  {
    pointsOfSurface[static_cast<size_t>(surfaceOfPoint[p])].push_back(p);
  }
  this->Surfaces.resize(static_cast<size_t>(surfaces));
  for (size_t s = 0; s < pointsOfSurface.size(); ++s)
  {
    const std::vector<size_t>& points = pointsOfSurface[s];
    SurfaceLayout& layout = this->Surfaces[s];
    if (points.empty())
    {
      continue;
    }
    layout.Points = points;
    // About one patch per bucket on a uniform layout (at least 1, at most 243 = 3^5 buckets
    // per side).
    const int side = std::clamp(
      static_cast<int>(std::ceil(std::sqrt(static_cast<double>(points.size())))), 1, 243);
    layout.BucketsU = side;
    layout.BucketsV = side;
    auto range = [side](double a, double b, int& first, int& last)
    {
      first = std::clamp(static_cast<int>(std::floor(a * side)), 0, side - 1);
      last = std::clamp(static_cast<int>(std::ceil(b * side)) - 1, first, side - 1);
    };
    std::vector<std::vector<size_t>> buckets(static_cast<size_t>(side * side));
    for (size_t p : points)
    {
      const UVRect& r = this->Domains[p];
      int u0;
      int u1;
      int v0;
      int v1;
      range(r.U0, r.U1, u0, u1);
      range(r.V0, r.V1, v0, v1);
      for (int j = v0; j <= v1; ++j)
      {
        for (int i = u0; i <= u1; ++i)
        {
          buckets[static_cast<size_t>(j * side + i)].push_back(p);
        }
      }
    }
    layout.BucketOffsets.push_back(0);
    for (const std::vector<size_t>& bucket : buckets)
    {
      layout.BucketPoints.insert(layout.BucketPoints.end(), bucket.begin(), bucket.end());
      layout.BucketOffsets.push_back(layout.BucketPoints.size());
    }
  }
}

void CharacteristicPointInterpolator::SetExcludedPoints(std::vector<bool> excluded)
{
  if (!excluded.empty() && excluded.size() != this->Domains.size())
  {
    throw std::invalid_argument(
      "CharacteristicPointInterpolator: " + std::to_string(excluded.size()) +
      " exclusion flags for " + std::to_string(this->Domains.size()) + " points");
  }
  this->Excluded = std::move(excluded);
}

std::ptrdiff_t CharacteristicPointInterpolator::NearestKept(const SurfaceLayout& layout,
  double u,
  double v) const
{
  std::ptrdiff_t nearest = -1;
  double nearestDistance = std::numeric_limits<double>::infinity();
  for (size_t p : layout.Points)
  {
    const double d = DistanceSquared(this->Domains[p], u, v);
    if (!this->IsExcluded(p) && d < nearestDistance)
    {
      nearestDistance = d;
      nearest = static_cast<std::ptrdiff_t>(p);
    }
  }
  return nearest;
}

bool CharacteristicPointInterpolator::HasPoints(int surface) const
{
  return surface >= 0 && static_cast<size_t>(surface) < this->Surfaces.size() &&
    !this->Surfaces[static_cast<size_t>(surface)].Points.empty();
}

std::ptrdiff_t CharacteristicPointInterpolator::Locate(const SurfaceLayout& layout,
  double u,
  double v) const
{
  if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0))
  {
    return -1;
  }
  const int i = std::min(static_cast<int>(u * layout.BucketsU), layout.BucketsU - 1);
  const int j = std::min(static_cast<int>(v * layout.BucketsV), layout.BucketsV - 1);
  const size_t bucket = static_cast<size_t>(j * layout.BucketsU + i);
  std::ptrdiff_t nearest = -1;
  double nearestDistance = std::numeric_limits<double>::infinity();
  for (size_t k = layout.BucketOffsets[bucket]; k < layout.BucketOffsets[bucket + 1]; ++k)
  {
    const size_t p = layout.BucketPoints[k];
    const UVRect& r = this->Domains[p];
    if (Inside(r, u, v))
    {
      return static_cast<std::ptrdiff_t>(p);
    }
    const double d = DistanceSquared(r, u, v);
    if (d < nearestDistance)
    {
      nearestDistance = d;
      nearest = static_cast<std::ptrdiff_t>(p);
    }
  }
  if (nearest < 0)
  {
    // A bucket no patch overlaps (the patches do not tile the surface): the nearest of all.
    for (size_t p : layout.Points)
    {
      const double d = DistanceSquared(this->Domains[p], u, v);
      if (d < nearestDistance)
      {
        nearestDistance = d;
        nearest = static_cast<std::ptrdiff_t>(p);
      }
    }
  }
  return nearest;
}

std::ptrdiff_t CharacteristicPointInterpolator::ContainingPoint(int surface,
  double u,
  double v) const
{
  if (!this->HasPoints(surface))
  {
    return -1;
  }
  return this->Locate(
    this->Surfaces[static_cast<size_t>(surface)], std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0));
}

std::array<std::ptrdiff_t, 4> CharacteristicPointInterpolator::QuadrantCorners(
  const SurfaceLayout& layout,
  std::ptrdiff_t found,
  double u,
  double v) const
{
  const UVRect& r = this->Domains[static_cast<size_t>(found)];
  const double cu = r.CenterU();
  const double cv = r.CenterV();
  double probeU = 0.0;
  double probeV = 0.0;
  const bool hasU = ProbeBeyondEdge(r.U0, r.U1, cu, u, probeU);
  const bool hasV = ProbeBeyondEdge(r.V0, r.V1, cv, v, probeV);
  std::array<std::ptrdiff_t, 4> corners = { { found, -1, -1, -1 } };
  if (hasU)
  {
    corners[1] = this->Locate(layout, probeU, cv);
  }
  if (hasU && hasV)
  {
    corners[2] = this->Locate(layout, probeU, probeV);
  }
  if (hasV)
  {
    corners[3] = this->Locate(layout, cu, probeV);
  }
  return corners;
}

bool CharacteristicPointInterpolator::Stencil(int surface,
  double u,
  double v,
  InterpolationStencil& stencil) const
{
  stencil = InterpolationStencil();
  std::ptrdiff_t found = this->ContainingPoint(surface, u, v);
  if (found < 0)
  {
    return false;
  }
  const SurfaceLayout& layout = this->Surfaces[static_cast<size_t>(surface)];
  if (this->IsExcluded(static_cast<size_t>(found)))
  {
    const std::ptrdiff_t kept =
      this->NearestKept(layout, std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0));
    found = kept >= 0 ? kept : found;
  }
  const UVRect& r = this->Domains[static_cast<size_t>(found)];

  // Step 2 of the file comment: c, X, D, Y, then the distinct points in that order; excluded
  // neighbours count as none.
  std::array<std::ptrdiff_t, 4> corners = this->QuadrantCorners(layout, found, u, v);
  for (size_t k = 1; k < corners.size(); ++k)
  {
    if (corners[k] >= 0 && this->IsExcluded(static_cast<size_t>(corners[k])))
    {
      corners[k] = -1;
    }
  }
  std::array<glm::dvec2, 4> q;
  int count = DistinctPoints(this->Domains, corners, stencil, q);
  stencil.Count = count;
  const glm::dvec2 x(u, v);
  double* weights = stencil.Weights.data();
  if (count == 4 && InverseBilinear(q, x, weights))
  {
    return true;
  }
  if (count >= 3 && PlaneWeights(q.data(), count, x, weights))
  {
    return true;
  }
  if (count < 3 || !PlaneWeights(q.data(), std::min(count, 3), x, weights))
  {
    count = CompleteWithNearestPoints(
      this->Domains, this->Excluded, layout.Points, r.CenterU(), r.CenterV(), count, stencil, q);
    stencil.Count = count;
  }
  if (count == 3 && PlaneWeights(q.data(), count, x, weights))
  {
    return true;
  }
  if (count >= 2)
  {
    LinearWeights(q, count, x, stencil);
    return true;
  }
  stencil.Weights = { { 1.0, 0.0, 0.0, 0.0 } };
  stencil.Count = 1;
  return true;
}

} // namespace sphcover
