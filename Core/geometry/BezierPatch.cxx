// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/BezierPatch.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphcover
{

namespace
{

/// |N| below this fraction of Size()^2 counts as zero for Normal(). N has units of area; a
/// patch of any sensible shape has |N| of order Size()^2 away from degenerate points, while
/// rounding in N is of order 1e-16 Size()^2.
constexpr double DegenerateNormalFraction = 1e-12;

void CheckParameter(double t, const char* what)
{
  if (!(t > 0.0 && t < 1.0))
  {
    throw std::invalid_argument(
      std::string("BezierPatch: ") + what + " must be in (0, 1), got " + std::to_string(t));
  }
}

} // namespace

double LargestCoordinate(const std::vector<glm::dvec3>& points)
{
  double largest = 0.0;
  for (const glm::dvec3& p : points)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double magnitude = std::fabs(p[k]);
      if (std::isnan(magnitude))
      {
        return magnitude;
      }
      largest = std::max(largest, magnitude);
    }
  }
  return largest;
}

BezierPatch::BezierPatch(int degreeU, int degreeV, std::vector<glm::dvec3> controlPoints)
  : DegreeUValue(degreeU)
  , DegreeVValue(degreeV)
  , Points(std::move(controlPoints))
{
  if (degreeU < 1 || degreeU > MaxDegree || degreeV < 1 || degreeV > MaxDegree)
  {
    throw std::invalid_argument("BezierPatch: degrees must be in [1, " + std::to_string(MaxDegree) +
      "], got (" + std::to_string(degreeU) + ", " + std::to_string(degreeV) + ")");
  }
  const int m = degreeU;
  const int n = degreeV;
  const size_t expected = static_cast<size_t>((m + 1) * (n + 1));
  if (this->Points.size() != expected)
  {
    throw std::invalid_argument("BezierPatch: a degree (" + std::to_string(m) + ", " +
      std::to_string(n) + ") patch needs " + std::to_string(expected) + " control points, got " +
      std::to_string(this->Points.size()));
  }
  glm::dvec3 lower = this->Points[0];
  glm::dvec3 upper = this->Points[0];
  for (size_t k = 0; k < this->Points.size(); ++k)
  {
    const glm::dvec3& p = this->Points[k];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
    {
      throw std::invalid_argument(
        "BezierPatch: control point " + std::to_string(k) + " has a non-finite coordinate");
    }
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  this->ControlNetBounds = IntervalVec3(
    Interval(lower.x, upper.x), Interval(lower.y, upper.y), Interval(lower.z, upper.z));
  this->BoundsDiagonal = glm::length(upper - lower);

  // Hodographs: dQ/du = sum B_i^{m-1}(u) B_j^n(v) m (P_{i+1,j} - P_ij), and likewise in v.
  this->NetU.resize(static_cast<size_t>(m * (n + 1)));
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i < m; ++i)
    {
      this->NetU[static_cast<size_t>(j * m + i)] =
        static_cast<double>(m) * (this->ControlPoint(i + 1, j) - this->ControlPoint(i, j));
    }
  }
  this->NetV.resize(static_cast<size_t>((m + 1) * n));
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      this->NetV[static_cast<size_t>(j * (m + 1) + i)] =
        static_cast<double>(n) * (this->ControlPoint(i, j + 1) - this->ControlPoint(i, j));
    }
  }

  // Vector area of the net: each quad's diagonal cross product is twice its vector area
  // (exact for planar quads), oriented like Qu x Qv.
  glm::dvec3 area(0.0);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < m; ++i)
    {
      area += glm::cross(this->ControlPoint(i + 1, j + 1) - this->ControlPoint(i, j),
        this->ControlPoint(i, j + 1) - this->ControlPoint(i + 1, j));
    }
  }
  const double areaLength = glm::length(area);
  if (areaLength > DegenerateNormalFraction * this->BoundsDiagonal * this->BoundsDiagonal)
  {
    this->NetNormal = area / areaLength;
  }
}

const glm::dvec3& BezierPatch::ControlPoint(int i, int j) const
{
  assert(i >= 0 && i <= this->DegreeUValue && j >= 0 && j <= this->DegreeVValue);
  return this->Points[static_cast<size_t>(j * (this->DegreeUValue + 1) + i)];
}

glm::dvec3 BezierPatch::Evaluate(double u, double v) const
{
  return EvaluateNet(this->Points.data(), this->DegreeUValue, this->DegreeVValue, u, v);
}

glm::dvec3 BezierPatch::PartialU(double u, double v) const
{
  return EvaluateNet(this->NetU.data(), this->DegreeUValue - 1, this->DegreeVValue, u, v);
}

glm::dvec3 BezierPatch::PartialV(double u, double v) const
{
  return EvaluateNet(this->NetV.data(), this->DegreeUValue, this->DegreeVValue - 1, u, v);
}

void BezierPatch::EvaluateWithPartials(double u,
  double v,
  glm::dvec3& position,
  glm::dvec3& partialU,
  glm::dvec3& partialV) const
{
  // The partials come from the hodographs rather than from differences of the last de
  // Casteljau level: along a collapsed edge the hodograph row is exactly zero, so dQ/du next
  // to the edge keeps full relative accuracy instead of cancelling.
  position = this->Evaluate(u, v);
  partialU = this->PartialU(u, v);
  partialV = this->PartialV(u, v);
}

glm::dvec3 BezierPatch::UnnormalizedNormal(double u, double v) const
{
  return glm::cross(this->PartialU(u, v), this->PartialV(u, v));
}

glm::dvec3 BezierPatch::Normal(double u, double v) const
{
  const double threshold = DegenerateNormalFraction * this->BoundsDiagonal * this->BoundsDiagonal;
  const glm::dvec3 n = this->UnnormalizedNormal(u, v);
  const double length = glm::length(n);
  if (length > threshold)
  {
    return n / length;
  }
  return this->DegenerateNormal(u, v, threshold);
}

void BezierPatch::SecondPartials(double u,
  double v,
  glm::dvec3& uu,
  glm::dvec3& uv,
  glm::dvec3& vv) const
{
  // Second derivative nets are differences of the hodographs; built on the stack since this
  // runs only at degenerate points.
  const int m = this->DegreeUValue;
  const int n = this->DegreeVValue;
  glm::dvec3 net[(MaxDegree + 1) * (MaxDegree + 1)];
  uu = glm::dvec3(0.0);
  if (m >= 2)
  {
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i < m - 1; ++i)
      {
        net[j * (m - 1) + i] = static_cast<double>(m - 1) *
          (this->NetU[static_cast<size_t>(j * m + i + 1)] -
            this->NetU[static_cast<size_t>(j * m + i)]);
      }
    }
    uu = EvaluateNet(net, m - 2, n, u, v);
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < m; ++i)
    {
      net[j * m + i] = static_cast<double>(n) *
        (this->NetU[static_cast<size_t>((j + 1) * m + i)] -
          this->NetU[static_cast<size_t>(j * m + i)]);
    }
  }
  uv = EvaluateNet(net, m - 1, n - 1, u, v);
  vv = glm::dvec3(0.0);
  if (n >= 2)
  {
    for (int j = 0; j < n - 1; ++j)
    {
      for (int i = 0; i <= m; ++i)
      {
        net[j * (m + 1) + i] = static_cast<double>(n - 1) *
          (this->NetV[static_cast<size_t>((j + 1) * (m + 1) + i)] -
            this->NetV[static_cast<size_t>(j * (m + 1) + i)]);
      }
    }
    vv = EvaluateNet(net, m, n - 2, u, v);
  }
}

glm::dvec3 BezierPatch::DegenerateNormal(double u, double v, double threshold) const
{
  const double du = 0.5 - u;
  const double dv = 0.5 - v;
  // At the centre itself there is no direction of approach; the nudges below would not move.
  if (std::fabs(du) + std::fabs(dv) > 1e-9)
  {
    const glm::dvec3 qu = this->PartialU(u, v);
    const glm::dvec3 qv = this->PartialV(u, v);
    glm::dvec3 quu;
    glm::dvec3 quv;
    glm::dvec3 qvv;
    this->SecondPartials(u, v, quu, quv, qvv);
    // Directional derivative of N = Qu x Qv along d = (du, dv).
    const glm::dvec3 derivative = du * (glm::cross(quu, qv) + glm::cross(qu, quv)) +
      dv * (glm::cross(quv, qv) + glm::cross(qu, qvv));
    const double length = glm::length(derivative);
    if (length > threshold)
    {
      return derivative / length;
    }
    for (const double fraction : { 1e-6, 1e-4, 1e-2, 0.1, 0.5 })
    {
      const glm::dvec3 n = this->UnnormalizedNormal(u + fraction * du, v + fraction * dv);
      const double nudgedLength = glm::length(n);
      if (nudgedLength > threshold)
      {
        return n / nudgedLength;
      }
    }
  }
  if (this->NetNormal != glm::dvec3(0.0))
  {
    return this->NetNormal;
  }
  // A patch without area (all control points on a line) has no normal at all; any fixed unit
  // vector keeps callers free of NaN.
  return { 0.0, 0.0, 1.0 };
}

std::pair<BezierPatch, BezierPatch> BezierPatch::SplitU(double t) const
{
  CheckParameter(t, "SplitU parameter");
  const int m = this->DegreeUValue;
  std::vector<glm::dvec3> left = this->Points;
  std::vector<glm::dvec3> right = this->Points;
  for (int j = 0; j <= this->DegreeVValue; ++j)
  {
    DeCasteljauKeepLeft(left.data() + j * (m + 1), 1, m, t);
    DeCasteljauKeepRight(right.data() + j * (m + 1), 1, m, t);
  }
  return { BezierPatch(m, this->DegreeVValue, std::move(left)),
    BezierPatch(m, this->DegreeVValue, std::move(right)) };
}

std::pair<BezierPatch, BezierPatch> BezierPatch::SplitV(double t) const
{
  CheckParameter(t, "SplitV parameter");
  const int m = this->DegreeUValue;
  const int n = this->DegreeVValue;
  std::vector<glm::dvec3> left = this->Points;
  std::vector<glm::dvec3> right = this->Points;
  for (int i = 0; i <= m; ++i)
  {
    DeCasteljauKeepLeft(left.data() + i, m + 1, n, t);
    DeCasteljauKeepRight(right.data() + i, m + 1, n, t);
  }
  return { BezierPatch(m, n, std::move(left)), BezierPatch(m, n, std::move(right)) };
}

BezierPatch BezierPatch::SubPatch(double u0, double u1, double v0, double v1) const
{
  if (!(0.0 <= u0 && u0 < u1 && u1 <= 1.0 && 0.0 <= v0 && v0 < v1 && v1 <= 1.0))
  {
    throw std::invalid_argument("BezierPatch: SubPatch needs 0 <= u0 < u1 <= 1 and "
                                "0 <= v0 < v1 <= 1, got [" +
      std::to_string(u0) + ", " + std::to_string(u1) + "] x [" + std::to_string(v0) + ", " +
      std::to_string(v1) + "]");
  }
  std::vector<glm::dvec3> points = this->Points;
  RestrictNet(points.data(), this->DegreeUValue, this->DegreeVValue, { u0, u1, v0, v1 });
  return BezierPatch(this->DegreeUValue, this->DegreeVValue, std::move(points));
}

BezierPatch BezierPatch::SubPatch(const UVRect& rect) const
{
  return this->SubPatch(rect.U0, rect.U1, rect.V0, rect.V1);
}

bool NearlyPlanar(const std::vector<glm::dvec3>& points, const glm::dvec3& normal, double size)
{
  if (!(glm::length(normal) > 0.0) || points.empty())
  {
    return false;
  }
  glm::dvec3 centroid(0.0);
  for (const glm::dvec3& point : points)
  {
    centroid += point;
  }
  centroid /= static_cast<double>(points.size());
  const glm::dvec3 unit = glm::normalize(normal);
  bool planar = true;
  for (const glm::dvec3& point : points)
  {
    planar = planar && std::fabs(glm::dot(point - centroid, unit)) <= NearlyPlanarFraction * size;
  }
  return planar;
}

} // namespace sphcover
