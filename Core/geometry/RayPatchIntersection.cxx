// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/RayPatchIntersection.h"

#include "geometry/DeCasteljau.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sphcover
{

void EvaluatePointAndPartials(const BezierPatch& patch,
  double u,
  double v,
  glm::dvec3& position,
  glm::dvec3& partialU,
  glm::dvec3& partialV)
{
  const int m = patch.DegreeU();
  const int n = patch.DegreeV();
  const glm::dvec3* net = patch.ControlPoints().data();
  glm::dvec3 rowPoints[BezierPatch::MaxDegree + 1];
  glm::dvec3 rowDerivatives[BezierPatch::MaxDegree + 1];
  glm::dvec3 work[BezierPatch::MaxDegree + 1];
  const double su = 1.0 - u;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      work[i] = net[j * (m + 1) + i];
    }
    for (int r = m; r > 1; --r)
    {
      for (int i = 0; i < r; ++i)
      {
        work[i] = su * work[i] + u * work[i + 1];
      }
    }
    rowPoints[j] = su * work[0] + u * work[1];
    rowDerivatives[j] = static_cast<double>(m) * (work[1] - work[0]);
  }
  const double sv = 1.0 - v;
  for (int r = n; r > 1; --r)
  {
    for (int j = 0; j < r; ++j)
    {
      rowPoints[j] = sv * rowPoints[j] + v * rowPoints[j + 1];
    }
  }
  position = sv * rowPoints[0] + v * rowPoints[1];
  partialV = static_cast<double>(n) * (rowPoints[1] - rowPoints[0]);
  partialU = DeCasteljauPoint(rowDerivatives, 1, n, v);
}

bool IntersectRayPatch(const BezierPatch& patch,
  const glm::dvec3& origin,
  const glm::dvec3& direction,
  double& u,
  double& v,
  double& t)
{
  const double scale = std::max(patch.Size(), 1e-300);
  constexpr int maxIterations = 40;
  bool converged = false;
  for (int iteration = 0; iteration < maxIterations; ++iteration)
  {
    glm::dvec3 q;
    glm::dvec3 qu;
    glm::dvec3 qv;
    EvaluatePointAndPartials(patch, u, v, q, qu, qv);
    const glm::dvec3 residual = q - origin - t * direction;
    if (glm::length(residual) <= 1e-12 * scale)
    {
      converged = true;
      break;
    }
    // J [du dv dt]^T = -residual with J = [qu qv -direction]; Cramer's rule.
    const glm::dvec3 d = -direction;
    const double det = glm::dot(qu, glm::cross(qv, d));
    if (!(std::fabs(det) > 1e-300) || !std::isfinite(det))
    {
      return false;
    }
    const glm::dvec3 r = -residual;
    double du = glm::dot(r, glm::cross(qv, d)) / det;
    double dv = glm::dot(qu, glm::cross(r, d)) / det;
    double dt = glm::dot(qu, glm::cross(qv, r)) / det;
    // Damp steps that would leave the neighbourhood of the domain (far from [0,1]^2 the
    // polynomial has other, meaningless roots).
    const double step = std::max(std::fabs(du), std::fabs(dv));
    if (step > 0.5)
    {
      const double damping = 0.5 / step;
      du *= damping;
      dv *= damping;
      dt *= damping;
    }
    u = std::min(std::max(u + du, -0.5), 1.5);
    v = std::min(std::max(v + dv, -0.5), 1.5);
    t += dt;
    if (std::fabs(du) + std::fabs(dv) < 1e-13 && std::fabs(dt) < 1e-13 * scale)
    {
      converged = true;
      break;
    }
  }
  return converged && t > 0.0 && std::isfinite(u) && std::isfinite(v) && std::isfinite(t);
}

} // namespace sphcover
