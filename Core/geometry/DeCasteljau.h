// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file DeCasteljau.h
 * @brief de Casteljau evaluation, subdivision and restriction of Bezier curves and
 * tensor-product control nets, in place on caller-owned buffers.
 *
 * These are the building blocks of BezierPatch and of the Bernstein range bounds of paper §4.2
 * (the exact sub-patches of paper §4.3 come from here). de Casteljau's algorithm only forms
 * convex combinations (1-t)a + t b with t in [0,1], so it never amplifies rounding errors:
 * the computed points are within a few ulps times the degree of the exact ones, far better than
 * evaluating the power or Bernstein basis directly.
 *
 * Nets are stored row-major with u fastest: point j*(degreeU+1)+i is P_ij. No function here
 * allocates; buffers of MaxNetDegree+1 points per row suffice.
 *
 * Complexity: a curve of degree d costs O(d^2); a net of degree (m, n) O(m^2 n + n^2) to
 * evaluate and O(m^2 n + n^2 m) to restrict (every row, then every column).
 */
#ifndef SPHCOVER_DECASTELJAU_H
#define SPHCOVER_DECASTELJAU_H

#include "math/UVRect.h"

#include <glm/vec3.hpp>

namespace sphcover
{

/// The largest degree any buffer of these helpers is sized for (BezierPatch::MaxDegree and the
/// derivative nets of lower degree).
constexpr int MaxNetDegree = 15;

/// Reduces the curve b[0], b[stride], ..., b[degree*stride] at t; returns the curve point.
/// The buffer is overwritten.
inline glm::dvec3 DeCasteljauPoint(glm::dvec3* b, int stride, int degree, double t)
{
  const double s = 1.0 - t;
  for (int r = degree; r > 0; --r)
  {
    for (int i = 0; i < r; ++i)
    {
      b[i * stride] = s * b[i * stride] + t * b[(i + 1) * stride];
    }
  }
  return b[0];
}

/// Replaces the curve by its part over [0, t] (the left half of the de Casteljau split):
/// afterwards b[i] is the first point of level i of the de Casteljau triangle.
inline void DeCasteljauKeepLeft(glm::dvec3* b, int stride, int degree, double t)
{
  const double s = 1.0 - t;
  for (int r = 1; r <= degree; ++r)
  {
    for (int i = degree; i >= r; --i)
    {
      b[i * stride] = s * b[(i - 1) * stride] + t * b[i * stride];
    }
  }
}

/// Replaces the curve by its part over [t, 1] (the right half of the de Casteljau split):
/// afterwards b[i] is the last point of level degree-i of the de Casteljau triangle.
inline void DeCasteljauKeepRight(glm::dvec3* b, int stride, int degree, double t)
{
  const double s = 1.0 - t;
  for (int r = 1; r <= degree; ++r)
  {
    for (int i = 0; i <= degree - r; ++i)
    {
      b[i * stride] = s * b[i * stride] + t * b[(i + 1) * stride];
    }
  }
}

/**
 * Replaces the curve by its exact part over [a, c], 0 <= a <= c <= 1, reparametrised to
 * [0, 1]: split at c, keep the left part (on [0, c]), split that at a/c and keep the right
 * part. The new control points are the blossom values f(a,...,a,c,...,c). When a == c the
 * result is the curve point at a repeated degree+1 times.
 */
inline void RestrictCurve(glm::dvec3* b, int stride, int degree, double a, double c)
{
  if (c < 1.0)
  {
    DeCasteljauKeepLeft(b, stride, degree, c);
  }
  if (a > 0.0)
  {
    // a > 0 implies c > 0. a/c is within half an ulp of the exact ratio, far below the
    // de Casteljau rounding of the points themselves.
    DeCasteljauKeepRight(b, stride, degree, a / c);
  }
}

/// Restricts a tensor-product net in place to the parametric rectangle `rect` (which must
/// satisfy rect.IsValid()): every row in u, then every column in v.
inline void RestrictNet(glm::dvec3* net, int degreeU, int degreeV, const UVRect& rect)
{
  const int rowLength = degreeU + 1;
  if (rect.U0 != 0.0 || rect.U1 != 1.0)
  {
    for (int j = 0; j <= degreeV; ++j)
    {
      RestrictCurve(net + j * rowLength, 1, degreeU, rect.U0, rect.U1);
    }
  }
  if (rect.V0 != 0.0 || rect.V1 != 1.0)
  {
    for (int i = 0; i <= degreeU; ++i)
    {
      RestrictCurve(net + i, rowLength, degreeV, rect.V0, rect.V1);
    }
  }
}

/// The point at (u, v) of the tensor-product Bezier surface with this net (not modified).
/// A net of degree 0 in a direction is constant in that direction.
inline glm::dvec3 EvaluateNet(const glm::dvec3* net, int degreeU, int degreeV, double u, double v)
{
  glm::dvec3 row[MaxNetDegree + 1];
  glm::dvec3 column[MaxNetDegree + 1];
  const int rowLength = degreeU + 1;
  for (int j = 0; j <= degreeV; ++j)
  {
    for (int i = 0; i <= degreeU; ++i)
    {
      row[i] = net[j * rowLength + i];
    }
    column[j] = DeCasteljauPoint(row, 1, degreeU, u);
  }
  return DeCasteljauPoint(column, 1, degreeV, v);
}

} // namespace sphcover

#endif
