// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PatchTestUtilities.h
 * @brief Shared fixtures of the Bezier patch tests: seeded random patches, the Utah teapot,
 * and an evaluation of the Bernstein sum that is independent of de Casteljau.
 */
#ifndef SPHCOVER_PATCHTESTUTILITIES_H
#define SPHCOVER_PATCHTESTUTILITIES_H

#include "geometry/BezierPatch.h"
#include "scene/BptReader.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace sphcover_test
{

/// The degrees the tests sweep: bilinear, mixed, bicubic, quartic, degree 7 and elongated.
inline std::vector<std::pair<int, int>> TestDegrees()
{
  return { { 1, 1 }, { 2, 3 }, { 3, 3 }, { 4, 4 }, { 7, 7 }, { 7, 2 } };
}

/// A random patch: a wavy height field over a grid (a realistic surface) plus random jitter
/// in all three coordinates, offset from the origin so absolute and relative errors differ.
inline sphcover::BezierPatch RandomPatch(std::mt19937_64& rng, int m, int n)
{
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  std::uniform_real_distribution<double> height(-1.0, 1.0);
  const glm::dvec3 offset(3.0 * height(rng), 3.0 * height(rng), 3.0 * height(rng));
  std::vector<glm::dvec3> points;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      const glm::dvec3 grid(double(i) / m, double(j) / n, 0.6 * height(rng));
      points.push_back(offset + grid + glm::dvec3(jitter(rng), jitter(rng), jitter(rng)) / 3.0);
    }
  }
  return sphcover::BezierPatch(m, n, std::move(points));
}

/// The 32 bicubic patches of the Utah teapot (Data/models/teapot.bpt), read by Core's reader.
inline const std::vector<sphcover::BezierPatch>& Teapot()
{
  static const std::vector<sphcover::BezierPatch> patches =
    sphcover::ReadBptFile(std::string(SPHCOVER_DATA_DIR) + "/models/teapot.bpt");
  return patches;
}

/// sum_ij C(m,i) u^i (1-u)^(m-i) C(n,j) v^j (1-v)^(n-j) P_ij, straight from the definition.
inline glm::dvec3 BernsteinSum(const sphcover::BezierPatch& patch, double u, double v)
{
  auto basis = [](int degree, int i, double t)
  {
    double binomial = 1.0;
    for (int k = 1; k <= i; ++k)
    {
      binomial = binomial * (degree - i + k) / k;
    }
    return binomial * std::pow(t, i) * std::pow(1.0 - t, degree - i);
  };
  glm::dvec3 sum(0.0);
  for (int j = 0; j <= patch.DegreeV(); ++j)
  {
    for (int i = 0; i <= patch.DegreeU(); ++i)
    {
      sum += basis(patch.DegreeU(), i, u) * basis(patch.DegreeV(), j, v) * patch.ControlPoint(i, j);
    }
  }
  return sum;
}

/// Largest distance between the two surfaces sampled at (s,t) and (map(s,t)) on a grid.
template<typename Map>
double MaxDeviation(const sphcover::BezierPatch& piece,
  const sphcover::BezierPatch& parent,
  Map map,
  int samples = 17)
{
  double worst = 0.0;
  for (int b = 0; b <= samples; ++b)
  {
    for (int a = 0; a <= samples; ++a)
    {
      const double s = double(a) / samples;
      const double t = double(b) / samples;
      const std::pair<double, double> uv = map(s, t);
      worst =
        std::max(worst, glm::length(piece.Evaluate(s, t) - parent.Evaluate(uv.first, uv.second)));
    }
  }
  return worst;
}

} // namespace sphcover_test

#endif
